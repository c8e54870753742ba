#pragma once
/// \file
/// A fault monitor for any `DiagnosableObserver`: a CUSUM and a windowed GLR on
/// its parameter estimates, which detect and isolate a parameter change (the
/// CUSUM tuned to a size of change, the GLR to none), and a χ² test on its
/// output errors, which sees the change while the observer adapts to it; all
/// designed from fault-free runs for one mean time between false alarms each.
///
/// Typical use, in the loop after each accepted update:
/// \code
/// adaptobs::FaultMonitor monitor(design);           // design_fault_monitor(...)
/// if (accepted(observer.update(sample))) (void)monitor.observe(observer);
/// if (monitor.cusum().alarm()) isolate(monitor.cusum().isolated());
/// \endcode

#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/observer.hpp>
#include <adaptobs/diagnostics/calibration.hpp>
#include <adaptobs/diagnostics/change_detector.hpp>
#include <adaptobs/diagnostics/chi_square_test.hpp>
#include <adaptobs/diagnostics/cusum.hpp>
#include <adaptobs/diagnostics/glr.hpp>

#include <Eigen/Core>

#include <concepts>
#include <sstream>
#include <string_view>
#include <utility>
#include <vector>

namespace adaptobs {

/// What an observer's fault-free runs showed: per run, its parameter
/// estimates and output errors after each accepted update, from the moment
/// monitoring would start (once the estimates have converged).
template <typename Scalar, int NY, int NP>
struct FaultFreeRecord {
  std::vector<std::vector<Eigen::Matrix<Scalar, NP, 1>>> parameters;
  std::vector<std::vector<Eigen::Matrix<Scalar, NY, 1>>> output_errors;

  /// Starts the record of a new run.
  void new_run() {
    parameters.emplace_back();
    output_errors.emplace_back();
  }
  /// Appends the observer's estimates after an accepted update to the current run.
  template <DiagnosableObserver O>
  void add(const O& observer) {
    if (parameters.empty()) new_run();
    parameters.back().push_back(observer.parameters());
    output_errors.back().push_back(observer.output_error());
  }
};

/// The design of a `FaultMonitor`.
template <typename Scalar, int NY, int NP>
struct FaultMonitorDesign {
  Eigen::Matrix<Scalar, NP, 1> nominal;                   ///< healthy parameters the CUSUM measures deviations from
  CusumCalibration<Scalar, NP> cusum;                     ///< scales and threshold, with what the runs showed
  CusumOptions cusum_options;                             ///< its stride (the GLR's too)
  Index glr_window = 10;                                  ///< evaluations the GLR searches for the change's start
  Scalar glr_threshold = 0;                               ///< by `glr_threshold`, on the CUSUM's scales
  Index glr_checked_alarms = 0;                           ///< alarms on the record of a GLR designed for about 50 there
  Eigen::Matrix<Scalar, NY, NY> output_error_covariance;  ///< S of the χ² test
  Index window = 1;                                       ///< samples per χ² decision
  Scalar false_alarm_probability = 0;                     ///< per χ² window
  ChiSquareOptions chi_square_options;                    ///< its two-moment correction
  Index chi_square_windows = 0;                           ///< fault-free windows the correction was measured on
};

/// Designs the three tests from fault-free runs for false alarms every
/// `mean_samples_between_false_alarms` samples on average, each:
/// - the CUSUM on \f$\hat\theta\f$ by `calibrate_cusum` with drift ν (in scales)
///   and `stride`, whose refusals it passes on;
/// - the χ² test on windows of `window` samples, with S the sample covariance
///   of the recorded output errors, α = window / mean_samples_between_false_alarms,
///   and the two-moment correction (chi_square_test.hpp, "Correlated errors")
///   from the mean and variance of T over the disjoint windows of the runs
///   (refused with fewer than 200 windows, naming 'record': the variance of T,
///   hence ν, would carry more than about 10 % of error);
/// - the GLR on \f$\hat\theta\f$ with the CUSUM's scales and stride, window
///   `glr_window` evaluations, threshold from `glr_threshold`, checked like the
///   CUSUM: a GLR designed for about 50 false alarms on the record must raise
///   between 25 and 100 there (refused otherwise, naming 'record').
///
/// Each test is designed for the rate asked for: a caller that acts on any of
/// the three alarms gets up to three times as many.
template <typename Scalar, int NY, int NP>
[[nodiscard]] FaultMonitorDesign<Scalar, NY, NP> design_fault_monitor(
    const FaultFreeRecord<Scalar, NY, NP>& record, const Eigen::Matrix<Scalar, NP, 1>& nominal, Scalar drift,
    Scalar mean_samples_between_false_alarms, Index stride, Index window, Index glr_window = 10) {
  constexpr std::string_view who = "design_fault_monitor";
  require_positive(mean_samples_between_false_alarms, who, "mean_samples_between_false_alarms");
  require(window >= 1 && Scalar(window) < mean_samples_between_false_alarms, who, "window",
          "must be at least 1 and shorter than mean_samples_between_false_alarms");
  require(stride >= 1, who, "stride", "must be at least 1");
  require_positive(drift, who, "drift");
  require(glr_window >= 1, who, "glr_window", "must be at least 1");
  const double evaluations_between =
      static_cast<double>(mean_samples_between_false_alarms) / static_cast<double>(stride);
  require(evaluations_between >= 2 && evaluations_between <= glr_max_mean_evaluations, who,
          "mean_samples_between_false_alarms",
          "must lie between 2 and 1e5 strides (the GLR's threshold is simulated over 50 times as many)");
  // The GLR's threshold is simulated (glr_threshold), at a cost of window × parameters × evaluations.
  require(detail::glr_simulation_affordable(glr_window, nominal.size(), evaluations_between), who, "glr_window",
          "times the parameters times mean_samples_between_false_alarms / stride must be at most 1e7 "
          "(glr_max_simulation_work: the GLR's threshold is simulated)");
  FaultMonitorDesign<Scalar, NY, NP> design;
  design.nominal = nominal;
  design.cusum = calibrate_cusum(record.parameters, nominal, drift,
                                 mean_samples_between_false_alarms / static_cast<Scalar>(stride), stride);
  design.cusum_options.stride = stride;
  design.glr_window = glr_window;
  design.glr_threshold = static_cast<Scalar>(glr_threshold(glr_window, evaluations_between, nominal.size()));
  {
    const double checked = static_cast<double>(design.cusum.evaluations) / 50;
    // The check simulates its own threshold, within glr_threshold's range.
    require(detail::glr_simulation_affordable(glr_window, nominal.size(), checked), who, "record",
            "is too long for the GLR's check, whose threshold is simulated for its estimates at the stride / 50 "
            "(at most 1e5, and 1e7 / (glr_window x parameters)): give fewer runs");
    GlrDetector<Scalar, NP> glr(nominal, design.cusum.scale, glr_window,
                                static_cast<Scalar>(glr_threshold(glr_window, checked, nominal.size())),
                                {.stride = stride});
    for (const auto& run : record.parameters) {
      glr.rearm(nominal);
      for (const auto& v : run) (void)glr.update(v);
    }
    design.glr_checked_alarms = glr.alarm_count();
    if (design.glr_checked_alarms < 25 || design.glr_checked_alarms > 100) {
      std::ostringstream os;
      os << "gives " << design.glr_checked_alarms << " false alarms to a GLR designed for 50 on it: the normalized "
         << "estimates are too far from independent normal draws";
      fail_argument(who, "record", os.str());
    }
  }
  design.output_error_covariance = sample_covariance(record.output_errors);
  design.window = window;
  design.false_alarm_probability = static_cast<Scalar>(window) / mean_samples_between_false_alarms;

  // Mean and variance of the window sums T without a fault.
  const ChiSquareTest<Scalar, NY> uncorrected(design.output_error_covariance, window, Scalar(0.5));
  double sum = 0, squares = 0;
  Index windows = 0;
  for (const auto& run : record.output_errors) {
    ChiSquareTest<Scalar, NY> test = uncorrected;
    for (const auto& e : run) {
      const Index decided = test.decisions();
      if (!accepted(test.update(e)) || test.decisions() == decided) continue;
      const double t = static_cast<double>(test.decision_statistic());
      sum += t;
      squares += t * t;
      ++windows;
    }
  }
  require(windows >= 200, who, "record", "must span at least 200 windows of the χ² test");
  const double mean = sum / static_cast<double>(windows);
  const double variance = (squares - sum * mean) / static_cast<double>(windows - 1);
  require(variance > 0, who, "record", "must have output errors that vary");
  design.chi_square_options = {.scale = variance / (2 * mean), .degrees_of_freedom = 2 * mean * mean / variance};
  // Window sums that hardly vary have a ν beyond what the χ² tail is computed for.
  const double dof = design.chi_square_options.degrees_of_freedom;
  if (!(dof >= chi_square_min_degrees_of_freedom && dof <= chi_square_max_degrees_of_freedom)) {
    std::ostringstream os;
    os << "has window sums of the output errors with mean " << mean << " and variance " << variance
       << ": their matched χ² has " << dof << " degrees of freedom, outside [" << chi_square_min_degrees_of_freedom
       << ", " << chi_square_max_degrees_of_freedom << "]";
    fail_argument(who, "record", os.str());
  }
  design.chi_square_windows = windows;
  return design;
}

/// Three change detectors fed together after each accepted update: two on the
/// parameter estimates (NP entries) and one on the output errors (NY entries).
/// By default the CUSUM, the GLR and the χ² test of a `FaultMonitorDesign`;
/// any `ChangeDetector` of the right vectors may take a slot (the accessors
/// keep the names of the default detectors: `cusum()` is the first parameter
/// detector, `glr()` the second, `chi_square()` the output-error detector).
template <typename Scalar, int NY, int NP,
          ChangeDetector<Eigen::Matrix<Scalar, NP, 1>> ParameterDetector = CusumDetector<Scalar, NP>,
          ChangeDetector<Eigen::Matrix<Scalar, NP, 1>> SecondParameterDetector = GlrDetector<Scalar, NP>,
          ChangeDetector<Eigen::Matrix<Scalar, NY, 1>> OutputErrorDetector = ChiSquareTest<Scalar, NY>>
class FaultMonitor {
 public:
  /// The three default tests of `design`.
  explicit FaultMonitor(const FaultMonitorDesign<Scalar, NY, NP>& design)
    requires std::same_as<ParameterDetector, CusumDetector<Scalar, NP>> &&
                 std::same_as<SecondParameterDetector, GlrDetector<Scalar, NP>> &&
                 std::same_as<OutputErrorDetector, ChiSquareTest<Scalar, NY>>
      : cusum_(design.nominal, design.cusum.scale, design.cusum.drift, design.cusum.threshold, design.cusum_options),
        glr_(design.nominal, design.cusum.scale, design.glr_window, design.glr_threshold, design.cusum_options),
        chi_square_(design.output_error_covariance, design.window, design.false_alarm_probability,
                    design.chi_square_options),
        parameters_(design.nominal.size()),
        outputs_(design.output_error_covariance.rows()) {}

  /// Any three detectors, for estimates of `parameters` entries and output
  /// errors of `outputs` entries (checked by `observe`; a negative size, or one
  /// other than a fixed NP or NY, is refused naming it).
  FaultMonitor(Index parameters, Index outputs, ParameterDetector parameter_detector,
               SecondParameterDetector second_parameter_detector, OutputErrorDetector output_error_detector)
      : cusum_(std::move(parameter_detector)),
        glr_(std::move(second_parameter_detector)),
        chi_square_(std::move(output_error_detector)),
        parameters_(parameters),
        outputs_(outputs) {
    require_size<NP>(parameters, "FaultMonitor", "parameters");
    require_size<NY>(outputs, "FaultMonitor", "outputs");
  }

  /// Feeds the observer's estimates after an accepted update to the three tests.
  /// Returns `nonfinite_input`, with every test unchanged, when one would reject them;
  /// estimates of sizes other than the design's are a `ConfigurationError`, also
  /// with every test unchanged (both sizes are checked before any test moves).
  template <DiagnosableObserver O>
  [[nodiscard]] UpdateStatus observe(const O& observer) {
    return observe(observer.parameters(), observer.output_error(), "observer.parameters()", "observer.output_error()");
  }

  /// The same with the estimates themselves (recorded, or from another process):
  /// \f$\hat\theta\f$ and the output error of one accepted update.
  template <class P, class E>
  [[nodiscard]] UpdateStatus observe(const Eigen::MatrixBase<P>& parameters, const Eigen::MatrixBase<E>& output_error) {
    return observe(parameters.derived(), output_error.derived(), "parameters", "output_error");
  }

  [[nodiscard]] const ParameterDetector& cusum() const noexcept { return cusum_; }
  [[nodiscard]] ParameterDetector& cusum() noexcept { return cusum_; }
  [[nodiscard]] const SecondParameterDetector& glr() const noexcept { return glr_; }
  [[nodiscard]] SecondParameterDetector& glr() noexcept { return glr_; }
  [[nodiscard]] const OutputErrorDetector& chi_square() const noexcept { return chi_square_; }
  [[nodiscard]] OutputErrorDetector& chi_square() noexcept { return chi_square_; }

  /// Its fields for `snapshot` and `restore` (core/snapshot.hpp): its three tests'.
  using SnapshotScalar = Scalar;
  static constexpr std::string_view snapshot_type = "FaultMonitor";
  static constexpr int snapshot_version = 1;
  template <class Self, class Archive>
  static void visit_state(Self& self, Archive& archive) {
    archive.object("cusum", self.cusum_);
    archive.object("glr", self.glr_);
    archive.object("chi_square", self.chi_square_);
  }

 private:
  template <class P, class E>
  UpdateStatus observe(const P& parameters, const E& output_error, std::string_view parameters_name,
                       std::string_view output_error_name) {
    constexpr std::string_view who = "FaultMonitor::observe";
    require_shape(parameters, parameters_, 1, who, parameters_name);
    require_shape(output_error, outputs_, 1, who, output_error_name);
    if (!detail::all_finite(parameters, output_error)) return UpdateStatus::nonfinite_input;
    const UpdateStatus chi = chi_square_.update(output_error);
    if (!accepted(chi)) return chi;  // an overflowing weighted error: the others have not moved either
    (void)glr_.update(parameters);   // finite, hence accepted, as by the CUSUM
    return cusum_.update(parameters);
  }

  ParameterDetector cusum_;
  SecondParameterDetector glr_;
  OutputErrorDetector chi_square_;
  Index parameters_, outputs_;
};

}  // namespace adaptobs
