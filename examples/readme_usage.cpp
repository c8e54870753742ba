// The README's usage example, compiled and run by CTest so that it cannot rot.
// Satellite of Guyader & Zhang (2003) §4 with the printed matrices: a steady-state
// Kalman gain, one Guyader–Zhang observer, its two diagnostics.
#include <adaptobs/design/dare.hpp>
#include <adaptobs/observers/guyader_zhang.hpp>

#include <iostream>

int main() {
  using Dims = adaptobs::Dimensions<double, /*nx*/ 4, /*nu*/ 2, /*ny*/ 2, /*np*/ 2>;
  Eigen::Matrix4d A, H;  // x_{k+1} = A x_k + Ψ_k θ,  Ψ_k = H [0 0; u¹ 0; 0 0; 0 u²],  y_k = C x_k
  A << 1, 0.1, 0, 3.49e-6, 3.66e-8, 1, 0, 6.98e-5, -4.25e-14, -3.49e-6, 1, 0.1, -1.28e-12, -6.98e-5, 0, 1;
  H << 0.1, 0.005, 0, 1.16e-7, 1.83e-9, 0.1, 0, 3.49e-6, -1.06e-15, -1.16e-7, 0.1, 0.005, -4.25e-14, -3.49e-6, 0, 0.1;
  Eigen::Matrix<double, 2, 4> C;
  C << 1, 0, 0, 0, 0, 0, 1, 0;
  const Eigen::Vector2d theta{1.0, 1.5};  // the true thrust efficiencies, unknown to the observer

  // A − KC Schur stable (assumption 1), from the steady-state Kalman gain.
  const auto kalman =
      adaptobs::steady_state_kalman_gain(A, C, Eigen::Matrix4d::Identity() * 1e-4, Eigen::Matrix2d::Identity() * 1e-2);
  adaptobs::DiscreteLtiModel<Dims> model(A, Eigen::Matrix<double, 4, 2>::Zero(), C);
  adaptobs::GuyaderZhangObserver observer(model, kalman.K, /*mu=*/4.0, Eigen::Vector4d{0.9, 0, 0, 3.14e-4},
                                          Eigen::Vector2d{0.5, 0.5}, {.excitation_window = 100});

  Eigen::Vector4d x{1, 0, 0, 3.49e-4};
  for (int k = 0; k < 3000; ++k) {
    const Eigen::Vector2d u{k % 100 < 10 ? 1.0 : 0.0, (k + 50) % 100 < 10 ? 1.0 : 0.0};  // thrust pulses
    Eigen::Matrix<double, 4, 2> Psi;
    Psi << H.col(1) * u(0), H.col(3) * u(1);
    const adaptobs::DiscreteSample<Dims> sample{u, C * x, Psi};  // measured u_k, y_k and known Ψ_k
    x = A * x + Psi * theta;
    // The second sensor loses one sample in seven: the mask says which outputs were measured,
    // and the step still moves the estimates with the plant (no channel at all: a time update).
    const adaptobs::OutputMask<Dims> present(true, k % 7 != 3);
    if (observer.update(sample, present) != adaptobs::UpdateStatus::accepted) {
      continue;  // NaN/Inf in u, Ψ or a present output: rejected, the observer is exactly as before
    }
  }
  std::cout << "theta_hat = " << observer.parameters().transpose() << '\n'
            << "state_error = " << (observer.state() - x).norm() << '\n'
            << "excitation_level = " << observer.excitation_level().value_or(0.0) << '\n'
            << "health = " << observer.health().message << '\n';  // a broken assumption, a divergence
  return (observer.parameters() - theta).norm() < 1e-6 ? 0 : 1;
}
