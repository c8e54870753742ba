// All four algorithms of Zhang (2005) on one plant where all apply — the
// third-order SISO plant of examples/models/siso_third_order.hpp (constant,
// observable, one output) — each brought to its own form by the library's
// static transforms, beside the Kalman–Bucy filter on [x; θ] (appendix).
//
//   Alg. 1 Bastin–Gevers (bg): form (5), k = (2, 0, 0), Γ = 5I
//   Alg. 2 Marino–Tomei (mt): form (7), γ = (1, 3, 2), k = (8, 17, 10), Γ = 20I
//   Alg. 3 Besançon (bes): form (8) with m = 1 (A22 from a Riccati design, decay 1), K1 = 2, Γ = 5I
//   Alg. 4 Zhang (primary columns): no coordinate change, K = steady Kalman–Bucy gain (Q = I, R = 0.1), Γ = 20I
//   Kalman–Bucy on [x; θ] (kb): P0 = I, Q = I, R = 0.1
//
// Usage: unified_comparison [--out DIR] [--seconds 100] [--noise 0] [--seed 1]
// Writes unified_comparison.csv (t,u_1,y_1,x_*,xhat_*,theta_*,thetahat_*, then
// xhat_<s>_*,thetahat_<s>_* for s = bg, mt, bes, kb) and unified_comparison.png.

#include <adaptobs/adaptobs.hpp>
#include <adaptobs/simulation.hpp>

#include "common/continuous_example.hpp"
#include "common/example_support.hpp"
#include "models/unified_designs.hpp"

#include <cmath>
#include <string>

namespace siso = adaptobs::examples::siso;
namespace designs = adaptobs::examples::designs;
using adaptobs::examples::print_value;

// Gnuplot body of unified_comparison.png: both parameter estimates of the five
// observers, and their error (below 1e-12 drawn at 1e-12).
constexpr const char* figure_script = R"(
set multiplot layout 3,1 title 'Zhang (2005): four adaptive observers of one unified formulation, and the Kalman-Bucy filter on [x; theta] (no units)'
set grid
set xlabel 't (s)'
set key outside right
set lmargin 12
set title 'theta^1 (true 2)'
set ylabel 'theta^1 estimate (no unit)'
plot csv using 't':'thetahat_bg_1' with lines lw 1.5 title 'Alg. 1 Bastin-Gevers', \
     csv using 't':'thetahat_mt_1' with lines lw 1.5 title 'Alg. 2 Marino-Tomei', \
     csv using 't':'thetahat_bes_1' with lines lw 1.5 title 'Alg. 3 Besancon', \
     csv using 't':'thetahat_1' with lines lw 1.5 title 'Alg. 4 Zhang', \
     csv using 't':'thetahat_kb_1' with lines lw 1.5 dt 2 title 'Kalman-Bucy [x; theta]', \
     csv using 't':'theta_1' with lines lc 'black' dt 3 title 'true'
set title 'theta^2 (true -1)'
set ylabel 'theta^2 estimate (no unit)'
plot csv using 't':'thetahat_bg_2' with lines lw 1.5 title 'Alg. 1 Bastin-Gevers', \
     csv using 't':'thetahat_mt_2' with lines lw 1.5 title 'Alg. 2 Marino-Tomei', \
     csv using 't':'thetahat_bes_2' with lines lw 1.5 title 'Alg. 3 Besancon', \
     csv using 't':'thetahat_2' with lines lw 1.5 title 'Alg. 4 Zhang', \
     csv using 't':'thetahat_kb_2' with lines lw 1.5 dt 2 title 'Kalman-Bucy [x; theta]', \
     csv using 't':'theta_2' with lines lc 'black' dt 3 title 'true'
set title 'parameter estimation error (log scale: below 10^{-12} drawn at 10^{-12})'
set ylabel '|estimate - theta| (no unit)'
set logscale y
set format y '10^{%T}'
e(a, b) = floored(sqrt((column(a.'_1') - column('theta_1'))**2 + (column(a.'_2') - column('theta_2'))**2), 1e-12)
plot csv using 't':(e('thetahat_bg', '')) with lines lw 1.5 title 'Alg. 1 Bastin-Gevers', \
     csv using 't':(e('thetahat_mt', '')) with lines lw 1.5 title 'Alg. 2 Marino-Tomei', \
     csv using 't':(e('thetahat_bes', '')) with lines lw 1.5 title 'Alg. 3 Besancon', \
     csv using 't':(e('thetahat', '')) with lines lw 1.5 title 'Alg. 4 Zhang', \
     csv using 't':(e('thetahat_kb', '')) with lines lw 1.5 dt 2 title 'Kalman-Bucy [x; theta]'
unset multiplot)";

int main(int argc, char** argv) try {
  const adaptobs::examples::Arguments args(argc, argv, "unified_comparison",
                                           adaptobs::examples::continuous_options("100"));
  auto bg = designs::bastin_gevers_observer<double>();
  auto mt = designs::marino_tomei_observer<double>();
  auto bes = designs::siso_besancon_observer<double>();
  auto zhang = designs::siso_zhang_observer<double>();
  auto kb = designs::kalman_bucy_filter<double>(1.0);

  print_value("T_bastin_gevers", bg.algorithm().static_transform.T());
  print_value("k_bastin_gevers", bg.algorithm().k);
  print_value("T_marino_tomei", mt.algorithm().static_transform.T());
  print_value("k_marino_tomei", mt.algorithm().k);
  print_value("T_besancon", bes.algorithm().static_transform.T());
  print_value("A22_besancon", bes.transformed_system(0.0).Ao.bottomRightCorner(2, 2));
  const auto zhang_system = zhang.transformed_system(0.0);
  print_value("K_zhang", zhang.algorithm().static_transform.K());
  print_value("eig_A_minus_KC", designs::eigenvalue_real_parts(zhang_system.Ao));

  auto plant = siso::make_plant<double>(
      {.output_noise = args.number("noise"), .seed = static_cast<std::uint64_t>(args.number("seed"))});
  adaptobs::SeriesTable table;
  adaptobs::examples::run_continuous(plant, args.number("seconds"), 0.01, 10, table, adaptobs::track(zhang),
                                     adaptobs::track(bg, "bg"), adaptobs::track(mt, "mt"), adaptobs::track(bes, "bes"),
                                     adaptobs::track(kb, "kb"));
  const auto relative = [&](const auto& o) {
    return (o.parameters() - plant.parameters()).norm() / plant.parameters().norm();
  };
  print_value("theta", plant.parameters());
  print_value("thetahat_zhang", zhang.parameters());
  print_value("thetahat_bastin_gevers", bg.parameters());
  print_value("thetahat_marino_tomei", mt.parameters());
  print_value("thetahat_besancon", bes.parameters());
  print_value("thetahat_kalman_bucy", kb.parameters());
  print_value("theta_relative_error_zhang", relative(zhang));
  print_value("theta_relative_error_bastin_gevers", relative(bg));
  print_value("theta_relative_error_marino_tomei", relative(mt));
  print_value("theta_relative_error_besancon", relative(bes));
  print_value("theta_relative_error_kalman_bucy", relative(kb));

  adaptobs::examples::write_outputs(table, args.out_dir(), "unified_comparison",
                                    std::string(adaptobs::examples::log_floor_function) + figure_script);
  return 0;
} catch (...) {
  return adaptobs::examples::failure("unified_comparison");
}
