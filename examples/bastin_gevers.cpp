// Algorithm 1 of Zhang (2005, §III-A, Bastin & Gevers): the third-order SISO
// plant of examples/models/siso_third_order.hpp, not in canonical form, is
// brought to the form (5) by the library's static transform
// (det(sI − A22) = (s + 1)(s + 3)); k makes c_o(sI − A_o + k c_o)⁻¹e1 = 1/(s + 2),
// whose SPR-ness is checked exactly, by a frequency sweep and by a KYP certificate.
//
// Usage: bastin_gevers [--out DIR] [--seconds 100] [--noise 0] [--seed 1]
// Writes bastin_gevers.csv (t,u_1,y_1,x_*,xhat_*,theta_*,thetahat_*) and bastin_gevers.png.

#include <adaptobs/adaptobs.hpp>
#include <adaptobs/simulation.hpp>

#include "common/continuous_example.hpp"
#include "common/example_support.hpp"
#include "models/unified_designs.hpp"

namespace designs = adaptobs::examples::designs;
using adaptobs::examples::print_value;

int main(int argc, char** argv) try {
  const adaptobs::examples::Arguments args(argc, argv, "bastin_gevers", adaptobs::examples::continuous_options("100"));
  auto observer = designs::bastin_gevers_observer<double>();
  const auto& algorithm = observer.algorithm();
  const auto so = observer.transformed_system(0.0);
  adaptobs::examples::print_coordinates(observer);
  print_value("eig_A22", designs::eigenvalue_real_parts(so.Ao.bottomRightCorner(2, 2)));
  print_value("k", algorithm.k);
  print_value("Gamma", observer.law().gamma());
  const auto spr = designs::spr_report(so.Ao - algorithm.k * so.Co, Eigen::Vector3d(1, 0, 0), so.Co);
  adaptobs::examples::print_spr_report(spr);

  adaptobs::examples::run_siso_example(
      observer, args, "bastin_gevers",
      "Bastin-Gevers adaptive observer (Zhang 2005, Algorithm 1) on a third-order SISO plant");
  return 0;
} catch (...) {
  return adaptobs::examples::failure("bastin_gevers");
}
