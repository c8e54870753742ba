// No heap allocation when a CUSUM or a GLR is re-armed (`rearm`, after a
// confirmed change, inside the loop) or updated, with fixed and run-time
// sizes: rearm once built its refusal's name, "CusumDetector::rearm", a string
// beyond the small-string buffer, on every call.

#include <adaptobs/diagnostics/cusum.hpp>
#include <adaptobs/diagnostics/glr.hpp>

#include "support/allocation_counter.hpp"
#include "support/eigen_testing.hpp"

#include <Eigen/Core>

#include <gtest/gtest.h>

#include <string>

namespace {

using adaptobs::testing::allocations_during;

// The allocations of 1000 updates of `detector` on alternating values, re-armed every seventh.
template <class Detector, class Vector>
long allocations_of_rearming(Detector& detector, const Vector& a, const Vector& b) {
  return allocations_during([&] {
    for (int k = 0; k < 1000; ++k) {
      (void)detector.update(k % 2 ? a : b);
      if (k % 7 == 0) detector.rearm(k % 2 ? b : a);
    }
  });
}

TEST(NoAllocation, DetectorsRearmWithFixedSizes) {
  adaptobs::CusumDetector<double, 2> cusum(Eigen::Vector2d::Zero(), Eigen::Vector2d::Ones(), 0.5, 2.0);
  adaptobs::GlrDetector<double, 2> glr(Eigen::Vector2d::Zero(), Eigen::Vector2d::Ones(), 10, 3.0);
  const Eigen::Vector2d a(0.1, -0.2), b(2.5, 0.3);
  EXPECT_EQ(allocations_of_rearming(cusum, a, b), 0);
  EXPECT_EQ(allocations_of_rearming(glr, a, b), 0);
  // The detectors ran: values 2.4 scales off the nominal raise alarms.
  EXPECT_GT(cusum.alarm_count(), 0);
  EXPECT_GT(glr.alarm_count(), 0);
  EXPECT_EQ(allocations_during([&] {
              for (int k = 0; k < 1000; ++k) {
                cusum.rearm(a);
                glr.rearm(b);
              }
            }),
            0);
}

TEST(NoAllocation, DetectorsRearmWithRunTimeSizes) {
  adaptobs::CusumDetector<double> cusum(Eigen::VectorXd::Zero(3), Eigen::VectorXd::Ones(3), 0.5, 2.0);
  adaptobs::GlrDetector<double> glr(Eigen::VectorXd::Zero(3), Eigen::VectorXd::Ones(3), 10, 3.0);
  const Eigen::VectorXd a = Eigen::VectorXd::Constant(3, 0.1), b = Eigen::VectorXd::Constant(3, 2.5);
  EXPECT_EQ(allocations_of_rearming(cusum, a, b), 0);
  EXPECT_EQ(allocations_of_rearming(glr, a, b), 0);
  EXPECT_GT(cusum.alarm_count(), 0);
  EXPECT_GT(glr.alarm_count(), 0);
  // A refusal still names the method and its argument, with the detector unchanged.
  const std::string refusal = adaptobs::testing::configuration_error_of([&] { cusum.rearm(Eigen::VectorXd::Zero(2)); });
  EXPECT_EQ(refusal.rfind("CusumDetector::rearm: argument 'nominal' must be 3x1", 0), 0u) << refusal;
  const Eigen::VectorXd before = glr.nominal();
  const std::string nan =
      adaptobs::testing::configuration_error_of([&] { glr.rearm(Eigen::VectorXd::Constant(3, NAN)); });
  EXPECT_EQ(nan, "GlrDetector::rearm: argument 'nominal' must contain only finite numbers");
  EXPECT_EQ(glr.nominal(), before);
}

}  // namespace
