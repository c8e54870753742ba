// The design routines in Python: Riccati equations and Kalman gains, pole
// placement, zero-order hold, stability tests. Each returns the certificate
// fields its C++ result has, or raises ConfigurationError with the reason in
// the caller's terms.

#include "arrays.hpp"

#include <adaptobs/core/discretization.hpp>
#include <adaptobs/design/care.hpp>
#include <adaptobs/design/dare.hpp>
#include <adaptobs/design/pole_placement.hpp>
#include <adaptobs/design/schur_stability.hpp>
#include <adaptobs/design/stability.hpp>

#include <nanobind/eigen/dense.h>

namespace adaptobs::python {

namespace {
constexpr int X = Eigen::Dynamic;
}

void bind_design(nb::module_& m) {
  using Dare = DareSolution<double, X>;
  nb::class_<Dare>(m, "DareSolution", "Stabilizing solution of a DARE with the figures that certify it.")
      .def_ro("X", &Dare::X, "symmetric positive semidefinite solution")
      .def_ro("iterations", &Dare::iterations, "doubling steps plus Newton steps")
      .def_ro("relative_residual", &Dare::relative_residual, "per-term relative residual, at most 1e-10");
  using Care = CareSolution<double, X>;
  nb::class_<Care>(m, "CareSolution", "Stabilizing solution of a CARE with the figures that certify it.")
      .def_ro("X", &Care::X, "symmetric solution with A - G X Hurwitz")
      .def_ro("iterations", &Care::iterations, "sign-function iterations plus Newton steps")
      .def_ro("relative_residual", &Care::relative_residual);
  using Kalman = KalmanGain<double, X, X>;
  nb::class_<Kalman>(m, "KalmanGain", "Steady-state Kalman gain in predictor form: A - K C is Schur.")
      .def_ro("K", &Kalman::K)
      .def_ro("P", &Kalman::P, "a-priori error covariance")
      .def_ro("relative_residual", &Kalman::relative_residual);
  using KalmanBucy = KalmanBucyGain<double, X, X>;
  nb::class_<KalmanBucy>(m, "KalmanBucyGain", "Steady-state Kalman-Bucy gain: A - K C is Hurwitz.")
      .def_ro("K", &KalmanBucy::K)
      .def_ro("P", &KalmanBucy::P)
      .def_ro("relative_residual", &KalmanBucy::relative_residual);
  using Injection = OutputInjectionGain<double, X, X>;
  nb::class_<Injection>(m, "OutputInjectionGain", "Gain L placing the spectrum of A - L C, with its certificate.")
      .def_ro("L", &Injection::L)
      .def_ro("cayley_hamilton_residual", &Injection::cayley_hamilton_residual)
      .def_ro("transformation_condition", &Injection::transformation_condition)
      .def_ro("eigenvalue_mismatch", &Injection::eigenvalue_mismatch);
  using Feedback = StateFeedbackGain<double, X, X>;
  nb::class_<Feedback>(m, "StateFeedbackGain", "Gain K placing the spectrum of A - B K, with its certificate.")
      .def_ro("K", &Feedback::K)
      .def_ro("cayley_hamilton_residual", &Feedback::cayley_hamilton_residual)
      .def_ro("transformation_condition", &Feedback::transformation_condition)
      .def_ro("eigenvalue_mismatch", &Feedback::eigenvalue_mismatch);
  using Zoh = ZeroOrderHold<double, X, X>;
  nb::class_<Zoh>(m, "ZeroOrderHold", "Ad = exp(A Ts), Bd = integral_0^Ts exp(A s) ds B.")
      .def_ro("Ad", &Zoh::Ad)
      .def_ro("Bd", &Zoh::Bd);

  m.def(
      "solve_dare",
      [](nb::handle A, nb::handle B, nb::handle Q, nb::handle R) {
        constexpr std::string_view who = "solve_dare";
        return solve_dare(matrix(A, who, "A"), matrix(B, who, "B"), matrix(Q, who, "Q"), matrix(R, who, "R"));
      },
      nb::arg("A"), nb::arg("B"), nb::arg("Q"), nb::arg("R"),
      "Stabilizing solution of A^T X A - X - A^T X B (R + B^T X B)^-1 B^T X A + Q = 0: scaled, then\n"
      "the structure-preserving doubling algorithm (Chu, Fan & Lin 2005) refined by Newton's method\n"
      "(Hewer's step); refuses a solution whose relative residual exceeds 1e-10.");
  m.def(
      "solve_care",
      [](nb::handle A, nb::handle B, nb::handle Q, nb::handle R) {
        constexpr std::string_view who = "solve_care";
        return solve_care(matrix(A, who, "A"), matrix(B, who, "B"), matrix(Q, who, "Q"), matrix(R, who, "R"));
      },
      nb::arg("A"), nb::arg("B"), nb::arg("Q"), nb::arg("R"),
      "Stabilizing solution of A^T X + X A - X B R^-1 B^T X + Q = 0: the matrix sign function of the\n"
      "Hamiltonian (Byers 1987), refined by Newton's method (Kleinman 1968).");
  m.def(
      "steady_state_kalman_gain",
      [](nb::handle A, nb::handle C, nb::handle Q, nb::handle R) {
        constexpr std::string_view who = "steady_state_kalman_gain";
        return steady_state_kalman_gain(matrix(A, who, "A"), matrix(C, who, "C"), matrix(Q, who, "Q"),
                                        matrix(R, who, "R"));
      },
      nb::arg("A"), nb::arg("C"), nb::arg("Q"), nb::arg("R"),
      "Predictor-form Kalman gain of x+ = A x + w, y = C x + v (cov(w) = Q, cov(v) = R): P solves the\n"
      "dual DARE and K = A P C^T (C P C^T + R)^-1.");
  m.def(
      "kalman_bucy_gain",
      [](nb::handle A, nb::handle C, nb::handle Q, nb::handle R) {
        constexpr std::string_view who = "kalman_bucy_gain";
        return kalman_bucy_gain(matrix(A, who, "A"), matrix(C, who, "C"), matrix(Q, who, "Q"), matrix(R, who, "R"));
      },
      nb::arg("A"), nb::arg("C"), nb::arg("Q"), nb::arg("R"),
      "Kalman-Bucy gain of dx/dt = A x + w, y = C x + v: A P + P A^T - P C^T R^-1 C P + Q = 0, K = P C^T R^-1.");
  m.def(
      "place_output_injection",
      [](nb::handle A, nb::handle C, nb::handle poles) {
        constexpr std::string_view who = "place_output_injection";
        return place_output_injection(matrix(A, who, "A"), matrix(C, who, "C"), complex_vector(poles, who, "poles"));
      },
      nb::arg("A"), nb::arg("C"), nb::arg("poles"),
      "Gain L such that A - L C has the spectrum `poles` (closed under conjugation), by Sylvester's\n"
      "equation X A - F X = G C, L = X^-1 G (Bhattacharyya & de Souza 1982); refuses an unobservable\n"
      "pair or a placement it cannot verify.");
  m.def(
      "place_state_feedback",
      [](nb::handle A, nb::handle B, nb::handle poles) {
        constexpr std::string_view who = "place_state_feedback";
        return place_state_feedback(matrix(A, who, "A"), matrix(B, who, "B"), complex_vector(poles, who, "poles"));
      },
      nb::arg("A"), nb::arg("B"), nb::arg("poles"),
      "Gain K such that A - B K has the spectrum `poles`: the dual of place_output_injection.");
  m.def(
      "discretize_zoh",
      [](nb::handle A, nb::handle B, nb::handle ts) {
        constexpr std::string_view who = "discretize_zoh";
        return discretize_zoh(matrix(A, who, "A"), matrix(B, who, "B"), real_scalar(ts, who, "ts"));
      },
      nb::arg("A"), nb::arg("B"), nb::arg("ts"),
      "Zero-order-hold discretization of (A, B) with period ts: Ad = exp(A ts), Bd = H B with\n"
      "H = integral_0^ts exp(A s) ds, as Guyader & Zhang (2003, section 4) sample the satellite.");
  m.def(
      "is_schur_stable",
      [](nb::handle M, nb::handle margin) {
        constexpr std::string_view who = "is_schur_stable";
        const Eigen::MatrixXd a = matrix(M, who, "M");
        adaptobs::require_square(a, who, "M");
        return is_schur_stable(a, real_scalar(margin, who, "margin"));
      },
      nb::arg("M"), nb::arg("margin") = 0.0, "Every eigenvalue strictly inside the circle of radius 1 - margin.");
  m.def(
      "is_hurwitz_stable",
      [](nb::handle M, nb::handle margin) {
        constexpr std::string_view who = "is_hurwitz_stable";
        const Eigen::MatrixXd a = matrix(M, who, "M");
        adaptobs::require_square(a, who, "M");
        return is_hurwitz_stable(a, real_scalar(margin, who, "margin"));
      },
      nb::arg("M"), nb::arg("margin") = 0.0, "Every eigenvalue's real part below -margin.");
}

}  // namespace adaptobs::python
