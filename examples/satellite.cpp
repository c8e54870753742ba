// Controlled satellite, Guyader & Zhang (2003), §4: joint estimation of
// the state and of the two thrust efficiencies θ = (1, 1.5) from noisy
// distance and angle measurements, beside the augmented-state Kalman filter.
//
// Usage: satellite [--out DIR] [--seconds 300] [--seed 2003] [--noise 0.01]
//                  [--drop 0] [--outage none|T0,T1]
// Writes satellite.csv (t,u_*,y_*,y_available,x_*,xhat_*,theta_*,thetahat_*,
// xhat_akf_*,thetahat_akf_*,assumption2) and satellite.png (figures 1–3).
// With --drop P each output sample is lost with probability P, with
// --outage T0,T1 none arrives in [T0, T1]: both observers then take the time
// update (Guyader-Zhang with its normalized step, as its header advises when
// outputs can be lost).

#include <adaptobs/adaptobs.hpp>
#include <adaptobs/design/stability.hpp>
#include <adaptobs/simulation.hpp>

#include "common/example_support.hpp"
#include "models/satellite.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

namespace satellite = adaptobs::examples::satellite;
using adaptobs::examples::print_text;
using adaptobs::examples::print_value;

namespace {

// The discrete model comes from the continuous linearized satellite through the
// library's zero-order-hold routine; printed beside the paper's gain to compare
// with its matrices.
void print_design(const Eigen::Matrix<double, 4, 2>& gain) {
  const auto zoh = satellite::discretized<double>();
  print_value("omega", satellite::omega);
  print_value("Ts", satellite::sampling_period);
  print_value("Ad", zoh.Ad);
  print_value("H", zoh.Bd);
  print_value("K", gain);
  print_value("mu", satellite::mu);
  print_value("spectral_radius_A_minus_KC",
              adaptobs::spectral_radius(Eigen::Matrix4d(zoh.Ad - gain * satellite::model<double>().system().C)));
  print_text("thrusts", "unit square pulses of 1 s every 10 s; radial from t = 0, tangential from t = 5 s");
}

// Baseline: Kalman filter on [x; θ] with the true output noise level.
auto augmented_kalman_filter(double noise) {
  using Matrix6 = Eigen::Matrix<double, 6, 6>;
  adaptobs::AugmentedKalmanCovariances<satellite::Dims<double>> covariances;
  covariances.P0 = Matrix6::Zero();
  covariances.P0.diagonal() << 0.1, 1e-4, 0.1, 1e-4, 1.0, 1.0;
  covariances.Q = Matrix6::Zero();
  covariances.Q.diagonal() << 1e-10, 1e-10, 1e-10, 1e-10, 0.0, 0.0;
  covariances.R = Eigen::Matrix2d::Identity() * std::max(noise * noise, 1e-12);
  return adaptobs::AugmentedKalmanFilter(satellite::model<double>(), satellite::initial_state_estimate<double>(),
                                         satellite::initial_parameter_estimate<double>(), covariances);
}

// The mean of θ̂ (columns `prefix`1 and `prefix`2) over the last `window` rows.
Eigen::Vector2d mean_over_last_rows(const adaptobs::SeriesTable& table, const std::string& prefix, std::size_t window) {
  const std::size_t rows = table.rows();
  window = std::min(rows, window);
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (std::size_t r = rows - window; r < rows; ++r)
    mean += Eigen::Vector2d(table.at(r, prefix + "1"), table.at(r, prefix + "2"));
  return mean / double(window);
}

double samples_without_output(const adaptobs::SeriesTable& table) {
  double lost = 0;
  for (std::size_t r = 0; r < table.rows(); ++r) lost += table.at(r, "y_available") == 0 ? 1 : 0;
  return lost;
}

void write_figure(const adaptobs::SeriesTable& table, const adaptobs::examples::Arguments& args,
                  const adaptobs::OutputLoss& loss) {
  // Four panels: the state errors in two, positions and velocities, each pair in one unit.
  adaptobs::examples::write_outputs(table, args.out_dir(), "satellite",
                                    adaptobs::examples::gap_shading(table, loss.options()) + R"(
set multiplot layout 4,1 title 'Guyader-Zhang adaptive observer, controlled satellite (Guyader and Zhang 2003, section 4): orbit radius normalized to 1'
set grid
# The legends beside the plots, and the four time axes aligned under one another.
set key outside right top
set lmargin at screen 0.08
set rmargin at screen 0.76
set xlabel 't (s)'
set title 'Figure 1: thrusts'
set ylabel 'thrust (unit pulses)'
set yrange [-0.2:1.2]
plot csv using 't':'u_1' with lines lw 1.5 title 'u^1 radial', \
     csv using 't':'u_2' with lines lw 1.5 title 'u^2 tangential'
set autoscale y
set title 'Figure 2: state estimation errors, positions (estimate - true)'
set ylabel 'error (orbit radii; rad)'
plot csv using 't':(column('xhat_1') - column('x_1')) with lines title 'radial position r (orbit radii)', \
     csv using 't':(column('xhat_3') - column('x_3')) with lines title 'angle (rad)'
set title 'Figure 2: state estimation errors, velocities (estimate - true)'
set ylabel 'error (orbit radii/s; rad/s)'
plot csv using 't':(column('xhat_2') - column('x_2')) with lines title 'radial velocity (orbit radii/s)', \
     csv using 't':(column('xhat_4') - column('x_4')) with lines title 'angular velocity (rad/s)'
set title 'Figure 3: parameter estimates (true 1 and 1.5; KF: Kalman filter on [x; theta])'
set ylabel 'thrust efficiency (no unit)'
plot csv using 't':'thetahat_1' with lines lw 1.5 title 'theta^1 radial, observer', \
     csv using 't':'thetahat_2' with lines lw 1.5 title 'theta^2 tangential, observer', \
     csv using 't':'thetahat_akf_1' with lines dt 2 title 'theta^1 radial, KF', \
     csv using 't':'thetahat_akf_2' with lines dt 2 title 'theta^2 tangential, KF', \
     csv using 't':'theta_1' with lines lc 'black' dt 3 title 'true', \
     csv using 't':'theta_2' with lines lc 'black' dt 3 notitle
unset multiplot)",
                                    "1200,1200");
}

}  // namespace

int main(int argc, char** argv) try {
  const adaptobs::examples::Arguments args(
      argc, argv, "satellite",
      adaptobs::examples::with_output_loss(
          {{"seconds", "300", "length of the run", "s", adaptobs::examples::real_in(1, 1e6)},
           adaptobs::examples::seed_option("2003", "seed of the output noise (the lost samples draw from seed + 1)"),
           adaptobs::examples::noise_option(
               "0.01", "output noise, standard deviation on both outputs (radial position and angle)")},
          "s"));
  const auto seed = static_cast<std::uint64_t>(args.integer("seed"));
  adaptobs::OutputLoss loss(adaptobs::examples::output_loss_options(args, seed + 1, args.number("seconds")));
  const auto steps = static_cast<adaptobs::Index>(std::llround(args.number("seconds") / satellite::sampling_period));
  const double noise = args.number("noise");

  const Eigen::Matrix<double, 4, 2> gain = satellite::paper_gain<double>();
  print_design(gain);
  adaptobs::GuyaderZhangObserver observer(
      satellite::model<double>(), gain, satellite::mu, satellite::initial_state_estimate<double>(),
      satellite::initial_parameter_estimate<double>(), {.excitation_window = 100, .normalized_step = !loss.lossless()});
  auto akf = augmented_kalman_filter(noise);

  auto plant = satellite::make_plant<double>(noise, seed);
  adaptobs::SeriesTable table;
  const auto report = adaptobs::simulate(
      plant, steps, table, loss,
      [&](adaptobs::SeriesTable& row, const auto&) { row.add("assumption2", observer.assumption2_norm()); },
      adaptobs::track(observer), adaptobs::track(akf, "akf"));

  // Final estimates, and their average over the last 100 s (noise makes θ̂ wander).
  print_value("steps", double(report.steps));
  print_value("rejected", double(report.rejected[0] + report.rejected[1]));
  print_value("samples_without_output", samples_without_output(table));
  print_value("theta", plant.parameters());
  print_value("thetahat", observer.parameters());
  print_value("thetahat_mean_last_100s", mean_over_last_rows(table, "thetahat_", 1000));
  print_value("thetahat_akf", akf.parameters());
  print_value("thetahat_akf_mean_last_100s", mean_over_last_rows(table, "thetahat_akf_", 1000));
  print_value("state_error_norm", (observer.state() - plant.state()).norm());
  print_value("excitation_level", observer.excitation_level().value_or(0.0));
  print_value("assumption2_norm", observer.assumption2_norm());
  write_figure(table, args, loss);
  return 0;
} catch (...) {
  return adaptobs::examples::failure("satellite");
}
