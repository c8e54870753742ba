// Thruster fault on the controlled satellite of Guyader & Zhang (2003) §4: the
// Guyader–Zhang observer's estimates watched by a CUSUM and a windowed GLR on θ̂
// (detection and isolation) and a χ² test on the output errors, all designed
// from fault-free runs for one mean time between false alarms.
//
// Usage: satellite_fault [--out DIR] [--fault-param 2] [--fault-time 150]
//                        [--fault-size -0.4] [--drift] [--seconds 300]
//                        [--seed 2003] [--seeds 0] [--mtbfa 1e5] [--threads 0]
// --fault-param I (1-based) loses the fraction -D of its efficiency at T s
// (--fault-size D; -0.4: θ₂ from 1.5 to 0.9), at once or, with --drift, along a
// 50-s ramp. One run writes satellite_fault.csv (t,u_*,y_*,x_*,xhat_*,theta_*,
// thetahat_*, then the monitor's columns, common/fault_scenario.hpp) and satellite_fault.png. With
// --seeds N it runs N seeds and their fault-free twins instead and prints the
// detection, delay, isolation and false-alarm figures of each test.

#include "models/satellite_fault.hpp"
#include "common/example_support.hpp"
#include "common/fault_scenario.hpp"

#include <cmath>
#include <cstdint>
#include <iostream>
#include <sstream>
#include <string>

namespace satellite = adaptobs::examples::satellite;
using adaptobs::examples::Detector;
using adaptobs::examples::print_text;
using adaptobs::examples::print_value;

namespace {

// θ̂ with its fault-free spread (± 2 scales), above the monitor's panels;
// dotted lines at the monitor's start and the fault's.
void write_figure(const adaptobs::SeriesTable& table, const satellite::MonitorDesign& design,
                  const satellite::ThrusterFault& fault, const adaptobs::examples::Arguments& args) {
  std::ostringstream band;  // θ̂ ± 2 scales: its spread without a fault
  band.precision(10);
  band << "s1 = " << design.cusum.scale(0) << "; s2 = " << design.cusum.scale(1) << "\n";
  const double monitor_start = double(satellite::monitor_from) * satellite::sampling_period;
  adaptobs::examples::write_outputs(table, args.out_dir(), "satellite_fault",
                                    band.str() + adaptobs::examples::log_floor_function +
                                        adaptobs::examples::fault_markers(monitor_start, fault.time, fault.ramp) + R"(
set multiplot layout 3,1 title 'Thruster fault on the satellite: tests on the Guyader-Zhang estimates (Guyader and Zhang 2003, section 4)'
set grid
# The legends beside the plots, and the time axes aligned under one another.
set key outside right top
set lmargin at screen 0.07
set rmargin at screen 0.78
set xlabel 't (s)'
set title 'thrust efficiencies: estimates with their fault-free spread (2 scales), and the true values'
set ylabel 'thrust efficiency (no unit)'
set offsets 0, 0, graph 0.05, graph 0.05
plot csv using 't':(column('thetahat_1') - 2*s1):(column('thetahat_1') + 2*s1) with filledcurves fs transparent solid 0.3 title 'theta^1 radial, band', \
     csv using 't':'thetahat_1' with lines lw 1.5 title 'theta^1 radial, estimate', \
     csv using 't':(column('thetahat_2') - 2*s2):(column('thetahat_2') + 2*s2) with filledcurves fs transparent solid 0.3 title 'theta^2 tangential, band', \
     csv using 't':'thetahat_2' with lines lw 1.5 title 'theta^2 tangential, estimate', \
     csv using 't':'theta_1' with lines lc 'black' dt 3 title 'true', \
     csv using 't':'theta_2' with lines lc 'black' dt 3 notitle)" +
                                        std::string(adaptobs::examples::monitor_panels) + "unset multiplot");
}

// One run, every quantity of the figure in the table (after an alarm the
// CUSUM holds off for 30 s, then re-anchors), its alarms and the figure.
void one_run(const satellite::MonitorDesign& design, const satellite::ThrusterFault& fault,
             const adaptobs::examples::Arguments& args) {
  auto monitor = adaptobs::examples::rearming_monitor(design);
  adaptobs::SeriesTable table;
  double first_alarm = -1;
  adaptobs::Index isolated = -1;
  const auto steps = static_cast<adaptobs::Index>(std::llround(args.number("seconds") / satellite::sampling_period));
  satellite::Simulation{fault}(static_cast<std::uint64_t>(args.integer("seed")), true, steps,
                               [&](adaptobs::Index k, const auto& observer, const auto& plant, const auto& sample) {
                                 const double t = static_cast<double>(k) * satellite::sampling_period;
                                 const bool watching =
                                     k >= satellite::monitor_from && adaptobs::accepted(monitor.observe(observer));
                                 if (watching && monitor.cusum().alarm() && first_alarm < 0) {
                                   first_alarm = t;
                                   isolated = monitor.cusum().isolated();
                                 }
                                 table.begin_row()
                                     .add("t", t)
                                     .add("u", sample.u)
                                     .add("y", sample.y)
                                     .add("x", plant.state())
                                     .add("xhat", observer.state())
                                     .add("theta", fault.parameters_at(t))
                                     .add("thetahat", observer.parameters());
                                 adaptobs::examples::add_monitor_columns(table, monitor, watching);
                                 return true;
                               });
  print_value("first_alarm_time", first_alarm);
  print_value("detection_delay", first_alarm >= 0 ? first_alarm - fault.time : -1.0);
  print_value("isolated_parameter", double(isolated + 1));
  print_value("cusum_alarms", double(monitor.cusum().alarm_count()));
  print_value("chi_square_alarms", double(monitor.chi_square().alarm_count()));

  write_figure(table, design, fault, args);
}

}  // namespace

int main(int argc, char** argv) try {
  using adaptobs::examples::integer_in;
  using adaptobs::examples::real_in;
  const double monitor_start = double(satellite::monitor_from) * satellite::sampling_period;
  const adaptobs::examples::Arguments args(
      argc, argv, "satellite_fault",
      {{"fault-param", "2", "thrust efficiency that fails: 1 radial, 2 tangential", "", integer_in(1, 2)},
       {"fault-time", "150", "start of the fault, after the monitor's start (100 s) and before the run's end", "s",
        real_in(monitor_start, 1e6)},
       {"fault-size", "-0.4", "relative change D of the efficiency: theta_I becomes (1 + D) theta_I", "",
        real_in(-1, 10, "()")},
       adaptobs::examples::toggle("drift", "the fault builds up along a 50-s ramp instead of at once"),
       {"seconds", "300", "length of the single run (with --seeds, each run lasts fault-time + ramp + 100 s)", "s",
        real_in(1, 1e6)},
       adaptobs::examples::seed_option("2003", "seed of the single run's output noise"),
       {"seeds", "0", "seeds of the Monte-Carlo evaluation, each with its fault-free twin (0: one run and its figure)",
        "", integer_in(0, 1e6)},
       {"mtbfa", "1e5", "designed mean time between false alarms of each test", "s", real_in(20, 1e6)},
       {"threads", "0", "threads of the evaluation (0: one per core)", "", integer_in(0, 1024)}});
  const auto seeds = static_cast<adaptobs::Index>(args.integer("seeds"));
  args.require(seeds > 0 || args.number("fault-time") < args.number("seconds"), "fault-time",
               "in [" + adaptobs::examples::format_number(monitor_start) + ", " +
                   adaptobs::examples::format_number(args.number("seconds")) + ") (inside the run, --seconds)");
  satellite::ThrusterFault fault{.parameter = static_cast<adaptobs::Index>(args.integer("fault-param")) - 1,
                                 .time = args.number("fault-time"),
                                 .relative_size = args.number("fault-size"),
                                 .ramp = args.on("drift") ? 50.0 : 0.0};
  const double mtbfa = args.number("mtbfa");

  // The three tests designed from 20 fault-free runs of 3100 s (seeds 1 to 20).
  const satellite::MonitorDesign design = satellite::design_monitor(mtbfa);
  print_value("designed_mean_time_between_false_alarms", mtbfa);
  adaptobs::examples::print_design(design);
  print_value("fault_parameter", double(fault.parameter + 1));
  print_value("fault_time", fault.time);
  print_value("fault_size", fault.relative_size);
  print_value("fault_ramp", fault.ramp);

  if (seeds > 0) {
    const double seconds = fault.time + fault.ramp + 100;
    adaptobs::examples::print_evaluation(
        [&](Detector which, std::uint64_t seed, bool faulty) {
          return satellite::monitored_run(design, which, fault, seed, faulty, seconds);
        },
        {.time = fault.time, .parameter = fault.parameter}, seeds, static_cast<unsigned>(args.integer("threads")),
        1 / mtbfa, args.out_dir(), "satellite_fault");
    return 0;
  }

  one_run(design, fault, args);
  return 0;
} catch (...) {
  return adaptobs::examples::failure("satellite_fault");
}
