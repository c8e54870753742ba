#pragma once
// What every discrete-time observer offers in Python, written once: the step
// API `update`, the batch API `run` (a loop in C++ with the GIL released),
// `reset`, the common properties, `snapshot`/`restore`, copy and pickle.
// Each observer's own binding adds its constructor and its diagnostics.

#include "arrays.hpp"
#include "discrete_models.hpp"
#include "snapshot_dict.hpp"

#include <adaptobs/core/discrete_model.hpp>
#include <adaptobs/core/snapshot.hpp>
#include <adaptobs/core/status.hpp>

#include <nanobind/eigen/dense.h>
#include <nanobind/nanobind.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/tuple.h>

#include <array>
#include <concepts>
#include <cstdint>
#include <limits>
#include <string>
#include <tuple>
#include <utility>

namespace adaptobs::python {

/// An observer whose samples carry a regressor Ψ_k (Guyader–Zhang, Guiro, the
/// augmented Kalman filter); the others take (u_k, y_k) alone (Dey–Bhasin, Suzuki).
template <class Observer>
constexpr bool takes_regressor = requires(typename Observer::Sample& sample) { sample.Psi; };

/// An observer whose samples may carry a known input term f_k (Guyader & Zhang
/// 2003, Remark 1: `DiscreteSample::f`).
template <class Observer>
constexpr bool takes_known_input = requires(typename Observer::Sample& sample) { sample.f; };

/// The Python object of an observer: the C++ observer and a sample sized once,
/// into which `update` copies its arguments (no allocation per call).
template <class Observer>
struct Bound {
  Observer observer;
  typename Observer::Sample sample;
  OutputMask<Dims> mask;
  UseFlag in_use;

  explicit Bound(Observer o) : observer(std::move(o)) {
    const Sizes s = observer.sizes();
    sample.u.setZero(s.nu);
    sample.y.setZero(s.ny);
    if constexpr (takes_regressor<Observer>) sample.Psi.setZero(s.nx, s.np);
    mask.setConstant(s.ny, true);
  }
};

/// What an observer reports besides its estimates, per sample of `run`: names,
/// and the values after each update. Observers without any have none.
template <class Observer>
struct Diagnostics {
  static constexpr std::array<const char*, 0> names{};
  static void record(const Observer&, double*) {}
};

/// The rows of a batch argument: sample k of an N × n array (1-D of length N
/// when n is 1); None only when n is 0.
struct Rows {
  Array keep;
  const double* data = nullptr;
  Index row_stride = 0;
  Index col_stride = 1;
  Index n = 0;

  [[nodiscard]] auto row(Index k) const {
    return Eigen::Map<const Eigen::VectorXd, 0, Eigen::InnerStride<>>(data + k * row_stride, n,
                                                                      Eigen::InnerStride<>(col_stride));
  }
};

inline Rows rows(const Array& array, Index samples, Index n, std::string_view who, std::string_view name) {
  Rows r;
  r.n = n;
  r.keep = array;
  const bool one_d = array.ndim() == 1 && n == 1;
  const bool fits = one_d || (array.ndim() == 2 && static_cast<Index>(array.shape(1)) == n);
  if (!fits || static_cast<Index>(array.shape(0)) != samples)
    fail_dimensions(who, name,
                    std::to_string(samples) + "x" + std::to_string(n) + " (samples x " + std::to_string(n) + ")",
                    shape_of(array));
  r.data = array.data();
  r.row_stride = static_cast<Index>(array.stride(0));
  r.col_stride = one_d ? 1 : static_cast<Index>(array.stride(1));
  return r;
}

inline Rows rows(nb::handle obj, Index samples, Index n, std::string_view who, std::string_view name) {
  if (!obj.is_none()) return rows(real_array(obj, who, name), samples, n, who, name);
  if (n != 0) adaptobs::fail_argument(who, name, "is required: the model has " + std::to_string(n) + " of them");
  Rows r;
  return r;
}

/// The regressor of each sample: an N × nx × np array, or one nx × np matrix for
/// every sample; None only when np is 0.
struct Regressors {
  Array keep;
  const double* data = nullptr;
  Index sample_stride = 0;
  Index row_stride = 0;
  Index col_stride = 0;
  Index nx = 0;
  Index np = 0;

  [[nodiscard]] auto at(Index k) const {
    return Eigen::Map<const Eigen::MatrixXd, 0, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>>(
        data + k * sample_stride, nx, np, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>(col_stride, row_stride));
  }
};

inline Regressors regressors(nb::handle obj, Index samples, Index nx, Index np, std::string_view who) {
  Regressors r;
  r.nx = nx;
  r.np = np;
  if (obj.is_none()) {
    if (np != 0)
      adaptobs::fail_argument(who, "Psi", "is required: the model has " + std::to_string(np) + " parameters");
    return r;
  }
  r.keep = real_array(obj, who, "Psi");
  const auto shape = shape_of(r.keep);
  const auto n = [](Index v) { return static_cast<std::size_t>(v); };
  if (r.keep.ndim() == 3 && shape[0] == n(samples) && shape[1] == n(nx) && shape[2] == n(np)) {
    r.sample_stride = static_cast<Index>(r.keep.stride(0));
    r.row_stride = static_cast<Index>(r.keep.stride(1));
    r.col_stride = static_cast<Index>(r.keep.stride(2));
  } else if (r.keep.ndim() == 2 && shape[0] == n(nx) && shape[1] == n(np)) {
    r.row_stride = static_cast<Index>(r.keep.stride(0));
    r.col_stride = static_cast<Index>(r.keep.stride(1));
  } else {
    fail_dimensions(who, "Psi",
                    "(" + std::to_string(samples) + ", " + std::to_string(nx) + ", " + std::to_string(np) + ") or " +
                        std::to_string(nx) + "x" + std::to_string(np),
                    shape);
  }
  r.data = r.keep.data();
  return r;
}

/// The output channels measured at each sample: an N × ny boolean array, or None (all).
struct Masks {
  BoolArray keep;
  bool given = false;

  [[nodiscard]] bool present(Index k, Index i) const { return keep.data()[k * keep.stride(0) + i * keep.stride(1)]; }

  /// `observer.update(sample)`, or with the mask of sample k (copied into `scratch`) when masks were given.
  template <class Observer, class Sample, class Mask>
  UpdateStatus update(Observer& observer, const Sample& sample, Index k, Mask& scratch) const {
    if (!given) return observer.update(sample);
    for (Index i = 0; i < scratch.size(); ++i) scratch(i) = present(k, i);
    return observer.update(sample, scratch);
  }
};

inline Masks masks(nb::handle obj, Index samples, Index ny, std::string_view who) {
  Masks m;
  if (obj.is_none()) return m;
  m.keep = as_array<BoolArray>(obj, who, "present", "bool", "an array of booleans", "b");
  if (m.keep.ndim() != 2 || static_cast<Index>(m.keep.shape(0)) != samples || static_cast<Index>(m.keep.shape(1)) != ny)
    fail_dimensions(who, "present", std::to_string(samples) + "x" + std::to_string(ny), shape_of(m.keep));
  m.given = true;
  return m;
}

/// The arrays `run` returns.
struct RunResult {
  nb::object state, parameters, output_error, status;
  nb::dict diagnostics;
};

[[noreturn]] inline void fail_no_regressor(std::string_view who) {
  adaptobs::fail_argument(who, "Psi", "must be None: this observer's samples have no regressor");
}

template <class Observer>
std::string update_name() {
  return std::string(Observer::snapshot_type) + ".update";
}

/// The ny booleans of `present` (one sample's measured output channels) into `mask`.
template <class Mask>
void read_mask(nb::handle present, Index ny, std::string_view who, Mask& mask) {
  const auto m = as_array<BoolArray>(present, who, "present", "bool", "an array of booleans", "b");
  if (m.ndim() != 1 || static_cast<Index>(m.shape(0)) != ny)
    fail_dimensions(who, "present", "(" + std::to_string(ny) + ",)", shape_of(m));
  for (Index i = 0; i < ny; ++i) mask(i) = m.data()[i * m.stride(0)];
}

/// One step with the sample in `self.sample` and, when given, the mask of `present`.
template <class Observer>
UpdateStatus step(Bound<Observer>& self, nb::handle present) {
  if (present.is_none()) return self.observer.update(self.sample);
  read_mask(present, self.observer.sizes().ny, update_name<Observer>(), self.mask);
  return self.observer.update(self.sample, self.mask);
}

[[noreturn]] inline void fail_no_known_input(std::string_view who) {
  adaptobs::fail_argument(who, "known_input", "must be None: this observer's samples have no known input term");
}

template <class Observer>
RunResult run(Bound<Observer>& self, nb::handle u, nb::handle y, nb::handle psi, nb::handle present,
              nb::handle known_input) {
  const auto who = std::string(Observer::snapshot_type) + ".run";
  const InUse guard(self.in_use.flag, who);
  const Sizes s = self.observer.sizes();
  const Array y_array = real_array(y, who, "Y");
  if (y_array.ndim() == 0) fail_dimensions(who, "Y", "samples x " + std::to_string(s.ny), shape_of(y_array));
  const Index samples = static_cast<Index>(y_array.shape(0));
  const Rows outputs = rows(y_array, samples, s.ny, who, "Y");
  const Rows inputs = rows(u, samples, s.nu, who, "U");
  Regressors regressor;
  if constexpr (takes_regressor<Observer>)
    regressor = regressors(psi, samples, s.nx, s.np, who);
  else if (!psi.is_none())
    fail_no_regressor(who);
  Rows known;
  if constexpr (takes_known_input<Observer>) {
    if (!known_input.is_none()) known = rows(known_input, samples, s.nx, who, "known_input");
  } else if (!known_input.is_none()) {
    fail_no_known_input(who);
  }
  const Masks mask = masks(present, samples, s.ny, who);
  if constexpr (requires {
                  { self.observer.model() } -> std::convertible_to<const SharedDiscreteModel&>;
                })
    require_steps(self.observer.model(), self.observer.step(), samples, who);

  using D = Diagnostics<Observer>;
  const auto n = static_cast<std::size_t>(samples);
  OutputArray x({n, static_cast<std::size_t>(s.nx)});
  OutputArray theta({n, static_cast<std::size_t>(s.np)});
  OutputArray error({n, static_cast<std::size_t>(s.ny)});
  OutputArray diagnostics({n, D::names.size()});
  StatusArray status(n);
  // A Python function of the model that raises (a Takagi-Sugeno premise
  // function) stops the run and leaves the observer as it was before it.
  all_or_nothing(self.observer, [&] {
    nb::gil_scoped_release release;
    Bound<Observer>& b = self;
    auto& sample = b.sample;
    if constexpr (takes_regressor<Observer>) sample.Psi.setZero();
    // Sized once: the rows of `known_input` are copied into it, or it stays empty (f_k = 0).
    if constexpr (takes_known_input<Observer>) sample.f.setZero(known.data ? s.nx : 0);
    std::array<double, D::names.size() + 1> values{};
    for (Index k = 0; k < samples; ++k) {
      sample.u = inputs.row(k);
      sample.y = outputs.row(k);
      if constexpr (takes_regressor<Observer>)
        if (regressor.data) sample.Psi = regressor.at(k);
      if constexpr (takes_known_input<Observer>)
        if (known.data) sample.f = known.row(k);
      const UpdateStatus result = mask.update(b.observer, sample, k, b.mask);
      status.data[k] = static_cast<std::int8_t>(result);
      Eigen::Map<Eigen::VectorXd>(x.data + k * s.nx, s.nx) = b.observer.state();
      Eigen::Map<Eigen::VectorXd>(theta.data + k * s.np, s.np) = b.observer.parameters();
      Eigen::Map<Eigen::VectorXd>(error.data + k * s.ny, s.ny) = b.observer.output_error();
      D::record(b.observer, values.data());
      for (std::size_t j = 0; j < D::names.size(); ++j) diagnostics.data[k * D::names.size() + j] = values[j];
    }
  });
  RunResult result;
  result.state = nb::cast(x.array);
  result.parameters = nb::cast(theta.array);
  result.output_error = nb::cast(error.array);
  result.status = nb::cast(status.array);
  const nb::object columns = nb::cast(diagnostics.array);
  for (std::size_t j = 0; j < D::names.size(); ++j) result.diagnostics[D::names[j]] = column(columns, j);
  return result;
}

/// What an observer's model holds beyond numbers: nothing, unless it says so.
struct NoPythonPart {
  template <class Observer>
  nb::object operator()(const Observer&) const {
    return nb::none();
  }
};

/// The methods and properties every discrete observer has. `construct` builds
/// an observer of the snapshot's configuration, which `restore` then fills:
/// what unpickling needs. `python_part(observer)` is what pickling carries
/// beside the snapshot (a model's Python function), given back to
/// `construct(snapshot, python_part)`.
template <class Observer, class Construct, class PythonPart = NoPythonPart>
void bind_discrete_observer(nb::class_<Bound<Observer>>& cls, Construct construct, PythonPart python_part = {}) {
  using B = Bound<Observer>;
  cls.def(
         "update",
         [](B& self, nb::handle u, nb::handle y, nb::handle psi, nb::handle present, nb::handle known_input) {
           const auto who = update_name<Observer>();
           const InUse guard(self.in_use.flag, who);
           const Sizes s = self.observer.sizes();
           if (u.is_none()) {
             if (s.nu != 0) adaptobs::fail_argument(who, "u", "is required: the model has inputs");
           } else {
             read_vector(u, s.nu, who, "u", self.sample.u);
           }
           read_vector(y, s.ny, who, "y", self.sample.y);
           if constexpr (takes_regressor<Observer>) {
             if (psi.is_none() && s.np != 0)
               adaptobs::fail_argument(who, "Psi",
                                       "is required: the model has " + std::to_string(s.np) + " parameters");
             if (!psi.is_none()) read_matrix(psi, s.nx, s.np, who, "Psi", self.sample.Psi);
           } else if (!psi.is_none()) {
             fail_no_regressor(who);
           }
           if constexpr (takes_known_input<Observer>) {
             if (known_input.is_none())
               self.sample.f.resize(0);
             else
               read_vector(known_input, s.nx, who, "known_input", self.sample.f);
           } else if (!known_input.is_none()) {
             fail_no_known_input(who);
           }
           return step(self, present);
         },
         nb::arg("u").none(), nb::arg("y"), nb::arg("Psi").none() = nb::none(), nb::arg("present").none() = nb::none(),
         nb::arg("known_input").none() = nb::none(),
         "One sample (u_k, y_k, Psi_k): advances the estimates to step k + 1 and returns the UpdateStatus.\n"
         "A rejected sample (NaN or Inf in it, or a step that would produce one) leaves the observer exactly\n"
         "as it was. `present` (ny booleans) marks the output channels that were measured; the others are\n"
         "ignored, and none present is the time update. `known_input` (nx values, None for zero) is a known\n"
         "term f_k of measured data added to the state's step (Guyader & Zhang 2003, Remark 1).")
      .def("run", &run<Observer>, nb::arg("U").none(), nb::arg("Y"), nb::arg("Psi").none() = nb::none(),
           nb::arg("present").none() = nb::none(), nb::arg("known_input").none() = nb::none(),
           "Every sample of U (N x nu), Y (N x ny) and Psi (N x nx x np, or one nx x np for all), in C++\n"
           "with the GIL released; `present` is N x ny booleans, `known_input` N x nx (the known term f_k\n"
           "of each sample; None for none). Returns a RunResult: the estimates after\n"
           "each sample (state N x nx, parameters N x np), the output errors (N x ny), the status of each\n"
           "sample (int8, UpdateStatus values) and the diagnostics. Equal, bit for bit, to a loop of update().")
      .def(
          "reset",
          [](B& self, nb::handle x0, nb::handle theta0, Index start_step) {
            const auto who = std::string(Observer::snapshot_type) + ".reset";
            const InUse guard(self.in_use.flag, who);
            if constexpr (requires { self.observer.reset(self.observer.state(), self.observer.parameters(), 0); })
              self.observer.reset(vector(x0, who, "x0"), vector(theta0, who, "theta0"), start_step);
            else if (start_step == 0)
              self.observer.reset(vector(x0, who, "x0"), vector(theta0, who, "theta0"));
            else
              adaptobs::fail_argument(who, "start_step", "must be 0: this observer restarts its filters from step 0");
          },
          nb::arg("x0"), nb::arg("theta0"), nb::arg("start_step") = 0,
          "Restarts from the initial estimates at step `start_step`, clearing the filters.")
      .def_prop_ro(
          "state", [](const B& self) { return Eigen::VectorXd(self.observer.state()); }, "State estimate x_hat_k.")
      .def_prop_ro(
          "parameters", [](const B& self) { return Eigen::VectorXd(self.observer.parameters()); },
          "Parameter estimate theta_hat_k.")
      .def_prop_ro(
          "output_error", [](const B& self) { return Eigen::VectorXd(self.observer.output_error()); },
          "Output error of the last accepted update (absent channels zero).")
      .def_prop_ro(
          "step", [](const B& self) { return self.observer.step(); },
          "Number of accepted samples since construction or the last reset.")
      .def_prop_ro(
          "health", [](const B& self) { return self.observer.health(); },
          "HealthReport: healthy, assumption_violated (from the step a checked assumption failed) or diverged\n"
          "(from the first of consecutive updates refused because the step overflows), with the remedy.")
      .def_prop_ro(
          "sizes", [](const B& self) { return sizes_tuple(self.observer.sizes()); }, "(nx, nu, ny, np).")
      .def(
          "snapshot", [](const B& self) { return to_dict(adaptobs::snapshot(self.observer)); },
          "The whole internal state as a dict of arrays (type, version, matrices, integers).")
      .def(
          "restore",
          [](B& self, nb::handle state) {
            const InUse guard(self.in_use.flag, "restore");
            adaptobs::restore(self.observer, from_dict(state));
          },
          nb::arg("state"),
          "Continues exactly as the observer `state` was taken from; a snapshot of another class, version\n"
          "or configuration raises ConfigurationError and changes nothing.")
      .def("__copy__", [](const B& self) { return B(self.observer); })
      .def(
          "__deepcopy__", [](const B& self, nb::handle) { return B(self.observer); }, nb::arg("memo"))
      .def("__getstate__",
           [python_part](const B& self) {
             return nb::make_tuple(to_dict(adaptobs::snapshot(self.observer)), python_part(self.observer));
           })
      .def("__setstate__", [construct](B& self, const std::tuple<nb::object, nb::object>& state) {
        const Snapshot<double> s = from_dict(std::get<0>(state));
        detail::require_snapshot_type<Observer>(s);
        Observer observer = [&] {
          if constexpr (std::invocable<Construct, const Snapshot<double>&, nb::handle>)
            return construct(s, std::get<1>(state));
          else
            return construct(s);
        }();
        adaptobs::restore(observer, s);
        new (&self) B(std::move(observer));
      });
}

}  // namespace adaptobs::python
