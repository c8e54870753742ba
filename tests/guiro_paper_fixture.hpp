#pragma once
// The example system of Guiro et al. (2008) §4, shared by the Guiro observer and design tests:
// E = e^{AT}, C and the closed-form H_0, and the gains designed for it.

#include <adaptobs/design/guiro_gains.hpp>

#include "models/guiro.hpp"

#include <Eigen/Core>

namespace adaptobs::testing::guiro {

struct Paper {
  Eigen::Matrix2d E = examples::guiro::model<double>().system().A;
  Eigen::RowVector2d C = examples::guiro::output_matrix<double>();
  Eigen::Vector2d H0 = examples::guiro::closed_form_H<double>(0);
};

inline auto paper_gains(const Eigen::Vector3d& poles = examples::guiro::requested_poles()) {
  const Paper paper;
  return design_guiro_gains(paper.E, paper.C, paper.H0, poles);
}

}  // namespace adaptobs::testing::guiro
