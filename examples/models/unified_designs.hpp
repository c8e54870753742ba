#pragma once
/// \file
/// The observer designs of the continuous-time examples (paper 001), shared
/// with the tests and the benchmarks: each algorithm with its static transform,
/// gains and adaptation gain, on the plant it is shown with.
///
/// | observer | plant | design |
/// |---|---|---|
/// | Bastin–Gevers | third-order SISO | form (5) with det(sI − A22) = (s+1)(s+3); k from `spr_injection_gain` (λ = 2: k = (2, 0, 0)); Γ = 5I |
/// | Marino–Tomei | third-order SISO | form (7); γ = (1, 3, 2); k for λ = 5: (8, 17, 10); Γ = 20I |
/// | Besançon | periodic MIMO | T of the plant model, K = 0; K1 = 2I; Γ = 10I |
/// | Zhang | periodic MIMO | K = T⁻¹[3I; 0]; Γ = γI |
/// | Kalman–Bucy on [x; θ] | third-order SISO | P0 = I, Q = diag(I, q_θ I), R = 0.1 |

#include <adaptobs/baselines/kalman_bucy.hpp>
#include <adaptobs/design/canonical_forms.hpp>
#include <adaptobs/design/positive_real.hpp>
#include <adaptobs/observers/bastin_gevers.hpp>
#include <adaptobs/observers/besancon.hpp>
#include <adaptobs/observers/marino_tomei.hpp>
#include <adaptobs/observers/zhang_continuous.hpp>

#include "models/periodic_mimo.hpp"
#include "models/siso_third_order.hpp"

namespace adaptobs::examples::designs {

/// One RK4 step per sample, u and y at the stage times (the samples carry midpoints).
inline SamplingOptions quadratic() {
  return {.substeps = 1, .input = SignalReconstruction::quadratic, .output = SignalReconstruction::quadratic};
}

template <typename S>
Polynomial<S> bastin_gevers_zeros() {
  Polynomial<S> nu(3);
  nu << 1, 4, 3;  // (s + 1)(s + 3)
  return nu;
}

template <typename S>
StaticTransform<siso::Dims<S>> bastin_gevers_transform() {
  return bastin_gevers_form<siso::Dims<S>>(siso::dynamics<S>(), siso::output_matrix<S>(), bastin_gevers_zeros<S>());
}

template <typename S>
auto bastin_gevers_observer(UnifiedObserverOptions options = {.sampling = quadratic()}) {
  const auto transform = bastin_gevers_transform<S>();
  const auto so = transform.apply(siso::model<S>().system());
  const Eigen::Matrix<S, 3, 1> k = spr_injection_gain(so.Ao, so.Co, Eigen::Matrix<S, 3, 1>(1, 0, 0), S(2));
  return make_bastin_gevers_observer(siso::model<S>(), transform, k, Eigen::Matrix<S, 2, 2>(S(5) * Eigen::Matrix<S, 2, 2>::Identity()),
                                     Eigen::Matrix<S, 3, 1>::Zero().eval(), Eigen::Matrix<S, 2, 1>::Zero().eval(), options);
}

template <typename S>
auto marino_tomei_observer(UnifiedObserverOptions options = {.sampling = quadratic()}) {
  const auto transform = marino_tomei_form<siso::Dims<S>>(siso::dynamics<S>(), siso::output_matrix<S>());
  const auto so = transform.apply(siso::model<S>().system());
  const Eigen::Matrix<S, 3, 1> gamma(1, 3, 2);
  const Eigen::Matrix<S, 3, 1> k = spr_injection_gain(so.Ao, so.Co, gamma, S(5));
  return make_marino_tomei_observer(siso::model<S>(), transform, gamma, k,
                                    Eigen::Matrix<S, 2, 2>(S(20) * Eigen::Matrix<S, 2, 2>::Identity()),
                                    Eigen::Matrix<S, 3, 1>::Zero().eval(), Eigen::Matrix<S, 2, 1>::Zero().eval(), options);
}

template <typename S>
auto besancon_observer(UnifiedObserverOptions options = {.sampling = quadratic()}) {
  const StaticTransform<periodic::Dims<S>> transform(periodic::coordinate_change<S>(), Eigen::Matrix<S, 4, 2>::Zero());
  return make_besancon_observer(periodic::model<S>(), transform, Eigen::Matrix<S, 2, 2>(S(2) * Eigen::Matrix<S, 2, 2>::Identity()),
                                Eigen::Matrix<S, 2, 2>(S(10) * Eigen::Matrix<S, 2, 2>::Identity()),
                                Eigen::Matrix<S, 4, 1>::Zero().eval(), Eigen::Matrix<S, 2, 1>::Zero().eval(), options);
}

template <typename S>
auto zhang_observer(S gamma, UnifiedObserverOptions options = {.sampling = quadratic()}) {
  return make_zhang_continuous_observer(periodic::model<S>(), periodic::zhang_gain<S>(),
                                        Eigen::Matrix<S, 2, 2>(gamma * Eigen::Matrix<S, 2, 2>::Identity()),
                                        Eigen::Matrix<S, 4, 1>::Zero().eval(), Eigen::Matrix<S, 2, 1>::Zero().eval(), options);
}

template <typename S>
auto kalman_bucy_filter(S q_theta, SamplingOptions options = quadratic()) {
  using Cov = AugmentedKalmanCovariances<siso::Dims<S>>;
  typename Cov::AugmentedMatrix q = Cov::AugmentedMatrix::Identity();
  q.template bottomRightCorner<2, 2>() *= q_theta;
  const Cov covariances{Cov::AugmentedMatrix::Identity(), q, Eigen::Matrix<S, 1, 1>(S(0.1))};
  return AugmentedKalmanBucyFilter(siso::model<S>(), Eigen::Matrix<S, 3, 1>::Zero().eval(),
                                   Eigen::Matrix<S, 2, 1>::Zero().eval(), covariances, options);
}

}  // namespace adaptobs::examples::designs
