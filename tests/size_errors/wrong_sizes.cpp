// Compiled by the CTest size_errors_name_the_argument with one WRONG_* macro
// defined: each must stop the compilation with the library's static_assert
// naming the argument, not with Eigen's YOU_MIXED_MATRICES_OF_DIFFERENT_SIZES.
#include <adaptobs/observers/guyader_zhang.hpp>

using Dims = adaptobs::Dimensions<double, /*nx*/ 4, /*nu*/ 2, /*ny*/ 2, /*np*/ 2>;

int main() {
  const Eigen::Matrix4d A = Eigen::Matrix4d::Identity() * 0.5;
#ifdef WRONG_B
  const Eigen::Matrix<double, 4, 3> B = Eigen::Matrix<double, 4, 3>::Zero();
#else
  const Eigen::Matrix<double, 4, 2> B = Eigen::Matrix<double, 4, 2>::Zero();
#endif
  const adaptobs::DiscreteLtiModel<Dims> model(A, B, Eigen::Matrix<double, 2, 4>::Identity());
#ifdef WRONG_K
  const Eigen::Matrix<double, 2, 4> K = Eigen::Matrix<double, 2, 4>::Zero();
#else
  const Eigen::Matrix<double, 4, 2> K = Eigen::Matrix<double, 4, 2>::Zero();
#endif
#ifdef WRONG_THETA0
  const Eigen::Vector3d theta0 = Eigen::Vector3d::Zero();
#else
  const Eigen::Vector2d theta0 = Eigen::Vector2d::Zero();
#endif
  const adaptobs::GuyaderZhangObserver observer(model, K, 1.0, Eigen::Vector4d::Zero(), theta0);
  return observer.step() == 0 ? 0 : 1;
}
