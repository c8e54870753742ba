// The discrete-time observers over a model in Python, with run-time sizes:
// GuyaderZhangObserver (Guyader & Zhang 2003, eq. (2a)-(2c)), GuiroObserver
// (Guiro et al. 2008, eq. (4)-(5)) with its gain design, and the
// AugmentedKalmanFilter baseline, over a DiscreteLtiModel or a DiscreteLtvModel.

#include "discrete_observer.hpp"
#include "snapshot_fields.hpp"

#include <adaptobs/baselines/augmented_kalman.hpp>
#include <adaptobs/design/guiro_gains.hpp>
#include <adaptobs/design/guyader_zhang_tuning.hpp>
#include <adaptobs/observers/guiro.hpp>
#include <adaptobs/observers/guyader_zhang.hpp>

#include <nanobind/stl/optional.h>

#include <limits>

namespace adaptobs::python {

using GuyaderZhang = GuyaderZhangObserver<SharedDiscreteModel>;
using AugmentedKalman = AugmentedKalmanFilter<SharedDiscreteModel>;
using Guiro = GuiroObserver<SharedDiscreteModel>;

template <>
struct Diagnostics<GuyaderZhang> {
  static constexpr std::array<const char*, 2> names{"assumption2_norm", "excitation_level"};
  static void record(const GuyaderZhang& o, double* out) {
    out[0] = o.assumption2_norm();
    out[1] = o.excitation_level().value_or(std::numeric_limits<double>::quiet_NaN());
  }
};

namespace {

// The model of a snapshot's "model." fields.
SharedDiscreteModel model_of(const Snapshot<double>& s) { return SharedDiscreteModel::of_snapshot(s, "model."); }

}  // namespace

namespace {

// The Ψ_k of an N x nx x np array, for the tuning routines.
std::vector<Eigen::MatrixXd> regressor_list(nb::handle psi, const SharedDiscreteModel& model, std::string_view who) {
  const Sizes s = model.sizes();
  const Array array = real_array(psi, who, "Psi");
  if (array.ndim() != 3 || array.shape(0) == 0)
    fail_dimensions(who, "Psi", "(N, " + std::to_string(s.nx) + ", " + std::to_string(s.np) + ") with N >= 1",
                    shape_of(array));
  const auto samples = static_cast<Index>(array.shape(0));
  const Regressors r = regressors(psi, samples, s.nx, s.np, who);
  std::vector<Eigen::MatrixXd> list;
  list.reserve(static_cast<std::size_t>(samples));
  for (Index k = 0; k < samples; ++k) list.emplace_back(r.at(k));
  return list;
}

nb::dict convergence_dict(const GuyaderZhangConvergence<double>& c) {
  nb::dict d;
  d["mu"] = c.mu;
  d["rate"] = c.rate;
  d["time_constant"] = c.time_constant;
  d["averaged_time_constant"] = c.averaged_time_constant;
  d["assumption2_measure"] = c.assumption2_measure;
  d["averaging_holds"] = c.averaging_holds;
  return d;
}

void bind_guyader_zhang_tuning(nb::module_& m) {
  m.def(
      "guyader_zhang_mu_bound",
      [](nb::handle model, nb::handle K, nb::handle Psi) {
        constexpr std::string_view who = "guyader_zhang_mu_bound";
        const SharedDiscreteModel shared = discrete_model(model, who);
        return guyader_zhang_mu_bound(shared, Eigen::MatrixXd(matrix(K, who, "K")), regressor_list(Psi, shared, who));
      },
      nb::arg("model"), nb::arg("K"), nb::arg("Psi"),
      "Largest mu for which assumption 2, ||sqrt(mu) C_k Upsilon_k|| <= 1, holds at every step of the\n"
      "regressors Psi (N x nx x np) with gain K: 1 / max_k ||C_k Upsilon_k||^2 (Upsilon of eq. (2a)).");
  m.def(
      "guyader_zhang_convergence",
      [](nb::handle model, nb::handle K, nb::handle Psi, nb::handle mu) {
        constexpr std::string_view who = "guyader_zhang_convergence";
        const SharedDiscreteModel shared = discrete_model(model, who);
        return convergence_dict(guyader_zhang_convergence(shared, Eigen::MatrixXd(matrix(K, who, "K")),
                                                          regressor_list(Psi, shared, who),
                                                          real_scalar(mu, who, "mu")));
      },
      nb::arg("model"), nb::arg("K"), nb::arg("Psi"), nb::arg("mu"),
      "The convergence of theta_hat at step size mu over the regressors: a dict of rate (per step),\n"
      "time_constant (steps), averaged_time_constant (the averaging theory's), assumption2_measure and\n"
      "averaging_holds (docs/tuning.md).");
  m.def(
      "guyader_zhang_fastest_mu",
      [](nb::handle model, nb::handle K, nb::handle Psi, int points) {
        constexpr std::string_view who = "guyader_zhang_fastest_mu";
        const SharedDiscreteModel shared = discrete_model(model, who);
        return convergence_dict(guyader_zhang_fastest_mu(shared, Eigen::MatrixXd(matrix(K, who, "K")),
                                                         regressor_list(Psi, shared, who), 0, points));
      },
      nb::arg("model"), nb::arg("K"), nb::arg("Psi"), nb::arg("points") = 25,
      "The fastest mu among `points` values from 1e-4 to 1 times guyader_zhang_mu_bound, with its\n"
      "convergence (the dict of guyader_zhang_convergence).");
}

}  // namespace

void bind_discrete_observers(nb::module_& m) {
  bind_guyader_zhang_tuning(m);
  nb::class_<RunResult>(m, "RunResult", "The arrays of a run(): row k is the observer after sample k.")
      .def_ro("state", &RunResult::state, "state estimates, N x nx")
      .def_ro("parameters", &RunResult::parameters, "parameter estimates, N x np")
      .def_ro("output_error", &RunResult::output_error, "output errors of the accepted updates, N x ny")
      .def_ro("status", &RunResult::status, "UpdateStatus of each sample (int8)")
      .def_ro("diagnostics", &RunResult::diagnostics, "the observer's diagnostics after each sample, by name");

  auto gz = nb::class_<Bound<GuyaderZhang>>(
      m, "GuyaderZhangObserver",
      "Guyader-Zhang adaptive observer (Guyader & Zhang 2003, eq. (2a)-(2c)):\n"
      "  (2a) Upsilon_{k+1} = (A - K C) Upsilon_k + Psi_k\n"
      "  (2b) theta_{k+1} = theta_k + mu Upsilon_k^T C^T (y_k - C x_k)\n"
      "  (2c) x_{k+1} = A x_k + B u_k + Psi_k theta_k + K (y_k - C x_k) + Upsilon_{k+1} (theta_{k+1} - theta_k)\n"
      "K must make A - K C Schur stable (assumption 1) and mu > 0 be small enough for assumption 2,\n"
      "||sqrt(mu) C Upsilon_k|| <= 1. excitation_window L > 0 turns on the assumption-3 monitor (eq. (4));\n"
      "normalized_step uses mu_k = mu / max(1, mu ||C Upsilon_k||_F^2), which keeps assumption 2 at every\n"
      "step (turn it on whenever outputs can be lost).");
  gz.def(
        "__init__",
        [](Bound<GuyaderZhang>* self, nb::handle model, nb::handle K, nb::handle mu, nb::handle x0, nb::handle theta0,
           nb::handle excitation_window, nb::handle normalized_step) {
          constexpr std::string_view who = "GuyaderZhangObserver";
          new (self) Bound<GuyaderZhang>(
              GuyaderZhang(discrete_model(model, who), matrix(K, who, "K"), real_scalar(mu, who, "mu"),
                           vector(x0, who, "x0"), vector(theta0, who, "theta0"),
                           {.excitation_window = integer_argument(excitation_window, who, "excitation_window"),
                            .normalized_step = flag_argument(normalized_step, who, "normalized_step")}));
        },
        nb::arg("model"), nb::arg("K"), nb::arg("mu"), nb::arg("x0"), nb::arg("theta0"), nb::kw_only(),
        nb::arg("excitation_window") = 0, nb::arg("normalized_step") = false)
      .def_prop_ro(
          "upsilon", [](const Bound<GuyaderZhang>& b) { return Eigen::MatrixXd(b.observer.upsilon()); },
          "Filtered regressor Upsilon_k (eq. (2a)).")
      .def_prop_ro("K", [](const Bound<GuyaderZhang>& b) { return Eigen::MatrixXd(b.observer.gain()); })
      .def_prop_ro("mu", [](const Bound<GuyaderZhang>& b) { return b.observer.mu(); })
      .def(
          "set_gain",
          [](Bound<GuyaderZhang>& b, nb::handle K) {
            const InUse guard(b.in_use.flag, "GuyaderZhangObserver.set_gain");
            b.observer.set_gain(matrix(K, "GuyaderZhangObserver.set_gain", "K"));
          },
          nb::arg("K"), "Gain K_k used from the next update on.")
      .def(
          "set_mu",
          [](Bound<GuyaderZhang>& b, nb::handle mu) {
            constexpr std::string_view who = "GuyaderZhangObserver.set_mu";
            const InUse guard(b.in_use.flag, who);
            b.observer.set_mu(real_scalar(mu, who, "mu"));
          },
          nb::arg("mu"), "Step size mu_k > 0 used from the next update on.")
      .def_prop_ro(
          "assumption2_norm", [](const Bound<GuyaderZhang>& b) { return b.observer.assumption2_norm(); },
          "||sqrt(mu_k) C Upsilon_k||_2 of the last accepted step (eq. (3)).")
      .def_prop_ro("assumption2_holds", [](const Bound<GuyaderZhang>& b) { return b.observer.assumption2_holds(); })
      .def_prop_ro(
          "excitation_level", [](const Bound<GuyaderZhang>& b) { return b.observer.excitation_level(); },
          "Excitation level alpha of assumption 3 (eq. (4)) over the last L steps; None while the monitor\n"
          "is off or its window has not filled.");
  bind_discrete_observer(gz, [](const Snapshot<double>& s) {
    return GuyaderZhang(
        model_of(s), field(s, "K"), scalar(s, "mu"), field(s, "x"), field(s, "theta"),
        {.excitation_window = integer(s, "excitation_window"), .normalized_step = integer(s, "normalized_step") != 0});
  });

  auto guiro = nb::class_<Bound<Guiro>>(
      m, "GuiroObserver",
      "Continuous-discrete adaptive observer of Guiro, Iggidr, Ngom & Toure (2008), eq. (4)-(5), over the\n"
      "sampled model (E = exp(A T), B, C) with the regressor H_k of each interval (Psi_k):\n"
      "  z_k = z-_k + K (y_k - C z-_k),  theta_{k+1} = theta_k - Gamma (C z_k - y_k),\n"
      "  z-_{k+1} = E z_k + H_k theta_k + B u_k.\n"
      "`state` is the prediction z-_k, `corrected_state` the paper's z_{k-1}; design K and Gamma with\n"
      "design_guiro_gains. correct_initial_estimate=False leaves the first prediction uncorrected.");
  guiro
      .def(
          "__init__",
          [](Bound<Guiro>* self, nb::handle model, nb::handle K, nb::handle Gamma, nb::handle z0, nb::handle theta0,
             nb::handle correct_initial_estimate) {
            constexpr std::string_view who = "GuiroObserver";
            new (self) Bound<Guiro>(Guiro(discrete_model(model, who), matrix(K, who, "K"), matrix(Gamma, who, "Gamma"),
                                          vector(z0, who, "z0"), vector(theta0, who, "theta0"),
                                          {.correct_initial_estimate = flag_argument(correct_initial_estimate, who,
                                                                                     "correct_initial_estimate")}));
          },
          nb::arg("model"), nb::arg("K"), nb::arg("Gamma"), nb::arg("z0"), nb::arg("theta0"), nb::kw_only(),
          nb::arg("correct_initial_estimate") = true)
      .def_prop_ro("corrected_state",
                   [](const Bound<Guiro>& b) { return Eigen::VectorXd(b.observer.corrected_state()); })
      .def_prop_ro("K", [](const Bound<Guiro>& b) { return Eigen::MatrixXd(b.observer.gain()); })
      .def_prop_ro("Gamma", [](const Bound<Guiro>& b) { return Eigen::MatrixXd(b.observer.parameter_gain()); })
      .def(
          "set_gains",
          [](Bound<Guiro>& b, nb::handle K, nb::handle Gamma) {
            constexpr std::string_view who = "GuiroObserver.set_gains";
            const InUse guard(b.in_use.flag, who);
            b.observer.set_gains(matrix(K, who, "K"), matrix(Gamma, who, "Gamma"));
          },
          nb::arg("K"), nb::arg("Gamma"), "Gains used from the next update on (a schedule over varying intervals).");
  bind_discrete_observer(guiro, [](const Snapshot<double>& s) {
    return Guiro(model_of(s), field(s, "K"), field(s, "Gamma"), field(s, "z"), field(s, "theta"),
                 {.correct_initial_estimate = integer(s, "correct_initial_estimate") != 0});
  });

  using GuiroDesign = GuiroGains<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::Dynamic>;
  nb::class_<GuiroDesign>(m, "GuiroGains", "Gains K and Gamma of a Guiro observer, with the figures that certify them.")
      .def_ro("K", &GuiroDesign::K)
      .def_ro("Gamma", &GuiroDesign::Gamma)
      .def_ro("L", &GuiroDesign::L, "the equivalent predictor gain [E K; Gamma (I - C K)]")
      .def_ro("U", &GuiroDesign::U, "the error matrix at Hbar, whose spectrum was placed")
      .def_ro("cayley_hamilton_residual", &GuiroDesign::cayley_hamilton_residual)
      .def_ro("spectral_radius", &GuiroDesign::spectral_radius)
      .def_ro("eigenvector_condition", &GuiroDesign::eigenvector_condition)
      .def_ro("eigenvalue_mismatch", &GuiroDesign::eigenvalue_mismatch);
  m.def(
      "design_guiro_gains",
      [](nb::handle E, nb::handle C, nb::handle Hbar, nb::handle poles) {
        constexpr std::string_view who = "design_guiro_gains";
        return design_guiro_gains(matrix(E, who, "E"), matrix(C, who, "C"), matrix(Hbar, who, "Hbar"),
                                  complex_vector(poles, who, "poles"));
      },
      nb::arg("E"), nb::arg("C"), nb::arg("Hbar"), nb::arg("poles"),
      "K and Gamma such that the error matrix U at the nominal regressor Hbar has the spectrum `poles`\n"
      "(n + p values inside the unit circle); refuses, naming the cause, when no gains exist.");

  auto akf = nb::class_<Bound<AugmentedKalman>>(
      m, "AugmentedKalmanFilter",
      "Baseline: the Kalman filter on the augmented state [x; theta] (Guyader & Zhang 2003, section 1;\n"
      "Zhang 2005, appendix), Joseph form. P0 and Q are (nx + np) x (nx + np), R is ny x ny.");
  akf.def(
         "__init__",
         [](Bound<AugmentedKalman>* self, nb::handle model, nb::handle x0, nb::handle theta0, nb::handle P0,
            nb::handle Q, nb::handle R) {
           constexpr std::string_view who = "AugmentedKalmanFilter";
           new (self) Bound<AugmentedKalman>(
               AugmentedKalman(discrete_model(model, who), vector(x0, who, "x0"), vector(theta0, who, "theta0"),
                               {matrix(P0, who, "P0"), matrix(Q, who, "Q"), matrix(R, who, "R")}));
         },
         nb::arg("model"), nb::arg("x0"), nb::arg("theta0"), nb::arg("P0"), nb::arg("Q"), nb::arg("R"))
      .def_prop_ro(
          "covariance", [](const Bound<AugmentedKalman>& b) { return Eigen::MatrixXd(b.observer.covariance()); },
          "Covariance of the augmented estimate [x_hat; theta_hat].");
  bind_discrete_observer(akf, [](const Snapshot<double>& s) {
    return AugmentedKalman(model_of(s), field(s, "x"), field(s, "theta"),
                           {field(s, "P0"), field(s, "Q"), field(s, "R")});
  });
}

}  // namespace adaptobs::python
