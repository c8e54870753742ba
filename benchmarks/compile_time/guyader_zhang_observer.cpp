// Compile-time benchmark, library side: one adaptobs::GuyaderZhangObserver at
// the satellite's sizes (Guyader & Zhang 2003, §4) from the printed gain, 1000 updates on
// a simulated noise-free plant, then both diagnostics.
// Paired with guyader_zhang_eigen.cpp (the same job with Eigen alone).

#include <adaptobs/observers/guyader_zhang.hpp>

#include "satellite_problem.hpp"

#include <cstdio>

using Dims = adaptobs::Dimensions<double, 4, 2, 2, 2>;

int main() {
  const SatelliteProblem problem = satellite_problem();
  const Eigen::Matrix4d& A = problem.A;
  const Eigen::Matrix<double, 2, 4>& C = problem.C;
  const Eigen::Matrix<double, 4, 2>& K = problem.K;

  adaptobs::DiscreteLtiModel<Dims> model(A, Eigen::Matrix<double, 4, 2>::Zero(), C);
  adaptobs::GuyaderZhangObserver observer(model, K, 4.0, Eigen::Vector4d(0.9, 0, 0, 3.14e-4), Eigen::Vector2d(0.5, 0.5),
                                          {.excitation_window = 100});

  const Eigen::Vector2d theta(1, 1.5);
  Eigen::Vector4d x(1, 0, 0, 3.49e-4);
  for (int k = 0; k < 1000; ++k) {
    const Eigen::Vector2d u = satellite_input(k);
    const Eigen::Matrix<double, 4, 2> psi = satellite_regressor(problem, u);
    const adaptobs::DiscreteSample<Dims> sample{u, C * x, psi};
    if (observer.update(sample) != adaptobs::UpdateStatus::accepted) return 1;
    x = A * x + psi * theta;
  }

  const Eigen::Vector4d& xhat = observer.state();
  const Eigen::Vector2d& thetahat = observer.parameters();
  std::printf("xhat %.17g %.17g %.17g %.17g\n", xhat(0), xhat(1), xhat(2), xhat(3));
  std::printf("thetahat %.17g %.17g\n", thetahat(0), thetahat(1));
  std::printf("assumption2_norm %.17g\n", observer.assumption2_norm());
  std::printf("excitation_level %.17g\n", observer.excitation_level().value_or(-1));
}
