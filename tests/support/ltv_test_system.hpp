#pragma once
// The time-varying dynamics shared by the LTV test systems of the discrete
// observers, defined once so that the one- and two-output systems move alike.

#include <adaptobs/core/dimensions.hpp>

#include <Eigen/Core>

#include <cmath>

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

}  // namespace adaptobs::testing
