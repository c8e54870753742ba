// The continuous-time observers of the unified formulation (Zhang 2005) in
// Python, with run-time sizes: Bastin-Gevers (Algorithm 1, eq. (2)-(6)),
// Marino-Tomei (Algorithm 2, eq. (2)-(4), (7)), Besancon (Algorithm 3,
// eq. (2)-(4), (8)-(9)) and Zhang (Algorithm 4, eq. (10)-(15)), over a
// ContinuousLtiModel or a ContinuousLtvModel whose regressor Phi is a constant
// matrix or a Python callable; their canonical forms and SPR gain.

#include "arrays.hpp"
#include "collected.hpp"
#include "discrete_observer.hpp"
#include "snapshot_dict.hpp"
#include "snapshot_fields.hpp"

#include <adaptobs/baselines/kalman_bucy.hpp>
#include <adaptobs/design/canonical_forms.hpp>
#include <adaptobs/design/positive_real.hpp>
#include <adaptobs/observers/bastin_gevers.hpp>
#include <adaptobs/observers/besancon.hpp>
#include <adaptobs/observers/marino_tomei.hpp>
#include <adaptobs/observers/zhang_continuous.hpp>

#include <nanobind/eigen/dense.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/tuple.h>

#include <optional>
#include <string>
#include <tuple>

namespace adaptobs::python {

namespace {

/// Φ of a continuous model from Python: a constant nx × np matrix, or a callable
/// Phi(t) or Phi(t, u, y) returning one. The callable runs with the GIL taken
/// back (once per Runge–Kutta stage); a constant never enters Python.
struct PythonRegressor {
  nb::object source;  // what the user gave: the array or the callable (kept for pickling)
  bool callable = false;
  bool signals = false;                           // Phi(t, u, y) rather than Phi(t)
  std::string_view model = "ContinuousLtiModel";  // the class its errors name
  mutable Eigen::MatrixXd value;

  const Eigen::MatrixXd& operator()(double t, const Eigen::VectorXd& u, const Eigen::VectorXd& y) const {
    if (!callable) return value;
    nb::gil_scoped_acquire gil;
    const nb::object phi = signals ? source(t, u, y) : source(t);
    value = matrix(phi, model, "Phi(t)");
    return value;
  }
};

PythonRegressor regressor_of(nb::handle phi, std::string_view model = "ContinuousLtiModel") {
  PythonRegressor r;
  r.source = nb::borrow(phi);
  r.model = model;
  r.callable = PyCallable_Check(phi.ptr()) != 0;
  if (r.callable) {
    // Phi(t, u, y) when the callable takes three positional arguments; Phi(t) when
    // Python cannot read its signature (a function compiled in C++).
    try {
      const nb::object signature = nb::module_::import_("inspect").attr("signature")(phi);
      r.signals = nb::len(nb::object(signature.attr("parameters"))) >= 3;
    } catch (nb::python_error&) {
      r.signals = false;
    }
  } else {
    r.value = matrix(phi, model, "Phi");
  }
  return r;
}

using ContinuousModel = ContinuousLtiModel<Dims, PythonRegressor>;

/// The model a continuous observer holds in Python, so that each observer is one
/// class whatever its model: a ContinuousLtiModel's (A, B, C), or the matrices a
/// ContinuousLtvModel's Python function matrices_at(t) returns, called (with the
/// GIL) wherever the integration needs them. Each observer owns its copy, so the
/// matrices of the last call are cached per observer, and an observer is never
/// stepped by two threads at once (UseFlag). Its Python class is ContinuousLtvModel.
class PythonContinuousModel : public Dims {
 public:
  static constexpr bool time_invariant = false;

  explicit PythonContinuousModel(const ContinuousModel& lti)
      : system_(lti.system()), phi_(lti.regressor_function()), sizes_(lti.sizes()), varying_(false) {}

  /// Sizes from matrices_at(0); Φ checked at t = 0 as for a constant model.
  PythonContinuousModel(nb::object matrices_at, PythonRegressor phi, Index np, std::string_view who)
      : phi_(std::move(phi)), matrices_at_(std::move(matrices_at)), varying_(true) {
    if (!PyCallable_Check(matrices_at_.ptr())) fail_type(who, "matrices_at", matrices_at_, "a callable t -> (A, B, C)");
    const auto [A, B, C] = system_tuple(matrices_at_(0.0), who, "matrices_at(0)");
    system_ = {matrix(A, who, "matrices_at(0)[0]"), matrix(B, who, "matrices_at(0)[1]"),
               matrix(C, who, "matrices_at(0)[2]")};
    adaptobs::validate_state_space(system_, who);
    adaptobs::require(np >= 0, who, "np", "must be non-negative");
    sizes_ = {system_.A.rows(), system_.B.cols(), system_.C.rows(), np};
    detail::validate_regressor<Dims>(phi_, sizes_, who);
  }

  [[nodiscard]] bool is_time_invariant() const noexcept { return !varying_; }

  /// (A(t), B(t), C(t)); matrices of other sizes than at t = 0, or not finite,
  /// raise ConfigurationError naming matrices_at(t).
  [[nodiscard]] const ContinuousSystem<Dims>& at(double t) const {
    if (is_time_invariant()) return system_;
    constexpr std::string_view who = "ContinuousLtvModel";
    nb::gil_scoped_acquire gil;
    const auto [A, B, C] = system_tuple(matrices_at_(t), who, "matrices_at(t)");
    read_as_at_zero(A, sizes_.nx, sizes_.nx, "matrices_at(t)[0]", system_.A);
    read_as_at_zero(B, sizes_.nx, sizes_.nu, "matrices_at(t)[1]", system_.B);
    read_as_at_zero(C, sizes_.ny, sizes_.nx, "matrices_at(t)[2]", system_.C);
    if (!detail::all_finite(system_.A) || !detail::all_finite(system_.B) || !detail::all_finite(system_.C))
      adaptobs::fail_argument(who, "matrices_at(t)",
                              "returned matrices that are not finite at t = " + std::to_string(t));
    return system_;
  }
  [[nodiscard]] decltype(auto) regressor(double t, const Eigen::VectorXd& u, const Eigen::VectorXd& y) const {
    return detail::evaluate_regressor<Dims>(phi_, t, u, y, sizes_, phi_.model);
  }
  [[nodiscard]] Sizes sizes() const noexcept { return sizes_; }
  [[nodiscard]] const PythonRegressor& regressor_function() const noexcept { return phi_; }
  [[nodiscard]] const nb::object& matrices_function() const noexcept { return matrices_at_; }

  /// Its fields: A, B, C of a time-invariant model; the sizes of a time-varying
  /// one, whose function is pickled by Python beside the snapshot, as Φ is.
  static constexpr std::string_view snapshot_type = "ContinuousLtvModel";
  static constexpr int snapshot_version = 1;
  template <class Self, class Archive>
  static void visit_state(Self& self, Archive& archive) {
    archive.setting("time_invariant", self.is_time_invariant() ? 1 : 0);
    archive.setting("np", self.sizes_.np);
    if (self.is_time_invariant()) {
      archive("A", self.system_.A);
      archive("B", self.system_.B);
      archive("C", self.system_.C);
    } else {
      archive.setting("nx", self.sizes_.nx);
      archive.setting("nu", self.sizes_.nu);
      archive.setting("ny", self.sizes_.ny);
    }
  }

  /// The references to Python objects it holds, for the garbage collector (collected.hpp).
  friend int traverse_python(const PythonContinuousModel& model, visitproc visit, void* arg) {
    Py_VISIT(model.phi_.source.ptr());
    if (model.varying_) Py_VISIT(model.matrices_at_.ptr());
    return 0;
  }
  friend void clear_python(const PythonContinuousModel& model) {
    // Part of the model's configuration, const to the library: only the collector
    // changes it, to break a cycle of an object about to go, never stepped again.
    auto& self = const_cast<PythonContinuousModel&>(model);
    self.phi_.source = nb::none();
    self.phi_.callable = false;
    if (self.varying_) self.matrices_at_ = nb::none();
  }

 private:
  // A matrix as matrix() reads it at t = 0 (a vector as a column), into `out`.
  static void read_as_at_zero(nb::handle obj, Index rows, Index cols, std::string_view name, Eigen::MatrixXd& out) {
    constexpr std::string_view who = "ContinuousLtvModel";
    const Array a = real_array(obj, who, name);
    const MatrixView v = view(a, who, name);
    if (v.rows() != rows || v.cols() != cols)
      fail_dimensions(who, name, std::to_string(rows) + "x" + std::to_string(cols), shape_of(a));
    out = v;
  }

  mutable ContinuousSystem<Dims> system_;  // of a time-varying model: the matrices of the last call
  PythonRegressor phi_;
  nb::object matrices_at_;  // of a time-varying model
  Sizes sizes_{};
  bool varying_;
};

using BastinGeversPy = BastinGeversObserver<PythonContinuousModel>;
using MarinoTomeiPy = MarinoTomeiObserver<PythonContinuousModel>;
using BesanconPy = BesanconObserver<PythonContinuousModel>;
using ZhangPy = ZhangContinuousObserver<PythonContinuousModel>;
using KalmanBucyPy = AugmentedKalmanBucyFilter<PythonContinuousModel>;

// The excitation level of the last window, NaN while unknown (the filter has none).
template <class Observer>
double excitation_of(const Observer& o) {
  if constexpr (requires { o.excitation_level(); })
    return o.excitation_level().value_or(std::numeric_limits<double>::quiet_NaN());
  else
    return std::numeric_limits<double>::quiet_NaN();
}
using Transform = StaticTransform<Dims>;

SignalReconstruction reconstruction_of(nb::handle obj, std::string_view who, std::string_view argument) {
  if (!nb::isinstance<nb::str>(obj)) fail_type(who, argument, obj, "'hold', 'linear' or 'quadratic'");
  const std::string name = nb::cast<std::string>(obj);
  if (name == "hold") return SignalReconstruction::hold;
  if (name == "linear") return SignalReconstruction::linear;
  if (name == "quadratic") return SignalReconstruction::quadratic;
  adaptobs::fail_argument(who, argument, "must be 'hold', 'linear' or 'quadratic' (got '" + name + "')");
}

// The sampling options from the keywords, each read by its Python name. The
// step counts must fit an int, as in C++.
UnifiedObserverOptions options_of(nb::handle substeps, nb::handle max_step, nb::handle max_substeps, nb::handle input,
                                  nb::handle output, nb::handle excitation_window, std::string_view who) {
  const auto step_count = [who](nb::handle obj, std::string_view name) {
    const Index value = integer_argument(obj, who, name);
    adaptobs::require(value >= 1 && value <= std::numeric_limits<int>::max(), who, name,
                      "must be at least 1 and fit an int");
    return static_cast<int>(value);
  };
  return {.sampling = {.substeps = step_count(substeps, "substeps"),
                       .max_step = real_scalar(max_step, who, "max_step"),
                       .max_substeps = step_count(max_substeps, "max_substeps"),
                       .input = reconstruction_of(input, who, "input"),
                       .output = reconstruction_of(output, who, "output")},
          .excitation_window = integer_argument(excitation_window, who, "excitation_window")};
}

UnifiedObserverOptions options_of(const Snapshot<double>& s) {
  return {.sampling = {.substeps = static_cast<int>(integer(s, "integrator.substeps")),
                       .max_step = scalar(s, "integrator.max_step"),
                       .max_substeps = static_cast<int>(integer(s, "integrator.max_substeps")),
                       .input = static_cast<SignalReconstruction>(integer(s, "integrator.input")),
                       .output = static_cast<SignalReconstruction>(integer(s, "integrator.output"))},
          .excitation_window = s.find_integer("excitation_window") ? integer(s, "excitation_window") : 0};
}

// The model of a snapshot's "model." fields, around the pickled Φ and matrices_at.
PythonContinuousModel model_of(const Snapshot<double>& s, nb::handle phi, nb::handle matrices_at) {
  if (integer(s, "model.time_invariant") != 0)
    return PythonContinuousModel(ContinuousModel(field(s, "model.A"), field(s, "model.B"), field(s, "model.C"),
                                                 regressor_of(phi), integer(s, "model.np")));
  return PythonContinuousModel(nb::borrow(matrices_at), regressor_of(phi, "ContinuousLtvModel"), integer(s, "model.np"),
                               "restore");
}

PythonContinuousModel continuous_model(nb::handle model, std::string_view who) {
  ContinuousModel* lti = nullptr;
  if (nb::try_cast<ContinuousModel*>(model, lti, false) && lti) return PythonContinuousModel(*lti);
  return object_argument<PythonContinuousModel>(model, who, "model",
                                                "an adaptobs.ContinuousLtiModel or ContinuousLtvModel");
}

const Transform& static_transform(nb::handle transform, std::string_view who) {
  return object_argument<Transform>(transform, who, "transform", "an adaptobs.StaticTransform");
}

Transform transform_of(const Snapshot<double>& s) {
  return Transform(field(s, "algorithm.static_transform.T"), field(s, "algorithm.static_transform.K"));
}

// The references a ContinuousLtiModel holds, for the garbage collector (collected.hpp).
int traverse_python(const ContinuousModel& model, visitproc visit, void* arg) {
  Py_VISIT(model.regressor_function().source.ptr());
  return 0;
}
void clear_python(const ContinuousModel& model) {
  auto& phi = const_cast<PythonRegressor&>(model.regressor_function());  // as PythonContinuousModel's
  phi.source = nb::none();
  phi.callable = false;
}

/// The Python object of a continuous-time observer, with a sample sized once.
template <class Observer>
struct ContinuousBound {
  Observer observer;
  ContinuousSample<Dims> sample;
  OutputMask<Dims> mask;
  UseFlag in_use;

  explicit ContinuousBound(Observer o) : observer(std::move(o)) {
    const Sizes s = observer.sizes();
    sample.u.setZero(s.nu);
    sample.y.setZero(s.ny);
    mask.setConstant(s.ny, true);
  }
};

// One sample (t, u, y), with the midpoint signals when both are given.
template <class Observer>
UpdateStatus continuous_step(ContinuousBound<Observer>& self, double t, nb::handle u, nb::handle y, nb::handle u_mid,
                             nb::handle y_mid, nb::handle present) {
  const std::string who = std::string(Observer::name) + ".update";
  const InUse guard(self.in_use.flag, who);
  const Sizes s = self.observer.sizes();
  read_vector(u, s.nu, who, "u", self.sample.u);
  read_vector(y, s.ny, who, "y", self.sample.y);
  self.sample.t = t;
  if (u_mid.is_none() != y_mid.is_none())
    adaptobs::fail_argument(who, u_mid.is_none() ? "u_mid" : "y_mid", "must be given with the other midpoint signal");
  if (u_mid.is_none()) {
    if (self.observer.started() && self.observer.sampling_options().needs_midpoint())
      adaptobs::fail_argument(who, "u_mid",
                              "must be given, with y_mid: a 'quadratic' reconstruction needs the signals "
                              "at the midpoint of every interval");
    self.sample.midpoint.reset();
  } else {
    if (!self.sample.midpoint) self.sample.midpoint.emplace();
    auto& mid = *self.sample.midpoint;
    read_vector(u_mid, s.nu, who, "u_mid", mid.u);
    read_vector(y_mid, s.ny, who, "y_mid", mid.y);
  }
  // The output error of the new sample reads C(t_k) after the integration is
  // committed: with a Python function of the model, which may raise there, the
  // observer is kept as it was.
  const bool masked = !present.is_none();
  if (masked) read_mask(present, s.ny, who, self.mask);
  const auto update = [&] {
    return masked ? self.observer.update(self.sample, self.mask) : self.observer.update(self.sample);
  };
  const PythonContinuousModel& model = self.observer.model();
  if (model.is_time_invariant() && !model.regressor_function().callable) return update();
  UpdateStatus status{};
  all_or_nothing(self.observer, [&] { status = update(); });
  return status;
}

template <class Observer>
RunResult continuous_run(ContinuousBound<Observer>& self, nb::handle times, nb::handle u, nb::handle y,
                         nb::handle u_mid, nb::handle y_mid, nb::handle present) {
  const std::string who = std::string(Observer::name) + ".run";
  const InUse guard(self.in_use.flag, who);
  const Sizes s = self.observer.sizes();
  const Array t_array = real_array(times, who, "t");
  if (t_array.ndim() != 1) fail_dimensions(who, "t", "a vector of sample times", shape_of(t_array));
  const Index samples = static_cast<Index>(t_array.shape(0));
  const Rows t_rows = rows(t_array, samples, 1, who, "t");
  const Rows inputs = rows(u, samples, s.nu, who, "U");
  const Rows outputs = rows(y, samples, s.ny, who, "Y");
  if (u_mid.is_none() != y_mid.is_none())
    adaptobs::fail_argument(who, u_mid.is_none() ? "U_mid" : "Y_mid", "must be given with the other midpoint signal");
  const bool midpoints = !u_mid.is_none();
  if (!midpoints && self.observer.sampling_options().needs_midpoint() && (samples > 1 || self.observer.started()))
    adaptobs::fail_argument(who, "U_mid",
                            "must be given, with Y_mid: a 'quadratic' reconstruction needs the signals at "
                            "the midpoint of every interval");
  const Rows mid_inputs = midpoints ? rows(u_mid, samples, s.nu, who, "U_mid") : Rows{};
  const Rows mid_outputs = midpoints ? rows(y_mid, samples, s.ny, who, "Y_mid") : Rows{};
  const Masks mask = masks(present, samples, s.ny, who);

  const auto n = static_cast<std::size_t>(samples);
  OutputArray x({n, static_cast<std::size_t>(s.nx)});
  OutputArray theta({n, static_cast<std::size_t>(s.np)});
  OutputArray error({n, static_cast<std::size_t>(s.ny)});
  OutputArray excitation({n, 1});
  StatusArray status(n);
  // A Python function of the model that raises, or returns matrices of another
  // size, stops the run: the observer is then put back as it was before it.
  all_or_nothing(self.observer, [&] {
    nb::gil_scoped_release release;  // a callable regressor takes the GIL back for its calls
    auto& sample = self.sample;
    for (Index k = 0; k < samples; ++k) {
      sample.t = t_rows.row(k)(0);
      sample.u = inputs.row(k);
      sample.y = outputs.row(k);
      // A sample with no accepted one before it ends no interval, hence has no midpoint.
      if (midpoints && self.observer.started()) {
        if (!sample.midpoint) sample.midpoint.emplace();
        sample.midpoint->u = mid_inputs.row(k);
        sample.midpoint->y = mid_outputs.row(k);
      } else {
        sample.midpoint.reset();
      }
      status.data[k] = static_cast<std::int8_t>(mask.update(self.observer, sample, k, self.mask));
      Eigen::Map<Eigen::VectorXd>(x.data + k * s.nx, s.nx) = self.observer.state();
      Eigen::Map<Eigen::VectorXd>(theta.data + k * s.np, s.np) = self.observer.parameters();
      Eigen::Map<Eigen::VectorXd>(error.data + k * s.ny, s.ny) = self.observer.output_error();
      excitation.data[k] = excitation_of(self.observer);
    }
  });
  RunResult result;
  result.state = nb::cast(x.array);
  result.parameters = nb::cast(theta.array);
  result.output_error = nb::cast(error.array);
  result.status = nb::cast(status.array);
  result.diagnostics["excitation_level"] = nb::cast(excitation.array).attr("reshape")(samples);
  return result;
}

/// What both continuous-time observers offer; `construct` builds one of a
/// snapshot's configuration around the pickled regressor.
template <class Observer, class Construct>
void bind_continuous_observer(nb::class_<ContinuousBound<Observer>>& cls, Construct construct) {
  using B = ContinuousBound<Observer>;
  cls.def("update", &continuous_step<Observer>, nb::arg("t"), nb::arg("u"), nb::arg("y"),
          nb::arg("u_mid").none() = nb::none(), nb::arg("y_mid").none() = nb::none(),
          nb::arg("present").none() = nb::none(),
          "The sample (u, y) measured at time t: integrates the observer from the previous sample with RK4,\n"
          "u and y rebuilt between samples as the `input` and `output` options say (u_mid, y_mid: the\n"
          "signals at the midpoint of the interval, which 'quadratic' needs). The first sample only sets\n"
          "the time origin. A rejected sample changes nothing. `present` (ny booleans) marks the output\n"
          "channels measured at t; the others are ignored, and over an interval in which a channel is not\n"
          "measured the observer predicts it (none: the open-loop time update, theta constant).")
      .def("run", &continuous_run<Observer>, nb::arg("t"), nb::arg("U"), nb::arg("Y"),
           nb::arg("U_mid").none() = nb::none(), nb::arg("Y_mid").none() = nb::none(),
           nb::arg("present").none() = nb::none(),
           "Every sample: t (N,), U (N x nu), Y (N x ny), and the midpoint signals of the interval ending\n"
           "at each sample (unused where no sample was accepted before, as row 0 of a new observer), in C++\n"
           "with the GIL released (a callable regressor takes it back for its calls); `present` is N x ny\n"
           "booleans, as in `update`. Returns a RunResult; diagnostics: excitation_level. An exception from\n"
           "a Python function of the model stops the run and leaves the observer as it was before it.")
      .def(
          "reset",
          [](B& self, nb::handle eta0, nb::handle theta0) {
            const std::string who = std::string(Observer::name) + ".reset";
            const InUse guard(self.in_use.flag, who);
            self.observer.reset(vector(eta0, who, "eta0"), vector(theta0, who, "theta0"));
          },
          nb::arg("eta0"), nb::arg("theta0"),
          "Restarts from the initial estimates; the next sample sets the time origin.")
      .def_prop_ro(
          "state", [](const B& self) { return Eigen::VectorXd(self.observer.state()); },
          "State estimate eta_hat in the original coordinates.")
      .def_prop_ro("parameters", [](const B& self) { return Eigen::VectorXd(self.observer.parameters()); })
      .def_prop_ro("output_error", [](const B& self) { return Eigen::VectorXd(self.observer.output_error()); })
      .def_prop_ro(
          "time", [](const B& self) { return self.observer.time(); }, "time of the last accepted sample")
      .def_prop_ro(
          "health", [](const B& self) { return self.observer.health(); },
          "HealthReport: healthy, or diverged from the first of consecutive samples refused because the\n"
          "integration overflows, with the remedy.")
      .def_prop_ro(
          "internal_state", [](const B& self) { return Eigen::VectorXd(self.observer.internal_state()); },
          "(z_hat, vec Xi, theta_hat), what the RK4 steps integrate")
      .def_prop_ro("excitation_level",
                   [](const B& self) {
                     const double level = excitation_of(self.observer);
                     return std::isnan(level) ? std::nullopt : std::optional<double>(level);
                   })
      .def_prop_ro(
          "sizes", [](const B& self) { return sizes_tuple(self.observer.sizes()); }, "(nx, nu, ny, np).")
      .def(
          "resynchronize",
          [](B& self) {
            const InUse guard(self.in_use.flag, "resynchronize");
            self.observer.resynchronize();
          },
          "Resumes from the next sample with the estimates kept (after interval_too_long).")
      .def(
          "snapshot", [](const B& self) { return to_dict(adaptobs::snapshot(self.observer)); },
          "The whole internal state as a dict of arrays; the regressor Phi is the model's code, not part of it.")
      .def(
          "restore",
          [](B& self, nb::handle state) {
            const InUse guard(self.in_use.flag, "restore");
            adaptobs::restore(self.observer, from_dict(state));
          },
          nb::arg("state"))
      .def("__copy__", [](const B& self) { return B(self.observer); })
      .def(
          "__deepcopy__", [](const B& self, nb::handle) { return B(self.observer); }, nb::arg("memo"))
      .def("__getstate__",
           [](const B& self) {
             const PythonContinuousModel& model = self.observer.model();
             return nb::make_tuple(to_dict(adaptobs::snapshot(self.observer)), model.regressor_function().source,
                                   model.is_time_invariant() ? nb::none() : model.matrices_function());
           })
      .def("__setstate__", [construct](B& self, const std::tuple<nb::object, nb::object, nb::object>& state) {
        const Snapshot<double> s = from_dict(std::get<0>(state));
        detail::require_snapshot_type<Observer>(s);
        Observer observer = construct(s, model_of(s, std::get<1>(state), std::get<2>(state)));
        adaptobs::restore(observer, s);
        new (&self) B(std::move(observer));
      });
}

}  // namespace

void bind_continuous_observers(nb::module_& m) {
  nb::class_<ContinuousModel>(
      m, "ContinuousLtiModel", nb::type_slots(CollectedReferences<ContinuousModel, ModelItself>::slots),
      "Continuous-time model d eta/dt = A eta + B u + Phi theta, y = C eta (Zhang 2005, eq. (1)).\n"
      "Phi is a constant nx x np array, or a callable Phi(t) or Phi(t, u, y) returning one;\n"
      "a callable is called from C++ at every Runge-Kutta stage (with the GIL), which costs\n"
      "about a microsecond a call. np defaults to the columns of a constant Phi.")
      .def(
          "__init__",
          [](ContinuousModel* self, nb::handle A, nb::handle B, nb::handle C, nb::handle Phi, nb::handle np) {
            constexpr std::string_view who = "ContinuousLtiModel";
            PythonRegressor phi = regressor_of(Phi);
            if (np.is_none() && phi.callable) adaptobs::fail_argument(who, "np", "is required when Phi is a callable");
            const Index parameters = np.is_none() ? phi.value.cols() : integer_argument(np, who, "np");
            new (self) ContinuousModel(matrix(A, who, "A"), matrix(B, who, "B"), matrix(C, who, "C"), std::move(phi),
                                       parameters);
          },
          nb::arg("A"), nb::arg("B"), nb::arg("C"), nb::arg("Phi"), nb::arg("np").none() = nb::none())
      .def_prop_ro("A", [](const ContinuousModel& self) { return Eigen::MatrixXd(self.system().A); })
      .def_prop_ro("B", [](const ContinuousModel& self) { return Eigen::MatrixXd(self.system().B); })
      .def_prop_ro("C", [](const ContinuousModel& self) { return Eigen::MatrixXd(self.system().C); })
      .def_prop_ro(
          "Phi", [](const ContinuousModel& self) { return self.regressor_function().source; },
          "the regressor as given: the array or the callable");

  nb::class_<PythonContinuousModel>(
      m, "ContinuousLtvModel", nb::type_slots(CollectedReferences<PythonContinuousModel, ModelItself>::slots),
      "Time-varying continuous model d eta/dt = A(t) eta + B(t) u + Phi theta, y = C(t) eta (Zhang 2005,\n"
      "eq. (1)). matrices_at(t) returns the tuple (A(t), B(t), C(t)); it is called from C++ (with the GIL)\n"
      "at every Runge-Kutta stage, about a microsecond a call, and its sizes at t = 0 are the model's.\n"
      "Phi as for ContinuousLtiModel. Pickled with its functions, which must be picklable (module level).")
      .def(
          "__init__",
          [](PythonContinuousModel* self, nb::handle matrices_at, nb::handle Phi, nb::handle np) {
            constexpr std::string_view who = "ContinuousLtvModel";
            PythonRegressor phi = regressor_of(Phi, who);
            if (np.is_none() && phi.callable) adaptobs::fail_argument(who, "np", "is required when Phi is a callable");
            const Index parameters = np.is_none() ? phi.value.cols() : integer_argument(np, who, "np");
            new (self) PythonContinuousModel(nb::borrow(matrices_at), std::move(phi), parameters, who);
          },
          nb::arg("matrices_at"), nb::arg("Phi"), nb::arg("np").none() = nb::none())
      .def(
          "at",
          [](const PythonContinuousModel& self, double t) {
            const ContinuousSystem<Dims>& s = self.at(t);
            return nb::make_tuple(Eigen::MatrixXd(s.A), Eigen::MatrixXd(s.B), Eigen::MatrixXd(s.C));
          },
          nb::arg("t"), "(A(t), B(t), C(t)).")
      .def_prop_ro("matrices_at", [](const PythonContinuousModel& self) { return self.matrices_function(); })
      .def_prop_ro(
          "Phi", [](const PythonContinuousModel& self) { return self.regressor_function().source; },
          "the regressor as given: the array or the callable")
      .def_prop_ro(
          "sizes", [](const PythonContinuousModel& self) { return sizes_tuple(self.sizes()); }, "(nx, nu, ny, np).")
      .def("__getstate__",
           [](const PythonContinuousModel& self) {
             return nb::make_tuple(self.matrices_function(), self.regressor_function().source, self.sizes().np);
           })
      .def("__setstate__", [](PythonContinuousModel& self, const std::tuple<nb::object, nb::object, Index>& state) {
        new (&self) PythonContinuousModel(std::get<0>(state), regressor_of(std::get<1>(state), "ContinuousLtvModel"),
                                          std::get<2>(state), "ContinuousLtvModel");
      });

  nb::class_<Transform>(m, "StaticTransform",
                        "Coordinate change x = T eta with output injection K (Zhang 2005, eq. (2)).")
      .def(
          "__init__",
          [](Transform* self, nb::handle T, nb::handle K) {
            new (self) Transform(matrix(T, "StaticTransform", "T"), matrix(K, "StaticTransform", "K"));
          },
          nb::arg("T"), nb::arg("K"))
      .def_prop_ro("T", [](const Transform& t) { return Eigen::MatrixXd(t.T()); })
      .def_prop_ro("K", [](const Transform& t) { return Eigen::MatrixXd(t.K()); })
      .def(
          "apply",
          [](const Transform& t, nb::handle A, nb::handle B, nb::handle C) {
            constexpr std::string_view who = "StaticTransform.apply";
            const ContinuousSystem<Dims> system{matrix(A, who, "A"), matrix(B, who, "B"), matrix(C, who, "C")};
            adaptobs::validate_state_space(system, who);
            adaptobs::require_shape(system.A, t.T().rows(), t.T().rows(), who, "A");
            const TransformedSystem<Dims> so = t.apply(system);
            nb::dict d;
            d["Ao"] = Eigen::MatrixXd(so.Ao);
            d["Co"] = Eigen::MatrixXd(so.Co);
            d["TB"] = Eigen::MatrixXd(so.TB);
            d["K"] = Eigen::MatrixXd(so.K);
            return d;
          },
          nb::arg("A"), nb::arg("B"), nb::arg("C"),
          "The transformed system: Ao = T A T^-1 - K Co, Co = C T^-1, T B, K.");

  m.def(
      "bastin_gevers_form",
      [](nb::handle A, nb::handle c, nb::handle zeros) {
        constexpr std::string_view who = "bastin_gevers_form";
        return bastin_gevers_form<Dims>(matrix(A, who, "A"), matrix(c, who, "c"),
                                        Polynomial<double>(vector(zeros, who, "zeros")));
      },
      nb::arg("A"), nb::arg("c"), nb::arg("zeros"),
      "The transform to the form (5) of Algorithm 1 (Zhang 2005) with det(sI - A22) = zeros (monic,\n"
      "highest power first, degree n - 1, Hurwitz).");
  m.def(
      "besancon_form",
      [](nb::handle A, nb::handle C) {
        constexpr std::string_view who = "besancon_form";
        return besancon_form<Dims>(matrix(A, who, "A"), matrix(C, who, "C"));
      },
      nb::arg("A"), nb::arg("C"),
      "The transform to the form (8) of Algorithm 3 for a constant (A, C) with m outputs:\n"
      "C_o = [I 0], A_o = [[0, A12], [0, A22]].");
  m.def(
      "marino_tomei_form",
      [](nb::handle A, nb::handle c) {
        constexpr std::string_view who = "marino_tomei_form";
        return marino_tomei_form<Dims>(matrix(A, who, "A"), matrix(c, who, "c"));
      },
      nb::arg("A"), nb::arg("c"), "The transform to the form (7) of Algorithm 2: c_o = e_1^T, A_o a shift.");
  m.def(
      "spr_injection_gain",
      [](nb::handle A, nb::handle c, nb::handle gamma, nb::handle lambda) {
        constexpr std::string_view who = "spr_injection_gain";
        return Eigen::VectorXd(spr_injection_gain(matrix(A, who, "A"), matrix(c, who, "c"),
                                                  Eigen::VectorXd(vector(gamma, who, "gamma")),
                                                  real_scalar(lambda, who, "lambda_")));
      },
      nb::arg("A"), nb::arg("c"), nb::arg("gamma"), nb::arg("lambda_"),
      "The gain k making c (sI - A + k c)^-1 gamma = c gamma / (s + lambda_), strictly positive real.");

  constexpr const char* sampling_doc =
      "\nSampling options: RK4 `substeps` per interval, `max_step` (0: learned from the first interval),\n"
      "`max_substeps`, and how u (`input`) and y (`output`) are rebuilt between samples: 'hold',\n"
      "'linear' or 'quadratic' (which needs the midpoint signals). excitation_window > 0 monitors\n"
      "the excitation.";

  auto bastin_gevers = nb::class_<ContinuousBound<BastinGeversPy>>(
      m, "BastinGeversObserver",
      nb::type_slots(CollectedReferences<ContinuousBound<BastinGeversPy>, ModelOfObserver>::slots),
      (std::string("Bastin-Gevers adaptive observer, continuous time, SISO: Algorithm 1 of the unified\n"
                   "formulation (Zhang 2005, section III-A, eq. (2)-(6)). `transform` gives the form (5)\n"
                   "(bastin_gevers_form), k the output injection (spr_injection_gain with gamma = e1), gamma\n"
                   "the adaptation gain (np x np).") +
       sampling_doc)
          .c_str());
  bastin_gevers.def(
      "__init__",
      [](ContinuousBound<BastinGeversPy>* self, nb::handle model, nb::handle transform, nb::handle k, nb::handle gamma,
         nb::handle eta0, nb::handle theta0, nb::handle substeps, nb::handle max_step, nb::handle max_substeps,
         nb::handle input, nb::handle output, nb::handle excitation_window) {
        constexpr std::string_view who = "BastinGeversObserver";
        new (self) ContinuousBound<BastinGeversPy>(make_bastin_gevers_observer(
            continuous_model(model, who), static_transform(transform, who), matrix(k, who, "k"),
            matrix(gamma, who, "gamma"), vector(eta0, who, "eta0"), vector(theta0, who, "theta0"),
            options_of(substeps, max_step, max_substeps, input, output, excitation_window, who)));
      },
      nb::arg("model"), nb::arg("transform"), nb::arg("k"), nb::arg("gamma"), nb::arg("eta0"), nb::arg("theta0"),
      nb::kw_only(), nb::arg("substeps") = 1, nb::arg("max_step") = 0.0, nb::arg("max_substeps") = 1'000'000,
      nb::arg("input") = "hold", nb::arg("output") = "linear", nb::arg("excitation_window") = 0);
  bind_continuous_observer(bastin_gevers, [](const Snapshot<double>& s, PythonContinuousModel model) {
    return make_bastin_gevers_observer(std::move(model), transform_of(s), field(s, "algorithm.k"),
                                       field(s, "law.gamma"), field(s, "eta"), field(s, "theta"), options_of(s));
  });

  auto marino_tomei = nb::class_<ContinuousBound<MarinoTomeiPy>>(
      m, "MarinoTomeiObserver",
      nb::type_slots(CollectedReferences<ContinuousBound<MarinoTomeiPy>, ModelOfObserver>::slots),
      (std::string("Marino-Tomei adaptive observer, continuous time, SISO: Algorithm 2 of the unified\n"
                   "formulation (Zhang 2005, section III-B, eq. (2)-(4), (7)). `transform` gives the form (7)\n"
                   "(marino_tomei_form), gamma = (1, gamma_2, ..., gamma_n) a Hurwitz polynomial, k the output\n"
                   "injection (spr_injection_gain with that gamma), adaptation_gain np x np.") +
       sampling_doc)
          .c_str());
  marino_tomei.def(
      "__init__",
      [](ContinuousBound<MarinoTomeiPy>* self, nb::handle model, nb::handle transform, nb::handle gamma, nb::handle k,
         nb::handle adaptation_gain, nb::handle eta0, nb::handle theta0, nb::handle substeps, nb::handle max_step,
         nb::handle max_substeps, nb::handle input, nb::handle output, nb::handle excitation_window) {
        constexpr std::string_view who = "MarinoTomeiObserver";
        new (self) ContinuousBound<MarinoTomeiPy>(make_marino_tomei_observer(
            continuous_model(model, who), static_transform(transform, who), vector(gamma, who, "gamma"),
            matrix(k, who, "k"), matrix(adaptation_gain, who, "adaptation_gain"), vector(eta0, who, "eta0"),
            vector(theta0, who, "theta0"),
            options_of(substeps, max_step, max_substeps, input, output, excitation_window, who)));
      },
      nb::arg("model"), nb::arg("transform"), nb::arg("gamma"), nb::arg("k"), nb::arg("adaptation_gain"),
      nb::arg("eta0"), nb::arg("theta0"), nb::kw_only(), nb::arg("substeps") = 1, nb::arg("max_step") = 0.0,
      nb::arg("max_substeps") = 1'000'000, nb::arg("input") = "hold", nb::arg("output") = "linear",
      nb::arg("excitation_window") = 0);
  bind_continuous_observer(marino_tomei, [](const Snapshot<double>& s, PythonContinuousModel model) {
    return make_marino_tomei_observer(std::move(model), transform_of(s), field(s, "algorithm.gamma"),
                                      field(s, "algorithm.k"), field(s, "law.gamma"), field(s, "eta"),
                                      field(s, "theta"), options_of(s));
  });

  auto besancon = nb::class_<ContinuousBound<BesanconPy>>(
      m, "BesanconObserver", nb::type_slots(CollectedReferences<ContinuousBound<BesanconPy>, ModelOfObserver>::slots),
      (std::string("Besancon adaptive observer, continuous time, MIMO: Algorithm 3 of the unified formulation\n"
                   "(Zhang 2005, section III-C, eq. (2)-(4), (8)-(9)). `transform` gives the form (8)\n"
                   "(besancon_form), K1 (m x m) the gain of the measured block, gamma the adaptation gain.") +
       sampling_doc)
          .c_str());
  besancon.def(
      "__init__",
      [](ContinuousBound<BesanconPy>* self, nb::handle model, nb::handle transform, nb::handle K1, nb::handle gamma,
         nb::handle eta0, nb::handle theta0, nb::handle substeps, nb::handle max_step, nb::handle max_substeps,
         nb::handle input, nb::handle output, nb::handle excitation_window) {
        constexpr std::string_view who = "BesanconObserver";
        new (self) ContinuousBound<BesanconPy>(make_besancon_observer(
            continuous_model(model, who), static_transform(transform, who), matrix(K1, who, "K1"),
            matrix(gamma, who, "gamma"), vector(eta0, who, "eta0"), vector(theta0, who, "theta0"),
            options_of(substeps, max_step, max_substeps, input, output, excitation_window, who)));
      },
      nb::arg("model"), nb::arg("transform"), nb::arg("K1"), nb::arg("gamma"), nb::arg("eta0"), nb::arg("theta0"),
      nb::kw_only(), nb::arg("substeps") = 1, nb::arg("max_step") = 0.0, nb::arg("max_substeps") = 1'000'000,
      nb::arg("input") = "hold", nb::arg("output") = "linear", nb::arg("excitation_window") = 0);
  bind_continuous_observer(besancon, [](const Snapshot<double>& s, PythonContinuousModel model) {
    return make_besancon_observer(std::move(model), transform_of(s), field(s, "algorithm.K1"), field(s, "law.gamma"),
                                  field(s, "eta"), field(s, "theta"), options_of(s));
  });

  auto zhang = nb::class_<ContinuousBound<ZhangPy>>(
      m, "ZhangContinuousObserver",
      nb::type_slots(CollectedReferences<ContinuousBound<ZhangPy>, ModelOfObserver>::slots),
      (std::string("Zhang's adaptive observer, continuous time, MIMO: Algorithm 4 of the unified formulation\n"
                   "(Zhang 2005, section III-D, eq. (10)-(15)). K makes A - K C stable (kalman_bucy_gain, for\n"
                   "instance), gamma is the adaptation gain; no coordinate change.") +
       sampling_doc)
          .c_str());
  zhang.def(
      "__init__",
      [](ContinuousBound<ZhangPy>* self, nb::handle model, nb::handle K, nb::handle gamma, nb::handle eta0,
         nb::handle theta0, nb::handle substeps, nb::handle max_step, nb::handle max_substeps, nb::handle input,
         nb::handle output, nb::handle excitation_window) {
        constexpr std::string_view who = "ZhangContinuousObserver";
        new (self) ContinuousBound<ZhangPy>(make_zhang_continuous_observer(
            continuous_model(model, who), matrix(K, who, "K"), matrix(gamma, who, "gamma"), vector(eta0, who, "eta0"),
            vector(theta0, who, "theta0"),
            options_of(substeps, max_step, max_substeps, input, output, excitation_window, who)));
      },
      nb::arg("model"), nb::arg("K"), nb::arg("gamma"), nb::arg("eta0"), nb::arg("theta0"), nb::kw_only(),
      nb::arg("substeps") = 1, nb::arg("max_step") = 0.0, nb::arg("max_substeps") = 1'000'000,
      nb::arg("input") = "hold", nb::arg("output") = "linear", nb::arg("excitation_window") = 0);
  bind_continuous_observer(zhang, [](const Snapshot<double>& s, PythonContinuousModel model) {
    return make_zhang_continuous_observer(std::move(model), field(s, "algorithm.static_transform.K"),
                                          field(s, "law.gamma"), field(s, "eta"), field(s, "theta"), options_of(s));
  });

  auto kalman_bucy = nb::class_<ContinuousBound<KalmanBucyPy>>(
      m, "AugmentedKalmanBucyFilter",
      nb::type_slots(CollectedReferences<ContinuousBound<KalmanBucyPy>, ModelOfObserver>::slots),
      "Baseline: the Kalman-Bucy filter on the augmented state [x; theta] (Zhang 2005, appendix), its\n"
      "Riccati equation integrated with the estimates; a step that would leave P indefinite is rejected\n"
      "(indefinite_covariance). P0 and Q are (nx + np) x (nx + np), R is ny x ny. Sampling options as for\n"
      "the observers (no excitation monitor).");
  kalman_bucy.def(
      "__init__",
      [](ContinuousBound<KalmanBucyPy>* self, nb::handle model, nb::handle eta0, nb::handle theta0, nb::handle P0,
         nb::handle Q, nb::handle R, nb::handle substeps, nb::handle max_step, nb::handle max_substeps,
         nb::handle input, nb::handle output) {
        constexpr std::string_view who = "AugmentedKalmanBucyFilter";
        const UnifiedObserverOptions options =
            options_of(substeps, max_step, max_substeps, input, output, nb::int_(0), who);
        new (self) ContinuousBound<KalmanBucyPy>(
            KalmanBucyPy(continuous_model(model, who), vector(eta0, who, "eta0"), vector(theta0, who, "theta0"),
                         {matrix(P0, who, "P0"), matrix(Q, who, "Q"), matrix(R, who, "R")}, options.sampling));
      },
      nb::arg("model"), nb::arg("eta0"), nb::arg("theta0"), nb::arg("P0"), nb::arg("Q"), nb::arg("R"), nb::kw_only(),
      nb::arg("substeps") = 1, nb::arg("max_step") = 0.0, nb::arg("max_substeps") = 1'000'000,
      nb::arg("input") = "hold", nb::arg("output") = "linear");
  kalman_bucy.def_prop_ro(
      "covariance", [](const ContinuousBound<KalmanBucyPy>& b) { return Eigen::MatrixXd(b.observer.covariance()); },
      "P of [x_hat; theta_hat]");
  bind_continuous_observer(kalman_bucy, [](const Snapshot<double>& s, PythonContinuousModel model) {
    return KalmanBucyPy(std::move(model), field(s, "eta"), field(s, "theta"),
                        {field(s, "P0"), field(s, "Q"), field(s, "R")}, options_of(s).sampling);
  });
}

}  // namespace adaptobs::python
