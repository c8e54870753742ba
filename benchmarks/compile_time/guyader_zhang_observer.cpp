// Compile-time benchmark, library side: one adaptobs::GuyaderZhangObserver at
// the satellite's sizes (paper 000 §4) from the printed gain, 1000 updates on
// a simulated noise-free plant, then both diagnostics.
// Paired with guyader_zhang_eigen.cpp (the same job with Eigen alone).

#include <adaptobs/observers/guyader_zhang.hpp>

#include <cstdio>

using Dims = adaptobs::Dimensions<double, 4, 2, 2, 2>;

int main() {
  Eigen::Matrix4d A, H;
  A << 1.000000001827015, 0.099999999979699827, 0, 3.4899999996457628e-06,                    //
      3.6540299992582279e-08, 0.99999999939099504, 0, 6.9799999985830497e-05,                  //
      -4.2508548997411251e-14, -3.4899999996457632e-06, 1, 0.099999999918799348,               //
      -1.2752564698705613e-12, -6.9799999985830497e-05, 0, 0.99999999756398017;
  H << 0.10000000006090048, 0.0049999999994924963, 0, 1.163333333262486e-07,                   //
      1.8270149998145573e-09, 0.099999999979699841, 0, 3.4899999996457628e-06,                 //
      -1.0627137249568544e-15, -1.1633333332624865e-07, 0.10000000000000001, 0.0049999999979699851,  //
      -4.2508548997411239e-14, -3.4899999996457632e-06, 0, 0.099999999918799348;
  Eigen::Matrix<double, 2, 4> C;
  C << 1, 0, 0, 0,  //
      0, 0, 1, 0;
  Eigen::Matrix<double, 4, 2> K;
  K << 0.1412, 4.93e-6, 0.0932, 5.26e-5, -4.93e-6, 0.1412, -5.26e-5, 0.0932;

  adaptobs::DiscreteLtiModel<Dims> model(A, Eigen::Matrix<double, 4, 2>::Zero(), C);
  adaptobs::GuyaderZhangObserver observer(model, K, 4.0, Eigen::Vector4d(0.9, 0, 0, 3.14e-4), Eigen::Vector2d(0.5, 0.5),
                                          {.excitation_window = 100});

  const Eigen::Vector2d theta(1, 1.5);
  Eigen::Vector4d x(1, 0, 0, 3.49e-4);
  for (int k = 0; k < 1000; ++k) {
    // Unit thrust pulses of 1 s every 10 s (Ts = 0.1 s), tangential ones 5 s later.
    const Eigen::Vector2d u(k % 100 < 10, k >= 50 && (k - 50) % 100 < 10);
    Eigen::Matrix<double, 4, 2> psi;
    psi << H.col(1) * u(0), H.col(3) * u(1);
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
