// A change of the growth parameter of the waste water treatment plant of
// Srinivasarengan et al. (2018), §6, watched on the Takagi–Sugeno observer (printed gains) by a CUSUM and a
// windowed GLR on θ̂ and a χ² test on the output errors, designed from fault-free runs for one
// mean time between false alarms. The biomass measurement carries noise of
// standard deviation 0.01 (the paper's simulation is noise-free).
//
// Usage: wwtp_fault [--out DIR] [--fault-time 400] [--fault-size 0.15] [--drift]
//                   [--steps 800] [--seed 1] [--seeds 0] [--mtbfa 1e5] [--threads 0]
// θ goes from 0 to the fault size at sample --fault-time, at once or, with
// --drift, along a 50-sample ramp. Times are sample indices. One run writes
// wwtp_fault.csv (t,u_1,y_1,x_*,xhat_*,theta_1,thetahat_1, then the monitor's
// columns, common/fault_scenario.hpp) and wwtp_fault.png; --seeds N runs N
// seeds and their fault-free twins and prints the detection figures.

#include "models/wwtp_fault.hpp"
#include "common/example_support.hpp"
#include "common/fault_scenario.hpp"

#include <cmath>
#include <cstdint>
#include <string>

namespace wwtp = adaptobs::examples::wwtp;
using adaptobs::examples::Detector;
using adaptobs::examples::print_value;

namespace {

// Gnuplot panel of the estimate and its fault-free band (s1, the CUSUM scale);
// the monitor panels follow. The paper gives the plant no units.
constexpr const char* estimate_panel = R"(
set multiplot layout 3,1 title 'Growth-rate change in the waste water treatment plant: Takagi-Sugeno observer (Srinivasarengan et al. 2018, section 6)'
set grid
# The legends beside the plots, and the time axes aligned under one another.
set key outside right top
set lmargin at screen 0.07
set rmargin at screen 0.80
set xlabel 'k (samples, T_s = 1)'
set title 'growth-rate error theta (a = 0.5 + theta): estimate with its fault-free spread (2 scales), and the true value'
set ylabel 'theta (no unit)'
set offsets 0, 0, graph 0.05, graph 0.05
plot csv using 't':(column('thetahat_1') - 2*s1):(column('thetahat_1') + 2*s1) with filledcurves fs transparent solid 0.3 title 'band', \
     csv using 't':'thetahat_1' with lines lw 1.5 title 'theta estimate', \
     csv using 't':'theta_1' with lines lc 'black' dt 3 title 'true')";

// One run, written to wwtp_fault.csv and .png (after an alarm the CUSUM holds
// off for 3 periods, then re-anchors).
void run_once(const adaptobs::examples::Arguments& args, const wwtp::MonitorDesign& design,
              const wwtp::GrowthFault& fault) {
  auto monitor = adaptobs::examples::rearming_monitor(design);
  adaptobs::SeriesTable table;
  double first_alarm = -1;
  wwtp::Simulation{fault}(
      static_cast<std::uint64_t>(args.integer("seed")), true, static_cast<adaptobs::Index>(args.integer("steps")),
      [&](adaptobs::Index k, const auto& observer, const auto& plant, const auto& sample) {
        const bool watching = k >= wwtp::monitor_from && adaptobs::accepted(monitor.observe(observer));
        if (watching && monitor.cusum().alarm() && first_alarm < 0) first_alarm = double(k);
        table.begin_row()
            .add("t", double(k))
            .add("u", sample.u)
            .add("y", sample.y)
            .add("x", plant.state())
            .add("xhat", observer.state())
            .add("theta", Eigen::Matrix<double, 1, 1>(fault.theta_at(k)))
            .add("thetahat", observer.parameters());
        adaptobs::examples::add_monitor_columns(table, monitor, watching);
        return true;
      });
  print_value("first_alarm_time", first_alarm);
  print_value("detection_delay", first_alarm >= 0 ? first_alarm - double(fault.step) : -1.0);
  print_value("cusum_alarms", double(monitor.cusum().alarm_count()));
  print_value("chi_square_alarms", double(monitor.chi_square().alarm_count()));

  const std::string band = "s1 = " + std::to_string(design.cusum.scale(0)) + "\n";
  adaptobs::examples::write_outputs(
      table, args.out_dir(), "wwtp_fault",
      band + adaptobs::examples::log_floor_function +
          adaptobs::examples::fault_markers(double(wwtp::monitor_from), double(fault.step), double(fault.ramp)) +
          estimate_panel + std::string(adaptobs::examples::monitor_panels) + "unset multiplot");
}

}  // namespace

int main(int argc, char** argv) try {
  using adaptobs::examples::integer_in;
  using adaptobs::examples::real_in;
  const adaptobs::examples::Arguments args(
      argc, argv, "wwtp_fault",
      {{"fault-time", "400",
        "sample at which the change starts, after the monitor's start (300) and before the run's end", "samples",
        integer_in(double(wwtp::monitor_from), 1e7)},
       {"fault-size", "0.15", "theta after the change, from 0 (the input keeps the plant in its sector)", "",
        real_in(-0.225, 0.3)},
       adaptobs::examples::toggle("drift", "the change builds up along a 50-sample ramp instead of at once"),
       {"steps", "800", "length of the single run (with --seeds, each run lasts fault-time + ramp + 200 samples)",
        "samples", integer_in(1, 1e7)},
       adaptobs::examples::seed_option("1", "seed of the single run's measurement noise"),
       {"seeds", "0", "seeds of the Monte-Carlo evaluation, each with its fault-free twin (0: one run and its figure)",
        "", integer_in(0, 1e6)},
       {"mtbfa", "1e5", "designed mean time between false alarms of each test", "samples", real_in(200, 1e7)},
       {"threads", "0", "threads of the evaluation (0: one per core)", "", integer_in(0, 1024)}});
  const auto seeds = static_cast<adaptobs::Index>(args.integer("seeds"));
  args.require(seeds > 0 || args.integer("fault-time") < args.integer("steps"), "fault-time",
               "an integer in [" + std::to_string(wwtp::monitor_from) + ", " + std::to_string(args.integer("steps")) +
                   ") (inside the run, --steps)");
  const wwtp::GrowthFault fault{.step = static_cast<adaptobs::Index>(args.integer("fault-time")),
                                .size = args.number("fault-size"),
                                .ramp = args.on("drift") ? 50 : 0};
  const double mtbfa = args.number("mtbfa");

  // The three tests designed from 20 fault-free runs of 10300 samples (seeds 1 to 20).
  const wwtp::MonitorDesign design = wwtp::design_monitor(mtbfa);
  print_value("designed_mean_time_between_false_alarms", mtbfa);
  adaptobs::examples::print_design(design);
  print_value("fault_time", double(fault.step));
  print_value("fault_size", fault.size);
  print_value("fault_ramp", double(fault.ramp));

  if (seeds > 0) {
    const adaptobs::Index steps = fault.step + fault.ramp + 200;
    adaptobs::examples::print_evaluation(
        [&](Detector which, std::uint64_t seed, bool faulty) {
          return wwtp::monitored_run(design, which, fault, seed, faulty, steps);
        },
        {.time = double(fault.step), .parameter = 0}, seeds, static_cast<unsigned>(args.integer("threads")), 1 / mtbfa,
        args.out_dir(), "wwtp_fault");
    return 0;
  }

  run_once(args, design, fault);
  return 0;
} catch (...) {
  return adaptobs::examples::failure("wwtp_fault");
}
