#pragma once
/// \file
/// The two systems of Dey & Bhasin (2022) §5 (Dey & Bhasin), shared by the examples
/// `dey_bhasin_mimo` and `suzuki_siso`, the tests and the benchmarks; and the
/// analysis helpers they use (normalized estimates, theorem-5 sums).
///
/// MIMO (q = 2, m = 2, r = 3, n = 6). Readings of the extracted text:
/// - the first block of A is printed `4 I2`. That plant has a pole at 4.0455
///   (spectral radius 4.05): under the bounded, prescribed inputs of figure 3
///   its state overflows double precision within a few hundred steps, and
///   lemma 2 and theorems 5–6 require a bounded state. No stabilizing feedback
///   is given anywhere. We read `0.4 I2` (a lost "0."): the plant is then
///   Schur stable (poles 0.8962 and −0.2481 ± 0.5227i), F = A + diag-shift of
///   the first column by [0, 0.1, −0.1], the same small-perturbation habit as
///   in the SISO example (1.52 → 1.49, −0.6 → −0.55), and the figures' behaviour
///   is reproduced. A test checks both readings;
/// - B is printed 2 × 6; it must be n × m = 6 × 2 (B̂₀ carries an explicit ᵀ).
///   The 12 printed numbers are read as Bᵀ, equivalently as vec(B);
/// - with this reading the first entry of p, a₁ − f₁ = 0.4 − 0.4, is exactly
///   0, so the paper's "normalized parameter estimates" are read as â/a and
///   b̂/b (every true entry of a and B is non-zero here).
///
/// SISO (Suzuki et al. 1980, via Dey & Bhasin (2022) §5): A = [1.52 1; −0.6 0],
/// B = [0.43; −0.35], F = [1.49 1; −0.55 0], x₀ = x̂₀ = 0, Â₀ = [0 1; 0 0],
/// B̂₀ = 0, k0 = 1e4, R = 1, kmin = 1e-4, weighting factor √0.5, u_t = sin(0.2t).

#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/discrete_model.hpp>
#include <adaptobs/design/companion_matrix.hpp>
#include <adaptobs/observers/dey_bhasin.hpp>
#include <adaptobs/simulation/discrete_plant.hpp>

#include <Eigen/Core>

#include <cmath>
#include <limits>

namespace adaptobs::examples::dey_bhasin {

/// Entry-wise \f$\hat\theta_k/\theta_k\f$ for \f$\theta = [a;\ \mathrm{vec}(B)]\f$. A true entry
/// equal to 0 has no normalized value: it is written as NaN (`nan` in the CSV).
inline Eigen::VectorXd normalized_estimates(const Eigen::VectorXd& a_hat, const Eigen::MatrixXd& B_hat,
                                            const Eigen::VectorXd& a, const Eigen::MatrixXd& B) {
  Eigen::VectorXd truth(a.size() + B.size()), estimate(a.size() + B.size());
  truth << a, B.reshaped();
  estimate << a_hat, B_hat.reshaped();
  Eigen::VectorXd ratio(truth.size());
  for (Index i = 0; i < truth.size(); ++i)
    ratio(i) = truth(i) == 0.0 ? std::numeric_limits<double>::quiet_NaN() : estimate(i) / truth(i);
  return ratio;
}

/// The same for the estimates of an observer (`a_hat()`, `B_hat()`).
template <class Observer>
Eigen::VectorXd normalized_estimates(const Observer& observer, const Eigen::VectorXd& a, const Eigen::MatrixXd& B) {
  return normalized_estimates(observer.a_hat().template cast<double>(), observer.B_hat().template cast<double>(), a, B);
}

/// \f$\sum_{i \ge \text{first}}\|W\,CF^i x\|\f$ for a Schur F, summed until the terms are
/// negligible: the perturbation budget of theorem 5 (W = I for the paper's
/// bound with first = 1, \f$W = R^{-1/2}\f$ for the corrected one).
inline double output_free_response_sum(const Eigen::MatrixXd& F, const Eigen::MatrixXd& C, Eigen::VectorXd x,
                                       const Eigen::MatrixXd& W, Index first = 1) {
  for (Index i = 0; i < first; ++i) x = F * x;
  double sum = 0;
  for (Index i = 0; i < 100000; ++i) {
    const double term = (W * (C * x)).norm();
    sum += term;
    if (i > 10 && term <= 1e-17 * sum) break;
    x = F * x;
  }
  return sum;
}

/// Output matrix \f$C = [I_q\ 0\ \cdots\ 0]\f$ (4).
template <typename S>
Eigen::Matrix<S, Eigen::Dynamic, Eigen::Dynamic> canonical_output_matrix(Index r, Index q) {
  Eigen::Matrix<S, Eigen::Dynamic, Eigen::Dynamic> c = Eigen::Matrix<S, Eigen::Dynamic, Eigen::Dynamic>::Zero(q, r * q);
  c.leftCols(q).setIdentity();
  return c;
}

/// The plant (2) \f$x_{t+1} = Ax_t + Bu_t,\ y_t = Cx_t\f$ with \f$A = \bar A(a)\otimes I_q\f$
/// (no Ψθ term: its unknowns are A and B themselves).
template <typename S, int R, int Q, int M, class InputFn>
auto make_canonical_plant(const Eigen::Matrix<S, R, 1>& a, const Eigen::Matrix<S, R * Q, M>& B,
                          const Eigen::Matrix<S, R * Q, 1>& x0, InputFn input) {
  using PlantDims = Dimensions<S, R * Q, M, Q, 0>;
  const typename PlantDims::StateMatrix A = block_companion_matrix<Q>(a);
  const typename PlantDims::OutputMatrix C = canonical_output_matrix<S>(R, Q);
  auto no_regressor = [](Index, const typename PlantDims::Input&) { return typename PlantDims::RegressorMatrix(); };
  return DiscreteLinearPlant(DiscreteLtiModel<PlantDims>(A, B, C), x0, typename PlantDims::Parameters(), input,
                             no_regressor);
}

/// §5 MIMO example.
namespace mimo {
inline constexpr int order = 3;
inline constexpr int outputs = 2;
inline constexpr int inputs = 2;
inline constexpr int states = order * outputs;
inline constexpr double k0 = 1000.0;
inline constexpr double kmin = 1e-4;

template <typename S = double>
using Observer = DeyBhasinObserver<S, order, outputs, inputs>;
template <typename S = double>
using Coefficients = Eigen::Matrix<S, order, 1>;
template <typename S = double>
using InputMatrix = Eigen::Matrix<S, states, inputs>;
template <typename S = double>
using State = Eigen::Matrix<S, states, 1>;
using Input = Eigen::Matrix<double, inputs, 1>;

/// First-column entries of A, read as [0.4, 0.11, 0.3] (printed [4, 0.11, 0.3]).
template <typename S = double>
Coefficients<S> a() {
  return {S(0.4), S(0.11), S(0.3)};
}
/// The printed first column [4, 0.11, 0.3]: an unstable plant (pole 4.0455).
template <typename S = double>
Coefficients<S> printed_a() {
  return {S(4), S(0.11), S(0.3)};
}
/// First-column entries of F.
template <typename S = double>
Coefficients<S> f() {
  return {S(0.4), S(0.21), S(0.2)};
}
/// First-column entries of Â₀.
template <typename S = double>
Coefficients<S> a_hat0() {
  return {S(1), S(0.51), S(0.6)};
}

/// B (6 × 2): the transpose of the printed 2 × 6 array.
template <typename S = double>
InputMatrix<S> B() {
  InputMatrix<S> b;
  b << 1, 2,     //
      0.2, -5,   //
      3, 4,      //
      0.1, 0.9,  //
      0.3, 0.2,  //
      -1, -1.1;
  return b;
}
template <typename S = double>
InputMatrix<S> B_hat0() {
  return InputMatrix<S>::Constant(S(0.5));
}

template <typename S = double>
State<S> x0() {
  State<S> x;
  x << -1, 0.2, 1, -3, -2, 2.5;
  return x;
}
template <typename S = double>
State<S> x_hat0() {
  State<S> x;
  x << 0, 1, 2, 0.1, 0.2, 0.3;
  return x;
}

template <typename S = double>
typename Observer<S>::LawOptions law_options() {
  return {.k0 = S(k0), .kmin = S(kmin), .R = Eigen::Matrix<S, outputs, outputs>::Identity()};
}

/// The paper's observer: covariance resetting with k0 = 1000, kmin = 1e-4, R = I.
template <typename S = double>
Observer<S> make_observer() {
  return Observer<S>(f<S>(), x_hat0<S>(), a_hat0<S>(), B_hat0<S>(), law_options<S>());
}

/// Input that is not sufficiently rich: one sinusoid per channel,
/// u = [sin 0.2t, sin 0.5t] (the regressor reaches rank 8 of 15).
struct NotRichInput {
  Input operator()(Index k) const {
    const double t = double(k);
    return {std::sin(0.2 * t), std::sin(0.5 * t)};
  }
};

/// Sufficiently rich input: two sinusoids per channel at frequencies the other
/// channel does not use, u = [sin 0.3t + sin 1.3t, sin 0.7t + sin 2.1t] (rank 15 of 15).
struct RichInput {
  Input operator()(Index k) const {
    const double t = double(k);
    return {std::sin(0.3 * t) + std::sin(1.3 * t), std::sin(0.7 * t) + std::sin(2.1 * t)};
  }
};

template <class InputFn>
auto make_plant(InputFn input, const Coefficients<double>& first_column = a<double>()) {
  return make_canonical_plant<double, order, outputs, inputs>(first_column, B<double>(), x0<double>(), input);
}
}  // namespace mimo

/// §5 SISO comparison with Suzuki et al. (1980).
namespace siso {
inline constexpr int order = 2;
inline constexpr double k0 = 1e4;
inline constexpr double kmin = 1e-4;
/// The weighting factor of Suzuki et al. as printed, √0.5, used as the forgetting factor λ.
inline const double lambda = std::sqrt(0.5);

template <typename S = double>
using Observer = DeyBhasinObserver<S, order, 1, 1>;
template <typename S = double>
using Suzuki = SuzukiObserver<S, order, 1, 1>;
template <typename S = double>
using Coefficients = Eigen::Matrix<S, order, 1>;
template <typename S = double>
using InputMatrix = Eigen::Matrix<S, order, 1>;
template <typename S = double>
using State = Eigen::Matrix<S, order, 1>;

template <typename S = double>
Coefficients<S> a() {
  return {S(1.52), S(-0.6)};
}
template <typename S = double>
InputMatrix<S> B() {
  return {S(0.43), S(-0.35)};
}
template <typename S = double>
Coefficients<S> f() {
  return {S(1.49), S(-0.55)};
}
/// Â₀ = [0 1; 0 0]: first column 0; B̂₀ = 0; x₀ = x̂₀ = 0.
template <typename S = double>
Coefficients<S> a_hat0() {
  return Coefficients<S>::Zero();
}
template <typename S = double>
InputMatrix<S> B_hat0() {
  return InputMatrix<S>::Zero();
}
template <typename S = double>
State<S> x0() {
  return State<S>::Zero();
}

template <typename S = double>
typename Observer<S>::LawOptions law_options(S k0_value = S(k0), S kmin_value = S(kmin)) {
  return {.k0 = k0_value, .kmin = kmin_value, .R = Eigen::Matrix<S, 1, 1>::Identity()};
}

/// The proposed observer: covariance resetting, k0 = 1e4, R = 1, kmin = 1e-4.
template <typename S = double>
Observer<S> make_observer(typename Observer<S>::LawOptions options = law_options<S>()) {
  return Observer<S>(f<S>(), x0<S>(), a_hat0<S>(), B_hat0<S>(), options);
}

template <typename S = double>
typename Suzuki<S>::LawOptions suzuki_options(S forgetting = S(lambda)) {
  return {.gamma0 = S(k0) * Eigen::Matrix<S, 4, 4>::Identity(),
          .R = Eigen::Matrix<S, 1, 1>::Identity(),
          .lambda = forgetting};
}

/// The baseline: same filters and initial values, exponential forgetting, Γ₀ = k0 I.
template <typename S = double>
Suzuki<S> make_suzuki(S forgetting = S(lambda)) {
  return Suzuki<S>(f<S>(), x0<S>(), a_hat0<S>(), B_hat0<S>(), suzuki_options<S>(forgetting));
}

/// u_t = sin(0.2 t).
template <typename S = double>
struct SineInput {
  Eigen::Matrix<S, 1, 1> operator()(Index k) const { return Eigen::Matrix<S, 1, 1>(S(std::sin(0.2 * double(k)))); }
};

template <typename S = double, class InputFn = SineInput<S>>
auto make_plant(InputFn input = {}) {
  return make_canonical_plant<S, order, 1, 1>(a<S>(), B<S>(), x0<S>(), input);
}
}  // namespace siso

}  // namespace adaptobs::examples::dey_bhasin
