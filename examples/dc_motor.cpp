// Tutorial: a plant of one's own, end to end (docs/tutorial.md walks through it).
//
// A DC motor at 1 kHz with noisy current and speed sensors; the unknowns are
// its load torque and viscous friction (examples/models/dc_motor.hpp writes the
// physics as x_{k+1} = A x_k + B u_k + Ψ_k θ). The program
//  1. designs the output-injection gain K (steady-state Kalman gain);
//  2. chooses μ from a simulated experiment's regressors: the bound of
//     assumption 2 and the fastest rate (design/guyader_zhang_tuning.hpp);
//  3. runs the observer and checks that θ̂ converges;
//  4. designs a fault monitor from fault-free runs and catches a friction
//     increase;
//  5. shows what a too-large μ does, and what `health()` says about it.
// It returns 1 when an estimate or a detection misses the bounds
// docs/tutorial.md states, so that CTest keeps the tutorial true.
//
// Usage: dc_motor [--out DIR] [--seconds 30] [--seed 1] [--fault-time 15] [--friction-factor 2]
// Writes dc_motor.csv (t, u_1, y_*, x_*, theta_*, thetahat_*, cusum, alarm),
// dc_motor_mu.csv (the μ sweep) and dc_motor.png.

#include <adaptobs/adaptobs.hpp>
#include <adaptobs/design/dare.hpp>
#include <adaptobs/design/guyader_zhang_tuning.hpp>
#include <adaptobs/diagnostics.hpp>

#include "common/example_support.hpp"
#include "models/dc_motor.hpp"

#include <cmath>
#include <cstdint>
#include <sstream>
#include <vector>

namespace motor = adaptobs::examples::dc_motor;
using adaptobs::examples::print_text;
using adaptobs::examples::print_value;
using Sample = adaptobs::DiscreteSample<motor::Dims>;

namespace {

// Settling: 5 time constants of the chosen μ; monitoring starts there.
adaptobs::Index settling_steps(const adaptobs::GuyaderZhangConvergence<double>& c) {
  return static_cast<adaptobs::Index>(std::ceil(5 * c.time_constant));
}

// RMS of θ̂ − θ over the samples from `from` on, in each component relative to θ.
Eigen::Vector2d relative_rms_error(const std::vector<Eigen::Vector2d>& estimates, const motor::Run& run,
                                   std::size_t from) {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (std::size_t k = from; k < estimates.size(); ++k)
    sum += (estimates[k] - run.parameters[k]).cwiseQuotient(run.parameters[k]).cwiseAbs2();
  return (sum / double(estimates.size() - from)).cwiseSqrt();
}

}  // namespace

int main(int argc, char** argv) try {
  using adaptobs::examples::real_in;
  const adaptobs::examples::Arguments args(
      argc, argv, "dc_motor",
      {{"seconds", "30", "length of the run with the fault", "s", real_in(5, 1e4)},
       adaptobs::examples::seed_option("1", "seed of the sensor noise (the design runs draw from seed + 1 on)"),
       {"fault-time", "15", "time at which the friction changes, after the estimates settle (2 s)", "s",
        real_in(2, 1e4)},
       {"friction-factor", "2", "factor of the friction from the fault time on", "", real_in(0, 100, "(]")}});
  args.require(args.number("fault-time") < args.number("seconds") - 1, "fault-time",
               "in [2, " + adaptobs::examples::format_number(args.number("seconds") - 1) +
                   ") (at least 1 s before the end of the run, --seconds)");
  const double seconds = args.number("seconds");
  const auto seed = static_cast<std::uint64_t>(args.integer("seed"));
  const motor::Scenario fault_free;  // the defaults: T_L = 0.02 N·m, b = 1e-4 N·m·s/rad, no fault
  motor::Scenario faulty = fault_free;
  faulty.fault_time = args.number("fault-time");
  faulty.friction_factor = args.number("friction-factor");

  // 1. The model and the gain. With C = I the Kalman gain weighs each sensor by its noise.
  const motor::SampledMotor plant{motor::Motor{}};
  const auto model = plant.model();
  const Eigen::Matrix2d sensor_covariance = Eigen::Vector2d(fault_free.current_noise * fault_free.current_noise,
                                                            fault_free.speed_noise * fault_free.speed_noise)
                                                .asDiagonal();
  const Eigen::Matrix2d K = adaptobs::steady_state_kalman_gain(plant.A, Eigen::Matrix2d::Identity(),
                                                               Eigen::Matrix2d::Identity() * 1e-4, sensor_covariance)
                                .K;
  print_value("A", plant.A);
  print_value("B", plant.B);
  print_value("K", K);

  // 2. μ from an experiment's regressors: Υ of eq. (2a) depends on neither μ nor θ̂.
  const std::vector<Eigen::Matrix2d> experiment = motor::regressors_of(fault_free.simulate(plant, 5, seed + 1000));
  const double mu_bound = adaptobs::guyader_zhang_mu_bound(model, K, experiment);
  const auto fastest = adaptobs::guyader_zhang_fastest_mu(model, K, experiment);
  const double mu = fastest.mu;
  const double ts = plant.motor.sampling_period;
  print_value("mu_bound_assumption2", mu_bound);
  print_value("mu", mu);
  print_value("predicted_time_constant_s", fastest.time_constant * ts);
  print_value("averaged_time_constant_s", fastest.averaged_time_constant * ts);

  // The trade-off of μ: speed (predicted time constant) against noise (RMS error of θ̂).
  adaptobs::SeriesTable sweep;
  const motor::Run check = fault_free.simulate(plant, seconds, seed + 2000);
  for (double factor = 1e-3; factor <= 1.0001; factor *= std::sqrt(10.0)) {
    const auto c = adaptobs::guyader_zhang_convergence(model, K, experiment, factor * mu_bound);
    adaptobs::GuyaderZhangObserver observer(model, K, c.mu, Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero());
    std::vector<Eigen::Vector2d> estimates;
    for (const Sample& s : check.samples) {
      (void)observer.update(s);
      estimates.push_back(observer.parameters());
    }
    const Eigen::Vector2d rms = relative_rms_error(estimates, check, estimates.size() / 2);
    sweep.begin_row().add("mu", c.mu);
    sweep.add("time_constant", c.time_constant * ts);
    sweep.add("averaged_time_constant", c.averaged_time_constant * ts);
    sweep.add("rms_load", rms(0));
    sweep.add("rms_friction", rms(1));
  }

  // 3. The observer on a run with a friction increase at fault_time.
  adaptobs::GuyaderZhangObserver observer(model, K, mu, Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero());
  const motor::Run run = faulty.simulate(plant, seconds, seed);

  // 4. The monitor, designed from 40 fault-free runs of 60 s after settling, for one
  // false alarm in 10^6 samples (17 min) per test.
  adaptobs::FaultFreeRecord<double, 2, 2> record;
  const adaptobs::Index settle = settling_steps(fastest);
  for (std::uint64_t r = 0; r < 40; ++r) {
    adaptobs::GuyaderZhangObserver healthy(model, K, mu, Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero());
    const motor::Run healthy_run = fault_free.simulate(plant, 60 + double(settle) * ts, seed + 1 + r);
    record.new_run();
    for (std::size_t k = 0; k < healthy_run.samples.size(); ++k)
      if (accepted(healthy.update(healthy_run.samples[k])) && adaptobs::Index(k) >= settle) record.add(healthy);
  }
  // The stride, the number of samples between the values of θ̂ the parameter tests see, must
  // let θ̂ decorrelate; the design searches for the shortest that does, among whole periods
  // of the test voltage (500 samples), so that θ̂ is read at one phase of it, with its
  // correlations at most half their limits (margin 0.5), clear of the record's sampling error.
  const auto design =
      adaptobs::design_fault_monitor(record, /*drift=*/1.0, /*samples between false alarms=*/1e6,
                                     /*chi-square window=*/500, {.stride_multiple = 500, .margin = 0.5});
  adaptobs::FaultMonitor monitor(design);
  print_value("stride", double(design.cusum_options.stride));
  print_value("nominal", design.nominal);
  print_text("design", design.explanation);

  adaptobs::SeriesTable table;
  double alarm_time = -1;
  Eigen::Vector2i alarms_per_parameter = Eigen::Vector2i::Zero();
  for (std::size_t k = 0; k < run.samples.size(); ++k) {
    const double t = double(k) * ts;
    if (!accepted(observer.update(run.samples[k]))) continue;
    if (adaptobs::Index(k) >= settle) (void)monitor.observe(observer);
    // The CUSUM rearms after each alarm and alarms again while the change
    // lasts. The first alarm may name either parameter (the change's transient
    // moves both estimates); the alarms that persist name the one that changed.
    if (monitor.cusum().alarm()) {
      if (alarm_time < 0) alarm_time = t;
      ++alarms_per_parameter(monitor.cusum().isolated());
    }
    table.begin_row().add("t", t);
    table.add("u_1", run.samples[k].u(0));
    table.add("y_1", run.samples[k].y(0));
    table.add("y_2", run.samples[k].y(1));
    table.add("x_1", run.states[k](0));
    table.add("x_2", run.states[k](1));
    table.add("theta_1", run.parameters[k](0));
    table.add("theta_2", run.parameters[k](1));
    table.add("thetahat_1", observer.parameters()(0));
    table.add("thetahat_2", observer.parameters()(1));
    table.add("alarm", alarm_time >= 0 ? 1.0 : 0.0);
  }
  print_value("theta_before_fault", fault_free.parameters_at(plant.motor, 0));
  print_value("theta_after_fault", run.parameters.back());
  print_value("thetahat", observer.parameters());
  print_value("alarm_time", alarm_time);
  print_value("detection_delay_s", alarm_time - faulty.fault_time);
  Eigen::Index isolated = 0;
  alarms_per_parameter.maxCoeff(&isolated);
  print_value("alarms_per_parameter", alarms_per_parameter.cast<double>());
  print_text("isolated_parameter", isolated == 0 ? "load torque" : "friction");

  // 5. A μ far above the bound: θ̂ overshoots, then overflows; health() says so.
  adaptobs::GuyaderZhangObserver reckless(model, K, 1e-3, Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero());
  for (const Sample& s : run.samples) (void)reckless.update(s);
  print_text("health_at_mu_1e-3", reckless.health().message);
  print_text("health", observer.health().message);

  std::ostringstream figure;
  figure << "fault_time = " << faulty.fault_time << "\n"
         << R"(
set multiplot layout 3,1 title sprintf('Guyader-Zhang observer on a DC motor: load torque and friction, friction x%g at t = %g s', )"
         << faulty.friction_factor << R"(, fault_time)
set grid
set key outside right top
set lmargin at screen 0.08
set rmargin at screen 0.78
set xlabel 't (s)'
set arrow 1 from fault_time, graph 0 to fault_time, graph 1 nohead lc 'red' dt 3
set ylabel 'T_L (N m)'
set title 'load torque (fault time dotted)'
plot csv using 't':'thetahat_1' with lines lw 1.5 title 'estimate', csv using 't':'theta_1' with lines lc 'black' dt 2 title 'true'
set ylabel 'b w_{ref} (N m)'
set title 'friction torque at the reference speed (after the first alarm: shaded)'
plot csv using 't':(column('alarm') > 0 ? column('thetahat_2') : 1/0) with filledcurves y=0 lc rgb '#f0d0d0' title 'after the alarm', \
     csv using 't':'thetahat_2' with lines lw 1.5 title 'estimate', csv using 't':'theta_2' with lines lc 'black' dt 2 title 'true'
unset arrow 1
set title 'choosing mu: predicted time constant and RMS error of the estimates (fault-free run, second half)'
set logscale xy
set xlabel 'step size mu'
set ylabel 'time constant (s) / relative RMS error'
plot sweep using 'mu':'time_constant' with linespoints lw 1.5 title 'time constant (exact rate)', \
     sweep using 'mu':'averaged_time_constant' with linespoints dt 2 title 'time constant (averaging)', \
     sweep using 'mu':'rms_load' with linespoints title 'RMS error T_L', \
     sweep using 'mu':'rms_friction' with linespoints title 'RMS error b'
unset multiplot)";
  adaptobs::examples::write_outputs({{table, "dc_motor", "csv"}, {sweep, "dc_motor_mu", "sweep"}}, args.out_dir(),
                                    "dc_motor", figure.str());

  // The bounds docs/tutorial.md states.
  const Eigen::Vector2d truth = run.parameters.back();
  const bool estimates_within = ((observer.parameters() - truth).cwiseQuotient(truth).cwiseAbs().array() < 0.1).all();
  const bool detected = alarm_time > faulty.fault_time && alarm_time < faulty.fault_time + 3 && isolated == 1;
  const bool diverged_reported = reckless.health().state == adaptobs::Health::diverged;
  return estimates_within && detected && diverged_reported ? 0 : 1;
} catch (...) {
  return adaptobs::examples::failure("dc_motor");
}
