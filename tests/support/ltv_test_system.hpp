#pragma once
// The time-varying dynamics shared by the LTV test systems of the discrete
// observers, defined once so that the one- and two-output systems move alike,
// and the check that a model's matrices of the wrong size at some step are
// refused.

#include "support/eigen_testing.hpp"

#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/discrete_model.hpp>
#include <adaptobs/core/status.hpp>

#include <gtest/gtest.h>
#include <Eigen/Core>

#include <cmath>
#include <string>
#include <tuple>

namespace adaptobs::testing {

/// A_k: the first two states rotated by 0.3 + 0.2 sin(0.05 k) and coupled
/// into a stable third one.
inline Eigen::Matrix3d rotating_ltv_dynamics(Index k) {
  const double angle = 0.3 + 0.2 * std::sin(0.05 * double(k));
  Eigen::Matrix3d a;
  a << std::cos(angle), -std::sin(angle), 0.1,  //
      std::sin(angle), std::cos(angle), 0.0,    //
      0.0, 0.2, 0.9;
  return a;
}

/// A two-state, one-input, one-output system of run-time sizes whose matrix
/// `wrong` ('A', 'B' or 'C') has one row too many from step 1 on: what a
/// time-varying model with a bug returns. Stable and observable at step 0.
inline DiscreteSystem<DynamicDimensions<double>> resizing_system(Index k, char wrong) {
  DiscreteSystem<DynamicDimensions<double>> s;
  const Index extra = k >= 1 ? 1 : 0;
  s.A = Eigen::MatrixXd::Identity(2 + (wrong == 'A' ? extra : 0), 2) * 0.5;
  s.B = Eigen::MatrixXd::Ones(2 + (wrong == 'B' ? extra : 0), 1);
  s.C = Eigen::MatrixXd::Zero(1 + (wrong == 'C' ? extra : 0), 2);
  s.C(0, 0) = 1;
  return s;
}

/// A time-varying model of the user's that serves `resizing_system` without
/// checking it (`DiscreteLtvModel` would refuse the wrong size itself).
struct UncheckedResizingModel : DynamicDimensions<double> {
  static constexpr bool time_invariant = false;
  char wrong;
  [[nodiscard]] DiscreteSystem<DynamicDimensions<double>> at(Index k) const { return resizing_system(k, wrong); }
  [[nodiscard]] Sizes sizes() const noexcept { return {2, 1, 1, 1}; }
};

/// For each matrix of `resizing_system`: an observer built by `make(model)` on
/// it accepts the step-0 sample, then refuses the step-1 one with a
/// `ConfigurationError` naming `model.at(k)`, every reading unchanged (a wrong
/// size would otherwise be read out of bounds).
template <class Make>
void expect_resized_step_refused(Make make) {
  for (const char wrong : {'A', 'B', 'C'}) {
    SCOPED_TRACE(std::string("wrong ") + wrong);
    auto observer = make(UncheckedResizingModel{{}, wrong});
    const DiscreteSample<DynamicDimensions<double>> sample{Eigen::VectorXd::Ones(1), Eigen::VectorXd::Ones(1),
                                                           Eigen::MatrixXd::Ones(2, 1)};
    ASSERT_EQ(observer.update(sample), UpdateStatus::accepted);
    const auto readings = [&] {
      return std::tuple{Eigen::VectorXd(observer.state()), Eigen::VectorXd(observer.parameters()),
                        Eigen::VectorXd(observer.output_error()), observer.step()};
    };
    const auto before = readings();
    EXPECT_CONFIGURATION_ERROR_NAMES((void)observer.update(sample), "model.at(k)");
    EXPECT_TRUE(readings() == before);
  }
}

}  // namespace adaptobs::testing
