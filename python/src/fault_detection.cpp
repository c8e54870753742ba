// Fault detection in Python: the CUSUM and GLR tests on the parameter
// estimates, the chi-square test on the output errors, the FaultMonitor that
// runs all three, and their calibration from fault-free runs
// (diagnostics/*.hpp). Sizes are run-time; values come as NumPy arrays.

#include "arrays.hpp"
#include "discrete_observer.hpp"
#include "snapshot_dict.hpp"
#include "snapshot_fields.hpp"

#include <adaptobs/diagnostics/calibration.hpp>
#include <adaptobs/diagnostics/chi_square_test.hpp>
#include <adaptobs/diagnostics/cusum.hpp>
#include <adaptobs/diagnostics/fault_monitor.hpp>
#include <adaptobs/diagnostics/glr.hpp>

#include <nanobind/eigen/dense.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/tuple.h>
#include <nanobind/stl/vector.h>

#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

namespace adaptobs::python {

namespace {

constexpr int X = Eigen::Dynamic;
using Cusum = CusumDetector<double, X>;
using Glr = GlrDetector<double, X>;
using ChiSquare = ChiSquareTest<double, X>;
using Monitor = FaultMonitor<double, X, X>;
using MonitorDesign = FaultMonitorDesign<double, X, X>;
using Calibration = CusumCalibration<double, X>;

// The options of a sequential test from its keywords, named as Python spells them.
SequentialTestOptions sequential_options(nb::handle stride, nb::handle hold_off, nb::handle reanchor,
                                         std::string_view who) {
  const SequentialTestOptions options{.stride = integer_argument(stride, who, "stride"),
                                      .hold_off = integer_argument(hold_off, who, "hold_off"),
                                      .reanchor = flag_argument(reanchor, who, "reanchor")};
  adaptobs::require(options.stride >= 1, who, "stride", "must be at least 1");
  adaptobs::require(options.hold_off >= 0, who, "hold_off", "must be non-negative");
  return options;
}

SequentialTestOptions sequential_options_of(const Snapshot<double>& s, const std::string& prefix) {
  return {.stride = integer(s, prefix + "stride"),
          .hold_off = integer(s, prefix + "hold_off"),
          .reanchor = integer(s, prefix + "reanchor") != 0};
}

// The scales a sequential test was built with, from the reciprocals it stores.
Eigen::VectorXd scale_of(const Snapshot<double>& s, const std::string& prefix) {
  return field(s, prefix + "inverse_scale").cwiseInverse();
}

// The record of fault-free runs of `design_fault_monitor`'s two forms, from the
// arrays of its 'parameters' and 'output_errors' (one per run), refused naming them.
FaultFreeRecord<double, X, X> record_of(nb::handle parameters, nb::handle output_errors, std::string_view who) {
  FaultFreeRecord<double, X, X> record;
  record.parameters = vector_runs(parameters, who, "parameters");
  record.output_errors = vector_runs(output_errors, who, "output_errors");
  adaptobs::require(record.parameters.size() == record.output_errors.size(), who, "output_errors",
                    "must hold one array per run of 'parameters'");
  return record;
}

/// The Python object of a FaultMonitor: the monitor and the flag of the calls
/// that release the GIL.
struct MonitorBound {
  Monitor monitor;
  UseFlag in_use;
};

/// snapshot, restore, copy and pickle of a detector (`T` itself, or the monitor
/// in its MonitorBound); `construct` builds one of a snapshot's configuration
/// for `restore` to fill.
template <class T, class Construct>
void bind_state(nb::class_<T>& cls, Construct construct) {
  const auto object = [](auto& self) -> auto& {
    if constexpr (std::is_same_v<std::remove_const_t<std::remove_reference_t<decltype(self)>>, MonitorBound>)
      return self.monitor;
    else
      return self;
  };
  using Object = std::remove_reference_t<decltype(object(std::declval<T&>()))>;
  cls.def(
         "snapshot", [object](const T& self) { return to_dict(adaptobs::snapshot(object(self))); },
         "The whole internal state as a dict of arrays.")
      .def(
          "restore",
          [object](T& self, nb::handle state) {
            if constexpr (std::is_same_v<T, MonitorBound>) {
              const InUse guard(self.in_use.flag, "restore");
              adaptobs::restore(object(self), from_dict(state));
            } else {
              adaptobs::restore(object(self), from_dict(state));
            }
          },
          nb::arg("state"),
          "Continues exactly as the object `state` was taken from; a snapshot of another class or version,\n"
          "or of other sizes or options, raises ConfigurationError and changes nothing.")
      .def("__copy__", [](const T& self) { return T(self); })
      .def(
          "__deepcopy__", [](const T& self, nb::handle) { return T(self); }, nb::arg("memo"))
      .def("__getstate__", [object](const T& self) { return to_dict(adaptobs::snapshot(object(self))); })
      .def("__setstate__", [construct](T& self, nb::handle state) {
        const Snapshot<double> s = from_dict(state);
        detail::require_snapshot_type<Object>(s);
        Object restored = construct(s, std::string());
        adaptobs::restore(restored, s);
        if constexpr (std::is_same_v<T, MonitorBound>)
          new (&self) T{std::move(restored), {}};
        else
          new (&self) T(std::move(restored));
      });
}

/// What the two sequential tests (CUSUM, GLR) share in Python.
template <class T>
void bind_sequential(nb::class_<T>& cls) {
  cls.def(
         "update",
         [](T& self, nb::handle value) {
           const std::string who = std::string(T::snapshot_type) + ".update";
           Eigen::VectorXd v(self.nominal().size());
           read_vector(value, v.size(), who, "value", v);
           return self.update(v);
         },
         nb::arg("value"),
         "Takes one value (e.g. theta_hat after an accepted update); `nonfinite_input` for NaN or Inf,\n"
         "the test unchanged.")
      .def_prop_ro("alarm", &T::alarm, "the last value raised an alarm")
      .def_prop_ro("alarm_count", &T::alarm_count)
      .def_prop_ro("threshold", &T::threshold)
      .def_prop_ro("isolated", &T::isolated, "component of the last alarm")
      .def_prop_ro("direction", &T::direction, "+1 or -1: the sign of the last alarm's deviation")
      .def_prop_ro("alarm_statistic", &T::alarm_statistic)
      .def_prop_ro("statistic", &T::statistic)
      .def_prop_ro("nominal", [](const T& self) { return Eigen::VectorXd(self.nominal()); })
      .def(
          "rearm",
          [](T& self, nb::handle nominal) {
            const std::string who = std::string(T::snapshot_type) + ".rearm";
            Eigen::VectorXd v(self.nominal().size());
            read_vector(nominal, v.size(), who, "nominal", v);
            self.rearm(v);
          },
          nb::arg("nominal"), "Restarts the statistic around a new nominal value.")
      .def("reset", &T::reset, "Back to the state after construction.");
}

// The per-sample figures of FaultMonitor.run.
struct MonitorColumns {
  static constexpr std::array<const char*, 9> statistics{
      "cusum_statistic",       "glr_statistic",       "chi_square_statistic",
      "cusum_isolated",        "cusum_direction",     "glr_isolated",
      "cusum_alarm_statistic", "glr_alarm_statistic", "chi_square_decision_statistic"};
};

nb::dict run_monitor(MonitorBound& self, nb::handle parameters, nb::handle output_errors, nb::handle status) {
  constexpr std::string_view who = "FaultMonitor.run";
  const InUse guard(self.in_use.flag, who);
  Monitor& monitor = self.monitor;
  const Array p = real_array(parameters, who, "parameters");
  if (p.ndim() != 2) fail_dimensions(who, "parameters", "an N x np array", shape_of(p));
  const Index samples = static_cast<Index>(p.shape(0));
  const Index np = monitor.cusum().nominal().size();
  const Index ny = monitor.chi_square().outputs();
  const Rows theta = rows(p, samples, np, who, "parameters");
  const Rows error = rows(output_errors, samples, ny, who, "output_errors");
  // The observer's status of each sample: integers (UpdateStatus values), never booleans.
  nb::ndarray<const std::int64_t, nb::device::cpu> observer_status;
  if (!status.is_none()) {
    observer_status = as_array<nb::ndarray<const std::int64_t, nb::device::cpu>>(
        status, who, "status", "int64", "an array of UpdateStatus values (integers)", "iu");
    if (observer_status.ndim() != 1 || static_cast<Index>(observer_status.shape(0)) != samples)
      fail_dimensions(who, "status", "(" + std::to_string(samples) + ",)", shape_of(observer_status));
  }
  const auto n = static_cast<std::size_t>(samples);
  OutputArray alarms({n, 3});
  OutputArray figures({n, MonitorColumns::statistics.size()});
  StatusArray result(n);
  {
    nb::gil_scoped_release release;
    Eigen::VectorXd estimate(np), error_k(ny);
    for (Index k = 0; k < samples; ++k) {
      const std::int64_t given =
          observer_status.ndim() == 0 ? 0 : observer_status.data()[k * observer_status.stride(0)];
      bool moved = false;
      if (given == static_cast<std::int64_t>(UpdateStatus::accepted)) {
        estimate = theta.row(k);
        error_k = error.row(k);
        const UpdateStatus s = monitor.observe(estimate, error_k);
        result.data[k] = static_cast<std::int8_t>(s);
        moved = accepted(s);
      } else {
        result.data[k] = static_cast<std::int8_t>(given);  // passed over, reported as the observer's
      }
      alarms.data[3 * k] = moved && monitor.cusum().alarm();
      alarms.data[3 * k + 1] = moved && monitor.glr().alarm();
      alarms.data[3 * k + 2] = moved && monitor.chi_square().alarm();
      double* f = figures.data + k * MonitorColumns::statistics.size();
      f[0] = monitor.cusum().statistic();
      f[1] = monitor.glr().statistic();
      f[2] = monitor.chi_square().statistic();
      f[3] = static_cast<double>(monitor.cusum().isolated());
      f[4] = static_cast<double>(monitor.cusum().direction());
      f[5] = static_cast<double>(monitor.glr().isolated());
      // What an alarm is reported with: the statistics above are cleared by the alarm itself.
      f[6] = monitor.cusum().alarm_statistic();
      f[7] = monitor.glr().alarm_statistic();
      f[8] = monitor.chi_square().decision_statistic();
    }
  }
  nb::dict out;
  nb::object numpy = nb::module_::import_("numpy");
  const nb::object alarm_columns = nb::cast(alarms.array).attr("astype")(numpy.attr("bool_"));
  out["cusum_alarm"] = column(alarm_columns, 0);
  out["glr_alarm"] = column(alarm_columns, 1);
  out["chi_square_alarm"] = column(alarm_columns, 2);
  const nb::object figure_columns = nb::cast(figures.array);
  for (std::size_t j = 0; j < MonitorColumns::statistics.size(); ++j)
    out[MonitorColumns::statistics[j]] = column(figure_columns, j);
  out["status"] = nb::cast(result.array);
  return out;
}

// A design as a dict of its fields, and back (pickling: a design is costly to
// compute from its runs).
nb::dict design_state(const MonitorDesign& d) {
  nb::dict state;
  state["nominal"] = d.nominal;
  state["scale"] = d.cusum.scale;
  state["drift"] = d.cusum.drift;
  state["threshold"] = d.cusum.threshold;
  state["lag_correlation"] = d.cusum.lag_correlation;
  state["long_run_excess"] = d.cusum.long_run_excess;
  state["bias"] = d.cusum.bias;
  state["evaluations"] = d.cusum.evaluations;
  state["checked_mean_evaluations"] = d.cusum.checked_mean_evaluations;
  state["checked_alarms"] = d.cusum.checked_alarms;
  state["alarms"] = d.cusum.alarms;
  state["stride"] = d.cusum_options.stride;
  state["hold_off"] = d.cusum_options.hold_off;
  state["reanchor"] = d.cusum_options.reanchor;
  state["glr_window"] = d.glr_window;
  state["glr_threshold"] = d.glr_threshold;
  state["glr_checked_alarms"] = d.glr_checked_alarms;
  state["output_error_covariance"] = d.output_error_covariance;
  state["window"] = d.window;
  state["false_alarm_probability"] = d.false_alarm_probability;
  state["chi_square_scale"] = d.chi_square_options.scale;
  state["chi_square_degrees_of_freedom"] = d.chi_square_options.degrees_of_freedom;
  state["chi_square_weights"] = d.chi_square_options.weights;
  state["chi_square_threshold"] = d.chi_square_threshold;
  state["chi_square_windows"] = d.chi_square_windows;
  state["explanation"] = d.explanation;
  nb::list correlations;
  for (const auto& c : d.stride_correlations)
    correlations.append(
        nb::make_tuple(c.stride, c.lag_correlation, c.long_run_excess, c.evaluations, c.checked_alarms));
  state["stride_correlations"] = correlations;
  return state;
}

MonitorDesign design_of(const nb::dict& state) {
  const auto get = [&](const char* key, auto& out) {
    if (!state.contains(key) || !nb::try_cast(state[key], out))
      adaptobs::fail_argument("FaultMonitorDesign", "state", std::string("has no valid entry '") + key + "'");
  };
  MonitorDesign d;
  get("nominal", d.nominal);
  get("scale", d.cusum.scale);
  get("drift", d.cusum.drift);
  get("threshold", d.cusum.threshold);
  get("lag_correlation", d.cusum.lag_correlation);
  get("long_run_excess", d.cusum.long_run_excess);
  get("bias", d.cusum.bias);
  get("evaluations", d.cusum.evaluations);
  get("checked_mean_evaluations", d.cusum.checked_mean_evaluations);
  get("checked_alarms", d.cusum.checked_alarms);
  get("alarms", d.cusum.alarms);
  get("stride", d.cusum_options.stride);
  get("hold_off", d.cusum_options.hold_off);
  get("reanchor", d.cusum_options.reanchor);
  get("glr_window", d.glr_window);
  get("glr_threshold", d.glr_threshold);
  get("glr_checked_alarms", d.glr_checked_alarms);
  get("output_error_covariance", d.output_error_covariance);
  get("window", d.window);
  get("false_alarm_probability", d.false_alarm_probability);
  get("chi_square_scale", d.chi_square_options.scale);
  get("chi_square_degrees_of_freedom", d.chi_square_options.degrees_of_freedom);
  get("chi_square_windows", d.chi_square_windows);
  // Absent from the states of designs pickled before the exact tail (their
  // threshold is then the two-moment match's, as it was).
  if (state.contains("chi_square_weights")) get("chi_square_weights", d.chi_square_options.weights);
  if (state.contains("chi_square_threshold")) get("chi_square_threshold", d.chi_square_threshold);
  // Absent from the states of designs pickled before the stride search.
  if (state.contains("explanation")) get("explanation", d.explanation);
  if (state.contains("stride_correlations")) {
    std::vector<std::tuple<Index, double, double, Index, Index>> correlations;
    get("stride_correlations", correlations);
    for (const auto& [stride, lag, excess, values, alarms] : correlations)
      d.stride_correlations.push_back({.stride = stride,
                                       .lag_correlation = lag,
                                       .long_run_excess = excess,
                                       .evaluations = values,
                                       .checked_alarms = alarms});
  }
  Monitor check(d);  // refuses, naming the argument, what no monitor can be built from
  (void)check;
  return d;
}

}  // namespace

void bind_fault_detection(nb::module_& m) {
  nb::class_<Cusum> cusum(m, "CusumDetector",
                          "Two-sided CUSUM on the normalized deviations z = (v - nominal) / scale, per component:\n"
                          "g+ = max(0, g+ + z - drift), g- = max(0, g- - z - drift); alarm when the largest exceeds\n"
                          "the threshold (Page 1954; Basseville & Nikiforov 1993, ch. 2; thresholds from Siegmund's\n"
                          "1985 approximation, calibrate_cusum).");
  cusum.def(
      "__init__",
      [](Cusum* self, nb::handle nominal, nb::handle scale, nb::handle drift, nb::handle threshold, nb::handle stride,
         nb::handle hold_off, nb::handle reanchor) {
        constexpr std::string_view who = "CusumDetector";
        new (self) Cusum(vector(nominal, who, "nominal"), vector(scale, who, "scale"), real_scalar(drift, who, "drift"),
                         real_scalar(threshold, who, "threshold"), sequential_options(stride, hold_off, reanchor, who));
      },
      nb::arg("nominal"), nb::arg("scale"), nb::arg("drift"), nb::arg("threshold"), nb::kw_only(),
      nb::arg("stride") = 1, nb::arg("hold_off") = 0, nb::arg("reanchor") = false);
  cusum.def_prop_ro("upper", [](const Cusum& self) { return Eigen::VectorXd(self.upper()); })
      .def_prop_ro("lower", [](const Cusum& self) { return Eigen::VectorXd(self.lower()); })
      .def_prop_ro("drift", &Cusum::drift);
  bind_sequential(cusum);
  const auto make_cusum = [](const Snapshot<double>& s, const std::string& prefix) {
    return Cusum(field(s, prefix + "initial_nominal"), scale_of(s, prefix), scalar(s, prefix + "drift"),
                 scalar(s, prefix + "threshold"), sequential_options_of(s, prefix));
  };
  bind_state(cusum, make_cusum);

  nb::class_<Glr> glr(m, "GlrDetector",
                      "Windowed GLR test for a mean change of unknown size on the normalized deviations:\n"
                      "g = max over the last `window` evaluations m of (sum of z)^2 / (2 m), per component\n"
                      "(Basseville & Nikiforov 1993, ch. 2; Lai 1995).");
  glr.def(
      "__init__",
      [](Glr* self, nb::handle nominal, nb::handle scale, nb::handle window, nb::handle threshold, nb::handle stride,
         nb::handle hold_off, nb::handle reanchor) {
        constexpr std::string_view who = "GlrDetector";
        new (self)
            Glr(vector(nominal, who, "nominal"), vector(scale, who, "scale"), integer_argument(window, who, "window"),
                real_scalar(threshold, who, "threshold"), sequential_options(stride, hold_off, reanchor, who));
      },
      nb::arg("nominal"), nb::arg("scale"), nb::arg("window"), nb::arg("threshold"), nb::kw_only(),
      nb::arg("stride") = 1, nb::arg("hold_off") = 0, nb::arg("reanchor") = false);
  glr.def_prop_ro("statistics", [](const Glr& self) { return Eigen::VectorXd(self.statistics()); })
      .def_prop_ro("window", &Glr::window);
  bind_sequential(glr);
  const auto make_glr = [](const Snapshot<double>& s, const std::string& prefix) {
    return Glr(field(s, prefix + "initial_nominal"), scale_of(s, prefix), integer(s, prefix + "window"),
               scalar(s, prefix + "threshold"), sequential_options_of(s, prefix));
  };
  bind_state(glr, make_glr);

  nb::class_<ChiSquare> chi(m, "ChiSquareTest",
                            "Windowed chi-square test of the output errors: T = sum over `window` samples of\n"
                            "e^T S^-1 e, alarm when T exceeds the upper quantile of probability\n"
                            "false_alarm_probability of c chi^2(nu) (nu = window ny unless given).");
  chi.def(
         "__init__",
         [](ChiSquare* self, nb::handle covariance, nb::handle window, nb::handle false_alarm_probability,
            nb::handle scale, nb::handle degrees_of_freedom) {
           constexpr std::string_view who = "ChiSquareTest";
           new (self) ChiSquare(matrix(covariance, who, "covariance"), integer_argument(window, who, "window"),
                                real_scalar(false_alarm_probability, who, "false_alarm_probability"),
                                {.scale = real_scalar(scale, who, "scale"),
                                 .degrees_of_freedom = real_scalar(degrees_of_freedom, who, "degrees_of_freedom")});
         },
         nb::arg("covariance"), nb::arg("window"), nb::arg("false_alarm_probability"), nb::kw_only(),
         nb::arg("scale") = 1.0, nb::arg("degrees_of_freedom") = 0.0)
      .def(
          "update",
          [](ChiSquare& self, nb::handle output_error) {
            Eigen::VectorXd e(self.outputs());
            read_vector(output_error, e.size(), "ChiSquareTest.update", "output_error", e);
            return self.update(e);
          },
          nb::arg("output_error"))
      .def_prop_ro("alarm", &ChiSquare::alarm)
      .def_prop_ro("alarm_count", &ChiSquare::alarm_count)
      .def_prop_ro("threshold", &ChiSquare::threshold)
      .def_prop_ro("statistic", &ChiSquare::statistic, "the sum over the window in progress")
      .def_prop_ro("decision_statistic", &ChiSquare::decision_statistic, "the sum of the last completed window")
      .def_prop_ro("decisions", &ChiSquare::decisions)
      .def_prop_ro("window", &ChiSquare::window)
      .def_prop_ro("mean_samples_between_false_alarms", &ChiSquare::mean_samples_between_false_alarms)
      .def("reset", &ChiSquare::reset);
  // The covariance is not stored (its inverse is); any positive definite one of the
  // right size builds the test that restore then fills, threshold included.
  const auto make_chi = [](const Snapshot<double>& s, const std::string& prefix) {
    const Eigen::MatrixXd information = field(s, prefix + "information");
    return ChiSquare(Eigen::MatrixXd::Identity(information.rows(), information.cols()), integer(s, prefix + "window"),
                     scalar(s, prefix + "false_alarm_probability"));
  };
  bind_state(chi, make_chi);

  nb::class_<Calibration>(m, "CusumCalibration", "A CUSUM designed from fault-free runs, with what the runs showed.")
      .def_ro("scale", &Calibration::scale, "RMS deviation from nominal of each component, at the stride")
      .def_ro("drift", &Calibration::drift)
      .def_ro("threshold", &Calibration::threshold, "h from Siegmund's approximation")
      .def_ro("lag_correlation", &Calibration::lag_correlation)
      .def_ro("long_run_excess", &Calibration::long_run_excess)
      .def_ro("bias", &Calibration::bias)
      .def_ro("evaluations", &Calibration::evaluations)
      .def_ro("checked_mean_evaluations", &Calibration::checked_mean_evaluations)
      .def_ro("checked_alarms", &Calibration::checked_alarms)
      .def_ro("alarms", &Calibration::alarms);

  nb::class_<MonitorDesign>(m, "FaultMonitorDesign",
                            "The three tests of a FaultMonitor, designed from fault-free runs.")
      .def_ro("nominal", &MonitorDesign::nominal)
      .def_ro("cusum", &MonitorDesign::cusum)
      .def_prop_ro("stride", [](const MonitorDesign& d) { return d.cusum_options.stride; })
      .def_ro("glr_window", &MonitorDesign::glr_window)
      .def_ro("glr_threshold", &MonitorDesign::glr_threshold)
      .def_ro("glr_checked_alarms", &MonitorDesign::glr_checked_alarms)
      .def_ro("output_error_covariance", &MonitorDesign::output_error_covariance)
      .def_ro("window", &MonitorDesign::window)
      .def_ro("false_alarm_probability", &MonitorDesign::false_alarm_probability)
      .def_prop_ro("chi_square_scale", [](const MonitorDesign& d) { return d.chi_square_options.scale; })
      .def_prop_ro("chi_square_degrees_of_freedom",
                   [](const MonitorDesign& d) { return d.chi_square_options.degrees_of_freedom; })
      .def_prop_ro(
          "chi_square_weights", [](const MonitorDesign& d) { return d.chi_square_options.weights; },
          "the weights of T as a sum of weighted chi-square(1) terms, whose exact tail sets the threshold")
      .def_ro("chi_square_windows", &MonitorDesign::chi_square_windows)
      .def_ro("explanation", &MonitorDesign::explanation, "what the design chose and why")
      .def_prop_ro(
          "stride_correlations",
          [](const MonitorDesign& d) {
            nb::list out;
            for (const auto& c : d.stride_correlations)
              out.append(
                  nb::make_tuple(c.stride, c.lag_correlation, c.long_run_excess, c.evaluations, c.checked_alarms));
            return out;
          },
          "(stride, lag-one autocorrelation, long-run variance excess, values, alarms of the rate check where it\n"
          "refused the stride or -1) of each stride measured")
      .def("__getstate__", &design_state)
      .def("__setstate__",
           [](MonitorDesign& self, const nb::dict& state) { new (&self) MonitorDesign(design_of(state)); });

  m.def(
      "calibrate_cusum",
      [](nb::handle runs, nb::handle nominal, nb::handle drift, nb::handle mean_evaluations, nb::handle stride) {
        constexpr std::string_view who = "calibrate_cusum";
        return calibrate_cusum(vector_runs(runs, who, "runs"), Eigen::VectorXd(vector(nominal, who, "nominal")),
                               real_scalar(drift, who, "drift"), real_scalar(mean_evaluations, who, "mean_evaluations"),
                               integer_argument(stride, who, "stride"));
      },
      nb::arg("runs"), nb::arg("nominal"), nb::arg("drift"), nb::arg("mean_evaluations"), nb::arg("stride"),
      "A CUSUM raising false alarms every `mean_evaluations` evaluations on average, from fault-free\n"
      "runs (a list of N_r x n arrays) sampled every step and read every `stride`-th; refuses runs\n"
      "that break its assumptions (correlation, bias, rate), naming the remedy.");
  // The form that chooses the stride and the nominal value first: a call with
  // seven or eight positional arguments has too many for it and goes on to the
  // form with a given stride and nominal value.
  m.def(
      "design_fault_monitor",
      [](nb::handle parameters, nb::handle output_errors, nb::handle drift,
         nb::handle mean_samples_between_false_alarms, nb::handle window, nb::handle glr_window,
         nb::handle stride_multiple) {
        constexpr std::string_view who = "design_fault_monitor";
        const FaultFreeRecord<double, X, X> record = record_of(parameters, output_errors, who);
        return design_fault_monitor(
            record, real_scalar(drift, who, "drift"),
            real_scalar(mean_samples_between_false_alarms, who, "mean_samples_between_false_alarms"),
            integer_argument(window, who, "window"),
            {.glr_window = integer_argument(glr_window, who, "glr_window"),
             .stride_multiple = integer_argument(stride_multiple, who, "stride_multiple")});
      },
      nb::arg("parameters"), nb::arg("output_errors"), nb::arg("drift"), nb::arg("mean_samples_between_false_alarms"),
      nb::arg("window"), nb::kw_only(), nb::arg("glr_window") = 10, nb::arg("stride_multiple") = 1,
      "Designs the three tests from fault-free runs (`parameters`, `output_errors`: one array per run,\n"
      "N_r x np and N_r x ny), choosing the stride (the smallest multiple of `stride_multiple` at which the\n"
      "estimates decorrelate by calibrate_cusum's criteria) and the nominal value (their mean at the stride).\n"
      "The design's `explanation` says what was chosen and why, `stride_correlations` lists what each\n"
      "stride tried showed. Runs too short for the\n"
      "stride are refused naming 'record', with the remedy quantified.");
  m.def(
      "design_fault_monitor",
      [](nb::handle parameters, nb::handle output_errors, nb::handle nominal, nb::handle drift,
         nb::handle mean_samples_between_false_alarms, nb::handle stride, nb::handle window, nb::handle glr_window) {
        constexpr std::string_view who = "design_fault_monitor";
        const FaultFreeRecord<double, X, X> record = record_of(parameters, output_errors, who);
        return design_fault_monitor(
            record, Eigen::VectorXd(vector(nominal, who, "nominal")), real_scalar(drift, who, "drift"),
            real_scalar(mean_samples_between_false_alarms, who, "mean_samples_between_false_alarms"),
            integer_argument(stride, who, "stride"), integer_argument(window, who, "window"),
            integer_argument(glr_window, who, "glr_window"));
      },
      nb::arg("parameters"), nb::arg("output_errors"), nb::arg("nominal"), nb::arg("drift"),
      nb::arg("mean_samples_between_false_alarms"), nb::arg("stride"), nb::arg("window"), nb::arg("glr_window") = 10,
      "Designs the CUSUM, GLR and chi-square tests of a FaultMonitor from fault-free runs: `parameters`\n"
      "and `output_errors` hold one array per run (N_r x np and N_r x ny, the observer's estimates after\n"
      "each accepted sample, from convergence on); false alarms every mean_samples_between_false_alarms\n"
      "samples per test; the parameter tests read every `stride`-th sample, the chi-square test decides\n"
      "every `window` samples.");

  nb::class_<MonitorBound> monitor(m, "FaultMonitor",
                                   "A CUSUM and a GLR on the parameter estimates and a chi-square test on the output\n"
                                   "errors, from one FaultMonitorDesign.");
  monitor
      .def(
          "__init__",
          [](MonitorBound* self, nb::handle design) {
            new (self) MonitorBound{Monitor(object_argument<MonitorDesign>(design, "FaultMonitor", "design",
                                                                           "an adaptobs.FaultMonitorDesign")),
                                    {}};
          },
          nb::arg("design"))
      .def(
          "observe",
          [](MonitorBound& self, nb::handle parameters, nb::handle output_error) {
            constexpr std::string_view who = "FaultMonitor.observe";
            const InUse guard(self.in_use.flag, who);
            Eigen::VectorXd theta(self.monitor.cusum().nominal().size()), error(self.monitor.chi_square().outputs());
            read_vector(parameters, theta.size(), who, "parameters", theta);
            read_vector(output_error, error.size(), who, "output_error", error);
            return self.monitor.observe(theta, error);
          },
          nb::arg("parameters"), nb::arg("output_error"),
          "Feeds an observer's estimates after an accepted update to the three tests.")
      .def("run", &run_monitor, nb::arg("parameters"), nb::arg("output_errors"), nb::arg("status").none() = nb::none(),
           "The three tests over N samples of an observer's run (parameters N x np, output_errors N x ny),\n"
           "with the GIL released; samples whose `status` is not accepted are passed over. Returns a dict of\n"
           "per-sample arrays: cusum_alarm, glr_alarm, chi_square_alarm, their statistics, the CUSUM's and\n"
           "GLR's isolated component and the CUSUM's direction, the statistic of each test's last alarm\n"
           "(cusum_alarm_statistic, glr_alarm_statistic) and of the chi-square test's last completed window\n"
           "(chi_square_decision_statistic), and the status of each sample.")
      .def_prop_ro(
          "cusum", [](const MonitorBound& self) { return self.monitor.cusum(); }, "a copy of the CUSUM")
      .def_prop_ro(
          "glr", [](const MonitorBound& self) { return self.monitor.glr(); }, "a copy of the GLR")
      .def_prop_ro(
          "chi_square", [](const MonitorBound& self) { return self.monitor.chi_square(); },
          "a copy of the chi-square test");
  bind_state(monitor, [make_cusum, make_glr, make_chi](const Snapshot<double>& s, const std::string&) {
    MonitorDesign design;
    const Cusum c = make_cusum(s, "cusum.");
    const Glr g = make_glr(s, "glr.");
    design.nominal = c.nominal();
    design.cusum.scale = Eigen::VectorXd::Ones(c.nominal().size());  // restore writes the scales
    design.cusum.drift = c.drift();
    design.cusum.threshold = c.threshold();
    design.cusum_options = sequential_options_of(s, "cusum.");
    design.glr_window = g.window();
    design.glr_threshold = g.threshold();
    const ChiSquare chi_square = make_chi(s, "chi_square.");
    design.output_error_covariance = Eigen::MatrixXd::Identity(chi_square.outputs(), chi_square.outputs());
    design.window = chi_square.window();
    design.false_alarm_probability = chi_square.false_alarm_probability();
    return Monitor(design);
  });
}

}  // namespace adaptobs::python
