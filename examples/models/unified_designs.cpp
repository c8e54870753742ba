// The one translation unit that compiles the continuous-time designs of
// unified_designs.hpp, for the examples and the tests that link them.

#include "models/unified_design_definitions.hpp"

#include <adaptobs/design/stability.hpp>

namespace adaptobs::examples::designs {

template StaticTransform<siso::Dims<double>> bastin_gevers_transform<double>();
template StaticTransform<siso::Dims<double>> marino_tomei_transform<double>();
template StaticTransform<siso::Dims<double>> besancon_transform<double>();
template BastinGeversObserver<SisoModel<double>> bastin_gevers_observer<double>(UnifiedObserverOptions);
template MarinoTomeiObserver<SisoModel<double>> marino_tomei_observer<double>(UnifiedObserverOptions);
template BesanconObserver<PeriodicModel<double>> besancon_observer<double>(UnifiedObserverOptions);
template ZhangContinuousObserver<PeriodicModel<double>> zhang_observer<double>(double, UnifiedObserverOptions);
template ZhangContinuousObserver<PeriodicModel<float>> zhang_observer<float>(float, UnifiedObserverOptions);
template AugmentedKalmanBucyFilter<SisoModel<double>> kalman_bucy_filter<double>(double, SamplingOptions);
template BesanconObserver<SisoModel<double>> siso_besancon_observer<double>(UnifiedObserverOptions);
template ZhangContinuousObserver<SisoModel<double>> siso_zhang_observer<double>(UnifiedObserverOptions);

SprReport spr_report(const Eigen::Matrix3d& A, const Eigen::Vector3d& b, const Eigen::RowVector3d& c) {
  return {.transfer_function = adaptobs::transfer_function(A, b, c),
          .exact = strictly_positive_real(A, b, c),
          .sweep = spr_frequency_sweep(A, b, c),
          .kyp = kyp_certificate(A, b, c)};
}

Eigen::VectorXd eigenvalue_real_parts(const Eigen::MatrixXd& A) { return eigenvalues(A).real(); }

}  // namespace adaptobs::examples::designs
