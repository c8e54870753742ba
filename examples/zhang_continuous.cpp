// Algorithm 4 of Zhang (2005, §III-D, Zhang 2002) on the MIMO LTV plant of
// examples/models/periodic_mimo.hpp: no coordinate change, eq. (12a)–(12b),
// with the constant gain K = T⁻¹[3I; 0] (Floquet exponents of A − KC printed)
// and, beside it (suffix `riccati`), with K(t) from the Riccati differential
// equation (Q = I, R = 0.1I, P0 = I) updated at every sample.
//
// Usage: zhang_continuous [--out DIR] [--seconds 40] [--gamma 50] [--noise 0] [--seed 1]
// Writes zhang_continuous.csv (t,u_1,y_*,x_*,xhat_*,theta_*,thetahat_*,
// xhat_riccati_*,thetahat_riccati_*) and zhang_continuous.png.

#include <adaptobs/adaptobs.hpp>
#include <adaptobs/design/ltv_stability.hpp>
#include <adaptobs/design/riccati_differential.hpp>
#include <adaptobs/simulation.hpp>

#include "common/continuous_example.hpp"
#include "common/example_support.hpp"
#include "models/unified_designs.hpp"

#include <string>
#include <utility>

namespace periodic = adaptobs::examples::periodic;
namespace designs = adaptobs::examples::designs;
using adaptobs::examples::print_value;

// Gnuplot body of zhang_continuous.png: the estimates and their error, constant K
// against the Riccati K(t); the error below 1e-12 is drawn at 1e-12.
constexpr const char* figure_script = R"(
set multiplot layout 2,1 title 'Zhang (2002) adaptive observer (Zhang 2005, Algorithm 4) on a periodic MIMO plant (no units)'
set grid
set lmargin 12
set xlabel 't (s)'
set title 'parameter estimates (true 1 and -2)'
set ylabel 'theta (no unit)'
plot csv using 't':'thetahat_1' with lines lw 1.5 title 'theta^1, constant K', \
     csv using 't':'thetahat_2' with lines lw 1.5 title 'theta^2, constant K', \
     csv using 't':'thetahat_riccati_1' with lines dt 2 title 'theta^1, Riccati K(t)', \
     csv using 't':'thetahat_riccati_2' with lines dt 2 title 'theta^2, Riccati K(t)', \
     csv using 't':'theta_1' with lines lc 'black' dt 3 title 'true', \
     csv using 't':'theta_2' with lines lc 'black' dt 3 notitle
set title 'parameter estimation error (log scale: below 10^{-12} drawn at 10^{-12})'
set ylabel '|theta estimate - theta| (no unit)'
set logscale y
set format y '10^{%T}'
plot csv using 't':(floored(sqrt((column('thetahat_1')-column('theta_1'))**2 + (column('thetahat_2')-column('theta_2'))**2), 1e-12)) with lines lw 1.5 title 'constant K', \
     csv using 't':(floored(sqrt((column('thetahat_riccati_1')-column('theta_1'))**2 + (column('thetahat_riccati_2')-column('theta_2'))**2), 1e-12)) with lines lw 1.5 title 'Riccati K(t)'
unset multiplot)";

int main(int argc, char** argv) try {
  auto flags = adaptobs::examples::continuous_options("40");
  flags.insert(flags.begin() + 1,
               {"gamma", "50", "adaptation gain, Gamma = gamma I (the run at h = 0.01 s diverges at 1000)", "",
                adaptobs::examples::real_in(0, 500, "(]")});
  const adaptobs::examples::Arguments args(argc, argv, "zhang_continuous", std::move(flags));
  const double gamma = args.number("gamma");
  const adaptobs::UnifiedObserverOptions options{.sampling = designs::quadratic(), .excitation_window = 629};
  auto observer = designs::zhang_observer<double>(gamma, options);
  auto with_riccati = designs::zhang_observer<double>(gamma, options);
  using D = periodic::Dims<double>;
  adaptobs::RiccatiDifferentialEquation<D> riccati(Eigen::Matrix4d::Identity(), Eigen::Matrix4d::Identity(),
                                                   0.1 * Eigen::Matrix2d::Identity());
  const auto model = periodic::model<double>();
  with_riccati.set_output_injection(riccati.gain(model.at(0.0).C));

  print_value("K", periodic::zhang_gain<double>());
  print_value("Gamma", observer.law().gamma());
  const auto closed = [](double t) {
    const auto s = periodic::system<double>(t);
    return Eigen::Matrix4d(s.A - periodic::zhang_gain<double>() * s.C);
  };
  print_value("floquet_exponents_A_minus_KC", adaptobs::floquet_exponents(closed, periodic::period).transpose());

  auto plant = periodic::make_plant<double>(
      {.output_noise = args.number("noise"), .seed = static_cast<std::uint64_t>(args.number("seed"))});
  adaptobs::SeriesTable table;
  // The Riccati gain follows the plant: P advances over each sampling interval,
  // and K = P Cᵀ R⁻¹ holds over the next one.
  adaptobs::examples::run_continuous_with(
      plant, args.number("seconds"), 0.01, 5, table,
      [&](double t0, double t1) {
        riccati.advance(model, t0, t1);
        with_riccati.set_output_injection(riccati.gain(model.at(t1).C));
      },
      adaptobs::track(observer), adaptobs::track(with_riccati, "riccati"));
  print_value("theta", plant.parameters());
  print_value("thetahat", observer.parameters());
  print_value("thetahat_riccati", with_riccati.parameters());
  print_value("theta_relative_error", (observer.parameters() - plant.parameters()).norm() / plant.parameters().norm());
  print_value("theta_relative_error_riccati",
              (with_riccati.parameters() - plant.parameters()).norm() / plant.parameters().norm());
  print_value("state_relative_error", (observer.state() - plant.state()).norm() / plant.state().norm());
  print_value("excitation_level_eq15", observer.excitation_level().value_or(0.0));
  print_value("riccati_final_K", riccati.gain(model.at(plant.time()).C));

  adaptobs::examples::write_outputs(table, args.out_dir(), "zhang_continuous",
                                    std::string(adaptobs::examples::log_floor_function) + figure_script);
  return 0;
} catch (...) {
  return adaptobs::examples::failure("zhang_continuous");
}
