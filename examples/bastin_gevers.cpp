// Algorithm 1 of paper 001 (§III-A, Bastin & Gevers): the third-order SISO
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

namespace siso = adaptobs::examples::siso;
namespace designs = adaptobs::examples::designs;
using adaptobs::examples::print_value;

int main(int argc, char** argv) {
  const adaptobs::examples::Arguments args(argc, argv, "bastin_gevers",
                                           {{"seconds", "100"}, {"noise", "0"}, {"seed", "1"}});
  auto observer = designs::bastin_gevers_observer<double>();
  const auto& algorithm = observer.algorithm();
  const auto so = observer.transformed_system(0.0);
  print_value("T", algorithm.static_transform.T());
  print_value("K", algorithm.static_transform.K());
  print_value("A_o", so.Ao);
  print_value("c_o", so.Co);
  print_value("eig_A22", designs::eigenvalue_real_parts(so.Ao.bottomRightCorner(2, 2)));
  print_value("k", algorithm.k);
  print_value("Gamma", observer.law().gamma());
  const auto spr = designs::spr_report(so.Ao - algorithm.k * so.Co, Eigen::Vector3d(1, 0, 0), so.Co);
  adaptobs::examples::print_spr_report(spr);

  auto plant = siso::make_plant<double>(
      {.output_noise = args.number("noise"), .seed = static_cast<std::uint64_t>(args.number("seed"))});
  adaptobs::SeriesTable table;
  adaptobs::examples::run_continuous(plant, args.number("seconds"), 0.01, 10, table, adaptobs::track(observer));
  adaptobs::examples::print_final_errors(plant, observer);

  adaptobs::examples::write_outputs(
      table, args.out_dir(), "bastin_gevers",
      adaptobs::examples::estimates_and_errors_figure(
          "Bastin-Gevers adaptive observer (paper 001, Algorithm 1) on a third-order SISO plant", "2 and -1", 2, 3));
  return 0;
}
