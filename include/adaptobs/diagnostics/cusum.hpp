#pragma once
/// \file
/// Two-sided CUSUM tests on the deviation of an estimate from its nominal value,
/// one per component, with the threshold set from a mean time between false alarms.
///
/// **Statistic** (Page 1954; Basseville & Nikiforov 1993, ch. 2). Each value
/// \f$v_k\f$ (typically \f$\hat\theta_k\f$) is normalized per component,
/// \f$z_{k,i} = (v_{k,i} - v^{nom}_i)/s_i\f$, and drives two one-sided sums
/// \f[ g^+_{k,i} = \max(0,\ g^+_{k-1,i} + z_{k,i} - \nu),\qquad
///     g^-_{k,i} = \max(0,\ g^-_{k-1,i} - z_{k,i} - \nu), \f]
/// where the drift ν is half the smallest shift, in units of s, worth detecting.
/// An alarm is raised when some sum exceeds the threshold h; the sums then
/// restart from zero, so that alarms form a renewal process whose mean spacing
/// is the run length the threshold was designed for.
///
/// **Isolation.** The alarm names the component whose sum exceeds h by the most
/// (`isolated()`), and its sign (`direction()`): with one sum per component, a
/// change of \f$\theta_i\f$ drives \f$g_i\f$ fastest, so the first and largest
/// crossing points at the parameter that moved. A change that moves several
/// components at once is named by the largest of them.
///
/// **Threshold.** When the \f$z_{k,i}\f$ fed to the sums are independent
/// standard normal draws, each one-sided sum's mean run length to a false
/// alarm follows Siegmund's (1985) corrected diffusion approximation
/// (`cusum_mean_run_length`), and with 2N independent sums racing the alarm
/// rate is 2N times each one's. An estimate \f$\hat\theta_k\f$ is not
/// independent from step to step: it moves in small increments. `stride`
/// feeds only every stride-th value to the sums; choose it at least the lag
/// over which the estimate decorrelates (for a periodic excitation, one period)
/// and check by `calibrate_cusum` (diagnostics/calibration.hpp), which measures
/// the scales s and that correlation on fault-free runs and refuses a stride
/// too short for the approximation, and normalizes by the values' long-run
/// standard deviation, which the sums far in their tail vary with.
///
/// Fixed sizes allocate nothing; every method is real-time safe.

#include <adaptobs/core/detail/bisection.hpp>
#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/status.hpp>
#include <adaptobs/core/validation.hpp>
#include <adaptobs/diagnostics/sequential_test.hpp>

#include <Eigen/Core>

#include <cmath>
#include <string_view>

namespace adaptobs {

/// Siegmund's correction for the CUSUM's two barriers: \f$2\rho\f$ with
/// \f$\rho = -\zeta(1/2)/\sqrt{2\pi} \approx 0.583\f$, the mean overshoot of a standard
/// normal random walk over a barrier, once for the threshold h and once for the
/// reflecting barrier at 0.
inline constexpr double siegmund_overshoot = 1.166;

/// Mean number of independent \f$N(\mu, 1)\f$ increments before a one-sided
/// CUSUM with drift ν > 0 exceeds h, by Siegmund's approximation (Siegmund
/// 1985; Basseville & Nikiforov 1993, ch. 5): with \f$\Delta = \mu - \nu\f$ and \f$b = h + 1.166\f$,
/// \f[ \bar L = \frac{e^{-2\Delta b} + 2\Delta b - 1}{2\Delta^2},\qquad \bar L = b^2 \text{ for } \Delta = 0. \f]
/// μ = 0 gives the mean run length to a false alarm, μ > ν the mean detection delay.
///
/// **Range.** The correction is exact as h → ∞ with Δb fixed; at finite drift
/// its error grows with ν. Against simulated two-sided CUSUMs on independent
/// N(0, 1) draws (4·10⁷ evaluations each, 10² to 10⁴ evaluations between false
/// alarms, 2·10⁴ to 4·10⁵ alarms), the rate it designs is within 1 % for
/// ν = 0.5 and 4 to 7 % too low for ν = 1, the error shrinking as h grows
/// (docs/fault_detection.md, "False-alarm rates in the tail"). Beyond ν = 1 it
/// is not checked.
[[nodiscard]] inline double cusum_mean_run_length(double drift, double threshold, double mean = 0.0) {
  const double delta = mean - drift;
  const double b = threshold + siegmund_overshoot;
  const double x = 2 * delta * b;
  // e^{−x} + x − 1 loses the digits of x²/2 to cancellation for small x:
  // its series (L = b²(1 − x/3 + x²/12 − x³/60 + …)) below 1e-3, where the
  // truncation is below x⁴/360 ≈ 3e-15, and expm1 above, relative error ≈ 2u/x.
  if (std::abs(x) < 1e-3) return b * b * (1 - x / 3 + x * x / 12 - x * x * x / 60);
  return (std::expm1(-x) + x) / (2 * delta * delta);
}

namespace detail {
/// Whether 2 × `components` sums can raise false alarms as rarely as every
/// `mean_evaluations` increments: more rarely than at h = 0, the least any threshold achieves.
[[nodiscard]] inline bool cusum_threshold_exists(double drift, double mean_evaluations, Index components) {
  return mean_evaluations * 2 * static_cast<double>(components) > cusum_mean_run_length(drift, 0.0);
}
}  // namespace detail

/// The threshold h at which \f$2\times\f$`components` one-sided sums, each fed
/// independent standard normal increments with drift ν, raise false alarms every
/// `mean_evaluations` increments on average (each sum then every
/// 2·components·mean_evaluations increments, `cusum_mean_run_length`).
[[nodiscard]] inline double cusum_threshold(double drift, double mean_evaluations, Index components = 1) {
  constexpr std::string_view who = "cusum_threshold";
  require_positive(drift, who, "drift");
  require_positive(mean_evaluations, who, "mean_evaluations");
  require(components >= 1, who, "components", "must be at least 1");
  const double per_sum = mean_evaluations * 2 * static_cast<double>(components);
  require(std::isfinite(per_sum), who, "mean_evaluations",
          "times 2 x components must be finite (no threshold reaches an infinite run length)");
  require(detail::cusum_threshold_exists(drift, mean_evaluations, components), who, "mean_evaluations",
          "is shorter than the run length at threshold 0: lower the drift");
  return detail::boundary_by_bisection([&](double h) { return cusum_mean_run_length(drift, h) < per_sum; });
}

/// Settings of a `CusumDetector`: stride, hold-off and re-anchoring.
using CusumOptions = SequentialTestOptions;

template <typename Scalar, int N = Eigen::Dynamic>
class CusumDetector : public SequentialTest<CusumDetector<Scalar, N>, Scalar, N> {
  using Base = SequentialTest<CusumDetector<Scalar, N>, Scalar, N>;
  friend Base;

 public:
  using Vector = typename Base::Vector;

  /// \param nominal healthy value \f$v^{nom}\f$; \param scale positive per-component
  /// scales s (e.g. from `calibrate_cusum`); \param drift ν > 0; \param threshold h > 0.
  CusumDetector(Vector nominal, const Vector& scale, Scalar drift, Scalar threshold, CusumOptions options = {})
      : Base("CusumDetector", std::move(nominal), scale, threshold, options), drift_(drift) {
    require_positive(drift, "CusumDetector", "drift");
    upper_.setZero(this->components());
    lower_.setZero(this->components());
  }

  /// The sums \f$g^+_i, g^-_i\f$ after the last value (zero right after an alarm).
  [[nodiscard]] const Vector& upper() const noexcept { return upper_; }
  [[nodiscard]] const Vector& lower() const noexcept { return lower_; }
  /// \f$\max_i \max(g^+_i, g^-_i)\f$.
  [[nodiscard]] Scalar statistic() const { return std::max(upper_.maxCoeff(), lower_.maxCoeff()); }
  [[nodiscard]] Scalar drift() const noexcept { return drift_; }

  /// Its fields for `snapshot` and `restore` (core/snapshot.hpp).
  using SnapshotScalar = Scalar;
  static constexpr std::string_view snapshot_type = "CusumDetector";
  static constexpr int snapshot_version = 1;
  template <class Self, class Archive>
  static void visit_state(Self& self, Archive& archive) {
    Base::visit_sequential_state(self, archive);
    archive("drift", self.drift_);
    archive("upper", self.upper_);
    archive("lower", self.lower_);
  }

 private:
  Scalar evaluate(const Vector& z, Index& component, int& sign) {
    // The sums, then their largest; which one it is matters only for an alarm,
    // and is looked up then (branches on every sum would mispredict at random).
    Scalar largest = 0;
    for (Index i = 0; i < z.size(); ++i) {
      upper_(i) = std::max(Scalar(0), upper_(i) + z(i) - drift_);
      lower_(i) = std::max(Scalar(0), lower_(i) - z(i) - drift_);
      largest = std::max(largest, std::max(upper_(i), lower_(i)));
    }
    for (Index i = 0; i < z.size(); ++i)
      if (upper_(i) == largest || lower_(i) == largest) {
        component = i;
        sign = upper_(i) == largest ? 1 : -1;
        break;
      }
    return largest;
  }

  void clear_statistics() {
    upper_.setZero();
    lower_.setZero();
  }

  Scalar drift_;
  Vector upper_;
  Vector lower_;
};

}  // namespace adaptobs
