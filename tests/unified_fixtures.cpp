// The one translation unit that runs the design routines of the continuous-time
// observer tests (see unified_fixtures.hpp).

#include "unified_fixtures.hpp"

#include <adaptobs/design/canonical_forms.hpp>
#include <adaptobs/design/positive_real.hpp>

namespace adaptobs::testing::unified {

namespace designs = adaptobs::examples::designs;

template <typename S>
adaptobs::BastinGeversObserver<SisoModel<S>> bastin_gevers_observer(adaptobs::UnifiedObserverOptions options) {
  return designs::bastin_gevers_observer<S>(options);
}
template <typename S>
adaptobs::MarinoTomeiObserver<SisoModel<S>> marino_tomei_observer(adaptobs::UnifiedObserverOptions options) {
  return designs::marino_tomei_observer<S>(options);
}
template <typename S>
adaptobs::BesanconObserver<PeriodicModel<S>> besancon_observer(adaptobs::UnifiedObserverOptions options) {
  return designs::besancon_observer<S>(options);
}
template <typename S>
adaptobs::ZhangContinuousObserver<PeriodicModel<S>> zhang_observer(S gamma, adaptobs::UnifiedObserverOptions options) {
  return designs::zhang_observer<S>(gamma, options);
}
template <typename S>
adaptobs::AugmentedKalmanBucyFilter<SisoModel<S>> kalman_bucy_filter(S q_theta, adaptobs::SamplingOptions options) {
  return designs::kalman_bucy_filter<S>(q_theta, options);
}

template adaptobs::BastinGeversObserver<SisoModel<double>> bastin_gevers_observer<double>(adaptobs::UnifiedObserverOptions);
template adaptobs::MarinoTomeiObserver<SisoModel<double>> marino_tomei_observer<double>(adaptobs::UnifiedObserverOptions);
template adaptobs::BesanconObserver<PeriodicModel<double>> besancon_observer<double>(adaptobs::UnifiedObserverOptions);
template adaptobs::ZhangContinuousObserver<PeriodicModel<double>> zhang_observer<double>(double,
                                                                                     adaptobs::UnifiedObserverOptions);
template adaptobs::ZhangContinuousObserver<PeriodicModel<float>> zhang_observer<float>(float,
                                                                                   adaptobs::UnifiedObserverOptions);
template adaptobs::AugmentedKalmanBucyFilter<SisoModel<double>> kalman_bucy_filter<double>(double,
                                                                                         adaptobs::SamplingOptions);

adaptobs::StaticTransform<siso::Dims<double>> bastin_gevers_transform() {
  return designs::bastin_gevers_transform<double>();
}
adaptobs::StaticTransform<siso::Dims<double>> marino_tomei_transform() {
  return adaptobs::marino_tomei_form<siso::Dims<double>>(siso::dynamics<double>(), siso::output_matrix<double>());
}
adaptobs::StaticTransform<siso::Dims<double>> besancon_transform() {
  return adaptobs::besancon_form<siso::Dims<double>>(siso::dynamics<double>(), siso::output_matrix<double>());
}

std::optional<Eigen::Matrix3d> kyp_matrix(const Eigen::Matrix3d& A, const Eigen::Vector3d& b,
                                               const Eigen::RowVector3d& c) {
  const auto k = adaptobs::kyp_certificate(A, b, c);
  if (!k) return std::nullopt;
  return k->P;
}

}  // namespace adaptobs::testing::unified
