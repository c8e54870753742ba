// Certificates and checks: Guiro's convergence conditions (Guiro et al. 2008,
// proposition 2.2), the SPR tests and the KYP certificate (Zhang 2005,
// §III-A, §III-B), the Floquet test of periodic systems, the thresholds and
// distributions of the detectors, and the Monte-Carlo evaluation of a
// detector. Each check returns the figures its verdict rests on.

#include "arrays.hpp"

#include <adaptobs/design/guiro_convergence.hpp>
#include <adaptobs/design/ltv_stability.hpp>
#include <adaptobs/design/positive_real.hpp>
#include <adaptobs/design/spr_test.hpp>
#include <adaptobs/diagnostics/calibration.hpp>
#include <adaptobs/diagnostics/chi_square_distribution.hpp>
#include <adaptobs/diagnostics/cusum.hpp>
#include <adaptobs/diagnostics/glr.hpp>
#include <adaptobs/simulation/detection_evaluation.hpp>

#include <nanobind/eigen/dense.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <cstdint>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <tuple>
#include <utility>
#include <vector>

namespace adaptobs::python {

namespace {

using Report = GuiroConvergenceReport<double>;
using GuiroPowerBound = PowerBound<double>;  // of U, in the Guiro report
using Conditions = SprConditions<double>;
using Test = SprTest<double>;
using Sweep = SprSweep<double>;
using Kyp = KypCertificate<double, Eigen::Dynamic>;

// ---- Arguments ---------------------------------------------------------------

/// A column argument b of a single-input triple: a 1-D array of length n, or an n x 1 matrix.
Eigen::MatrixXd column_argument(nb::handle obj, std::string_view who, std::string_view name) {
  return matrix(obj, who, name);  // a 1-D array is read as a column
}

/// A row argument c of a single-output pair: a 1-D array of length n, or a 1 x n matrix.
Eigen::MatrixXd row_argument(nb::handle obj, std::string_view who, std::string_view name) {
  const Array a = real_array(obj, who, name);
  if (a.ndim() == 1) return view(a, who, name).transpose();
  return view(a, who, name);
}

/// The polynomial coefficients of an argument, highest power first (a 1-D array or a scalar).
Polynomial<double> coefficients_argument(nb::handle obj, std::string_view who, std::string_view name) {
  return vector(obj, who, name);
}

/// H_0, ..., H_{N-1} of `check_guiro_convergence`: an N x n x p array (N = 0: an empty array).
std::vector<Eigen::MatrixXd> regressor_sequence(nb::handle obj, Index n, Index p, std::string_view who,
                                                std::string_view name) {
  const Array a = real_array(obj, who, name);
  std::vector<Eigen::MatrixXd> sequence;
  if (a.ndim() == 1 && a.shape(0) == 0) return sequence;
  if (a.ndim() != 3 || static_cast<Index>(a.shape(1)) != n || static_cast<Index>(a.shape(2)) != p)
    fail_dimensions(who, name, "an N x " + std::to_string(n) + " x " + std::to_string(p) + " array (H_k in row k)",
                    shape_of(a));
  const Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic> stride(static_cast<Index>(a.stride(2)),
                                                             static_cast<Index>(a.stride(1)));
  sequence.reserve(a.shape(0));
  for (std::size_t k = 0; k < a.shape(0); ++k)
    sequence.emplace_back(MatrixView(a.data() + static_cast<Index>(k) * static_cast<Index>(a.stride(0)), n, p, stride));
  return sequence;
}

/// A count argument that the library takes as an int.
int int_argument(nb::handle obj, std::string_view who, std::string_view name) {
  const Index value = integer_argument(obj, who, name);
  adaptobs::require(value >= std::numeric_limits<int>::min() && value <= std::numeric_limits<int>::max(), who, name,
                    "must fit an int");
  return static_cast<int>(value);
}

// ---- A(t) of the periodic checks -----------------------------------------------

/// A(t) from Python: a callable returning an n x n array, or a constant array.
/// The routines run with the GIL released; a callable takes it back for each
/// evaluation (four per RK4 step). Its first value fixes n; every later value
/// must have that shape, or the error names 'A', both shapes and the time. An
/// exception the callable raises propagates as it is.
struct PythonDynamics {
  nb::handle source;
  bool callable = false;
  Eigen::MatrixXd constant;
  std::string_view who;
  mutable std::vector<std::size_t> first_shape;  // empty until the first value

  Eigen::MatrixXd operator()(double t) const {
    if (!callable) return constant;
    nb::gil_scoped_acquire gil;
    const nb::object value = source(t);
    const Array a = real_array(value, who, "A");
    const std::vector<std::size_t> shape = shape_of(a);
    if (first_shape.empty()) {
      if (a.ndim() != 2 || a.shape(0) != a.shape(1)) {
        std::ostringstream os;
        os << "must return a square matrix, an n x n array (got " << shape_text(shape) << " at t = " << t << ")";
        adaptobs::fail_argument(who, "A", os.str());
      }
      first_shape = shape;
    } else if (shape != first_shape) {
      std::ostringstream os;
      os << "must return an array of its first value's shape " << shape_text(first_shape) << " at every t (got "
         << shape_text(shape) << " at t = " << t << ")";
      adaptobs::fail_argument(who, "A", os.str());
    }
    return view(a, who, "A");
  }
};

PythonDynamics dynamics_of(nb::handle A, std::string_view who) {
  PythonDynamics d;
  d.source = A;
  d.who = who;
  d.callable = PyCallable_Check(A.ptr()) != 0;
  if (!d.callable) {
    d.constant = matrix(A, who, "A");
    adaptobs::require_square(d.constant, who, "A");
  }
  return d;
}

// ---- The Monte-Carlo evaluation ---------------------------------------------------

/// One run from Python: a MonitoredRun, or a tuple (start, end, times) or
/// (start, end, times, isolated).
MonitoredRun alarm_run(double start, double end, nb::handle times, nb::handle isolated, std::string_view who,
                       const std::string& times_name, const std::string& isolated_name) {
  MonitoredRun run{start, end, {}};
  if (times.is_none()) {
    if (!isolated.is_none()) adaptobs::fail_argument(who, isolated_name, "must come with the alarm times");
    return run;
  }
  const Eigen::VectorXd t = vector(times, who, times_name);
  run.alarms.resize(static_cast<std::size_t>(t.size()));
  for (Index i = 0; i < t.size(); ++i) run.alarms[static_cast<std::size_t>(i)].time = t(i);
  if (!isolated.is_none()) {
    const auto which = as_array<nb::ndarray<const std::int64_t, nb::device::cpu>>(
        isolated, who, isolated_name, "int64", "an array of parameter indices (integers)", "iu");
    if (which.ndim() != 1 || static_cast<Index>(which.shape(0)) != t.size())
      fail_dimensions(who, isolated_name, "(" + std::to_string(t.size()) + ",), one per alarm time", shape_of(which));
    for (Index i = 0; i < t.size(); ++i)
      run.alarms[static_cast<std::size_t>(i)].isolated = static_cast<Index>(which.data()[i * which.stride(0)]);
  }
  return run;
}

MonitoredRun run_of(nb::handle obj, std::string_view who, std::string_view name) {
  MonitoredRun* run = nullptr;
  if (nb::try_cast<MonitoredRun*>(obj, run, false) && run != nullptr) return *run;
  if (nb::isinstance<nb::tuple>(obj)) {
    const auto items = nb::borrow<nb::tuple>(obj);
    const std::size_t n = nb::len(items);
    if (n == 3 || n == 4) {
      const nb::object start = items[0], end = items[1], times = items[2];
      const nb::object isolated = n == 4 ? nb::object(items[3]) : nb::none();
      const std::string item(name);
      return alarm_run(real_scalar(start, who, item + "[0] (start)"), real_scalar(end, who, item + "[1] (end)"), times,
                       isolated, who, item + "[2] (alarm times)", item + "[3] (isolated)");
    }
  }
  fail_type(who, name, obj,
            "an adaptobs.MonitoredRun or a tuple (start, end, alarm_times) or (start, end, alarm_times, isolated)");
}

/// scenario(seed, faulty) from Python, called concurrently by the evaluator's
/// threads: each call takes the GIL back, and converts what it returns before
/// letting it go (the Python objects are touched only under the GIL).
struct PythonScenario {
  nb::handle function;

  MonitoredRun operator()(std::uint64_t seed, bool faulty) const {
    nb::gil_scoped_acquire gil;
    const nb::object run = function(seed, faulty);
    return run_of(run, "evaluate_detection", "scenario(seed, faulty)");
  }
};

/// Recorded runs: the faulty and fault-free run of seed first_seed + i at index i.
struct RecordedScenario {
  const std::vector<MonitoredRun>* faulty;
  const std::vector<MonitoredRun>* twins;
  std::uint64_t first_seed;

  MonitoredRun operator()(std::uint64_t seed, bool is_faulty) const {
    return (is_faulty ? *faulty : *twins)[static_cast<std::size_t>(seed - first_seed)];
  }
};

std::vector<MonitoredRun> recorded_runs(nb::handle obj, std::string_view who, std::string_view name) {
  if (!nb::isinstance<nb::sequence>(obj) || nb::isinstance<nb::str>(obj))
    fail_type(who, name, obj, "a list of runs, one per seed");
  std::vector<MonitoredRun> runs;
  std::size_t i = 0;
  for (nb::handle run : obj) runs.push_back(run_of(run, who, detail::element_name(name, i++)));
  return runs;
}

FaultDescription fault_of(nb::handle obj, std::string_view who) {
  FaultDescription* fault = nullptr;
  if (nb::try_cast<FaultDescription*>(obj, fault, false) && fault != nullptr) return *fault;
  if (PyFloat_Check(obj.ptr()) || (PyIndex_Check(obj.ptr()) && !PyBool_Check(obj.ptr())))
    return {real_scalar(obj, who, "fault"), -1};
  fail_type(who, "fault", obj, "an adaptobs.FaultDescription or the fault's time");
}

DetectionSummary evaluate(nb::handle scenario, nb::handle fault_obj, nb::handle seeds_obj, nb::handle first_seed_obj,
                          nb::handle threads_obj) {
  constexpr std::string_view who = "evaluate_detection";
  const FaultDescription fault = fault_of(fault_obj, who);
  const Index first = integer_argument(first_seed_obj, who, "first_seed");
  adaptobs::require(first >= 0, who, "first_seed", "must be non-negative");
  const Index threads = integer_argument(threads_obj, who, "threads");
  adaptobs::require(threads >= 0 && threads <= std::numeric_limits<unsigned>::max(), who, "threads",
                    "must be non-negative (0: one per core)");
  const auto first_seed = static_cast<std::uint64_t>(first);
  if (PyCallable_Check(scenario.ptr())) {
    if (seeds_obj.is_none()) adaptobs::fail_argument(who, "seeds", "is required when the scenario is a callable");
    const Index seeds = integer_argument(seeds_obj, who, "seeds");
    const PythonScenario python{scenario};
    nb::gil_scoped_release release;  // each scenario call takes the GIL back
    return evaluate_detection(python, fault, first_seed, seeds, static_cast<unsigned>(threads));
  }
  // Recorded runs: (faulty runs, fault-free runs), one of each per seed.
  if (!nb::isinstance<nb::sequence>(scenario) || nb::isinstance<nb::str>(scenario) || nb::len(scenario) != 2)
    fail_type(who, "scenario", scenario,
              "a callable scenario(seed, faulty) or a pair (faulty_runs, fault_free_runs) of recorded runs");
  const nb::object faulty_runs = scenario[0], fault_free_runs = scenario[1];
  const std::vector<MonitoredRun> faulty = recorded_runs(faulty_runs, who, "scenario[0]");
  const std::vector<MonitoredRun> twins = recorded_runs(fault_free_runs, who, "scenario[1]");
  adaptobs::require(faulty.size() == twins.size(), who, "scenario[1]",
                    "must hold one fault-free run per faulty run of scenario[0] (" + std::to_string(faulty.size()) +
                        ", got " + std::to_string(twins.size()) + ")");
  const auto recorded = static_cast<Index>(faulty.size());
  const Index seeds = seeds_obj.is_none() ? recorded : integer_argument(seeds_obj, who, "seeds");
  adaptobs::require(
      seeds == recorded, who, "seeds",
      "must equal the number of recorded runs (" + std::to_string(recorded) + ", got " + std::to_string(seeds) + ")");
  const RecordedScenario replay{&faulty, &twins, first_seed};
  nb::gil_scoped_release release;
  return evaluate_detection(replay, fault, first_seed, seeds, static_cast<unsigned>(threads));
}

/// A vector of doubles as a NumPy array.
Eigen::VectorXd array_of(const std::vector<double>& values) {
  return Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Index>(values.size()));
}

// The window, mean_evaluations and components of the GLR threshold functions, checked and named.
std::tuple<Index, double, Index> glr_arguments(nb::handle window, nb::handle mean_evaluations, nb::handle components,
                                               std::string_view who) {
  return {integer_argument(window, who, "window"), real_scalar(mean_evaluations, who, "mean_evaluations"),
          integer_argument(components, who, "components")};
}

}  // namespace

void bind_checks(nb::module_& m) {
  // ---- Guiro et al. (2008), proposition 2.2 -----------------------------------------
  nb::enum_<ConditionVerdict>(m, "ConditionVerdict",
                              "Whether a sufficient condition holds on the data: an enum.Enum whose names are the C++\n"
                              "to_string's, 'holds', 'fails' and 'undetermined'.")
      .value("holds", ConditionVerdict::holds)
      .value("fails", ConditionVerdict::fails)
      .value("undetermined", ConditionVerdict::undetermined);

  nb::class_<GuiroPowerBound>(m, "PowerBound",
                              "||U^k||_2 <= M lambda^k for every k >= 0 (the smallest M for that lambda).")
      .def_ro("lambda_", &GuiroPowerBound::lambda, "the rate lambda in (rho(U), 1)")
      .def_ro("M", &GuiroPowerBound::M)
      .def_prop_ro("perturbation_margin", &GuiroPowerBound::perturbation_margin,
                   "(1 - lambda) / M: the ||W(k)|| that v_{k+1} = (U + W(k)) v_k tolerates (proposition 2.1 (i))")
      .def("__repr__", [](const GuiroPowerBound& b) {
        std::ostringstream os;
        os.precision(17);
        os << "PowerBound(lambda_=" << b.lambda << ", M=" << b.M << ")";
        return os.str();
      });

  nb::class_<Report>(m, "GuiroConvergenceReport",
                     "Outcome of check_guiro_convergence: proposition 2.2 of Guiro et al. (2008) on the data.\n"
                     "The errors obey v_{k+1} = (U + W(k)) v_k, ||W(k)||_2 = ||(I - K C) E (H_k - Hbar)||_2;\n"
                     "(i) ||W(k)|| < (1 - lambda)/M from k0 on, (ii) sum_k ||W(k)|| finite.")
      .def_ro("spectral_radius", &Report::spectral_radius, "rho(U) at the chosen Hbar")
      .def_ro("bound", &Report::bound, "the PowerBound of U maximizing (1 - lambda)/M; None when U is not Schur")
      .def_prop_ro(
          "w_norms", [](const Report& r) { return array_of(r.w_norms); }, "||W(k)||_2 for the supplied H_k")
      .def_ro("condition_i", &Report::condition_i, "ConditionVerdict of (i)")
      .def_ro("k0", &Report::k0, "first index from which ||W(k)|| < (1 - lambda)/M on the data; None if none")
      .def_ro("tail_sup", &Report::tail_sup, "sup_{k >= k0} ||W(k)|| on the data")
      .def_ro("rate", &Report::rate, "lambda + M tail_sup: the decay rate (i) certifies")
      .def_ro("condition_ii", &Report::condition_ii,
              "ConditionVerdict of (ii), from the fit ||W(k)|| ~ k^-alpha over the second half of the data:\n"
              "holds when W vanishes there or alpha > 1.25, fails when alpha < 0.75, else undetermined")
      .def_ro("w_sum", &Report::w_sum, "sum_k ||W(k)|| over the data")
      .def_ro("decay_exponent", &Report::decay_exponent, "alpha (inf when W vanishes on the second half)")
      .def_prop_ro("certified", &Report::certified, "U is Schur and (i) or (ii) holds on the data")
      .def("summary", &Report::summary, "One paragraph in words.")
      .def("__repr__", &Report::summary);

  m.def(
      "check_guiro_convergence",
      [](nb::handle E, nb::handle C, nb::handle K, nb::handle Gamma, nb::handle Hbar, nb::handle H_sequence) {
        constexpr std::string_view who = "check_guiro_convergence";
        const Eigen::MatrixXd e = matrix(E, who, "E"), h = matrix(Hbar, who, "Hbar");
        adaptobs::require_square(e, who, "E");
        const std::vector<Eigen::MatrixXd> sequence =
            regressor_sequence(H_sequence, e.rows(), h.cols(), who, "H_sequence");
        return check_guiro_convergence(e, matrix(C, who, "C"), matrix(K, who, "K"), matrix(Gamma, who, "Gamma"), h,
                                       sequence);
      },
      nb::arg("E"), nb::arg("C"), nb::arg("K"), nb::arg("Gamma"), nb::arg("Hbar"), nb::arg("H_sequence"),
      "Proposition 2.2 of Guiro et al. (2008) for the gains (K, Gamma), the nominal regressor Hbar and the\n"
      "regressors H_0, ..., H_{N-1} of the data (an N x n x p array; examples.simulate_guiro's Psi holds\n"
      "Psi_k = E H_k): U at Hbar\n"
      "and its best power bound ||U^k|| <= M lambda^k, then proposition 2.1's conditions (i)\n"
      "||W(k)|| < (1 - lambda)/M from some k0 and (ii) sum ||W(k)|| < inf on the data. A failed check is not\n"
      "a proof of divergence: around H0 the paper's example certifies nothing, around the limit Hbar (i) holds.");

  // ---- Strict positive realness (Zhang 2005, §III-A, §III-B) --------------------------
  nb::class_<Conditions>(m, "SprConditions",
                         "The verdict of the exact SPR test of G = N/D and the figures it rests on: D Hurwitz,\n"
                         "relative degree 1 with a positive leading coefficient of N, and q(w) = Re G(j sqrt w)\n"
                         "|D(j sqrt w)|^2 positive on [0, inf) with degree n - 1 and a positive leading coefficient.")
      .def_ro("strictly_positive_real", &Conditions::strictly_positive_real)
      .def_ro("denominator_hurwitz", &Conditions::denominator_hurwitz)
      .def_ro("relative_degree", &Conditions::relative_degree)
      .def_ro("high_frequency_gain", &Conditions::high_frequency_gain,
              "leading coefficient of N (= c b when the relative degree is 1)")
      .def_ro("q_positive_on_nonnegative_axis", &Conditions::q_positive_on_nonnegative_axis,
              "q(0) > 0 and no real root of q in [0, inf) (Sturm count)")
      .def_ro("strict_at_infinity", &Conditions::strict_at_infinity,
              "deg q = n - 1 with a positive leading coefficient: lim w^2 Re G(jw) > 0")
      .def("__bool__", [](const Conditions& c) { return c.strictly_positive_real; });
  nb::class_<Test, Conditions>(m, "SprTest", "The exact SPR test with its polynomial q.")
      .def_prop_ro(
          "q", [](const Test& t) { return Eigen::VectorXd(t.q); },
          "q(w) = Re G(j sqrt w) |D(j sqrt w)|^2, highest power first");
  nb::class_<Sweep>(m, "SprSweep", "Frequency-sweep cross-check of strict positive realness, with its margins.")
      .def_ro("strictly_positive_real", &Sweep::strictly_positive_real)
      .def_ro("hurwitz", &Sweep::hurwitz)
      .def_ro("min_weighted_real_part", &Sweep::min_weighted_real_part,
              "min over the grid of (1 + w^2) Re G(jw): the margin at finite frequencies")
      .def_ro("at_frequency", &Sweep::at_frequency, "w of that minimum")
      .def_ro("high_frequency_limit", &Sweep::high_frequency_limit, "lim w^2 Re G(jw) = -c A b: the margin at infinity")
      .def("__bool__", [](const Sweep& s) { return s.strictly_positive_real; });
  nb::class_<Kyp>(m, "KypCertificate",
                  "A Kalman-Yakubovich-Popov certificate of c (sI - A)^-1 b being SPR: P = P^T > 0 with\n"
                  "A^T P + P A < 0 and P b = c^T, and its residuals.")
      .def_ro("P", &Kyp::P)
      .def_ro("equality_residual", &Kyp::equality_residual, "||P b - c^T||_inf")
      .def_ro("min_eigenvalue_P", &Kyp::min_eigenvalue_P, "lambda_min(P) (> 0)")
      .def_ro("max_eigenvalue_lyapunov", &Kyp::max_eigenvalue_lyapunov, "lambda_max(A^T P + P A) (< 0)");

  m.def(
      "strictly_positive_real",
      [](nb::handle numerator, nb::handle denominator) {
        constexpr std::string_view who = "strictly_positive_real";
        return strictly_positive_real<double>(coefficients_argument(numerator, who, "numerator"),
                                              coefficients_argument(denominator, who, "denominator"));
      },
      nb::arg("numerator"), nb::arg("denominator"),
      "Exact SPR test of G = N/D: coefficients highest power first, D monic of degree n, deg N < n.\n"
      "D by Routh-Hurwitz, the real roots of q(w) = Re G(j sqrt w) |D(j sqrt w)|^2 by a Sturm sequence\n"
      "(no root finding). (s + 2)/((s + 1)(s + 3)) is SPR; (s + 3)/((s + 1)(s + 2)) is not: w^2 Re G(jw) -> 0.\n"
      "Algorithms 1 and 2 of Zhang (2005, sections III-A, III-B) converge when c_o (sI - A_o + k c_o)^-1 gamma is "
      "SPR.");
  m.def(
      "strictly_positive_real",
      [](nb::handle A, nb::handle b, nb::handle c) {
        constexpr std::string_view who = "strictly_positive_real";
        const Eigen::MatrixXd a = matrix(A, who, "A"), bb = column_argument(b, who, "b"),
                              cc = row_argument(c, who, "c");
        detail::require_siso_triple(a, bb, cc, who);
        return strictly_positive_real(a, bb, cc);
      },
      nb::arg("A"), nb::arg("b"), nb::arg("c"),
      "Exact SPR test of G(s) = c (sI - A)^-1 b (b a column, c a row: 1-D arrays of length n or matrices).");
  m.def(
      "spr_conditions",
      [](nb::handle numerator, nb::handle denominator) {
        constexpr std::string_view who = "spr_conditions";
        const Polynomial<double> n = coefficients_argument(numerator, who, "numerator");
        const Polynomial<double> d = coefficients_argument(denominator, who, "denominator");
        try {
          return SprConditions<double>(strictly_positive_real(n, d));
        } catch (const ConfigurationError& e) {
          // The shared test names itself strictly_positive_real; the caller called this.
          constexpr std::string_view shared = "strictly_positive_real";
          const std::string message = e.what();
          if (message.starts_with(shared)) throw ConfigurationError(std::string(who) + message.substr(shared.size()));
          throw;
        }
      },
      nb::arg("numerator"), nb::arg("denominator"),
      "The verdict of the exact SPR test of G = N/D and its figures, without q (strictly_positive_real\n"
      "returns them with q).");
  m.def(
      "spr_frequency_sweep",
      [](nb::handle A, nb::handle b, nb::handle c, nb::handle omega_min, nb::handle omega_max, nb::handle points) {
        constexpr std::string_view who = "spr_frequency_sweep";
        return spr_frequency_sweep(matrix(A, who, "A"), column_argument(b, who, "b"), row_argument(c, who, "c"),
                                   real_scalar(omega_min, who, "omega_min"), real_scalar(omega_max, who, "omega_max"),
                                   int_argument(points, who, "points"));
      },
      nb::arg("A"), nb::arg("b"), nb::arg("c"), nb::arg("omega_min") = 1e-4, nb::arg("omega_max") = 1e4,
      nb::arg("points") = 2001,
      "Samples (1 + w^2) Re G(jw) at w = 0 and on a logarithmic grid of [omega_min, omega_max]; SPR when it\n"
      "is positive, A is Hurwitz and -c A b > 0 (the weighting keeps round-off from reading as a sign where\n"
      "Re G decays like w^-2).");
  m.def(
      "kyp_certificate",
      [](nb::handle A, nb::handle b, nb::handle c) -> std::optional<Kyp> {
        constexpr std::string_view who = "kyp_certificate";
        return kyp_certificate(matrix(A, who, "A"), column_argument(b, who, "b"), row_argument(c, who, "c"));
      },
      nb::arg("A"), nb::arg("b"), nb::arg("c"),
      "KYP certificate of an SPR c (sI - A)^-1 b without an SDP solver, or None when G is not SPR. In\n"
      "coordinates x' = [c; N_perp] x, P' = diag(1/cb, X) and X solves the Riccati equation\n"
      "At^T X + X At + X r r^T X / delta + q q^T / ((cb)^2 delta) + eps I = 0 from its Hamiltonian;\n"
      "the P returned is verified: ||P b - c^T|| <= 1e-10 ||c||, P > 0, lambda_max(A^T P + P A) < -1e-9 ||P|| ||A||.");
  m.def(
      "kyp_residuals",
      [](nb::handle P, nb::handle A, nb::handle b, nb::handle c) {
        constexpr std::string_view who = "kyp_residuals";
        const Eigen::MatrixXd a = matrix(A, who, "A"), bb = column_argument(b, who, "b"),
                              cc = row_argument(c, who, "c");
        const Index n = detail::require_siso_triple(a, bb, cc, who);
        const Eigen::MatrixXd p = matrix(P, who, "P");
        adaptobs::require_finite_shape(p, n, n, who, "P");
        return kyp_residuals(p, a, bb, cc);
      },
      nb::arg("P"), nb::arg("A"), nb::arg("b"), nb::arg("c"),
      "Residuals of a candidate certificate P: ||P b - c^T||_inf, lambda_min(P), lambda_max(A^T P + P A).");
  m.def(
      "ackermann_observer_gain",
      [](nb::handle A, nb::handle c, nb::handle p) {
        constexpr std::string_view who = "ackermann_observer_gain";
        return Eigen::VectorXd(ackermann_observer_gain(matrix(A, who, "A"), row_argument(c, who, "c"),
                                                       coefficients_argument(p, who, "p")));
      },
      nb::arg("A"), nb::arg("c"), nb::arg("p"),
      "Output-injection gain k with det(sI - A + k c) = p(s) (p monic of degree n, highest power first):\n"
      "Ackermann's formula in observer form, k = p(A) O^-1 e_n. Refuses an unobservable pair (staircase\n"
      "test) or one whose observability matrix is singular to working accuracy.");

  // ---- Periodic linear time-varying systems ---------------------------------------------
  m.def(
      "transition_matrix",
      [](nb::handle A, nb::handle t0, nb::handle t1, nb::handle steps) {
        constexpr std::string_view who = "transition_matrix";
        const PythonDynamics a = dynamics_of(A, who);
        const double from = real_scalar(t0, who, "t0"), to = real_scalar(t1, who, "t1");
        const int n_steps = int_argument(steps, who, "steps");
        nb::gil_scoped_release release;  // a callable A(t) takes the GIL back for its calls
        return transition_matrix(a, from, to, n_steps);
      },
      nb::arg("A"), nb::arg("t0"), nb::arg("t1"), nb::arg("steps") = 2000,
      "Transition matrix Phi(t1, t0) of de/dt = A(t) e by `steps` equal RK4 steps. A is a callable A(t)\n"
      "returning an n x n array (called with the GIL, four times a step) or a constant array. A fixed-step\n"
      "integration without an error estimate: its error is O(h^4), h = (t1 - t0)/steps, small only when\n"
      "h max ||A(t)|| << 1 (the error-controlled monodromy matrix: floquet_exponents).");
  m.def(
      "floquet_exponents",
      [](nb::handle A, nb::handle period, nb::handle steps) {
        constexpr std::string_view who = "floquet_exponents";
        const PythonDynamics a = dynamics_of(A, who);
        const double T = real_scalar(period, who, "period");
        const int n_steps = int_argument(steps, who, "steps");
        nb::gil_scoped_release release;
        return floquet_exponents(a, T, n_steps);
      },
      nb::arg("A"), nb::arg("period"), nb::arg("steps") = 2000,
      "Floquet exponents log|mu_i| / T of a T-periodic de/dt = A(t) e, largest first: mu_i the eigenvalues\n"
      "of the monodromy matrix Phi(T, 0), integrated by RK4 with N = max(steps, ceil(10 T max ||A(t)||))\n"
      "steps and step doubling until two passes agree within tau = 1e-6 max(max ||A(t)||, 1/T). An\n"
      "exponent below lambda_max + log(n eps)/T is kept when two passes agree on it, else reported as that\n"
      "bound. All NaN when the solution leaves the floating-point range within one period. Frozen-time\n"
      "eigenvalues decide nothing (Markus-Yamabe: -1/4 +- 0.66i at every t, exponent +1/2). The conditions\n"
      "of Algorithm 3 (de2/dt = A22(t) e2) and Algorithm 4 (eq. (13), A(t) - K(t) C(t)) of Zhang (2005).");
  m.def(
      "is_exponentially_stable_periodic",
      [](nb::handle A, nb::handle period, nb::handle margin, nb::handle steps) {
        constexpr std::string_view who = "is_exponentially_stable_periodic";
        const PythonDynamics a = dynamics_of(A, who);
        const double T = real_scalar(period, who, "period"), m_ = real_scalar(margin, who, "margin");
        const int n_steps = int_argument(steps, who, "steps");
        nb::gil_scoped_release release;
        return is_exponentially_stable_periodic(a, T, m_, n_steps);
      },
      nb::arg("A"), nb::arg("period"), nb::arg("margin") = 0.0, nb::arg("steps") = 2000,
      "Every Floquet exponent of the T-periodic de/dt = A(t) e below -margin (False when they are NaN); only\n"
      "the largest is error-controlled, within tau as in floquet_exponents.");

  // ---- Thresholds and distributions of the detectors ------------------------------------
  m.attr("siegmund_overshoot") = siegmund_overshoot;
  m.attr("chi_square_min_degrees_of_freedom") = chi_square_min_degrees_of_freedom;
  m.attr("chi_square_max_degrees_of_freedom") = chi_square_max_degrees_of_freedom;
  m.attr("glr_max_window") = glr_max_window;
  m.attr("glr_max_simulation_work") = glr_max_simulation_work;
  m.attr("glr_max_mean_evaluations") = glr_max_mean_evaluations;

  m.def(
      "chi_square_upper_tail",
      [](nb::handle degrees_of_freedom, nb::handle x) {
        constexpr std::string_view who = "chi_square_upper_tail";
        return chi_square_upper_tail(real_scalar(degrees_of_freedom, who, "degrees_of_freedom"),
                                     real_scalar(x, who, "x"));
      },
      nb::arg("degrees_of_freedom"), nb::arg("x"),
      "Pr[chi^2_nu > x] = Q(nu/2, x/2), the regularized upper incomplete gamma function: its series below\n"
      "x/2 < nu/2 + 1 and its continued fraction above (Abramowitz & Stegun 6.5.29, 6.5.31), for\n"
      "chi_square_min_degrees_of_freedom <= nu <= chi_square_max_degrees_of_freedom.");
  m.def(
      "chi_square_upper_quantile",
      [](nb::handle degrees_of_freedom, nb::handle p) {
        constexpr std::string_view who = "chi_square_upper_quantile";
        return chi_square_upper_quantile(real_scalar(degrees_of_freedom, who, "degrees_of_freedom"),
                                         real_scalar(p, who, "p"));
      },
      nb::arg("degrees_of_freedom"), nb::arg("p"),
      "The x with Pr[chi^2_nu > x] = p, 0 < p < 1 (the threshold of a chi-square test of false-alarm\n"
      "probability p), by bisection to a relative 1e-13.");
  m.def(
      "cusum_mean_run_length",
      [](nb::handle drift, nb::handle threshold, nb::handle mean) {
        constexpr std::string_view who = "cusum_mean_run_length";
        return cusum_mean_run_length(real_scalar(drift, who, "drift"), real_scalar(threshold, who, "threshold"),
                                     real_scalar(mean, who, "mean"));
      },
      nb::arg("drift"), nb::arg("threshold"), nb::arg("mean") = 0.0,
      "Mean number of independent N(mean, 1) increments before a one-sided CUSUM with drift nu exceeds h,\n"
      "by Siegmund's approximation: with Delta = mean - nu and b = h + 1.166 (siegmund_overshoot),\n"
      "L = (exp(-2 Delta b) + 2 Delta b - 1) / (2 Delta^2), and L = b^2 for Delta = 0. mean = 0 gives the\n"
      "run length to a false alarm, mean > drift the detection delay.");
  m.def(
      "cusum_threshold",
      [](nb::handle drift, nb::handle mean_evaluations, nb::handle components) {
        constexpr std::string_view who = "cusum_threshold";
        return cusum_threshold(real_scalar(drift, who, "drift"), real_scalar(mean_evaluations, who, "mean_evaluations"),
                               integer_argument(components, who, "components"));
      },
      nb::arg("drift"), nb::arg("mean_evaluations"), nb::arg("components") = 1,
      "The threshold h at which 2 x components one-sided CUSUMs fed independent standard normal increments\n"
      "raise false alarms every mean_evaluations increments on average: cusum_mean_run_length(drift, h) =\n"
      "2 components mean_evaluations.");
  m.def(
      "glr_threshold",
      [](nb::handle window, nb::handle mean_evaluations, nb::handle components) {
        const auto [w, mean, c] = glr_arguments(window, mean_evaluations, components, "glr_threshold");
        nb::gil_scoped_release release;  // a simulation: up to seconds
        return glr_threshold(w, mean, c);
      },
      nb::arg("window"), nb::arg("mean_evaluations"), nb::arg("components") = 1,
      "The threshold h at which `components` windowed GLR statistics of window M, fed independent standard\n"
      "normal values, raise false alarms every mean_evaluations evaluations (all components together), by\n"
      "simulation from a fixed seed (about 50 alarms at the answer: a relative Monte-Carlo error of about\n"
      "14 %); mean_evaluations in [2, 1e5], and glr_simulation_work(window, mean_evaluations, components) at\n"
      "most glr_max_simulation_work per candidate threshold (refused otherwise, naming what to lower).");
  m.def(
      "glr_simulation_work",
      [](nb::handle window, nb::handle mean_evaluations, nb::handle components) {
        const auto [w, mean, c] = glr_arguments(window, mean_evaluations, components, "glr_simulation_work");
        return glr_simulation_work(w, mean, c);
      },
      nb::arg("window"), nb::arg("mean_evaluations"), nb::arg("components") = 1,
      "The work of one candidate threshold of glr_threshold, in window steps: every simulated value of every\n"
      "component, its window and, beyond 2^22 values, its draw anew for each candidate.");
  m.def(
      "sample_covariance",
      [](nb::handle runs) {
        return Eigen::MatrixXd(sample_covariance(vector_runs(runs, "sample_covariance", "runs")));
      },
      nb::arg("runs"),
      "Sample covariance (1/n) sum_k v_k v_k^T of zero-mean vectors (e.g. the output errors of fault-free\n"
      "runs) over every row of every run (a list of N_r x n arrays); the covariance of a ChiSquareTest.");

  // ---- Monte-Carlo evaluation of a detector ------------------------------------------------
  nb::class_<Alarm>(m, "Alarm", "One alarm: when, and which parameter it names (-1 for none).")
      .def(
          "__init__",
          [](Alarm* self, nb::handle time, nb::handle isolated) {
            new (self) Alarm{real_scalar(time, "Alarm", "time"), integer_argument(isolated, "Alarm", "isolated")};
          },
          nb::arg("time"), nb::arg("isolated") = -1)
      .def_rw("time", &Alarm::time)
      .def_rw("isolated", &Alarm::isolated)
      .def("__repr__", [](const Alarm& a) {
        std::ostringstream os;
        os.precision(17);
        os << "Alarm(time=" << a.time << ", isolated=" << a.isolated << ")";
        return os.str();
      });
  nb::class_<MonitoredRun>(m, "MonitoredRun",
                           "The alarms of one run, monitored over [start, end] (in any order: the evaluator sorts\n"
                           "them by time).")
      .def(
          "__init__",
          [](MonitoredRun* self, nb::handle start, nb::handle end, nb::handle times, nb::handle isolated) {
            constexpr std::string_view who = "MonitoredRun";
            MonitoredRun run = alarm_run(real_scalar(start, who, "start"), real_scalar(end, who, "end"), times,
                                         isolated, who, "times", "isolated");
            new (self) MonitoredRun(std::move(run));
          },
          nb::arg("start"), nb::arg("end"), nb::arg("times").none() = nb::none(),
          nb::arg("isolated").none() = nb::none(),
          "times: the alarm times (1-D); isolated: the parameter each names (integers, -1 for none; default\n"
          "all -1).")
      .def_rw("start", &MonitoredRun::start)
      .def_rw("end", &MonitoredRun::end)
      .def_prop_ro(
          "alarms", [](const MonitoredRun& r) { return r.alarms; }, "a list of the Alarm objects (copies)")
      .def_prop_ro("times",
                   [](const MonitoredRun& r) {
                     Eigen::VectorXd t(static_cast<Index>(r.alarms.size()));
                     for (std::size_t i = 0; i < r.alarms.size(); ++i) t(static_cast<Index>(i)) = r.alarms[i].time;
                     return t;
                   })
      .def_prop_ro("isolated", [](const MonitoredRun& r) {
        Eigen::Matrix<std::int64_t, Eigen::Dynamic, 1> which(static_cast<Index>(r.alarms.size()));
        for (std::size_t i = 0; i < r.alarms.size(); ++i) which(static_cast<Index>(i)) = r.alarms[i].isolated;
        return which;
      });
  nb::class_<FaultDescription>(m, "FaultDescription",
                               "The fault a scenario injects: from `time` on, on parameter `parameter` (0-based; -1\n"
                               "when isolation is not scored). Detections are alarms strictly after `time`.")
      .def(
          "__init__",
          [](FaultDescription* self, nb::handle time, nb::handle parameter) {
            new (self) FaultDescription{real_scalar(time, "FaultDescription", "time"),
                                        integer_argument(parameter, "FaultDescription", "parameter")};
          },
          nb::arg("time"), nb::arg("parameter") = -1)
      .def_rw("time", &FaultDescription::time)
      .def_rw("parameter", &FaultDescription::parameter);
  nb::class_<DetectionSummary>(m, "DetectionSummary", "Outcome of evaluate_detection over all seeds.")
      .def_ro("seeds", &DetectionSummary::seeds)
      .def_ro("detection_rate", &DetectionSummary::detection_rate, "faulty runs with an alarm after the fault")
      .def_ro("mean_detection_delay", &DetectionSummary::mean_detection_delay,
              "from the fault to the first alarm after it (NaN without a detection)")
      .def_ro("p95_detection_delay", &DetectionSummary::p95_detection_delay,
              "nearest-rank 95th percentile of the delays")
      .def_ro("isolation_rate", &DetectionSummary::isolation_rate,
              "detections whose first alarm names the faulty parameter (NaN when not scored)")
      .def_ro("quiet_before_fault_rate", &DetectionSummary::quiet_before_fault_rate,
              "faulty runs without an alarm up to the fault's time")
      .def_ro("false_alarms", &DetectionSummary::false_alarms, "alarms of the fault-free twins")
      .def_ro("fault_free_time", &DetectionSummary::fault_free_time, "their monitored time, sum of end - start")
      .def_ro("false_alarm_rate", &DetectionSummary::false_alarm_rate,
              "false_alarms / fault_free_time (NaN when no fault-free time was monitored)")
      .def_prop_ro(
          "delays", [](const DetectionSummary& s) { return array_of(s.delays); },
          "the delay of each detected seed, in seed order")
      .def("__repr__", [](const DetectionSummary& s) {
        std::ostringstream os;
        os.precision(6);
        os << "DetectionSummary(seeds=" << s.seeds << ", detection_rate=" << s.detection_rate
           << ", mean_detection_delay=" << s.mean_detection_delay << ", p95_detection_delay=" << s.p95_detection_delay
           << ", isolation_rate=" << s.isolation_rate << ", quiet_before_fault_rate=" << s.quiet_before_fault_rate
           << ", false_alarms=" << s.false_alarms << ", false_alarm_rate=" << s.false_alarm_rate << ")";
        return os.str();
      });

  m.def("evaluate_detection", &evaluate, nb::arg("scenario"), nb::arg("fault"), nb::arg("seeds").none() = nb::none(),
        nb::kw_only(), nb::arg("first_seed") = 0, nb::arg("threads") = 0,
        "Monte-Carlo evaluation of a detector: scenario(seed, True) and scenario(seed, False) for `seeds`\n"
        "seeds from first_seed, over `threads` threads (0: one per core), scored against `fault` (a\n"
        "FaultDescription or the fault's time). scenario(seed, faulty) runs one simulation (plant, noise and\n"
        "observer seeded by `seed`, the fault injected when `faulty`) and returns its alarms: a MonitoredRun\n"
        "or a tuple (start, end, alarm_times[, isolated]). The GIL is released while the evaluator waits and\n"
        "each call takes it back, so scenarios whose work is an adaptobs run() (which releases it) proceed in\n"
        "parallel; the same seed gives the same summary on any number of threads. An exception the scenario\n"
        "raises stops the evaluation and is raised here. `scenario` may also be recorded runs, a pair\n"
        "(faulty_runs, fault_free_runs) of lists with one run per seed (seeds: their length).");
}

}  // namespace adaptobs::python
