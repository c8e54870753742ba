// The discrete-time models in Python: DiscreteLtiModel, one (A, B, C), and
// DiscreteLtvModel, the (A_k, B_k, C_k) of each step, given as arrays or by a
// function of k evaluated once per step when the model is built.

#include "discrete_models.hpp"
#include "snapshot_dict.hpp"

#include <nanobind/eigen/dense.h>
#include <nanobind/stl/string.h>

#include <optional>

namespace adaptobs::python {

namespace {

/// One of A, B, C as given to DiscreteLtvModel: per step (N × rows × cols) or
/// one matrix for every step (rows × cols).
struct PerStep {
  Array keep;
  bool varying = false;

  [[nodiscard]] Index steps() const { return varying ? static_cast<Index>(keep.shape(0)) : 0; }
  [[nodiscard]] Index rows() const { return static_cast<Index>(keep.shape(varying ? 1 : 0)); }
  [[nodiscard]] Index cols() const { return static_cast<Index>(keep.shape(varying ? 2 : 1)); }
  [[nodiscard]] Eigen::MatrixXd at(Index k) const {
    const Index s = varying ? 1 : 0;
    return Eigen::Map<const Eigen::MatrixXd, 0, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>>(
        keep.data() + (varying ? k * static_cast<Index>(keep.stride(0)) : 0), rows(), cols(),
        Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>(static_cast<Index>(keep.stride(s + 1)),
                                                      static_cast<Index>(keep.stride(s))));
  }
};

PerStep per_step(nb::handle obj, std::string_view who, std::string_view name) {
  PerStep p;
  p.keep = real_array(obj, who, name);
  if (p.keep.ndim() != 2 && p.keep.ndim() != 3)
    fail_dimensions(who, name, "steps x rows x cols, or one rows x cols matrix for every step", shape_of(p.keep));
  p.varying = p.keep.ndim() == 3;
  if (p.varying && p.keep.shape(0) == 0) fail_dimensions(who, name, "at least one step", shape_of(p.keep));
  return p;
}

SharedDiscreteModel ltv_from_arrays(nb::handle A, nb::handle B, nb::handle C, nb::handle np_arg) {
  constexpr std::string_view who = "DiscreteLtvModel";
  const Index np = integer_argument(np_arg, who, "np");
  const PerStep a = per_step(A, who, "A"), b = per_step(B, who, "B"), c = per_step(C, who, "C");
  Index steps = 0;  // none seen yet: per_step refuses an array of no steps
  for (const auto& [p, name] : {std::pair{&a, "A"}, std::pair{&b, "B"}, std::pair{&c, "C"}}) {
    if (!p->varying) continue;
    if (steps != 0 && p->steps() != steps)
      fail_dimensions(who, name, std::to_string(steps) + " steps, as the other per-step matrices", shape_of(p->keep));
    steps = p->steps();
  }
  if (steps == 0)
    adaptobs::fail_argument(who, "A",
                            "(or B or C) must be given per step (steps x rows x cols); a model with the "
                            "same matrices at every step is a DiscreteLtiModel");
  SharedDiscreteModel::Systems systems;
  systems.reserve(static_cast<std::size_t>(steps));
  for (Index k = 0; k < steps; ++k) systems.push_back({a.at(k), b.at(k), c.at(k)});
  return SharedDiscreteModel(std::move(systems), np, who, SharedDiscreteModel::element_of_arrays);
}

SharedDiscreteModel ltv_from_function(nb::handle matrices_at, nb::handle steps_arg, nb::handle np_arg) {
  constexpr std::string_view who = "DiscreteLtvModel.from_function";
  const Index steps = integer_argument(steps_arg, who, "steps");
  const Index np = integer_argument(np_arg, who, "np");
  if (!PyCallable_Check(matrices_at.ptr())) fail_type(who, "matrices_at", matrices_at, "a callable k -> (A, B, C)");
  SharedDiscreteModel::Systems systems;
  for (Index k = 0; k < steps; ++k) {
    const std::string name = "matrices_at(" + std::to_string(k) + ")";
    const auto [A, B, C] = system_tuple(matrices_at(k), who, name);
    systems.push_back({matrix(A, who, name + "[0]"), matrix(B, who, name + "[1]"), matrix(C, who, name + "[2]")});
  }
  return SharedDiscreteModel(std::move(systems), np, who, [](std::size_t k, int i) {
    return "matrices_at(" + std::to_string(k) + ")[" + std::to_string(i) + "]";
  });
}

/// The matrices of every step as one steps × rows × cols array.
template <class Get>
nb::object stacked(const SharedDiscreteModel& model, Index rows, Index cols, Get get) {
  const auto n = static_cast<std::size_t>(model.steps());
  OutputArray out({n, static_cast<std::size_t>(rows), static_cast<std::size_t>(cols)});
  for (std::size_t k = 0; k < n; ++k)
    Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
        out.data + k * static_cast<std::size_t>(rows * cols), rows, cols) = get(model.systems()[k]);
  return nb::cast(out.array);
}

}  // namespace

void bind_discrete_models(nb::module_& m) {
  nb::class_<LtiModel>(m, "DiscreteLtiModel",
                       "Time-invariant discrete model x_{k+1} = A x_k + B u_k + Psi_k theta, y_k = C x_k;\n"
                       "np is the number of unknown parameters.")
      .def(
          "__init__",
          [](LtiModel* self, nb::handle A, nb::handle B, nb::handle C, nb::handle np) {
            constexpr std::string_view who = "DiscreteLtiModel";
            new (self) LtiModel(matrix(A, who, "A"), matrix(B, who, "B"), matrix(C, who, "C"),
                                integer_argument(np, who, "np"));
          },
          nb::arg("A"), nb::arg("B"), nb::arg("C"), nb::arg("np"))
      .def_prop_ro("A", [](const LtiModel& self) { return Eigen::MatrixXd(self.system().A); })
      .def_prop_ro("B", [](const LtiModel& self) { return Eigen::MatrixXd(self.system().B); })
      .def_prop_ro("C", [](const LtiModel& self) { return Eigen::MatrixXd(self.system().C); })
      .def_prop_ro(
          "sizes", [](const LtiModel& self) { return sizes_tuple(self.sizes()); }, "(nx, nu, ny, np).")
      .def("__getstate__", [](const LtiModel& self) { return to_dict(adaptobs::snapshot(self)); })
      .def("__setstate__", [](LtiModel& self, nb::handle state) {
        const Snapshot<double> s = from_dict(state);
        detail::require_snapshot_type<LtiModel>(s);
        new (&self) LtiModel(field(s, "A"), field(s, "B"), field(s, "C"), integer(s, "np"));
      });

  nb::class_<SharedDiscreteModel>(
      m, "DiscreteLtvModel",
      "Time-varying discrete model x_{k+1} = A_k x_k + B_k u_k + Psi_k theta, y_k = C_k x_k over steps\n"
      "0 ... N-1. Each of A, B, C is N x rows x cols (one matrix per step) or rows x cols (the same at\n"
      "every step); at least one varies. The matrices are copied once, when the model is built, and\n"
      "shared by the observers built on it. An update beyond step N-1 raises ConfigurationError and\n"
      "changes nothing. The step is the observer's count of accepted samples: a sample rejected as\n"
      "not finite does not advance it, so mark a lost output with `present` (a time update), not NaN.")
      .def(
          "__init__",
          [](SharedDiscreteModel* self, nb::handle A, nb::handle B, nb::handle C, nb::handle np) {
            new (self) SharedDiscreteModel(ltv_from_arrays(A, B, C, np));
          },
          nb::arg("A"), nb::arg("B"), nb::arg("C"), nb::arg("np"))
      .def_static("from_function", &ltv_from_function, nb::arg("matrices_at"), nb::arg("steps"), nb::arg("np"),
                  "The model whose step k has the matrices (A_k, B_k, C_k) = matrices_at(k), for k in\n"
                  "range(steps): one call per step, here, and none while an observer runs.")
      .def(
          "at",
          [](const SharedDiscreteModel& self, Index k) {
            if (k < 0 || k >= self.steps())
              adaptobs::fail_argument("DiscreteLtvModel.at", "k",
                                      "must lie in [0, " + std::to_string(self.steps()) + ")");
            const System& s = self.at(k);
            return nb::make_tuple(Eigen::MatrixXd(s.A), Eigen::MatrixXd(s.B), Eigen::MatrixXd(s.C));
          },
          nb::arg("k"), "(A_k, B_k, C_k).")
      .def_prop_ro(
          "A",
          [](const SharedDiscreteModel& self) {
            return stacked(self, self.sizes().nx, self.sizes().nx, [](const System& s) { return s.A; });
          },
          "A_k of every step, N x nx x nx.")
      .def_prop_ro(
          "B",
          [](const SharedDiscreteModel& self) {
            return stacked(self, self.sizes().nx, self.sizes().nu, [](const System& s) { return s.B; });
          },
          "B_k of every step, N x nx x nu.")
      .def_prop_ro(
          "C",
          [](const SharedDiscreteModel& self) {
            return stacked(self, self.sizes().ny, self.sizes().nx, [](const System& s) { return s.C; });
          },
          "C_k of every step, N x ny x nx.")
      .def_prop_ro("steps", &SharedDiscreteModel::steps, "N, the number of steps the model covers.")
      .def_prop_ro(
          "sizes", [](const SharedDiscreteModel& self) { return sizes_tuple(self.sizes()); }, "(nx, nu, ny, np).")
      .def("__getstate__", [](const SharedDiscreteModel& self) { return to_dict(adaptobs::snapshot(self)); })
      .def("__setstate__", [](SharedDiscreteModel& self, nb::handle state) {
        const Snapshot<double> s = from_dict(state);
        detail::require_snapshot_type<SharedDiscreteModel>(s);
        new (&self) SharedDiscreteModel(SharedDiscreteModel::of_snapshot(s, ""));
      });
}

}  // namespace adaptobs::python
