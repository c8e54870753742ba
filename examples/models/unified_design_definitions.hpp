#pragma once
/// \file
/// Definitions of the designs declared in unified_designs.hpp. Examples and
/// tests link the instances compiled once in unified_designs.cpp; the
/// benchmarks include this file to build them with their own instruction set.

#include "models/unified_designs.hpp"

#include <adaptobs/baselines/kalman_bucy.hpp>
#include <adaptobs/design/canonical_forms.hpp>
#include <adaptobs/design/care.hpp>
#include <adaptobs/design/positive_real.hpp>
#include <adaptobs/observers/bastin_gevers.hpp>
#include <adaptobs/observers/besancon.hpp>
#include <adaptobs/observers/marino_tomei.hpp>
#include <adaptobs/observers/zhang_continuous.hpp>

#include "models/periodic_mimo.hpp"
#include "models/siso_third_order.hpp"

namespace adaptobs::examples::designs {

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
StaticTransform<siso::Dims<S>> marino_tomei_transform() {
  return marino_tomei_form<siso::Dims<S>>(siso::dynamics<S>(), siso::output_matrix<S>());
}

template <typename S>
StaticTransform<siso::Dims<S>> besancon_transform() {
  return besancon_form<siso::Dims<S>>(siso::dynamics<S>(), siso::output_matrix<S>());
}

template <typename S>
BastinGeversObserver<SisoModel<S>> bastin_gevers_observer(UnifiedObserverOptions options) {
  const auto transform = bastin_gevers_transform<S>();
  const auto so = transform.apply(siso::model<S>().system());
  const Eigen::Matrix<S, 3, 1> k = spr_injection_gain(so.Ao, so.Co, Eigen::Matrix<S, 3, 1>(1, 0, 0), S(2));
  return make_bastin_gevers_observer(
      siso::model<S>(), transform, k, Eigen::Matrix<S, 2, 2>(S(5) * Eigen::Matrix<S, 2, 2>::Identity()),
      Eigen::Matrix<S, 3, 1>::Zero().eval(), Eigen::Matrix<S, 2, 1>::Zero().eval(), options);
}

template <typename S>
MarinoTomeiObserver<SisoModel<S>> marino_tomei_observer(UnifiedObserverOptions options) {
  const auto transform = marino_tomei_transform<S>();
  const auto so = transform.apply(siso::model<S>().system());
  const Eigen::Matrix<S, 3, 1> gamma(1, 3, 2);
  const Eigen::Matrix<S, 3, 1> k = spr_injection_gain(so.Ao, so.Co, gamma, S(5));
  return make_marino_tomei_observer(
      siso::model<S>(), transform, gamma, k, Eigen::Matrix<S, 2, 2>(S(20) * Eigen::Matrix<S, 2, 2>::Identity()),
      Eigen::Matrix<S, 3, 1>::Zero().eval(), Eigen::Matrix<S, 2, 1>::Zero().eval(), options);
}

template <typename S>
BesanconObserver<PeriodicModel<S>> besancon_observer(UnifiedObserverOptions options) {
  const StaticTransform<periodic::Dims<S>> transform(periodic::coordinate_change<S>(), Eigen::Matrix<S, 4, 2>::Zero());
  return make_besancon_observer(periodic::model<S>(), transform,
                                Eigen::Matrix<S, 2, 2>(S(2) * Eigen::Matrix<S, 2, 2>::Identity()),
                                Eigen::Matrix<S, 2, 2>(S(10) * Eigen::Matrix<S, 2, 2>::Identity()),
                                Eigen::Matrix<S, 4, 1>::Zero().eval(), Eigen::Matrix<S, 2, 1>::Zero().eval(), options);
}

template <typename S>
ZhangContinuousObserver<PeriodicModel<S>> zhang_observer(S gamma, UnifiedObserverOptions options) {
  return make_zhang_continuous_observer(periodic::model<S>(), periodic::zhang_gain<S>(),
                                        Eigen::Matrix<S, 2, 2>(gamma * Eigen::Matrix<S, 2, 2>::Identity()),
                                        Eigen::Matrix<S, 4, 1>::Zero().eval(), Eigen::Matrix<S, 2, 1>::Zero().eval(),
                                        options);
}

template <typename S>
AugmentedKalmanBucyFilter<SisoModel<S>> kalman_bucy_filter(S q_theta, SamplingOptions options) {
  using Cov = AugmentedKalmanCovariances<siso::Dims<S>>;
  typename Cov::AugmentedMatrix q = Cov::AugmentedMatrix::Identity();
  q.template bottomRightCorner<2, 2>() *= q_theta;
  const Cov covariances{Cov::AugmentedMatrix::Identity(), q, Eigen::Matrix<S, 1, 1>(S(0.1))};
  return AugmentedKalmanBucyFilter(siso::model<S>(), Eigen::Matrix<S, 3, 1>::Zero().eval(),
                                   Eigen::Matrix<S, 2, 1>::Zero().eval(), covariances, options);
}

template <typename S>
BesanconObserver<SisoModel<S>> siso_besancon_observer(UnifiedObserverOptions options) {
  return make_besancon_observer(siso::model<S>(), besancon_transform<S>(), Eigen::Matrix<S, 1, 1>(S(2)),
                                Eigen::Matrix<S, 2, 2>(S(5) * Eigen::Matrix<S, 2, 2>::Identity()),
                                Eigen::Matrix<S, 3, 1>::Zero().eval(), Eigen::Matrix<S, 2, 1>::Zero().eval(), options);
}

template <typename S>
ZhangContinuousObserver<SisoModel<S>> siso_zhang_observer(UnifiedObserverOptions options) {
  const auto kalman = kalman_bucy_gain(siso::dynamics<S>(), siso::output_matrix<S>(),
                                       Eigen::Matrix<S, 3, 3>::Identity().eval(), Eigen::Matrix<S, 1, 1>(S(0.1)));
  return make_zhang_continuous_observer(siso::model<S>(), Eigen::Matrix<S, 3, 1>(kalman.K),
                                        Eigen::Matrix<S, 2, 2>(S(20) * Eigen::Matrix<S, 2, 2>::Identity()),
                                        Eigen::Matrix<S, 3, 1>::Zero().eval(), Eigen::Matrix<S, 2, 1>::Zero().eval(),
                                        options);
}

}  // namespace adaptobs::examples::designs
