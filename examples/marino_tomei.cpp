// Algorithm 2 of Zhang (2005, §III-B, Marino & Tomei): the third-order SISO
// plant of examples/models/siso_third_order.hpp, not in canonical form, is
// brought to the form (7) (c_o = e1ᵀ, A_o the shift) by the library's static
// transform; γ = (1, 3, 2) and k = (8, 17, 10) make
// c_o(sI − A_o + k c_o)⁻¹γ = 1/(s + 5), strictly positive real.
//
// Usage: marino_tomei [--out DIR] [--seconds 100] [--noise 0] [--seed 1]
// Writes marino_tomei.csv (t,u_1,y_1,x_*,xhat_*,theta_*,thetahat_*) and marino_tomei.png.

#include <adaptobs/adaptobs.hpp>
#include <adaptobs/simulation.hpp>

#include "common/continuous_example.hpp"
#include "common/example_support.hpp"
#include "models/unified_designs.hpp"

namespace designs = adaptobs::examples::designs;
using adaptobs::examples::print_value;

int main(int argc, char** argv) try {
  const adaptobs::examples::Arguments args(argc, argv, "marino_tomei", adaptobs::examples::continuous_options("100"));
  auto observer = designs::marino_tomei_observer<double>();
  const auto& algorithm = observer.algorithm();
  const auto so = observer.transformed_system(0.0);
  adaptobs::examples::print_coordinates(observer);
  print_value("gamma", algorithm.gamma);
  print_value("F", algorithm.dynamic_transform.filter_matrix(so.Ao));
  print_value("G", algorithm.dynamic_transform.G());
  print_value("k", algorithm.k);
  print_value("Gamma", observer.law().gamma());
  const auto spr = designs::spr_report(so.Ao - algorithm.k * so.Co, algorithm.gamma, so.Co);
  adaptobs::examples::print_spr_report(spr);

  adaptobs::examples::run_siso_example(
      observer, args, "marino_tomei",
      "Marino-Tomei adaptive observer (Zhang 2005, Algorithm 2) on a third-order SISO plant");
  return 0;
} catch (...) {
  return adaptobs::examples::failure("marino_tomei");
}
