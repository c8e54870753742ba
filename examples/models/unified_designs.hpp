#pragma once
/// \file
/// The observer designs of the continuous-time examples (Zhang 2005), shared
/// with the tests and the benchmarks: each algorithm with its static transform,
/// gains and adaptation gain, on the plant it is shown with.
///
/// | observer | plant | design |
/// |---|---|---|
/// | Bastin–Gevers | third-order SISO | form (5) with det(sI − A22) = (s+1)(s+3); k from `spr_injection_gain` (λ = 2: k = (2, 0, 0)); Γ = 5I |
/// | Marino–Tomei | third-order SISO | form (7); γ = (1, 3, 2); k for λ = 5: (8, 17, 10); Γ = 20I |
/// | Besançon | periodic MIMO | T of the plant model, K = 0; K1 = 2I; Γ = 10I |
/// | Zhang | periodic MIMO | K = T⁻¹[3I; 0]; Γ = γI |
/// | Besançon (comparison) | third-order SISO | form (8), A22 from a Riccati design with decay 1; K1 = 2; Γ = 5I |
/// | Zhang (comparison) | third-order SISO | K = steady Kalman–Bucy gain (Q = I, R = 0.1); Γ = 20I |
/// | Kalman–Bucy on [x; θ] | third-order SISO | P0 = I, Q = diag(I, q_θ I), R = 0.1 |
///
/// Only declared here. The design routines behind them (canonical forms, SPR
/// gains, Riccati equations) run dynamic-size Eigen decompositions that cost a
/// minute of compilation per translation unit, so their double instances (and
/// float for Algorithm 4) are compiled once, in unified_designs.cpp (library
/// `adaptobs_example_designs`), and linked by the examples and the tests. The
/// definitions are in unified_design_definitions.hpp.

#include <adaptobs/baselines/kalman_bucy.hpp>
#include <adaptobs/design/polynomial.hpp>
#include <adaptobs/design/positive_real.hpp>
#include <adaptobs/observers/bastin_gevers.hpp>
#include <adaptobs/observers/besancon.hpp>
#include <adaptobs/observers/marino_tomei.hpp>
#include <adaptobs/observers/zhang_continuous.hpp>

#include "models/periodic_mimo.hpp"
#include "models/siso_third_order.hpp"

#include <optional>

namespace adaptobs::examples::designs {

template <typename S>
using SisoModel = decltype(siso::model<S>());
template <typename S>
using PeriodicModel = decltype(periodic::model<S>());

/// One RK4 step per sample, u and y at the stage times (the samples carry midpoints).
inline SamplingOptions quadratic() {
  return {.substeps = 1, .input = SignalReconstruction::quadratic, .output = SignalReconstruction::quadratic};
}

/// Static transforms of the third-order plant to the forms of Algorithms 1, 2 and 3.
template <typename S>
StaticTransform<siso::Dims<S>> bastin_gevers_transform();
template <typename S>
StaticTransform<siso::Dims<S>> marino_tomei_transform();
template <typename S>
StaticTransform<siso::Dims<S>> besancon_transform();

template <typename S>
BastinGeversObserver<SisoModel<S>> bastin_gevers_observer(UnifiedObserverOptions options = {.sampling = quadratic()});
template <typename S>
MarinoTomeiObserver<SisoModel<S>> marino_tomei_observer(UnifiedObserverOptions options = {.sampling = quadratic()});
template <typename S>
BesanconObserver<PeriodicModel<S>> besancon_observer(UnifiedObserverOptions options = {.sampling = quadratic()});
template <typename S>
ZhangContinuousObserver<PeriodicModel<S>> zhang_observer(S gamma,
                                                         UnifiedObserverOptions options = {.sampling = quadratic()});
template <typename S>
AugmentedKalmanBucyFilter<SisoModel<S>> kalman_bucy_filter(S q_theta, SamplingOptions options = quadratic());

/// Algorithms 3 and 4 on the third-order plant, for the comparison of all four.
template <typename S>
BesanconObserver<SisoModel<S>> siso_besancon_observer(UnifiedObserverOptions options = {.sampling = quadratic()});
template <typename S>
ZhangContinuousObserver<SisoModel<S>> siso_zhang_observer(UnifiedObserverOptions options = {.sampling = quadratic()});

/// What the examples print about the SPR condition of \f$c(sI - A)^{-1}b\f$
/// (third order): the transfer function, the exact test, the frequency sweep
/// and, when G is SPR, the KYP certificate with its residuals.
struct SprReport {
  SisoTransferFunction<double> transfer_function;
  SprTest<double> exact;
  SprSweep<double> sweep;
  std::optional<KypCertificate<double, 3>> kyp;
};
[[nodiscard]] SprReport spr_report(const Eigen::Matrix3d& A, const Eigen::Vector3d& b, const Eigen::RowVector3d& c);

/// Real parts of the eigenvalues of A (printed by the examples as decay rates).
[[nodiscard]] Eigen::VectorXd eigenvalue_real_parts(const Eigen::MatrixXd& A);

}  // namespace adaptobs::examples::designs
