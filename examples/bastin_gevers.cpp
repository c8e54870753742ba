// Algorithm 1 of paper 001 (§III-A, Bastin & Gevers): the third-order SISO
// plant of examples/models/siso_third_order.hpp, not in canonical form, is
// brought to the form (5) by the library's static transform
// (det(sI − A22) = (s + 1)(s + 3)); k makes c_o(sI − A_o + k c_o)⁻¹e1 = 1/(s + 2),
// whose SPR-ness is checked exactly, by a frequency sweep and by a KYP certificate.
//
// Usage: bastin_gevers [--out DIR] [--seconds 100] [--noise 0] [--seed 1]
// Writes bastin_gevers.csv (t,u_1,y_1,x_*,xhat_*,theta_*,thetahat_*) and bastin_gevers.png.

#include <adaptobs/adaptobs.hpp>

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
  print_value("G_numerator", spr.transfer_function.numerator.transpose());
  print_value("G_denominator", spr.transfer_function.denominator.transpose());
  print_value("spr_exact", double(spr.exact.strictly_positive_real));
  print_value("spr_sweep_min_weighted_re", spr.sweep.min_weighted_real_part);
  if (spr.kyp) {
    print_value("kyp_P", spr.kyp->P);
    print_value("kyp_residual_Pb_minus_c", spr.kyp->equality_residual);
    print_value("kyp_max_eig_AtP_PA", spr.kyp->max_eigenvalue_lyapunov);
  }

  auto plant = siso::make_plant<double>(
      {.output_noise = args.number("noise"), .seed = static_cast<std::uint64_t>(args.number("seed"))});
  adaptobs::SeriesTable table;
  adaptobs::examples::run_continuous(plant, args.number("seconds"), 0.01, 10, table, adaptobs::track(observer));
  print_value("theta", plant.parameters());
  print_value("thetahat", observer.parameters());
  print_value("theta_relative_error", (observer.parameters() - plant.parameters()).norm() / plant.parameters().norm());
  print_value("state_relative_error", (observer.state() - plant.state()).norm() / plant.state().norm());

  adaptobs::examples::write_outputs(table, args.out_dir(), "bastin_gevers", R"(
set multiplot layout 2,1 title 'Bastin-Gevers adaptive observer (paper 001, Algorithm 1) on a third-order SISO plant'
set grid
set xlabel 't (s)'
set title 'parameter estimates (true 2 and -1)'
plot csv using 't':'thetahat_1' with lines lw 1.5 title 'theta^1', \
     csv using 't':'thetahat_2' with lines lw 1.5 title 'theta^2', \
     csv using 't':'theta_1' with lines lc 'black' dt 3 title 'true', \
     csv using 't':'theta_2' with lines lc 'black' dt 3 notitle
set title 'estimation errors'
set logscale y
set format y '10^{%T}'
plot csv using 't':(sqrt((column('thetahat_1')-column('theta_1'))**2 + (column('thetahat_2')-column('theta_2'))**2)) with lines lw 1.5 title '|theta error|', \
     csv using 't':(sqrt((column('xhat_1')-column('x_1'))**2 + (column('xhat_2')-column('x_2'))**2 + (column('xhat_3')-column('x_3'))**2)) with lines lw 1.5 title '|state error|'
unset multiplot)");
  return 0;
}
