#pragma once
/// \file
/// Lost measurements in simulation: which output channels of each sample reach
/// the observers.
///
/// Two mechanisms, as met on real data: every sample is lost with probability
/// `drop` (a sensor or bus that drops frames at random, drawn from a seeded
/// generator so that a run is reproducible), and no sample arrives during the
/// outage \f$[t_0, t_1]\f$ (a sensor out of service). `simulate` hands the
/// observers the channels that arrived (`simulation/runner.hpp`).

#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/validation.hpp>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

namespace adaptobs {

struct OutputLossOptions {
  /// Probability that a sample is lost, in [0, 1).
  double drop = 0;
  /// No sample arrives for \f$t\in[\text{outage\_begin}, \text{outage\_end}]\f$ (none when begin > end).
  double outage_begin = std::numeric_limits<double>::infinity();
  double outage_end = -std::numeric_limits<double>::infinity();
  /// Only this output channel is lost (−1: the whole sample).
  Index channel = -1;
  std::uint64_t seed = 1;
};

/// Draws, sample after sample, which output channels arrive.
class OutputLoss {
 public:
  explicit OutputLoss(OutputLossOptions options = {}) : options_(options), rng_(options.seed) {
    constexpr std::string_view who = "OutputLoss";
    require(options.drop >= 0 && options.drop < 1, who, "drop", "must be in [0, 1)");
    require(!std::isnan(options.outage_begin) && !std::isnan(options.outage_end), who, "outage",
            "bounds must not be NaN");
    require(options.channel >= -1, who, "channel", "must be −1 (whole sample) or a channel index");
  }

  /// Whether the model ever loses a sample.
  [[nodiscard]] bool lossless() const noexcept {
    return options_.drop == 0 && !(options_.outage_begin <= options_.outage_end);
  }

  /// The channels of the sample at time t that arrive (one draw per call).
  template <StateSpace D>
  [[nodiscard]] OutputMask<D> channels_at(double t, Index ny) {
    OutputMask<D> present = OutputMask<D>::Constant(ny, true);
    const bool in_outage = t >= options_.outage_begin && t <= options_.outage_end;
    const bool dropped = options_.drop > 0 && std::bernoulli_distribution(options_.drop)(rng_);
    if (in_outage || dropped) {
      require(options_.channel < ny, "OutputLoss", "channel", "exceeds the number of outputs");
      if (options_.channel < 0)
        present.setConstant(false);
      else
        present(options_.channel) = false;
    }
    return present;
  }

  [[nodiscard]] const OutputLossOptions& options() const noexcept { return options_; }

 private:
  OutputLossOptions options_;
  std::mt19937_64 rng_;
};

/// The mask as an integer, channel i as bit i: 1/0 for one output, 2^ny − 1 when all arrive.
template <class Mask>
[[nodiscard]] double channel_bits(const Mask& present) {
  double bits = 0;
  for (Index i = present.size() - 1; i >= 0; --i) bits = 2 * bits + (present(i) ? 1 : 0);
  return bits;
}

}  // namespace adaptobs
