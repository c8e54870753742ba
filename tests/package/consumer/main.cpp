// A project that uses an installed adaptobs through find_package.
#include <adaptobs/adaptobs.hpp>
#include <adaptobs/design.hpp>
#include <adaptobs/simulation.hpp>

#include <cstdio>

int main() {
  using Dims = adaptobs::Dimensions<double, 2, 1, 1, 1>;
  Eigen::Matrix2d a;
  a << 1, 0.1, 0, 1;
  const adaptobs::DiscreteLtiModel<Dims> model(a, Eigen::Vector2d(0, 0.1), Eigen::RowVector2d(1, 0));
  const auto kalman = adaptobs::steady_state_kalman_gain(a, Eigen::RowVector2d(1, 0), Eigen::Matrix2d::Identity(),
                                                         Eigen::Matrix<double, 1, 1>::Identity());
  adaptobs::GuyaderZhangObserver observer(model, kalman.K, 1.0, Eigen::Vector2d::Zero(),
                                          Eigen::Matrix<double, 1, 1>::Zero());
  static_assert(adaptobs::Observer<decltype(observer)>);
  const adaptobs::DiscreteSample<Dims> sample{Eigen::Matrix<double, 1, 1>::Ones(), Eigen::Matrix<double, 1, 1>::Ones(),
                                              Eigen::Vector2d(0, 0.1)};
  if (observer.update(sample) != adaptobs::UpdateStatus::accepted) return 1;
  std::puts("adaptobs consumer ok");
  return 0;
}
