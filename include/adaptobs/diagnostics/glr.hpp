#pragma once
/// \file
/// Windowed GLR tests on the deviation of an estimate from its nominal value,
/// one per component: the CUSUM's companion when the size of the change is not
/// known in advance.
///
/// **Statistic** (Basseville & Nikiforov 1993, ch. 2; Lai 1995). With the same
/// normalized values \f$z_{k,i} = (v_{k,i} - v^{nom}_i)/s_i\f$ as the CUSUM
/// (diagnostics/cusum.hpp), assumed independent \f$N(\mu_i, 1)\f$ with μ = 0
/// before a change, the log-likelihood ratio of "a change of unknown size began
/// m evaluations ago", maximized over the size, is \f$(\sum_{j=k-m+1}^{k} z_{j,i})^2/(2m)\f$.
/// The test maximizes it over the last M evaluations,
/// \f[ g_{k,i} = \max_{1\le m\le \min(M, k)} \frac{1}{2m}\Big(\sum_{j=k-m+1}^{k} z_{j,i}\Big)^2, \f]
/// and alarms when some \f$g_{k,i}\f$ exceeds h. Unlike the CUSUM's drift ν, nothing
/// fixes the size of change it is tuned to: a large change is caught by a short
/// window, a small one by a long window. The cost is M additions per component
/// and evaluation. An alarm clears the window, names the component with the
/// largest statistic (`isolated()`) and the sign of its sum (`direction()`).
///
/// **Threshold.** No closed form gives the GLR's run length; `glr_threshold`
/// finds h by simulating independent standard normal values from a fixed seed
/// (the same h for a given standard library), so the design holds under the same
/// conditions as the CUSUM's: a stride long enough for the values to be
/// independent. `calibrate_cusum` checks that on fault-free runs, and
/// `design_fault_monitor` also counts the GLR's alarms on them.
///
/// The window buffer is allocated at construction; updates allocate nothing.

#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/status.hpp>
#include <adaptobs/core/validation.hpp>
#include <adaptobs/diagnostics/sequential_test.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string_view>

namespace adaptobs {

/// Longest window a GLR searches: each evaluation costs O(window) per component.
inline constexpr Index glr_max_window = Index{1} << 20;
/// Most work `glr_threshold` spends on one candidate threshold, in window steps
/// (`glr_simulation_work`): about a second on a current core. The search
/// simulates 4 to 10 candidates for the thresholds in the tests and examples
/// (at most 40 after its bracketing doublings), so about ten seconds in all.
inline constexpr double glr_max_simulation_work = 5e8;
/// Longest mean run between false alarms `glr_threshold` simulates, in evaluations.
inline constexpr double glr_max_mean_evaluations = 1e5;

namespace detail {
/// Normal values `glr_threshold` keeps between its candidates (32 MB); beyond,
/// each candidate draws them anew from the seed.
inline constexpr Index glr_kept_values = Index{1} << 22;
/// What a simulated value costs beside its window steps, in window steps: the
/// detector's own update of it (normalizing, the circular buffer, the largest
/// statistic), and, for a value drawn anew for each candidate, the draw (a
/// Mersenne twister and the polar method: for short windows most of the cost).
inline constexpr double glr_value_overhead = 4;
inline constexpr double glr_draw_cost = 16;

/// Evaluations `glr_threshold` simulates for a target of `mean_evaluations`:
/// 50 false alarms at the answer, and at least 20000 evaluations.
[[nodiscard]] inline Index glr_simulated_length(double mean_evaluations) {
  return static_cast<Index>(std::max(20000.0, 50 * mean_evaluations));
}
}  // namespace detail

/// The work of one candidate threshold of `glr_threshold(window,
/// mean_evaluations, components)`, in window steps (one addition to a window
/// sum of one component): each of its
/// \f$L = \max(20000, 50\,\text{mean\_evaluations})\f$ evaluations costs
/// `window` steps per component, plus the value's own update and, for more than
/// 2²² values (L × components), their draw from the seed, which is then repeated for
/// every candidate. Values of 2²² or fewer are drawn once, for about
/// 16 × 2²² ≈ 7·10⁷ steps, not counted here. `glr_threshold` refuses a call whose
/// work exceeds `glr_max_simulation_work`. The arguments are taken as given
/// (mean_evaluations at most 1e5).
[[nodiscard]] inline double glr_simulation_work(Index window, double mean_evaluations, Index components = 1) {
  const double values =
      static_cast<double>(detail::glr_simulated_length(mean_evaluations)) * static_cast<double>(components);
  const bool kept = values <= static_cast<double>(detail::glr_kept_values);
  return values * (static_cast<double>(window) + detail::glr_value_overhead + (kept ? 0.0 : detail::glr_draw_cost));
}

namespace detail {

/// The names under which a caller of `glr_threshold` takes its window, its
/// mean run length (in units of `mean_per_evaluation` of its own: a design
/// routine's samples per evaluation) and its component count; an empty name is
/// an argument the caller cannot lower.
struct GlrSimulationNames {
  std::string_view window = "window";
  std::string_view mean_evaluations = "mean_evaluations";
  std::string_view components = "components";
  double mean_per_evaluation = 1;
};

/// The largest x in [low, high] at which `fits(x)` holds, for `fits` true at
/// `low` and monotone (true, then false).
template <class Fits>
[[nodiscard]] Index largest_fitting(Index low, Index high, Fits fits) {
  while (low < high) {
    const Index middle = low + (high - low + 1) / 2;
    if (fits(middle))
      low = middle;
    else
      high = middle - 1;
  }
  return low;
}

/// Refuses, under `who`, a `glr_threshold` simulation whose work exceeds
/// `glr_max_simulation_work`, naming the first of the window, the mean run
/// length and the component count (among those `names` names) whose lowering
/// alone brings the work within it, and the largest value that does.
inline void require_glr_simulation_affordable(Index window, double mean_evaluations, Index components,
                                              std::string_view who, const GlrSimulationNames& names = {}) {
  const double work = glr_simulation_work(window, mean_evaluations, components);
  if (work <= glr_max_simulation_work) return;
  const auto fits = [](double w) { return w <= glr_max_simulation_work; };
  Message os;
  const auto explain = [&] {
    const double values = static_cast<double>(glr_simulated_length(mean_evaluations)) * static_cast<double>(components);
    os << " (the GLR's threshold is simulated over " << glr_simulated_length(mean_evaluations) << " evaluations of "
       << components << (components == 1 ? " component: " : " components: ") << values << " values";
    if (values > static_cast<double>(glr_kept_values)) os << ", drawn anew for each candidate threshold,";
    os << " of " << window << (window == 1 ? " window step" : " window steps") << " each plus overhead, " << work
       << " steps per candidate where glr_max_simulation_work allows " << glr_max_simulation_work << ")";
  };

  if (!names.window.empty() && window > 1 && fits(glr_simulation_work(1, mean_evaluations, components))) {
    const Index largest =
        largest_fitting(1, window, [&](Index w) { return fits(glr_simulation_work(w, mean_evaluations, components)); });
    os << "must be at most " << largest << " here";
    explain();
    fail_argument(who, names.window, os.str());
  }
  if (!names.mean_evaluations.empty() && fits(glr_simulation_work(window, 2, components))) {
    // Whole evaluations: the length changes with the mean in steps of 50.
    const Index largest = largest_fitting(2, static_cast<Index>(mean_evaluations), [&](Index m) {
      return fits(glr_simulation_work(window, static_cast<double>(m), components));
    });
    os << "must be at most " << static_cast<double>(largest) * names.mean_per_evaluation << " here";
    explain();
    fail_argument(who, names.mean_evaluations, os.str());
  }
  if (!names.components.empty() && components > 1 && fits(glr_simulation_work(window, mean_evaluations, 1))) {
    const Index largest =
        largest_fitting(1, components, [&](Index c) { return fits(glr_simulation_work(window, mean_evaluations, c)); });
    os << "must be at most " << largest << " here";
    explain();
    fail_argument(who, names.components, os.str());
  }
  os << "together with the others costs too much to simulate: lower them";
  explain();
  fail_argument(who, !names.window.empty() ? names.window : names.mean_evaluations, os.str());
}

}  // namespace detail

template <typename Scalar, int N = Eigen::Dynamic>
class GlrDetector : public SequentialTest<GlrDetector<Scalar, N>, Scalar, N> {
  using Base = SequentialTest<GlrDetector<Scalar, N>, Scalar, N>;
  friend Base;

 public:
  using Vector = typename Base::Vector;

  /// \param nominal healthy value, as for `CusumDetector`;
  /// \param scale positive per-component scales, as for `CusumDetector`;
  /// \param window M ≥ 1 evaluations searched for the change's start;
  /// \param threshold h > 0;
  /// \param options stride, hold-off and re-anchoring as for the CUSUM.
  GlrDetector(Vector nominal, const Vector& scale, Index window, Scalar threshold, SequentialTestOptions options = {})
      : Base("GlrDetector", std::move(nominal), scale, threshold, options), window_(window) {
    require(window >= 1 && window <= glr_max_window, "GlrDetector", "window",
            "must lie in [1, 2^20] (each evaluation costs O(window))");
    history_.setZero(this->components(), window);
    statistic_.setZero(this->components());
    half_inverse_.resize(window);
    for (Index m = 1; m <= window; ++m) half_inverse_(m - 1) = Scalar(1) / (Scalar(2) * Scalar(m));
  }

  /// \f$g_{k,i}\f$ per component after the last evaluation (zero right after an alarm).
  [[nodiscard]] const Vector& statistics() const noexcept { return statistic_; }
  [[nodiscard]] Scalar statistic() const { return statistic_.maxCoeff(); }
  [[nodiscard]] Index window() const noexcept { return window_; }

  /// Its fields for `snapshot` and `restore` (core/snapshot.hpp): the window of
  /// normalized values and the position in it; the window length a setting.
  using SnapshotScalar = Scalar;
  static constexpr std::string_view snapshot_type = "GlrDetector";
  static constexpr int snapshot_version = 1;
  template <class Self, class Archive>
  static void visit_state(Self& self, Archive& archive) {
    Base::visit_sequential_state(self, archive);
    archive.setting("window", self.window_);
    archive("history", self.history_);
    archive("statistic", self.statistic_);
    archive("newest", self.newest_);
    archive("filled", self.filled_);
    if constexpr (Archive::reading)
      require(self.newest_ >= 0 && self.newest_ < self.window_ && self.filled_ >= 0 && self.filled_ <= self.window_,
              "restore", "snapshot", "holds a GLR window position outside the window");
  }

 private:
  Scalar evaluate(const Vector& z, Index& component, int& sign) {
    // The newest value goes to column `newest_`; older ones precede it circularly.
    newest_ = newest_ + 1 == window_ ? 0 : newest_ + 1;
    history_.col(newest_) = z;
    filled_ = std::min(filled_ + 1, window_);
    Scalar largest = 0;
    for (Index i = 0; i < z.size(); ++i) {
      Scalar sum = 0, best = 0, best_sum = 0;
      Index column = newest_;
      for (Index m = 1; m <= filled_; ++m) {
        sum += history_(i, column);
        column = column == 0 ? window_ - 1 : column - 1;
        const Scalar g = sum * sum * half_inverse_(m - 1);
        if (g > best) {
          best = g;
          best_sum = sum;
        }
      }
      statistic_(i) = best;
      if (best > largest) {
        largest = best;
        component = i;
        sign = best_sum > 0 ? 1 : -1;
      }
    }
    return largest;
  }

  void clear_statistics() {
    filled_ = 0;
    statistic_.setZero();
  }

  Index window_;
  Eigen::Matrix<Scalar, N, Eigen::Dynamic> history_;
  Eigen::Matrix<Scalar, Eigen::Dynamic, 1> half_inverse_;  // 1/(2m), m = 1..M
  Vector statistic_;
  Index newest_ = 0;
  Index filled_ = 0;
};

namespace detail {

/// What `glr_threshold`'s search found and what it cost.
struct GlrThresholdSearch {
  double threshold = 0;
  Index candidates = 0;    ///< thresholds simulated
  Index values_drawn = 0;  ///< normal values drawn, over all candidates
  Index evaluations = 0;   ///< GLR updates, over all candidates
};

/// `glr_threshold`'s search, its arguments checked. The search tries 4 to 10
/// candidates on the same values; drawing a normal value costs more than a GLR
/// step, so the values are drawn once and kept when there are at most
/// `kept_values` of them (`glr_threshold` keeps `glr_kept_values`), and drawn anew
/// from the seed for each candidate otherwise: the same numbers either way,
/// hence the same h.
[[nodiscard]] inline GlrThresholdSearch glr_threshold_search(Index window, double mean_evaluations, Index components,
                                                             Index kept_values) {
  const Index length = glr_simulated_length(mean_evaluations);
  const double wanted = static_cast<double>(length) / mean_evaluations;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(components), one = Eigen::VectorXd::Ones(components);
  const bool kept = length * components <= kept_values;
  GlrThresholdSearch search;
  auto draw = [&](auto&& use) {
    search.values_drawn += length * components;
    std::mt19937_64 rng(20261125);
    std::normal_distribution<double> normal(0.0, 1.0);
    Eigen::VectorXd z(components);
    for (Index k = 0; k < length; ++k) {
      for (Index i = 0; i < components; ++i) z(i) = normal(rng);
      use(k, z);
    }
  };
  Eigen::MatrixXd values;
  if (kept) {
    values.resize(components, length);
    draw([&](Index k, const Eigen::VectorXd& z) { values.col(k) = z; });
  }
  auto alarms_at = [&](double h) {
    ++search.candidates;
    search.evaluations += length;
    GlrDetector<double> glr(zero, one, window, h);
    if (kept) {
      Eigen::VectorXd z(components);
      for (Index k = 0; k < length; ++k) {
        z = values.col(k);
        (void)glr.update(z);
      }
    } else {
      draw([&](Index, const Eigen::VectorXd& z) { (void)glr.update(z); });
    }
    return static_cast<double>(glr.alarm_count());
  };
  // Bracket the answer (the count falls as h grows; h → 0 alarms at every evaluation).
  double low = 0, high = 4, count_low = static_cast<double>(length), count_high = alarms_at(high);
  while (count_high > wanted) {
    low = high;
    count_low = count_high;
    high *= 2;
    count_high = alarms_at(high);
  }
  // Regula falsi on the logarithm of the count, which falls nearly linearly in h
  // (the log of a run length grows like 2νh for the CUSUM), each step kept off the
  // ends of the bracket; a count within one alarm of the target ends it.
  for (int i = 0; i < 40 && high - low > 1e-4 * high; ++i) {
    const double log_low = std::log(count_low), log_high = std::log(std::max(count_high, 0.5));
    double h = low + (log_low - std::log(wanted)) / (log_low - log_high) * (high - low);
    h = std::clamp(h, low + 0.05 * (high - low), high - 0.05 * (high - low));
    const double count = alarms_at(h);
    if (std::abs(count - wanted) <= 1) {
      search.threshold = h;
      return search;
    }
    (count > wanted ? low : high) = h;
    (count > wanted ? count_low : count_high) = count;
  }
  search.threshold = 0.5 * (low + high);
  return search;
}

}  // namespace detail

/// The threshold h at which `components` windowed GLR statistics of window M,
/// fed independent standard normal values, raise false alarms every
/// `mean_evaluations` evaluations on average (all components together).
///
/// Found by simulation: a `GlrDetector` with restarts after each alarm runs on
/// `50 × mean_evaluations` evaluations (at least 20000) of standard normal
/// values, the same ones, from a fixed seed, for every candidate h, and h is
/// searched (bracketing, then regula falsi on the log of the count) until the
/// alarm count is within one of its target. With about 50 alarms at the answer,
/// the rate it gives carries a relative Monte-Carlo error of about
/// \f$1/\sqrt{50} \approx 14\,\%\f$ (which the tests' tolerances allow for).
/// Refuses, naming 'mean_evaluations', a target outside [2, 10⁵] evaluations,
/// and a call whose simulation would cost more than `glr_max_simulation_work`
/// per candidate (`glr_simulation_work`: every simulated value and every draw
/// counted), naming the first of 'window', 'mean_evaluations' and 'components'
/// whose lowering alone brings it within, with the largest value that does.
[[nodiscard]] inline double glr_threshold(Index window, double mean_evaluations, Index components = 1) {
  constexpr std::string_view who = "glr_threshold";
  require(window >= 1 && window <= glr_max_window, who, "window", "must lie in [1, 2^20]");
  require(components >= 1, who, "components", "must be at least 1");
  require(mean_evaluations >= 2 && mean_evaluations <= glr_max_mean_evaluations, who, "mean_evaluations",
          "must lie in [2, 1e5] evaluations");
  detail::require_glr_simulation_affordable(window, mean_evaluations, components, who);
  return detail::glr_threshold_search(window, mean_evaluations, components, detail::glr_kept_values).threshold;
}

}  // namespace adaptobs
