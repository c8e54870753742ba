#pragma once
/// \file
/// A fault monitor for any `DiagnosableObserver`: a CUSUM and a windowed GLR on
/// its parameter estimates, which detect and isolate a parameter change (the
/// CUSUM tuned to a size of change, the GLR to none), and a χ² test on its
/// output errors, which sees the change while the observer adapts to it; all
/// designed from fault-free runs for one mean time between false alarms each.
///
/// Typical use: a design from fault-free runs, then the loop after each accepted update:
/// \code
/// // record: fault-free runs (FaultFreeRecord); the stride and nominal value chosen from them
/// const auto design = adaptobs::design_fault_monitor(record, drift, mean_samples_between_false_alarms, window);
/// adaptobs::FaultMonitor monitor(design);           // design.explanation says what was chosen
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

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <functional>
#include <iomanip>
#include <sstream>
#include <string>
#include <string_view>
#include <type_traits>
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

namespace detail {

template <class T>
inline constexpr bool is_fault_free_record = false;
template <typename Scalar, int NY, int NP>
inline constexpr bool is_fault_free_record<FaultFreeRecord<Scalar, NY, NP>> = true;

template <class Record>
struct record_scalar;
template <typename Scalar, int NY, int NP>
struct record_scalar<FaultFreeRecord<Scalar, NY, NP>> {
  using type = Scalar;
};
/// The scalar of the records a simulator returns.
template <class Simulate>
using simulated_scalar =
    typename record_scalar<std::remove_cvref_t<std::invoke_result_t<Simulate&, std::uint64_t>>>::type;

}  // namespace detail

/// What the parameter estimates of fault-free runs showed at one stride.
template <typename Scalar>
struct StrideCorrelation {
  Index stride = 1;            ///< samples between the values read
  Scalar lag_correlation = 0;  ///< largest |lag-one| autocorrelation of a component (`StrideStatistics`)
  Scalar long_run_excess = 0;  ///< largest departure from 1 of a long-run variance ratio
  Index evaluations = 0;       ///< values read over all runs
  /// Where the correlations were within their limits but `calibrate_cusum`'s
  /// rate check (`cusum_rate_check`) refused the stride: the false alarms of
  /// its check (designed for 50); −1 elsewhere.
  Index checked_alarms = -1;
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
  ChiSquareOptions chi_square_options;                    ///< its weights, and T's two-moment match
  /// The χ² test's threshold at `false_alarm_probability` from those options,
  /// computed once by the design (0: a FaultMonitor computes it from them).
  Scalar chi_square_threshold = 0;
  Index chi_square_windows = 0;  ///< fault-free windows the correction was measured on
  /// The strides whose correlations were measured: the one given, or every one
  /// the search tried, smallest first (the last is the stride chosen).
  std::vector<StrideCorrelation<Scalar>> stride_correlations;
  /// What the design chose and why, in a few lines: the stride and the
  /// correlations that justify it, the nominal value, and each test's threshold.
  std::string explanation;
};

/// Settings of the `design_fault_monitor` that chooses the stride and the nominal value.
struct FaultMonitorDesignOptions {
  Index glr_window = 10;  ///< evaluations the GLR searches for the change's start
  /// The strides searched are multiples of this: the period of a periodic
  /// excitation, so that the parameter tests read \f$\hat\theta\f$ at one phase
  /// of it (its mean there may differ from phase to phase).
  Index stride_multiple = 1;
  /// The search's limits on the lag-one autocorrelation and the long-run
  /// variance ratio, as a fraction of `calibrate_cusum`'s (0.1 and 0.25). The
  /// record measures them only within a sampling error (about 2√5/√n on the
  /// ratio, for n values at the stride). The long-run scales absorb most of the
  /// correlation left (at 1, a stride just inside the limits raised 0.9 times
  /// the designed false alarms on AR(1) estimates, 1.7 times with RMS scales);
  /// 0.5 keeps clear of the limits, at a longer stride.
  double margin = 1;
};

namespace detail {

/// The refusal of one entry of a record: "holds <what> <problem>: number k of run r (counted from 0)".
[[noreturn]] inline void fail_record_entry(std::string_view who, std::string_view argument, std::string_view what,
                                           std::size_t run, std::size_t k, std::string_view problem) {
  std::ostringstream os;
  os << "holds " << what << " " << problem << ": number " << k << " of run " << run << " (counted from 0)";
  fail_argument(who, argument, os.str());
}

/// Checks a record as the user passed it, before any design routine sees its
/// runs (their refusals would name their own arguments, not the record): as
/// many runs of output errors as of parameters, and every parameter estimate
/// (of `parameters` entries, or of the first one's size when negative) and
/// every output error (of the first one's size, at least one entry) finite.
/// Returns the number of parameters (−1 for a record without estimates).
template <typename Scalar, int NY, int NP>
Index check_record(const FaultFreeRecord<Scalar, NY, NP>& record, Index parameters, std::string_view who,
                   std::string_view argument) {
  require(record.parameters.size() == record.output_errors.size(), who, argument,
          "must hold as many runs of output errors as of parameters");
  const auto check = [&](const auto& runs, Index& size, std::string_view what) {
    for (std::size_t r = 0; r < runs.size(); ++r)
      for (std::size_t k = 0; k < runs[r].size(); ++k) {
        const auto& v = runs[r][k];
        if (size < 0) size = v.size();
        if (v.size() != size) {
          std::ostringstream os;
          os << "of " << v.size() << " entries where " << size << " were expected";
          fail_record_entry(who, argument, what, r, k, os.str());
        }
        if (!detail::all_finite(v)) fail_record_entry(who, argument, what, r, k, "that is not finite");
      }
  };
  check(record.parameters, parameters, "a parameter estimate");
  Index outputs = -1;
  check(record.output_errors, outputs, "an output error");
  require(outputs != 0, who, argument, "must hold output errors of at least one entry");
  return parameters;
}

/// Whether the χ² test can take `covariance`, the sample covariance of a
/// record's output errors: positive definite, with a finite inverse (as its
/// constructor requires).
template <typename Scalar, int NY>
[[nodiscard]] bool chi_square_covariance_usable(const Eigen::Matrix<Scalar, NY, NY>& covariance) {
  detail::CholeskyFactor<Eigen::Matrix<Scalar, NY, NY>> factor;
  if (covariance.rows() < 1 || !factor.compute(covariance)) return false;
  Eigen::Matrix<Scalar, NY, NY> information =
      Eigen::Matrix<Scalar, NY, NY>::Identity(covariance.rows(), covariance.rows());
  factor.solve_in_place(information);
  return information.allFinite();
}

/// The weights \f$\lambda_i\f$ of a χ² window sum \f$T = \sum_i\lambda_i\chi^2_{1,i}\f$
/// (chi_square_test.hpp, "Correlated errors"), from fault-free output errors
/// and their sample covariance S = LLᵀ: the positive eigenvalues of the
/// covariance of W stacked whitened errors \f$w_k = L^{-1}\varepsilon_k\f$, the
/// block-Toeplitz matrix of their autocovariances
/// \f$\Gamma_l = \frac1N\sum_k w_{k+l}w_k^T\f$, l = 0 … W − 1 (pairs within a run, N all
/// the errors; \f$\Gamma_0 = I\f$, so the weights sum to \f$Wn_y\f$). Dividing by N rather
/// than by the pairs at each lag keeps the matrix positive semidefinite (it is
/// then a sum over runs of Gram matrices of the zero-padded runs), at a
/// relative bias of l/n in runs of n samples. Each \f$\Gamma_l\f$ carries a
/// sampling error of about \f$1/\sqrt N\f$: the rate the weights give at α = 1e-6 is
/// within 11 % of α on 2·10⁵ AR(1) errors, 20 a window (docs/fault_detection.md).
/// Costs N·W·n_y² products and an eigenvalue problem of order W·n_y, once.
template <typename Scalar, int NY>
[[nodiscard]] std::vector<double> window_sum_weights(const std::vector<std::vector<Eigen::Matrix<Scalar, NY, 1>>>& runs,
                                                     const Eigen::Matrix<Scalar, NY, NY>& covariance, Index window) {
  const Index ny = covariance.rows(), size = window * ny;
  const Eigen::LLT<Eigen::MatrixXd> factor(covariance.template cast<double>());
  std::vector<Eigen::MatrixXd> lags(static_cast<std::size_t>(window), Eigen::MatrixXd::Zero(ny, ny));
  std::size_t count = 0;
  Eigen::MatrixXd whitened;
  for (const auto& run : runs) {
    const auto n = static_cast<Index>(run.size());
    whitened.resize(ny, n);
    for (Index k = 0; k < n; ++k) whitened.col(k) = run[static_cast<std::size_t>(k)].template cast<double>();
    factor.matrixL().solveInPlace(whitened);
    for (Index l = 0; l < std::min(window, n); ++l)
      lags[static_cast<std::size_t>(l)].noalias() += whitened.rightCols(n - l) * whitened.leftCols(n - l).transpose();
    count += run.size();
  }
  // Block (i, j) of the stacked covariance is E[w_{k+i} w_{k+j}ᵀ] = Γ_{i−j} for
  // i ≥ j; the solver reads the lower triangle only.
  Eigen::MatrixXd stacked = Eigen::MatrixXd::Zero(size, size);
  for (Index i = 0; i < window; ++i)
    for (Index j = 0; j <= i; ++j)
      stacked.block(i * ny, j * ny, ny, ny) = lags[static_cast<std::size_t>(i - j)] / static_cast<double>(count);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(stacked, Eigen::EigenvaluesOnly);
  std::vector<double> weights;
  for (Index i = 0; i < size; ++i)
    if (solver.eigenvalues()(i) > 0) weights.push_back(solver.eigenvalues()(i));
  return weights;
}

/// The `explanation` of a design: its stride and the correlations behind it,
/// its nominal value, and the tests' thresholds with their checks on the record.
template <typename Scalar, int NY, int NP>
std::string explain_design(const FaultMonitorDesign<Scalar, NY, NP>& design, std::size_t runs, bool searched,
                           Index multiple) {
  const CusumCalibrationOptions limits;  // calibrate_cusum's defaults
  std::ostringstream os;
  os << std::setprecision(3);
  const Index stride = design.cusum_options.stride;
  const auto& at = design.stride_correlations.back();
  os << "stride " << stride << " samples, ";
  if (searched)
    os << "the smallest " << (multiple > 1 ? "multiple of " + std::to_string(multiple) + " " : std::string())
       << "at which theta-hat decorrelates";
  else
    os << "as given";
  os << ": lag-one autocorrelation of theta-hat " << at.lag_correlation << " (limit " << limits.max_lag_correlation
     << "), long-run variance ratio off 1 by " << at.long_run_excess << " (limit " << limits.max_long_run_excess
     << "), over " << at.evaluations << " values in " << runs << " runs";
  if (searched && design.stride_correlations.size() >= 2) {
    const auto& before = design.stride_correlations[design.stride_correlations.size() - 2];
    os << "; at " << before.stride << " samples " << before.lag_correlation << " and " << before.long_run_excess;
    const Index half = stride / 2 / multiple * multiple;
    for (const auto& c : design.stride_correlations)
      if (c.stride == half && half != before.stride)
        os << ", at " << half << " (half the stride) " << c.lag_correlation << " and " << c.long_run_excess;
    // Shorter strides whose correlations passed but whose rate check did not.
    std::ostringstream refused;
    Index worst = 0, count = 0;
    for (const auto& c : design.stride_correlations)
      if (c.checked_alarms >= 0) {
        refused << (count++ ? ", " : "") << c.stride;
        worst = std::max(worst, c.checked_alarms);
      }
    if (count > 0)
      os << "; the rate check of calibrate_cusum refused " << count << " shorter stride(s) whose correlations were "
         << "within the limits (" << refused.str() << " samples: up to " << worst
         << " false alarms where 50 were designed)";
  }
  os << ".\nnominal = " << (searched ? "mean of theta-hat at the stride" : "as given") << ": [";
  for (Index i = 0; i < design.nominal.size(); ++i) os << (i ? ", " : "") << std::setprecision(6) << design.nominal(i);
  os << std::setprecision(3) << "], " << design.cusum.bias << " scales from the runs' mean; scales [";
  for (Index i = 0; i < design.cusum.scale.size(); ++i) os << (i ? ", " : "") << design.cusum.scale(i);
  os << "].\nCUSUM: drift " << design.cusum.drift << " (in scales), threshold " << design.cusum.threshold
     << " (a check "
     << "designed for 50 false alarms on the record raised " << design.cusum.checked_alarms << "). GLR: window "
     << design.glr_window << ", threshold " << design.glr_threshold << " (its check raised "
     << design.glr_checked_alarms << " of 50). chi-square: windows of " << design.window << " samples, false-alarm "
     << "probability " << design.false_alarm_probability << " per window";
  const std::vector<double>& weights = design.chi_square_options.weights;
  if (!weights.empty())
    os << ", threshold the larger of the exact tail of T as a sum of " << weights.size()
       << " weighted chi-square(1) terms (largest weight " << *std::max_element(weights.begin(), weights.end())
       << ", from the errors' autocovariances) and of its two-moment match, which";
  os << " is " << design.chi_square_options.scale << " chi-square with " << design.chi_square_options.degrees_of_freedom
     << " degrees of freedom over " << design.chi_square_windows << " windows.";
  return os.str();
}

}  // namespace detail

/// Designs the three tests from fault-free runs for false alarms every
/// `mean_samples_between_false_alarms` samples on average, each:
/// - the CUSUM on \f$\hat\theta\f$ by `calibrate_cusum` with drift ν (in scales)
///   and `stride`, whose refusals it passes on;
/// - the χ² test on windows of `window` samples, with S the sample covariance
///   of the recorded output errors, α = window / mean_samples_between_false_alarms,
///   and the threshold the larger of two (`ChiSquareOptions`): the exact tail
///   of T as a weighted sum of \f$\chi^2_1\f$ terms (chi_square_test.hpp,
///   "Correlated errors"), its weights from the errors' autocovariances over the
///   window (`detail::window_sum_weights`), and the two-moment match from the
///   mean and variance of T over the disjoint windows of the runs (refused with
///   fewer than 200 windows, naming 'record': the variance of T, hence ν, would
///   carry more than about 10 % of error);
/// - the GLR on \f$\hat\theta\f$ with the CUSUM's scales and stride, window
///   `glr_window` evaluations, threshold from `glr_threshold`, checked like the
///   CUSUM: a GLR designed for about 50 false alarms on the record must raise
///   between 25 and 100 there (refused otherwise, naming 'record').
///
/// The record itself is checked first, its refusals naming 'record' and the
/// entry: as many runs of output errors as of parameters, every estimate and
/// output error finite and of one size; and output errors whose sample
/// covariance the χ² test can take (positive definite, with a finite inverse).
/// The GLR's threshold is simulated (`glr_threshold`): a simulation beyond
/// `glr_max_simulation_work` is refused naming 'glr_window' or
/// 'mean_samples_between_false_alarms', with the largest value allowed.
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
  require(glr_window <= glr_max_window, who, "glr_window",
          "must be at most 2^20 (each evaluation costs O(glr_window))");
  // The GLR's threshold is simulated (glr_threshold): its work, refused in this call's terms.
  detail::require_glr_simulation_affordable(glr_window, evaluations_between, nominal.size(), who,
                                            {.window = "glr_window",
                                             .mean_evaluations = "mean_samples_between_false_alarms",
                                             .components = {},
                                             .mean_per_evaluation = static_cast<double>(stride)});
  // The record as passed, named as such: calibrate_cusum and sample_covariance
  // would refuse its runs under their own names.
  (void)detail::check_record(record, nominal.size(), who, "record");
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
    require(checked <= glr_max_mean_evaluations &&
                glr_simulation_work(glr_window, checked, nominal.size()) <= glr_max_simulation_work,
            who, "record",
            "is too long for the GLR's check, whose threshold is simulated for its estimates at the stride / 50 "
            "(at most 1e5, and a simulation within glr_max_simulation_work, glr_simulation_work): give fewer runs");
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
  std::size_t output_errors = 0;
  for (const auto& run : record.output_errors) output_errors += run.size();
  // Necessary for the windows counted below (which do not span runs), and for a covariance.
  require(static_cast<double>(output_errors) >= 200 * static_cast<double>(window), who, "record",
          "must span at least 200 windows of the χ² test");
  design.output_error_covariance = sample_covariance(record.output_errors);
  if (!detail::chi_square_covariance_usable(design.output_error_covariance))
    fail_argument(who, "record",
                  "has output errors whose sample covariance is singular, or has an inverse beyond the floating-point "
                  "range (errors all zero, an output that never varies or is a fixed combination of others, or "
                  "errors too small): the chi-square test cannot normalize them");
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
  // The threshold: the larger of the exact tail of T's weighted sum and of the
  // two-moment match above (ChiSquareOptions).
  design.chi_square_options.weights =
      detail::window_sum_weights(record.output_errors, design.output_error_covariance, window);
  // Computed once here, not by every FaultMonitor built from the design: the
  // weighted tail's quantile costs about 50 evaluations of the tail.
  design.chi_square_threshold = ChiSquareTest<Scalar, NY>(design.output_error_covariance, window,
                                                          design.false_alarm_probability, design.chi_square_options)
                                    .threshold();
  design.chi_square_windows = windows;
  design.stride_correlations = {{.stride = stride,
                                 .lag_correlation = design.cusum.lag_correlation,
                                 .long_run_excess = design.cusum.long_run_excess,
                                 .evaluations = design.cusum.evaluations}};
  design.explanation = detail::explain_design(design, record.parameters.size(), false, 1);
  return design;
}

namespace detail {

/// The ratio ρ₁ of a correlation decaying as ρ_l = ρ₁^l whose long-run variance
/// ratio \f$1 + 2\sum_{l=1}^{5}\rho_1^l\f$ is off 1 by `excess` (bisection: the
/// sum grows with ρ₁ on [0, 1]).
inline double ratio_of_long_run_excess(double excess) {
  double low = 0, high = 1;
  for (int i = 0; i < 60; ++i) {
    const double q = (low + high) / 2;
    double sum = 0, power = 1;
    for (int l = 1; l <= 5; ++l) sum += power *= q;
    (2 * sum > excess ? high : low) = q;
  }
  return (low + high) / 2;
}

/// The refusal of a record whose runs support no stride at which the estimates
/// decorrelate, with the remedies that are possible and how much of each. The
/// correlation at the largest stride the runs support, S, is extrapolated as
/// an exponential decay, ρ(s) = exp(−s/τ): the needed stride is where it meets
/// the limits. θ̂'s correlation time τ is about 1/(μ·excitation) for an update
/// law of step size μ (averaging: θ̃ decays at the rate μ·λ_min of the
/// regressors' mean product), so a larger μ or a richer input shortens it.
[[noreturn]] inline void fail_without_decorrelation(std::string_view who, std::string_view argument,
                                                    const std::vector<std::size_t>& lengths,
                                                    const std::vector<StrideCorrelation<double>>& tried, Index multiple,
                                                    const CusumCalibrationOptions& limits) {
  const auto runs = static_cast<double>(lengths.size());
  double total = 0;
  for (const std::size_t n : lengths) total += static_cast<double>(n);
  const double mean_length = std::floor(total / runs);
  // Values a run must hold at the stride: six (five strides between the first
  // and the last), 500 over all runs, and 100 pairs five strides apart.
  const double values_per_run = std::max({6.0, std::ceil(500 / runs), 5 + std::ceil(100 / runs)});
  std::ostringstream os;
  os << std::setprecision(3);
  double needed = static_cast<double>(multiple), supported = 0;
  if (tried.empty()) {
    os << "holds too few values for any stride (" << total << " samples in " << lengths.size()
       << " runs; at the stride, at least 500 values in all and runs of at least six are needed): the stride needs "
          "at least "
       << multiple << " samples";
  } else {
    const StrideCorrelation<double>& last = tried.back();
    supported = static_cast<double>(last.stride);
    const double q_needed = std::min(limits.max_lag_correlation, ratio_of_long_run_excess(limits.max_long_run_excess));
    const double q =
        std::clamp(std::max(last.lag_correlation, ratio_of_long_run_excess(last.long_run_excess)), 1e-9, 1 - 1e-9);
    const double tau = -supported / std::log(q);
    needed = std::max(supported + static_cast<double>(multiple), std::ceil(tau * std::log(1 / q_needed)));
    needed = std::ceil(needed / static_cast<double>(multiple)) * static_cast<double>(multiple);
    os << "has runs too short for theta-hat to decorrelate within them: at " << last.stride
       << " samples, the largest stride they support (at the stride, runs of at least six values and 500 values in "
          "all), the lag-one autocorrelation of theta-hat is "
       << last.lag_correlation << " (limit " << limits.max_lag_correlation << ") and the long-run variance ratio is "
       << "off 1 by " << last.long_run_excess << " (limit " << limits.max_long_run_excess
       << "); as an exponential decay, theta-hat's correlation time is about " << tau
       << " samples and the stride needs about " << needed << " samples";
  }
  os << std::setprecision(12) << ". Possible remedies: runs of at least " << (values_per_run - 1) * needed + 1
     << " samples each (now " << lengths.size() << " runs of " << mean_length << " samples on average";
  const double values = std::ceil(mean_length / needed);
  if (values >= 6) {
    const double more = std::max(std::ceil(500 / values), std::ceil(100 / (values - 5))) - runs;
    os << "), or " << std::max(1.0, more) << " more runs of " << mean_length << " samples";
  } else {
    os << "; more runs of " << mean_length << " samples cannot help: each holds fewer than six strides)";
  }
  if (supported > 0)
    os << std::setprecision(3) << ", or a correlation time of theta-hat about " << needed / supported
       << " times shorter: it is about 1/(mu x excitation), so a step size mu about " << needed / supported
       << " times larger (within its admissible range) or a richer input";
  fail_argument(who, argument, os.str());
}

/// The stride search and the design at the stride found (`design_fault_monitor`
/// without a stride), its refusals naming `argument` (the record or its runs).
template <typename Scalar, int NY, int NP>
FaultMonitorDesign<Scalar, NY, NP> design_fault_monitor_searched(const FaultFreeRecord<Scalar, NY, NP>& record,
                                                                 Scalar drift, Scalar mean_samples_between_false_alarms,
                                                                 Index window, const FaultMonitorDesignOptions& options,
                                                                 std::string_view who, std::string_view argument) {
  using Vector = Eigen::Matrix<Scalar, NP, 1>;
  require_positive(mean_samples_between_false_alarms, who, "mean_samples_between_false_alarms");
  require(window >= 1 && Scalar(window) < mean_samples_between_false_alarms, who, "window",
          "must be at least 1 and shorter than mean_samples_between_false_alarms");
  require_positive(drift, who, "drift");
  require(options.glr_window >= 1, who, "options.glr_window", "must be at least 1");
  require(options.stride_multiple >= 1, who, "options.stride_multiple", "must be at least 1");
  require(options.margin > 0 && options.margin <= 1, who, "options.margin", "must be in (0, 1]");
  const Index n = check_record(record, -1, who, argument);
  require(n >= 1, who, argument, "must hold parameter estimates of at least one component");
  const auto& runs = record.parameters;
  std::vector<std::size_t> lengths;
  for (const auto& run : runs) lengths.push_back(run.size());
  const CusumCalibrationOptions limits;  // calibrate_cusum's defaults, which it checks again at the stride
  // Values and pairs five strides apart that the runs hold at a stride: these
  // decrease as the stride grows, which ends the search.
  const auto supported = [&](Index stride) {
    Index values = 0, pairs = 0;
    for (const std::size_t length : lengths) {
      const Index v = (static_cast<Index>(length) + stride - 1) / stride;
      values += v;
      pairs += std::max<Index>(0, v - StrideStatistics<Scalar, NP>::max_lag);
    }
    return values >= 500 && pairs >= 100;
  };
  const Vector reference = [&] {
    for (const auto& run : runs)
      if (!run.empty()) return Vector(run.front());
    return Vector();
  }();
  std::vector<StrideCorrelation<double>> tried;
  std::vector<StrideCorrelation<Scalar>> correlations;
  Vector nominal;
  bool found = false;
  for (Index stride = options.stride_multiple; supported(stride); stride += options.stride_multiple) {
    const StrideStatistics<Scalar, NP> s = stride_statistics(runs, reference, stride);
    correlations.push_back({.stride = stride,
                            .lag_correlation = s.lag_correlation,
                            .long_run_excess = s.long_run_excess,
                            .evaluations = s.evaluations});
    tried.push_back({.stride = stride,
                     .lag_correlation = static_cast<double>(s.lag_correlation),
                     .long_run_excess = static_cast<double>(s.long_run_excess),
                     .evaluations = s.evaluations});
    if (!(s.lag_correlation <= Scalar(options.margin * limits.max_lag_correlation) &&
          s.long_run_excess <= Scalar(options.margin * limits.max_long_run_excess)))
      continue;
    nominal = reference + s.mean;
    // Correlations within their limits may still hide a dependence the rate
    // check sees (θ̂ read at drifting phases of a periodic excitation): then
    // calibrate_cusum would refuse the stride, and the search goes on. Its
    // check, on its scales: the long-run RMS deviations from the nominal value.
    const StrideStatistics<Scalar, NP> about_nominal = stride_statistics(runs, nominal, stride);
    if (!(about_nominal.root_mean_square.array() > Scalar(0)).all())
      fail_argument(who, argument,
                    "has parameter estimates constant in some component at the stride: they must vary in every "
                    "component (a zero scale cannot normalize)");
    if (!cusum_threshold_exists(static_cast<double>(drift),
                                static_cast<double>(static_cast<Scalar>(s.evaluations) / Scalar(50)), n)) {
      std::ostringstream os;
      os << "holds too few values at stride " << stride << " (" << s.evaluations << ") for drift " << drift
         << ": a check expecting 50 false alarms on them needs a threshold below 0; give longer runs or lower the "
            "drift";
      fail_argument(who, argument, os.str());
    }
    if (!(about_nominal.long_run_scale.array() > Scalar(0)).all()) continue;  // refused by calibrate_cusum
    const Index alarms = cusum_rate_check(runs, nominal, about_nominal.long_run_scale, drift, stride);
    if (!rate_within(alarms, limits.rate_tolerance)) {
      correlations.back().checked_alarms = alarms;
      continue;
    }
    found = true;
    break;
  }
  if (!found) {
    CusumCalibrationOptions searched = limits;
    searched.max_lag_correlation *= options.margin;
    searched.max_long_run_excess *= options.margin;
    fail_without_decorrelation(who, argument, lengths, tried, options.stride_multiple, searched);
  }
  const Index stride = correlations.back().stride;
  FaultMonitorDesign<Scalar, NY, NP> design;
  try {
    design = design_fault_monitor(record, nominal, drift, mean_samples_between_false_alarms, stride, window,
                                  options.glr_window);
  } catch (const ConfigurationError& e) {
    // The checks at the stride found refuse the record, whatever argument of
    // the form with a given stride their message names.
    const std::string_view message = e.what();
    std::ostringstream os;
    os << "was refused at the stride found, " << stride << " samples: " << message;
    if (message.find("argument 'runs'") != std::string_view::npos ||
        message.find("argument 'record'") != std::string_view::npos ||
        message.find("argument 'stride'") != std::string_view::npos ||
        message.find("argument 'nominal'") != std::string_view::npos)
      fail_argument(who, argument, os.str());
    throw;
  }
  // The stride chosen as calibrate_cusum measured it, about the nominal value
  // (the search's sums were about a reference value: the last digits differ).
  correlations.back().lag_correlation = design.cusum.lag_correlation;
  correlations.back().long_run_excess = design.cusum.long_run_excess;
  design.stride_correlations = std::move(correlations);
  design.explanation = explain_design(design, runs.size(), true, options.stride_multiple);
  return design;
}

}  // namespace detail

/// Designs the three tests from fault-free runs, choosing the stride and the
/// nominal value from the runs themselves, for false alarms every
/// `mean_samples_between_false_alarms` samples on average each:
/// - the stride is the smallest (multiple of `options.stride_multiple`) at which
///   \f$\hat\theta\f$ read every stride decorrelates by `calibrate_cusum`'s own
///   criteria at their default limits (`CusumCalibrationOptions`): lag-one
///   autocorrelation at most 0.1 and long-run variance ratio within 0.25 of 1,
///   measured by `stride_statistics`; the search tries every stride up to the
///   largest the runs support (500 values at the stride in all, and runs of at
///   least six). A stride whose correlations pass but whose values fail
///   `calibrate_cusum`'s check of the rate (`cusum_rate_check`: θ̂ read at
///   drifting phases of a periodic excitation) is passed over, its count kept
///   in `StrideCorrelation::checked_alarms`;
/// - the nominal value is the mean of \f$\hat\theta\f$ at that stride, over
///   every run: the healthy value the CUSUM's sums stay centred on;
/// - then the tests as by the form with a given stride and nominal value.
///
/// The design's `explanation` says what was chosen and why, and
/// `stride_correlations` holds the correlations of every stride tried.
///
/// Throws `ConfigurationError` naming 'record' where no stride the runs
/// support decorrelates, or the runs hold too few values; the message says
/// which remedy is possible and how much of it: runs at least N samples long,
/// M more runs, or a correlation time of \f$\hat\theta\f$ shorter by a factor
/// (a larger step size or a richer input). The refusals of the tests'
/// checks at the stride chosen name 'record' too.
template <typename Scalar, int NY, int NP>
[[nodiscard]] FaultMonitorDesign<Scalar, NY, NP> design_fault_monitor(const FaultFreeRecord<Scalar, NY, NP>& record,
                                                                      Scalar drift,
                                                                      Scalar mean_samples_between_false_alarms,
                                                                      Index window,
                                                                      FaultMonitorDesignOptions options = {}) {
  return detail::design_fault_monitor_searched(record, drift, mean_samples_between_false_alarms, window, options,
                                               "design_fault_monitor", "record");
}

/// The same from a simulator: `simulate(seed)` returns one fault-free run (a
/// `FaultFreeRecord` holding it, or several), recorded from the estimates'
/// convergence on, for seeds 1 to `runs`. The refusals for too few or too
/// short runs name 'runs'.
template <class Simulate>
  requires detail::is_fault_free_record<std::remove_cvref_t<std::invoke_result_t<Simulate&, std::uint64_t>>>
[[nodiscard]] auto design_fault_monitor(Simulate&& simulate, Index runs, detail::simulated_scalar<Simulate> drift,
                                        detail::simulated_scalar<Simulate> mean_samples_between_false_alarms,
                                        Index window, FaultMonitorDesignOptions options = {}) {
  constexpr std::string_view who = "design_fault_monitor";
  require(runs >= 1, who, "runs", "must be at least 1");
  std::remove_cvref_t<std::invoke_result_t<Simulate&, std::uint64_t>> record;
  for (Index seed = 1; seed <= runs; ++seed) {
    auto run = std::invoke(simulate, static_cast<std::uint64_t>(seed));
    require(run.parameters.size() == run.output_errors.size(), who, "simulate",
            "must return a record with as many runs of output errors as of parameters");
    for (std::size_t r = 0; r < run.parameters.size(); ++r) {
      record.parameters.push_back(std::move(run.parameters[r]));
      record.output_errors.push_back(std::move(run.output_errors[r]));
    }
  }
  return detail::design_fault_monitor_searched(record, drift, mean_samples_between_false_alarms, window, options, who,
                                               "runs");
}

namespace detail {
/// A design's χ² options with the threshold it computed, if it did.
inline ChiSquareOptions with_threshold(ChiSquareOptions options, double threshold) {
  options.threshold = threshold;
  return options;
}
}  // namespace detail

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
                    detail::with_threshold(design.chi_square_options, design.chi_square_threshold)),
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
