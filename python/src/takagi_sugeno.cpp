// The Takagi–Sugeno part of the library in Python, with run-time sizes: the
// polytopic model (Srinivasarengan et al. 2018, eq. (9)–(11), (64)) whose
// premise variables z(x, u, theta) come from a Python callable, the adaptive
// observer of eq. (65) (eq. (21) with K_theta), the vertex LMIs of theorems 1–2
// (eq. (29)–(30), (55), (71)) and their check, the DSDP synthesis of the gains
// when the module is built with it, and the waste water plant of §6 in
// adaptobs.examples.

#include "arrays.hpp"
#include "collected.hpp"
#include "discrete_observer.hpp"
#include "snapshot_dict.hpp"
#include "snapshot_fields.hpp"

#include <adaptobs/design/takagi_sugeno_lmi.hpp>
#include <adaptobs/models/takagi_sugeno_model.hpp>
#include <adaptobs/observers/takagi_sugeno.hpp>
#include <adaptobs/simulation/output_loss.hpp>
#ifdef ADAPTOBS_PYTHON_HAS_LMI
#include <adaptobs/design/lmi/takagi_sugeno_synthesis.hpp>
#endif

#include "models/wwtp.hpp"

#include <nanobind/eigen/dense.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/tuple.h>
#include <nanobind/stl/vector.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

namespace adaptobs::python {

namespace {

/// A new float64 NumPy array holding v: NumPy's copy of a cached array of v's
/// length, filled through the buffer protocol. Cheaper than the general
/// conversion (numpy.asarray of an exported buffer), which an update would pay
/// three times.
nb::object fresh_array(const Eigen::VectorXd& v, nb::object& pattern) {
  if (!pattern.is_valid()) pattern = nb::cast(Eigen::VectorXd(Eigen::VectorXd::Zero(v.size())));
  static PyObject* const copy = PyUnicode_InternFromString("copy");
  const nb::object a = nb::steal(PyObject_CallMethodNoArgs(pattern.ptr(), copy));
  if (!a.is_valid()) throw nb::python_error();
  Py_buffer view;
  if (PyObject_GetBuffer(a.ptr(), &view, PyBUF_WRITABLE | PyBUF_C_CONTIGUOUS) != 0) throw nb::python_error();
  std::copy(v.data(), v.data() + v.size(), static_cast<double*>(view.buf));
  PyBuffer_Release(&view);
  return a;
}

/// The premise variables z = z(x, u, theta) of a model from Python: a callable
/// returning nz numbers, called with new NumPy arrays of the estimates (so that a
/// callable that keeps its arguments keeps values that do not change, and no view
/// of the observer's memory). It runs with the GIL taken back, once per update; a
/// model without premise variables (nz = 0, weights from the parameters alone)
/// never enters Python.
struct PythonPremises {
  nb::object source;  // the callable, or None (kept for pickling)
  Index nz = 0;
  mutable Eigen::VectorXd value;
  // Arrays of the lengths of x, u and theta that `fresh_array` copies, made on
  // the first call (with the GIL) and never written.
  mutable nb::object x_pattern, u_pattern, theta_pattern;

  const Eigen::VectorXd& operator()(const Eigen::VectorXd& x, const Eigen::VectorXd& u,
                                    const Eigen::VectorXd& theta) const {
    if (nz == 0 || !source.is_valid() || source.is_none()) return value;
    nb::gil_scoped_acquire gil;
    const nb::object z =
        source(fresh_array(x, x_pattern), fresh_array(u, u_pattern), fresh_array(theta, theta_pattern));
    // The shape is checked before anything is copied; a wrong one is an error
    // naming the callable, and the observer's update, which calls it first, changes nothing.
    read_vector(z, nz, "TakagiSugenoModel", "premises(x, u, theta)", value);
    return value;
  }
};

PythonPremises premises_of(nb::handle premises, Index nz, std::string_view who) {
  PythonPremises p;
  p.nz = nz;
  p.value.setZero(nz);
  if (premises.is_none()) {
    if (nz != 0)
      adaptobs::fail_argument(who, "premises",
                              "is required: premise_bounds gives " + std::to_string(nz) + " premise variables");
    p.source = nb::none();
    return p;
  }
  if (!PyCallable_Check(premises.ptr()))
    fail_type(who, "premises", premises, "a callable premises(x, u, theta) or None");
  p.source = nb::borrow(premises);
  return p;
}

using TsModel = TakagiSugenoModel<Dims, Eigen::Dynamic, PythonPremises>;
using TsObserver = TakagiSugenoObserver<TsModel>;
using TsGains = TakagiSugenoGains<Dims>;
using Sectors = SectorBounds<double, Eigen::Dynamic>;

}  // namespace

template <>
struct Diagnostics<TsObserver> {
  static constexpr std::array<const char*, 1> names{"premises_in_sectors"};
  static void record(const TsObserver& o, double* out) { out[0] = o.premises_in_sectors() ? 1.0 : 0.0; }
};

namespace {

// --- Arguments ---------------------------------------------------------------

bool is_sequence(nb::handle obj) {
  return PySequence_Check(obj.ptr()) && !PyUnicode_Check(obj.ptr()) && !PyBytes_Check(obj.ptr());
}

/// A list of matrices: a sequence (or a 3-D array), element i named "name[i]".
std::vector<Eigen::MatrixXd> matrix_list(nb::handle obj, std::string_view who, std::string_view name) {
  if (!is_sequence(obj)) fail_type(who, name, obj, "a sequence of matrices");
  std::vector<Eigen::MatrixXd> out;
  const std::size_t n = nb::len(obj);
  out.reserve(n);
  for (std::size_t i = 0; i < n; ++i) out.push_back(matrix(obj[i], who, detail::element_name(name, i)));
  return out;
}

nb::list list_of(const std::vector<Eigen::MatrixXd>& matrices) {
  nb::list out;
  for (const auto& m : matrices) out.append(nb::cast(m));
  return out;
}

/// Sectors (9) as a pair (lower, upper) of vectors; None is no entries.
Sectors sectors(nb::handle obj, std::string_view who, std::string_view name) {
  Sectors s;
  s.lower.resize(0);
  s.upper.resize(0);
  if (obj.is_none()) return s;
  if (!is_sequence(obj) || nb::len(obj) != 2) fail_type(who, name, obj, "a pair (lower, upper) of vectors");
  const std::string base(name);
  s.lower = vector(obj[0], who, base + "[0]");
  s.upper = vector(obj[1], who, base + "[1]");
  return s;
}

nb::tuple sector_tuple(const Sectors& s) { return nb::make_tuple(Eigen::VectorXd(s.lower), Eigen::VectorXd(s.upper)); }

std::optional<Eigen::MatrixXd> optional_matrix(nb::handle obj, std::string_view who, std::string_view name) {
  if (obj.is_none()) return std::nullopt;
  return matrix(obj, who, name);
}

TsGains gains_of(nb::handle L, nb::handle K, nb::handle K_theta, std::string_view who) {
  TsGains g;
  g.L = matrix_list(L, who, "L");
  g.K = matrix_list(K, who, "K");
  g.K_theta = optional_matrix(K_theta, who, "K_theta");
  return g;
}

const TsModel& ts_model(nb::handle model, std::string_view who) {
  return object_argument<TsModel>(model, who, "model", "an adaptobs.TakagiSugenoModel");
}

const TsGains& ts_gains(nb::handle gains, std::string_view who) {
  return object_argument<TsGains>(gains, who, "gains", "an adaptobs.TakagiSugenoGains");
}

/// The vertex matrices of `model` side by side, [M_1 ... M_r] (eq. (24)-(25)), with M_i = (model.*vertex)(i).
Eigen::MatrixXd side_by_side(const TsModel& model, const Eigen::MatrixXd& (TsModel::*vertex)(Index) const) {
  const Index r = model.vertex_count();
  const Index rows = (model.*vertex)(0).rows(), cols = (model.*vertex)(0).cols();
  Eigen::MatrixXd out(rows, cols * r);
  for (Index i = 0; i < r; ++i) out.middleCols(i * cols, cols) = (model.*vertex)(i);
  return out;
}

// --- Snapshots -----------------------------------------------------------------

/// The model of a snapshot's fields under `prefix` ("" or "model."), with the premise callable.
TsModel model_of(const Snapshot<double>& s, const std::string& prefix, nb::handle premises) {
  const Eigen::MatrixXd A = field(s, prefix + "A"), B = field(s, prefix + "B"), C = field(s, prefix + "C");
  Sectors z, theta;
  z.lower = field(s, prefix + "premise_bounds.lower").reshaped();
  z.upper = field(s, prefix + "premise_bounds.upper").reshaped();
  theta.lower = field(s, prefix + "parameter_bounds.lower").reshaped();
  theta.upper = field(s, prefix + "parameter_bounds.upper").reshaped();
  const Index k = z.size() + theta.size();
  adaptobs::require(k <= 20, "restore", "snapshot", "holds more than 2^20 vertices");
  const Index r = Index(1) << k, nx = A.rows();
  adaptobs::require(A.cols() == nx * r && B.rows() == nx && B.cols() % r == 0, "restore", "snapshot",
                    "holds vertex matrices that do not match its sectors");
  const Index nu = B.cols() / r;
  std::vector<TakagiSugenoVertex<Dims>> vertices(static_cast<std::size_t>(r));
  for (Index i = 0; i < r; ++i) {
    vertices[static_cast<std::size_t>(i)] = {A.middleCols(i * nx, nx), B.middleCols(i * nu, nu)};
  }
  return TsModel(vertices, C, premises_of(premises, z.size(), "restore"), z, theta);
}

TsObserver observer_of(const Snapshot<double>& s, nb::handle premises) {
  TsModel model = model_of(s, "model.", premises);
  TsGains gains;
  const Index r = model.vertex_count();
  for (Index i = 0; i < r; ++i) {
    gains.L.push_back(field(s, detail::element_name("L", static_cast<std::size_t>(i))));
    gains.K.push_back(field(s, detail::element_name("K_y", static_cast<std::size_t>(i))));
  }
  if (integer(s, "has_leakage") != 0) gains.K_theta = field(s, "K_theta");
  return TsObserver(std::move(model), gains, field(s, "x").reshaped(), field(s, "theta").reshaped());
}

// --- Cyclic garbage collection (collected.hpp) -----------------------------------

int traverse_python(const TsModel& model, visitproc visit, void* arg) {
  Py_VISIT(model.premise_function().source.ptr());
  return 0;
}
void clear_python(const TsModel& model) {
  // The premise function is part of the model's configuration, const to the
  // library: only the collector changes it, to break a cycle of an object about
  // to go, which is never stepped again.
  const_cast<PythonPremises&>(model.premise_function()).source = nb::none();
}

// --- The model ------------------------------------------------------------------

/// The x, u and theta of a call to the model's own functions, read to its sizes.
struct StateInputParameters {
  Eigen::VectorXd x, u, theta;
};

StateInputParameters state_input_parameters(const TsModel& model, nb::handle x, nb::handle u, nb::handle theta,
                                            std::string_view who) {
  const Sizes s = model.sizes();
  StateInputParameters v;
  read_vector(x, s.nx, who, "x", v.x);
  read_vector(u, s.nu, who, "u", v.u);
  read_vector(theta, s.np, who, "theta", v.theta);
  return v;
}

void bind_model(nb::module_& m) {
  nb::class_<TsGains>(m, "TakagiSugenoGains",
                      "Gains of a TakagiSugenoObserver (Srinivasarengan et al. 2018): one L_i (nx x ny) and one\n"
                      "K_i = K_{y,i} (np x ny) per vertex, in the vertex order of the model, and the leakage\n"
                      "K_theta (np x np) of eq. (21), None for constant parameters (eq. (65)).")
      .def(
          "__init__",
          [](TsGains* self, nb::handle L, nb::handle K, nb::handle K_theta) {
            new (self) TsGains(gains_of(L, K, K_theta, "TakagiSugenoGains"));
          },
          nb::arg("L"), nb::arg("K"), nb::arg("K_theta").none() = nb::none())
      .def_prop_ro(
          "L", [](const TsGains& g) { return list_of(g.L); }, "L_i per vertex (a list of arrays)")
      .def_prop_ro(
          "K", [](const TsGains& g) { return list_of(g.K); }, "K_{y,i} per vertex (a list of arrays)")
      .def_prop_ro(
          "K_theta", [](const TsGains& g) { return g.K_theta; }, "K_theta of eq. (21), or None")
      .def("__getstate__", [](const TsGains& g) { return nb::make_tuple(list_of(g.L), list_of(g.K), g.K_theta); })
      .def("__setstate__", [](TsGains& self, const std::tuple<nb::object, nb::object, nb::object>& state) {
        new (&self) TsGains(gains_of(std::get<0>(state), std::get<1>(state), std::get<2>(state), "restore"));
      });

  nb::class_<TsModel>(
      m, "TakagiSugenoModel", nb::type_slots(CollectedReferences<TsModel, ModelItself>::slots),
      "Polytopic (Takagi-Sugeno) model with unknown parameters (Srinivasarengan et al. 2018, eq. (64)):\n"
      "  x_{k+1} = sum_i h_i(z_k, theta) (A_i x_k + B_i u_k),  y_k = C x_k,\n"
      "with r = 2^(nz + np) vertices (A_i, B_i) and the sector-nonlinearity weights h_i of eq. (10) and\n"
      "Remark 1: each premise variable z_j in [z_j^1, z_j^2] and parameter theta_l in [theta_l^1, theta_l^2]\n"
      "has the memberships mu^1(v) = (v^2 - v)/(v^2 - v^1), mu^2(v) = (v - v^1)/(v^2 - v^1), and a vertex's\n"
      "weight is the product of one membership per variable. z and theta are clipped to their sectors\n"
      "first, so h_i >= 0 and sum h_i = 1 (11).\n"
      "Vertex order: v = (z_1..z_nz, theta_1..theta_np); vertex i (0-based) takes the upper bound of v_j\n"
      "when bit (nz + np - 1 - j) of i is set (z_1 the most significant bit), as sector_vertices makes them.\n"
      "`vertices` is a sequence of pairs (A_i, B_i); premise_bounds and parameter_bounds are pairs\n"
      "(lower, upper) of vectors. `premises(x, u, theta)` is a Python callable returning the nz premise\n"
      "variables (it may use unmeasured states; an observer calls it at its estimates, once per update,\n"
      "with the GIL); None when premise_bounds is None (weights from theta alone). Pickling a model\n"
      "pickles the callable with it: it must be picklable, e.g. a module-level function.")
      .def(
          "__init__",
          [](TsModel* self, nb::handle vertices, nb::handle C, nb::handle premises, nb::handle premise_bounds,
             nb::handle parameter_bounds) {
            constexpr std::string_view who = "TakagiSugenoModel";
            if (!is_sequence(vertices)) fail_type(who, "vertices", vertices, "a sequence of pairs (A_i, B_i)");
            std::vector<TakagiSugenoVertex<Dims>> list;
            const std::size_t n = nb::len(vertices);
            for (std::size_t i = 0; i < n; ++i) {
              const nb::object v = vertices[i];
              const std::string name = detail::element_name("vertices", i);
              if (!is_sequence(v) || nb::len(v) != 2) fail_type(who, name, v, "a pair (A_i, B_i)");
              list.push_back({matrix(v[0], who, name + ".A"), matrix(v[1], who, name + ".B")});
            }
            Sectors z = sectors(premise_bounds, who, "premise_bounds");
            Sectors theta = sectors(parameter_bounds, who, "parameter_bounds");
            // The C++ constructor reads the sizes off the first vertex: none is refused here, as it counts.
            if (list.empty() && z.size() + theta.size() <= 20)
              detail::fail_count(Index(1) << (z.size() + theta.size()), 0, "2^(nz + np) vertices", who, "vertices");
            PythonPremises function = premises_of(premises, z.size(), who);
            new (self) TsModel(list, matrix(C, who, "C"), std::move(function), std::move(z), std::move(theta));
          },
          nb::arg("vertices"), nb::arg("C"), nb::arg("premises").none(), nb::arg("premise_bounds").none(),
          nb::arg("parameter_bounds").none())
      .def_prop_ro(
          "sizes", [](const TsModel& self) { return sizes_tuple(self.sizes()); }, "(nx, nu, ny, np).")
      .def_prop_ro("premise_count", &TsModel::premise_count, "nz")
      .def_prop_ro("vertex_count", &TsModel::vertex_count, "r = 2^(nz + np)")
      .def(
          "A",
          [](const TsModel& self, Index i) {
            adaptobs::require(i >= 0 && i < self.vertex_count(), "TakagiSugenoModel.A", "i",
                              "must be a vertex index in [0, vertex_count)");
            return Eigen::MatrixXd(self.A(i));
          },
          nb::arg("i"), "Vertex matrix A_i (0-based).")
      .def(
          "B",
          [](const TsModel& self, Index i) {
            adaptobs::require(i >= 0 && i < self.vertex_count(), "TakagiSugenoModel.B", "i",
                              "must be a vertex index in [0, vertex_count)");
            return Eigen::MatrixXd(self.B(i));
          },
          nb::arg("i"), "Vertex matrix B_i (0-based).")
      .def_prop_ro("C", [](const TsModel& self) { return Eigen::MatrixXd(self.C()); })
      .def_prop_ro(
          "vertex_state_matrices", [](const TsModel& self) { return side_by_side(self, &TsModel::A); },
          "[A_1 ... A_r] (eq. (24)).")
      .def_prop_ro(
          "vertex_input_matrices", [](const TsModel& self) { return side_by_side(self, &TsModel::B); },
          "[B_1 ... B_r] (eq. (25)).")
      .def_prop_ro(
          "premise_bounds", [](const TsModel& self) { return sector_tuple(self.premise_bounds()); },
          "(lower, upper) of the premise variables.")
      .def_prop_ro(
          "parameter_bounds", [](const TsModel& self) { return sector_tuple(self.parameter_bounds()); },
          "(lower, upper) of the parameters.")
      .def_prop_ro(
          "premise_function", [](const TsModel& self) { return self.premise_function().source; },
          "The premise callable as given (None without premise variables).")
      .def(
          "premises",
          [](const TsModel& self, nb::handle x, nb::handle u, nb::handle theta) {
            const auto v = state_input_parameters(self, x, u, theta, "TakagiSugenoModel.premises");
            return Eigen::VectorXd(self.premises(v.x, v.u, v.theta));
          },
          nb::arg("x"), nb::arg("u"), nb::arg("theta"), "Premise variables z(x, u, theta), unclipped.")
      .def(
          "weights",
          [](const TsModel& self, nb::handle z, nb::handle theta) {
            constexpr std::string_view who = "TakagiSugenoModel.weights";
            Eigen::VectorXd zv, tv;
            read_vector(z, self.premise_count(), who, "z", zv);
            read_vector(theta, self.sizes().np, who, "theta", tv);
            return Eigen::VectorXd(self.weights(zv, tv));
          },
          nb::arg("z"), nb::arg("theta"),
          "Weights h_i(z, theta) of every vertex (eq. (10), Remark 1), z and theta clipped to their sectors.")
      .def(
          "step",
          [](const TsModel& self, nb::handle x, nb::handle u, nb::handle theta) {
            const auto v = state_input_parameters(self, x, u, theta, "TakagiSugenoModel.step");
            return Eigen::VectorXd(self.step(v.x, v.u, v.theta));
          },
          nb::arg("x"), nb::arg("u"), nb::arg("theta"),
          "One step of eq. (64): sum_i h_i(z(x, u, theta), theta) (A_i x + B_i u).")
      .def("__getstate__",
           [](const TsModel& self) {
             return nb::make_tuple(to_dict(adaptobs::snapshot(self)), self.premise_function().source);
           })
      .def("__setstate__", [](TsModel& self, const std::tuple<nb::object, nb::object>& state) {
        const Snapshot<double> s = from_dict(std::get<0>(state));
        detail::require_snapshot_type<TsModel>(s);
        new (&self) TsModel(model_of(s, "", std::get<1>(state)));
      });

  m.def(
      "sector_vertices",
      [](nb::handle matrices_at, nb::handle premise_bounds, nb::handle parameter_bounds) {
        constexpr std::string_view who = "sector_vertices";
        if (!PyCallable_Check(matrices_at.ptr()))
          fail_type(who, "matrices_at", matrices_at, "a callable (z, theta) -> (A, B)");
        const Sectors z = sectors(premise_bounds, who, "premise_bounds");
        const Sectors theta = sectors(parameter_bounds, who, "parameter_bounds");
        const auto at = [&](const Eigen::VectorXd& zv, const Eigen::VectorXd& tv) {
          const nb::object pair = matrices_at(zv, tv);
          if (!is_sequence(pair) || nb::len(pair) != 2) fail_type(who, "matrices_at(z, theta)", pair, "a pair (A, B)");
          return TakagiSugenoVertex<Dims>{matrix(pair[0], who, "matrices_at(z, theta)[0]"),
                                          matrix(pair[1], who, "matrices_at(z, theta)[1]")};
        };
        nb::list out;
        for (const auto& v : sector_vertices<Dims, Eigen::Dynamic>(at, z, theta))
          out.append(nb::make_tuple(Eigen::MatrixXd(v.A), Eigen::MatrixXd(v.B)));
        return out;
      },
      nb::arg("matrices_at"), nb::arg("premise_bounds").none(), nb::arg("parameter_bounds").none(),
      "The 2^(nz + np) vertices (A_i, B_i) = matrices_at(z^(i), theta^(i)) of a quasi-LPV description by the\n"
      "sector-nonlinearity transformation (Srinivasarengan et al. 2018, eq. (16)-(20), (64)), in the vertex\n"
      "order of TakagiSugenoModel; exact inside the sectors when A(z, theta) and B(z, theta) are affine in each\n"
      "premise variable and each parameter separately.");

  m.def(
      "sector_weights",
      [](nb::handle z, nb::handle premise_bounds, nb::handle theta, nb::handle parameter_bounds) {
        constexpr std::string_view who = "sector_weights";
        const Sectors zb = sectors(premise_bounds, who, "premise_bounds");
        const Sectors tb = sectors(parameter_bounds, who, "parameter_bounds");
        detail::validate_sectors(zb, zb.size(), who, "premise_bounds");
        detail::validate_sectors(tb, tb.size(), who, "parameter_bounds");
        adaptobs::require(zb.size() + tb.size() <= 20, who, "premise_bounds",
                          "with parameter_bounds gives more than 2^20 vertices");
        Eigen::VectorXd zv, tv;
        read_vector(z, zb.size(), who, "z", zv);
        read_vector(theta, tb.size(), who, "theta", tv);
        Eigen::VectorXd h(Index(1) << (zb.size() + tb.size()));
        sector_weights(zv, zb, tv, tb, h);
        return h;
      },
      nb::arg("z"), nb::arg("premise_bounds").none(), nb::arg("theta"), nb::arg("parameter_bounds").none(),
      "Sector-nonlinearity weights h_i(z, theta) of all 2^(nz + np) vertices (eq. (10), Remark 1, (64)), each\n"
      "variable clipped to its sector first: non-negative, summing to 1 (11).");
}

// --- The observer -------------------------------------------------------------------

void bind_observer(nb::module_& m) {
  using B = Bound<TsObserver>;
  auto cls = nb::class_<B>(
      m, "TakagiSugenoObserver", nb::type_slots(CollectedReferences<B, ModelOfObserver>::slots),
      "Takagi-Sugeno polytopic adaptive observer of Srinivasarengan, Ragot, Aubrun & Maquin (2018),\n"
      "eq. (65) for constant parameters, eq. (21) with Remark 5 when gains.K_theta is set:\n"
      "  x_{k+1} = sum_i h_i [A_i x_k + B_i u_k + L_i (y_k - C x_k)]\n"
      "  theta_{k+1} = theta_k + sum_i h_i [K_{y,i} (y_k - C x_k) - K_theta theta_k]\n"
      "with the weights h_i = h_i(z(x_k, u_k, theta_k), theta_k) at the estimates, z and theta clipped to\n"
      "their sectors (10). `gains` is a TakagiSugenoGains (see synthesize_takagi_sugeno_gains for the LMI\n"
      "design of theorems 1-2). Samples are (u, y) without a regressor; `present` marks the measured outputs\n"
      "(output error D_k (y_k - C x_k)). diagnostics: premises_in_sectors (1.0 or 0.0) after each sample.\n"
      "snapshot()/restore() hold the model's matrices and sectors, the gains and the estimates, not the\n"
      "premise callable (a restored observer keeps its own); pickling pickles the callable with the\n"
      "observer: it must be picklable, e.g. a module-level function.");
  cls.def(
         "__init__",
         [](B* self, nb::handle model, nb::handle gains, nb::handle x0, nb::handle theta0) {
           constexpr std::string_view who = "TakagiSugenoObserver";
           new (self) B(TsObserver(ts_model(model, who), ts_gains(gains, who), vector(x0, who, "x0"),
                                   vector(theta0, who, "theta0")));
         },
         nb::arg("model"), nb::arg("gains"), nb::arg("x0"), nb::arg("theta0"))
      .def_prop_ro(
          "weights", [](const B& b) { return Eigen::VectorXd(b.observer.weights()); },
          "Weights h_i of the last accepted update (zero before the first).")
      .def_prop_ro(
          "premises", [](const B& b) { return Eigen::VectorXd(b.observer.premises()); },
          "Premise variables z_k of the last accepted update, before clipping.")
      .def_prop_ro(
          "premises_in_sectors", [](const B& b) { return b.observer.premises_in_sectors(); },
          "False when the last accepted update had to clip z_k or theta_k to its sector (Remark 8).")
      .def_prop_ro(
          "gains", [](const B& b) { return b.observer.gains(); }, "The gains in use (a TakagiSugenoGains).")
      .def_prop_ro(
          "has_leakage", [](const B& b) { return b.observer.has_leakage(); },
          "True for the time-varying-parameter observer (eq. (21), K_theta set).")
      .def_prop_ro(
          "model", [](const B& b) { return TsModel(b.observer.model()); }, "A copy of the model.")
      .def(
          "set_gains",
          [](B& b, nb::handle gains) {
            constexpr std::string_view who = "TakagiSugenoObserver.set_gains";
            const InUse guard(b.in_use.flag, who);
            b.observer.set_gains(ts_gains(gains, who));
          },
          nb::arg("gains"), "Gains used from the next update on (checked as at construction).");
  // Pickling carries the premise callable beside the snapshot, which holds numbers only.
  bind_discrete_observer(
      cls, [](const Snapshot<double>& s, nb::handle premises) { return observer_of(s, premises); },
      [](const TsObserver& o) { return o.model().premise_function().source; });
}

// --- The LMIs of theorems 1-2 -------------------------------------------------------

TakagiSugenoLmiData lmi_data_of(nb::handle A, nb::handle Bm, nb::handle C, nb::handle Q_x, nb::handle Q_theta,
                                TakagiSugenoTheorem theorem, ParameterErrorModel error_model, nb::handle K_theta) {
  constexpr std::string_view who = "TakagiSugenoLmiData";
  TakagiSugenoLmiData d;
  d.A = matrix_list(A, who, "A");
  d.B = matrix_list(Bm, who, "B");
  d.C = matrix(C, who, "C");
  d.Q_x = matrix(Q_x, who, "Q_x");
  d.Q_theta = matrix(Q_theta, who, "Q_theta");
  d.theorem = theorem;
  d.error_model = error_model;
  if (!K_theta.is_none()) d.K_theta = matrix(K_theta, who, "K_theta");
  return d;
}

std::array<double, 4> four_numbers(nb::handle obj, std::string_view who, std::string_view name) {
  const Eigen::VectorXd v = vector(obj, who, name);
  if (v.size() != 4) fail_dimensions(who, name, "(4,)", {static_cast<std::size_t>(v.size())});
  return {v(0), v(1), v(2), v(3)};
}

Eigen::MatrixXd matrix_or_empty(nb::handle obj, std::string_view who, std::string_view name) {
  return obj.is_none() ? Eigen::MatrixXd() : matrix(obj, who, name);
}

nb::object matrix_or_none(const Eigen::MatrixXd& m) { return m.size() == 0 ? nb::none() : nb::cast(m); }

void bind_lmi(nb::module_& m) {
  nb::enum_<TakagiSugenoTheorem>(m, "TakagiSugenoTheorem", "Which observer the LMIs certify.")
      .value("constant_parameters", TakagiSugenoTheorem::constant_parameters,
             "theorem 2, observer (65): perturbation (x, u)")
      .value("time_varying_parameters", TakagiSugenoTheorem::time_varying_parameters,
             "theorem 1, observer (21) with K_theta: perturbation (x, u, Theta, Delta Theta)");
  nb::enum_<ParameterErrorModel>(m, "ParameterErrorModel",
                                 "Which recursion of the parameter error the LMIs are written for.")
      .value("as_printed", ParameterErrorModel::as_printed,
             "eq. (66) / (32)-(33): Phi22 = 0 / -K_theta, G_theta = I + K_theta")
      .value("exact", ParameterErrorModel::exact,
             "the recursion of observer (65) / (21): Phi22 = I / I - K_theta, G_theta = K_theta");

  nb::class_<TakagiSugenoLmiData>(
      m, "TakagiSugenoLmiData",
      "Problem data of the vertex LMIs of theorems 1-2 (Srinivasarengan et al. 2018, eq. (29)-(30), (55), (71)):\n"
      "the vertices A_i, B_i, C, Q_e = diag(Q_x, Q_theta) in place of the theorems' I (Remark 4), the theorem,\n"
      "the reading of the parameter error (ParameterErrorModel) and K_theta (theorem 1 only).")
      .def(
          "__init__",
          [](TakagiSugenoLmiData* self, nb::handle A, nb::handle B, nb::handle C, nb::handle Q_x, nb::handle Q_theta,
             TakagiSugenoTheorem theorem, ParameterErrorModel error_model, nb::handle K_theta) {
            new (self) TakagiSugenoLmiData(lmi_data_of(A, B, C, Q_x, Q_theta, theorem, error_model, K_theta));
          },
          nb::arg("A"), nb::arg("B"), nb::arg("C"), nb::arg("Q_x"), nb::arg("Q_theta"), nb::kw_only(),
          nb::arg("theorem") = TakagiSugenoTheorem::constant_parameters,
          nb::arg("error_model") = ParameterErrorModel::as_printed, nb::arg("K_theta").none() = nb::none())
      .def_prop_ro("A", [](const TakagiSugenoLmiData& d) { return list_of(d.A); })
      .def_prop_ro("B", [](const TakagiSugenoLmiData& d) { return list_of(d.B); })
      .def_ro("C", &TakagiSugenoLmiData::C)
      .def_ro("Q_x", &TakagiSugenoLmiData::Q_x)
      .def_ro("Q_theta", &TakagiSugenoLmiData::Q_theta)
      .def_ro("theorem", &TakagiSugenoLmiData::theorem)
      .def_ro("error_model", &TakagiSugenoLmiData::error_model)
      .def_prop_ro("K_theta", [](const TakagiSugenoLmiData& d) { return matrix_or_none(d.K_theta); })
      .def_prop_ro("vertex_count", &TakagiSugenoLmiData::vertex_count)
      .def_prop_ro("perturbation_size", &TakagiSugenoLmiData::perturbation_size,
                   "nx + nu (theorem 2) or nx + nu + 2 np (theorem 1)")
      .def_prop_ro("vertex_lmi_size", &TakagiSugenoLmiData::vertex_lmi_size,
                   "size of each M_i: 3 (nx + np) + perturbation_size + 2 r (nx + nu)")
      .def_prop_ro("stacked_A", &TakagiSugenoLmiData::stacked_A, "[A_1 ... A_r] (24)")
      .def_prop_ro("stacked_B", &TakagiSugenoLmiData::stacked_B, "[B_1 ... B_r] (25)");

  m.def(
      "parameter_error_blocks",
      [](const TakagiSugenoLmiData& data) {
        const ParameterErrorBlocks b = parameter_error_blocks(data);
        return nb::make_tuple(b.Phi22, matrix_or_none(b.G_theta));
      },
      nb::arg("data"), "(Phi22, G_theta) of the error model (33) / (66); G_theta None for theorem 2.");

  nb::class_<TakagiSugenoCertificate>(
      m, "TakagiSugenoCertificate",
      "Decision variables of theorems 1-2 at one point: P0, P1, R_i = P0 L_i, F_i = P1 K_{y,i} (40),\n"
      "lambda_1..4 (`lambda_`), Gamma_x, Gamma_u and, for theorem 1, Gamma_theta, Gamma_dtheta.")
      .def(
          "__init__",
          [](TakagiSugenoCertificate* self, nb::handle P0, nb::handle P1, nb::handle R, nb::handle F, nb::handle lambda,
             nb::handle Gamma_x, nb::handle Gamma_u, nb::handle Gamma_theta, nb::handle Gamma_dtheta) {
            constexpr std::string_view who = "TakagiSugenoCertificate";
            TakagiSugenoCertificate c;
            c.P0 = matrix(P0, who, "P0");
            c.P1 = matrix(P1, who, "P1");
            c.R = matrix_list(R, who, "R");
            c.F = matrix_list(F, who, "F");
            c.lambda = four_numbers(lambda, who, "lambda_");
            c.Gamma_x = matrix(Gamma_x, who, "Gamma_x");
            c.Gamma_u = matrix(Gamma_u, who, "Gamma_u");
            c.Gamma_theta = matrix_or_empty(Gamma_theta, who, "Gamma_theta");
            c.Gamma_dtheta = matrix_or_empty(Gamma_dtheta, who, "Gamma_dtheta");
            new (self) TakagiSugenoCertificate(std::move(c));
          },
          nb::arg("P0"), nb::arg("P1"), nb::arg("R"), nb::arg("F"), nb::arg("lambda_"), nb::arg("Gamma_x"),
          nb::arg("Gamma_u"), nb::arg("Gamma_theta").none() = nb::none(), nb::arg("Gamma_dtheta").none() = nb::none())
      .def_ro("P0", &TakagiSugenoCertificate::P0)
      .def_ro("P1", &TakagiSugenoCertificate::P1)
      .def_prop_ro("R", [](const TakagiSugenoCertificate& c) { return list_of(c.R); })
      .def_prop_ro("F", [](const TakagiSugenoCertificate& c) { return list_of(c.F); })
      .def_prop_ro(
          "lambda_",
          [](const TakagiSugenoCertificate& c) {
            return nb::make_tuple(c.lambda[0], c.lambda[1], c.lambda[2], c.lambda[3]);
          },
          "(lambda_1, ..., lambda_4)")
      .def_ro("Gamma_x", &TakagiSugenoCertificate::Gamma_x)
      .def_ro("Gamma_u", &TakagiSugenoCertificate::Gamma_u)
      .def_prop_ro("Gamma_theta", [](const TakagiSugenoCertificate& c) { return matrix_or_none(c.Gamma_theta); })
      .def_prop_ro("Gamma_dtheta", [](const TakagiSugenoCertificate& c) { return matrix_or_none(c.Gamma_dtheta); });

  nb::class_<TakagiSugenoCertificateCheck>(m, "TakagiSugenoCertificateCheck",
                                           "Outcome of checking a candidate solution against theorem 1 or 2.")
      .def_ro("max_vertex_eigenvalue", &TakagiSugenoCertificateCheck::max_vertex_eigenvalue,
              "max_i lambda_max(M_i) (eq. (29) / (71)); negative when every vertex LMI holds")
      .def_ro("min_eigenvalue_P0", &TakagiSugenoCertificateCheck::min_eigenvalue_P0, "-inf unless P0 is symmetric")
      .def_ro("min_eigenvalue_P1", &TakagiSugenoCertificateCheck::min_eigenvalue_P1, "-inf unless P1 is symmetric")
      .def_ro("min_lambda", &TakagiSugenoCertificateCheck::min_lambda)
      .def_ro("min_eigenvalue_Gamma", &TakagiSugenoCertificateCheck::min_eigenvalue_Gamma,
              "smallest over the Gamma^j; -inf unless each is symmetric")
      .def_prop_ro("holds", &TakagiSugenoCertificateCheck::holds,
                   "Every M_i < 0 and P0, P1, lambda_m, Gamma^j > 0 (strictly; (28), (69)-(70)).");

  m.def(
      "takagi_sugeno_vertex_lmi",
      [](const TakagiSugenoLmiData& data, const TakagiSugenoCertificate& certificate, Index i) {
        return takagi_sugeno_vertex_lmi(data, certificate, i);
      },
      nb::arg("data"), nb::arg("certificate"), nb::arg("i"),
      "M_i of eq. (29) / (71) at a candidate solution, vertex i (0-based), assembled block by block\n"
      "(the blocks: include/adaptobs/design/takagi_sugeno_lmi.hpp).");
  m.def(
      "check_takagi_sugeno_certificate",
      [](const TakagiSugenoLmiData& data, const TakagiSugenoCertificate& certificate) {
        return check_takagi_sugeno_certificate(data, certificate);
      },
      nb::arg("data"), nb::arg("certificate"),
      "Rebuilds every M_i from the candidate and returns its largest eigenvalue, with the smallest\n"
      "eigenvalues of P0, P1, Gamma^j and the smallest lambda_m ((28), (69)-(71)).");
}

#ifdef ADAPTOBS_PYTHON_HAS_LMI
using Synthesis = TakagiSugenoSynthesis<Dims>;

void bind_synthesis(nb::module_& m) {
  nb::enum_<TakagiSugenoObjective>(m, "TakagiSugenoObjective", "What the SDP optimises over the LMIs.")
      .value("minimize_beta", TakagiSugenoObjective::minimize_beta,
             "corollary 1 (56)-(57): min beta, beta I >= Gamma^j, M_i <= -margin I")
      .value("maximize_margin", TakagiSugenoObjective::maximize_margin,
             "max t <= 1 with M_i <= -t I and P0, P1, lambda_m >= t I (needs fixed_gamma)")
      .value("feasibility", TakagiSugenoObjective::feasibility, "M_i <= -margin I, minimising tr P0");
  nb::enum_<SynthesisStatus>(m, "SynthesisStatus", "Outcome of a synthesis.")
      .value("feasible", SynthesisStatus::feasible, "the returned point was verified")
      .value("infeasible", SynthesisStatus::infeasible,
             "DSDP reports the LMIs infeasible, or the largest margin is <= 0")
      .value("not_verified", SynthesisStatus::not_verified, "DSDP's point fails the independent check")
      .value("solver_failed", SynthesisStatus::solver_failed, "a DSDP call failed");
  nb::enum_<lmi::SdpStatus>(m, "SdpStatus", "DSDP's classification of the problem it solved.")
      .value("feasible", lmi::SdpStatus::feasible)
      .value("infeasible", lmi::SdpStatus::infeasible)
      .value("unbounded", lmi::SdpStatus::unbounded)
      .value("unknown", lmi::SdpStatus::unknown)
      .value("error", lmi::SdpStatus::error);

  nb::class_<lmi::SdpSolution>(m, "SdpSolution", "What DSDP returned.")
      .def_ro("status", &lmi::SdpSolution::status)
      .def_ro("y", &lmi::SdpSolution::y, "the point (decision variables)")
      .def_ro("infeasibility", &lmi::SdpSolution::infeasibility, "DSDP's r >= 0: r > 0 means the LMIs were not met")
      .def_ro("objective", &lmi::SdpSolution::objective)
      .def_ro("iterations", &lmi::SdpSolution::iterations)
      .def_ro("seconds", &lmi::SdpSolution::seconds)
      .def_ro("stop_reason", &lmi::SdpSolution::stop_reason)
      .def_ro("message", &lmi::SdpSolution::message);

  nb::class_<Synthesis>(m, "TakagiSugenoSynthesis", "Result of synthesize_takagi_sugeno_gains.")
      .def_ro("status", &Synthesis::status)
      .def_ro("gains", &Synthesis::gains, "L_i = P0^-1 R_i, K_{y,i} = P1^-1 F_i (31) and K_theta; None unless feasible")
      .def_ro("certificate", &Synthesis::certificate, "the point DSDP returned")
      .def_ro("check", &Synthesis::check, "the independent eigenvalue check of that point")
      .def_ro("beta", &Synthesis::beta, "corollary 1: the minimised beta (NaN for the other objectives)")
      .def_ro("margin", &Synthesis::margin, "the margin t of maximize_margin (NaN otherwise)")
      .def_ro("solver", &Synthesis::solver)
      .def_ro("message", &Synthesis::message)
      .def_prop_ro("feasible", &Synthesis::feasible);

  m.def(
      "synthesize_takagi_sugeno_gains",
      [](nb::handle model, TakagiSugenoTheorem theorem, std::optional<ParameterErrorModel> error_model, nb::handle Q_x,
         nb::handle Q_theta, nb::handle K_theta, nb::handle parameter_gain, nb::handle min_parameter_gain,
         nb::handle fixed_lambda, nb::handle fixed_gamma, TakagiSugenoObjective objective, nb::handle margin,
         nb::handle variable_bound, nb::handle penalty, nb::handle gap_tolerance, nb::handle max_iterations) {
        constexpr std::string_view who = "synthesize_takagi_sugeno_gains";
        const TsModel& ts = ts_model(model, who);
        TakagiSugenoLmiOptions o;
        o.theorem = theorem;
        o.error_model = error_model;
        o.Q_x = matrix_or_empty(Q_x, who, "Q_x");
        o.Q_theta = matrix_or_empty(Q_theta, who, "Q_theta");
        o.K_theta = matrix_or_empty(K_theta, who, "K_theta");
        o.parameter_gain = matrix_or_empty(parameter_gain, who, "parameter_gain");
        if (!min_parameter_gain.is_none())
          o.min_parameter_gain = real_scalar(min_parameter_gain, who, "min_parameter_gain");
        if (!fixed_lambda.is_none()) o.fixed_lambda = four_numbers(fixed_lambda, who, "fixed_lambda");
        if (!fixed_gamma.is_none()) o.fixed_gamma = real_scalar(fixed_gamma, who, "fixed_gamma");
        o.objective = objective;
        o.margin = real_scalar(margin, who, "margin");
        o.solver.variable_bound = real_scalar(variable_bound, who, "variable_bound");
        o.solver.penalty = real_scalar(penalty, who, "penalty");
        o.solver.gap_tolerance = real_scalar(gap_tolerance, who, "gap_tolerance");
        const Index iterations = integer_argument(max_iterations, who, "max_iterations");
        adaptobs::require(iterations >= 1 && iterations <= std::numeric_limits<int>::max(), who, "max_iterations",
                          "must be at least 1 and fit an int");
        o.solver.max_iterations = static_cast<int>(iterations);
        Synthesis result;
        {
          // The solve reads the vertex matrices only, never the premise callable.
          nb::gil_scoped_release release;
          result = synthesize_takagi_sugeno_gains(ts, o);
        }
        // A point DSDP returned that fails the independent check, or a failed DSDP call, is
        // no answer at the stated margin: refused with the library's message. An
        // infeasibility DSDP proved is an answer, returned with its status.
        if (result.status == SynthesisStatus::not_verified || result.status == SynthesisStatus::solver_failed)
          adaptobs::fail_argument(who, "model",
                                  std::string("gives no verified solution (") + std::string(to_string(result.status)) +
                                      "): " + result.message);
        return result;
      },
      nb::arg("model"), nb::kw_only(), nb::arg("theorem") = TakagiSugenoTheorem::constant_parameters,
      nb::arg("error_model").none() = nb::none(), nb::arg("Q_x").none() = nb::none(),
      nb::arg("Q_theta").none() = nb::none(), nb::arg("K_theta").none() = nb::none(),
      nb::arg("parameter_gain").none() = nb::none(), nb::arg("min_parameter_gain").none() = nb::none(),
      nb::arg("fixed_lambda").none() = nb::none(), nb::arg("fixed_gamma").none() = nb::none(),
      nb::arg("objective") = TakagiSugenoObjective::minimize_beta, nb::arg("margin") = 1e-7,
      nb::arg("variable_bound") = 1e12, nb::arg("penalty") = 1e10, nb::arg("gap_tolerance") = 1e-7,
      nb::arg("max_iterations") = 500,
      "Designs the gains of a TakagiSugenoObserver by theorem 2 (or theorem 1 with K_theta) of Srinivasarengan\n"
      "et al. (2018), optionally minimising beta (corollary 1, (56)-(57)), solving the LMIs with DSDP (GIL\n"
      "released) and verifying the point independently (check_takagi_sugeno_certificate). Keywords are the\n"
      "fields of the C++ TakagiSugenoLmiOptions (and of its DsdpOptions): Q_x, Q_theta (default I; Remark 4),\n"
      "error_model (default: as_printed for theorem 2, exact for theorem 1), K_theta (theorem 1),\n"
      "parameter_gain (K_{y,i} = K imposed, F_i = P1 K; Remark 6), min_parameter_gain (F_i >= kappa P1, (62)),\n"
      "fixed_lambda (4 values), fixed_gamma (Remark 7), objective, margin (epsilon of the strict inequalities).\n"
      "Returns a TakagiSugenoSynthesis: status feasible with the gains L_i = P0^-1 R_i, K_{y,i} = P1^-1 F_i (31),\n"
      "or infeasible (DSDP's claim) without gains. A point that fails the check, or a failed solve, raises\n"
      "ConfigurationError with the library's message.");
}
#endif

// --- The waste water treatment plant of §6 (adaptobs.examples) ---------------------------

namespace wwtp = adaptobs::examples::wwtp;

nb::list vertex_list(const wwtp::Model<double>& model) {
  nb::list out;
  for (Index i = 0; i < model.vertex_count(); ++i)
    out.append(nb::make_tuple(Eigen::MatrixXd(model.A(i)), Eigen::MatrixXd(model.B(i))));
  return out;
}

template <class Bounds>
nb::tuple bounds_tuple(const Bounds& b) {
  return nb::make_tuple(Eigen::VectorXd(b.lower), Eigen::VectorXd(b.upper));
}

nb::dict wwtp_system() {
  const auto model = wwtp::model<double>();
  const auto lmi_model = wwtp::model<double>(0.05);
  const auto paper = wwtp::paper_gains<double>();
  nb::dict d;
  d["vertices"] = vertex_list(model);
  d["C"] = Eigen::MatrixXd(wwtp::output_matrix<double>());
  d["premise_bounds"] = bounds_tuple(wwtp::premise_bounds<double>());
  d["parameter_bounds"] = bounds_tuple(wwtp::parameter_bounds<double>());
  d["lmi_vertices"] = vertex_list(lmi_model);
  d["lmi_premise_bounds"] = bounds_tuple(wwtp::premise_bounds<double>(0.05));
  nb::list L, K;
  for (const auto& l : paper.L) L.append(Eigen::MatrixXd(l));
  for (const auto& k : paper.K) K.append(Eigen::MatrixXd(k));
  d["L"] = L;
  d["K"] = K;
  d["a0"] = wwtp::a0;
  d["b"] = wwtp::b;
  d["c"] = wwtp::c;
  d["d"] = wwtp::d;
  d["Ts"] = wwtp::sampling_period;
  d["theta"] = Eigen::VectorXd(Eigen::VectorXd::Constant(1, 0.1));
  d["x0"] = Eigen::VectorXd(wwtp::initial_state<double>());
  d["x0_estimate"] = Eigen::VectorXd(wwtp::initial_state_estimate<double>());
  d["theta0_estimate"] = Eigen::VectorXd(wwtp::initial_parameter_estimate<double>());
  const wwtp::DilutionRate rate;
  d["input_mean"] = rate.mean;
  d["input_amplitude"] = rate.amplitude;
  d["input_period"] = rate.period;
  // The LMI design of the C++ example (theorem 2, Remark 6): Q_e and the imposed K_i.
  d["lmi_Q_x"] = Eigen::MatrixXd(1e-3 * Eigen::MatrixXd::Identity(2, 2));
  d["lmi_Q_theta"] = Eigen::MatrixXd(Eigen::MatrixXd::Constant(1, 1, 0.1));
  d["lmi_parameter_gain"] = Eigen::MatrixXd(Eigen::MatrixXd::Constant(1, 1, 0.03));
  return d;
}

// `steps` samples of plant (72) with constant theta from x0 = (4, 0.3) under the
// dilution rate, and the output channels that arrive under `drop` and `outage`
// drawn from `seed` as the C++ example's OutputLoss draws them.
nb::dict simulate_wwtp(Index steps, double theta, double drop, nb::handle outage, std::uint64_t seed) {
  constexpr std::string_view who = "examples.simulate_wwtp";
  adaptobs::require(steps >= 0, who, "steps", "must be non-negative");
  adaptobs::require(std::isfinite(theta), who, "theta", "must be finite");
  OutputLossOptions options{.drop = drop, .seed = seed};
  if (!outage.is_none()) {
    if (!is_sequence(outage) || nb::len(outage) != 2) fail_type(who, "outage", outage, "a pair (t0, t1) or None");
    options.outage_begin = real_scalar(outage[0], who, "outage[0]");
    options.outage_end = real_scalar(outage[1], who, "outage[1]");
  }
  OutputLoss loss(options);
  auto plant = wwtp::make_plant<double>(theta);
  const auto n = static_cast<std::size_t>(steps);
  OutputArray t({n}), u({n, 1}), y({n, 1}), x({n, 2}), th({n, 1});
  NewArray<bool> present({n, 1});
  for (Index k = 0; k < steps; ++k, plant.advance()) {
    const auto& sample = plant.sample();
    present.data[k] = loss.channels_at<wwtp::Dims<double>>(plant.time(), 1)(0);
    t.data[k] = plant.time();
    u.data[k] = sample.u(0);
    y.data[k] = sample.y(0);
    x.data[2 * k] = plant.state()(0);
    x.data[2 * k + 1] = plant.state()(1);
    th.data[k] = plant.parameters()(0);
  }
  nb::dict d;
  d["t"] = t.array;
  d["U"] = u.array;
  d["Y"] = y.array;
  d["present"] = present.array;
  d["X"] = x.array;
  d["theta"] = th.array;
  return d;
}

void bind_wwtp(nb::module_& examples) {
  examples.def(
      "wwtp", &wwtp_system,
      "The simplified waste water treatment plant of Srinivasarengan et al. (2018), section 6: plant (72)\n"
      "with a = a0 + theta, premise variables (75) z1 = u, z2 = x1 / (x2 + b) (uses the unmeasured x2),\n"
      "the eight vertices (A_i, B_i) of (77) on the sectors (74), (76) (`vertices`, `premise_bounds`,\n"
      "`parameter_bounds`, C), the printed gains L_i and K_i = 0.03 (`L`, `K`), Ts, the constants a0, b, c, d,\n"
      "theta = 0.1 of the C++ example, the initial state and estimates, the dilution rate\n"
      "u_k = mean + amplitude sin(2 pi k / period), and the C++ example's LMI design: the input sector\n"
      "[0.05, 0.4] (`lmi_vertices`, `lmi_premise_bounds`), Q_x, Q_theta and the imposed K (Remark 6).\n"
      "Give a TakagiSugenoModel the premise function yourself, e.g.\n"
      "  def premises(x, u, theta): return np.array([u[0], x[0] / (x[1] + 0.4)])");
  examples.def("simulate_wwtp", &simulate_wwtp, nb::arg("steps") = 500, nb::arg("theta") = 0.1, nb::arg("drop") = 0.0,
               nb::arg("outage").none() = nb::none(), nb::arg("seed") = 1,
               "`steps` samples of plant (72) with constant theta from x0 = (4, 0.3) under the dilution rate (the C++\n"
               "example's plant), and which outputs arrive: each sample lost with probability `drop` (drawn from\n"
               "`seed`) or inside `outage` = (t0, t1), as the example's --drop, --outage and --seed. A dict of t, U,\n"
               "Y, present (N x 1 booleans), the true states X and theta, sample k in row k.");
}

}  // namespace

void bind_takagi_sugeno(nb::module_& m) {
  bind_model(m);
  bind_observer(m);
  bind_lmi(m);
#ifdef ADAPTOBS_PYTHON_HAS_LMI
  bind_synthesis(m);
  m.attr("has_lmi") = true;
#else
  m.attr("has_lmi") = false;
#endif
  nb::module_ examples = nb::borrow<nb::module_>(m.attr("examples"));
  bind_wwtp(examples);
}

}  // namespace adaptobs::python
