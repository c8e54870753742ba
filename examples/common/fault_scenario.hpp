#pragma once
// Fault scenarios shared by the fault examples, tests and benchmarks: the
// fault-free record a monitor is designed from, and one monitored run, for any
// simulation given as
//
//   simulate(seed, faulty, steps, visit)
//
// which runs `steps` samples of a plant (its noise from `seed`, with the
// scenario's fault when `faulty`) through an observer and calls
// `visit(k, observer, plant, sample)` after each accepted update with the
// sample measured at step k; the run stops early when `visit` returns false.

#include "common/example_support.hpp"

#include <adaptobs/diagnostics/fault_monitor.hpp>
#include <adaptobs/simulation/detection_evaluation.hpp>
#include <adaptobs/simulation/series_table.hpp>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace adaptobs::examples {

/// Which test of a `FaultMonitor` a scenario scores.
enum class Detector { cusum, glr, chi_square };

/// Fault-free runs of seeds 1 to `seeds`, recorded from sample `first` on.
template <int NY, int NP, class Simulate>
FaultFreeRecord<double, NY, NP> record_fault_free(const Simulate& simulate, int seeds, Index steps, Index first) {
  FaultFreeRecord<double, NY, NP> record;
  for (int s = 1; s <= seeds; ++s) {
    record.new_run();
    simulate(static_cast<std::uint64_t>(s), false, steps, [&](Index k, const auto& observer, const auto&, const auto&) {
      if (k >= first) record.add(observer);
      return true;
    });
  }
  return record;
}

/// The alarms of one test of a monitor designed by `design`, watching from
/// sample `first` on, times in units of `period` per sample. A faulty run stops
/// at its first alarm after `fault_time`, all the evaluation scores of it.
template <int NY, int NP, class Simulate>
MonitoredRun monitored_run(const Simulate& simulate, const FaultMonitorDesign<double, NY, NP>& design, Detector which,
                           std::uint64_t seed, bool faulty, Index steps, Index first, double period,
                           double fault_time) {
  FaultMonitor monitor(design);
  MonitoredRun run{
      .start = static_cast<double>(first) * period, .end = static_cast<double>(steps) * period, .alarms = {}};
  simulate(seed, faulty, steps, [&](Index k, const auto& observer, const auto&, const auto&) {
    if (k < first || !accepted(monitor.observe(observer))) return true;
    const double t = static_cast<double>(k) * period;
    const bool alarm = which == Detector::cusum ? monitor.cusum().alarm()
                       : which == Detector::glr ? monitor.glr().alarm()
                                                : monitor.chi_square().alarm();
    if (alarm)
      run.alarms.push_back({t, which == Detector::cusum ? monitor.cusum().isolated()
                               : which == Detector::glr ? monitor.glr().isolated()
                                                        : Index{-1}});
    return !(faulty && alarm && t > fault_time);
  });
  return run;
}

/// Runs `seeds` seeds (from 1000, beyond any design's) of a fault and of its
/// fault-free twin, for each test, and prints the summaries as `name = value`
/// lines: the CUSUM's unprefixed, the GLR's prefixed `glr_`, the χ² test's `chi_square_`;
/// the same lines go to DIR/<name>_evaluation.txt. `run(which, seed, faulty)` is one monitored run.
template <class Run>
void print_evaluation(const Run& run, const FaultDescription& fault, Index seeds, unsigned threads,
                      double designed_false_alarm_rate, const std::filesystem::path& dir, const std::string& name) {
  std::string summary;
  double fault_free_time = 0;
  for (const Detector which : {Detector::cusum, Detector::glr, Detector::chi_square}) {
    const auto result = evaluate_detection([&](std::uint64_t seed, bool faulty) { return run(which, seed, faulty); },
                                           fault, 1000, seeds, threads);
    const std::string prefix = which == Detector::cusum ? "" : which == Detector::glr ? "glr_" : "chi_square_";
    summary += value_line(prefix + "detection_rate", result.detection_rate);
    summary += value_line(prefix + "mean_detection_delay", result.mean_detection_delay);
    summary += value_line(prefix + "p95_detection_delay", result.p95_detection_delay);
    if (which != Detector::chi_square) summary += value_line(prefix + "isolation_rate", result.isolation_rate);
    summary += value_line(prefix + "quiet_before_fault_rate", result.quiet_before_fault_rate);
    summary += value_line(prefix + "false_alarms", double(result.false_alarms));
    summary += value_line(prefix + "false_alarm_rate", result.false_alarm_rate);
    fault_free_time = result.fault_free_time;
  }
  summary += value_line("seeds", double(seeds));
  summary += value_line("fault_free_time", fault_free_time);
  summary += value_line("designed_false_alarm_rate", designed_false_alarm_rate);
  std::cout << summary;
  const std::filesystem::path file = dir / (name + "_evaluation.txt");
  std::ofstream out(file);
  out << summary;
  if (!out) throw std::runtime_error("cannot write " + file.string());
  print_text("summary", file.string());
}

/// The monitor of a single watched run: after an alarm its CUSUM holds off for
/// 3 evaluations, while θ̂ settles on the new value, then re-anchors there and
/// watches for the next change.
template <int NY, int NP>
FaultMonitor<double, NY, NP> rearming_monitor(FaultMonitorDesign<double, NY, NP> design) {
  design.cusum_options.hold_off = 3;
  design.cusum_options.reanchor = true;
  return FaultMonitor<double, NY, NP>(design);
}

/// Prints a monitor's design.
template <int NY, int NP>
void print_design(const FaultMonitorDesign<double, NY, NP>& design) {
  print_value("cusum_scale", design.cusum.scale);
  print_value("cusum_drift", design.cusum.drift);
  print_value("cusum_threshold", design.cusum.threshold);
  print_value("cusum_stride", double(design.cusum_options.stride));
  print_value("cusum_lag_correlation", design.cusum.lag_correlation);
  print_value("cusum_long_run_excess", design.cusum.long_run_excess);
  print_value("cusum_bias", design.cusum.bias);
  print_value("cusum_checked_alarms_of_50", double(design.cusum.checked_alarms));
  print_value("glr_checked_alarms_of_50", double(design.glr_checked_alarms));
  print_value("glr_window", double(design.glr_window));
  print_value("glr_threshold", design.glr_threshold);
  print_value("output_error_covariance", design.output_error_covariance);
  print_value("chi_square_window", double(design.window));
  print_value("chi_square_false_alarm_probability", design.false_alarm_probability);
  print_value("chi_square_scale", design.chi_square_options.scale);
  print_value("chi_square_degrees_of_freedom", design.chi_square_options.degrees_of_freedom);
}

/// The fault examples' columns of a monitor after one sample (`watching`: the
/// sample was fed to it): statistic_cusum, threshold, alarm, isolated (1-based,
/// 0 for none), statistic_glr, threshold_glr, alarm_glr, statistic_chi_square,
/// threshold_chi_square, alarm_chi_square.
template <int NY, int NP>
void add_monitor_columns(SeriesTable& row, const FaultMonitor<double, NY, NP>& monitor, bool watching) {
  const auto& cusum = monitor.cusum();
  const auto& chi_square = monitor.chi_square();
  const bool alarm = watching && cusum.alarm();
  row.add("statistic_cusum", watching ? (alarm ? cusum.alarm_statistic() : cusum.statistic()) : 0.0)
      .add("threshold", cusum.threshold())
      .add("alarm", alarm ? 1.0 : 0.0)
      .add("isolated", alarm ? double(cusum.isolated() + 1) : 0.0)
      .add("statistic_glr",
           watching ? (monitor.glr().alarm() ? monitor.glr().alarm_statistic() : monitor.glr().statistic()) : 0.0)
      .add("threshold_glr", monitor.glr().threshold())
      .add("alarm_glr", watching && monitor.glr().alarm() ? 1.0 : 0.0)
      .add("statistic_chi_square", watching ? chi_square.statistic() : 0.0)
      .add("threshold_chi_square", chi_square.threshold())
      .add("alarm_chi_square", watching && chi_square.alarm() ? 1.0 : 0.0);
}

/// Gnuplot commands of a fault example's figure, before its panels: the
/// variable `monitor_start` (the monitor's first sample, in the x axis' unit)
/// and dotted lines at it, at the fault's start and, for a ramp, at its end.
inline std::string fault_markers(double monitor_start, double fault_time, double ramp) {
  std::ostringstream gp;
  gp.precision(10);
  gp << "monitor_start = " << monitor_start << "\n"
     << time_marker(monitor_start, "monitor starts", "#404040") << time_marker(fault_time, "fault");
  if (ramp > 0) gp << time_marker(fault_time + ramp, "ramp ends");
  return gp.str();
}

/// Gnuplot panels of the CUSUM and χ² columns, after the example's own panels,
/// with `monitor_start` set by `fault_markers` and `floored` by
/// `log_floor_function`. The statistics are 0 before the monitor starts, drawn
/// as nothing, and at rest or after an alarm, while the CUSUM holds off: on the
/// log axis these zeros show at its floor, 0.01.
inline constexpr const char* monitor_panels = R"(
set offsets 0, 0, 0, 0
set title 'CUSUM and windowed GLR on the normalized estimates: largest statistic, threshold, alarms (log scale: below 0.01, as at rest, drawn at 0.01)'
set ylabel 'statistic (no unit)'
set logscale y
set yrange [0.005:*]
plot csv using 't':(column('t') >= monitor_start ? floored(column('statistic_cusum'), 0.01) : NaN) with lines title 'CUSUM', \
     csv using 't':'threshold' with lines dt 2 lc 'red' title 'CUSUM threshold', \
     csv using 't':(column('alarm') > 0 ? column('statistic_cusum') : NaN) with points pt 7 ps 1.5 lc 'red' title 'CUSUM alarm', \
     csv using 't':(column('t') >= monitor_start ? floored(column('statistic_glr'), 0.01) : NaN) with lines title 'GLR', \
     csv using 't':'threshold_glr' with lines dt 3 lc 'blue' title 'GLR threshold', \
     csv using 't':(column('alarm_glr') > 0 ? column('statistic_glr') : NaN) with points pt 9 ps 1.5 lc 'blue' title 'GLR alarm'
unset logscale y
set autoscale y
set title 'chi-square test on the output errors: window sum and threshold'
set ylabel 'sum of squared normalized errors (no unit)'
plot csv using 't':'statistic_chi_square' with lines title 'statistic', \
     csv using 't':'threshold_chi_square' with lines dt 2 lc 'red' title 'threshold', \
     csv using 't':(column('alarm_chi_square') > 0 ? column('threshold_chi_square') : NaN) with points pt 7 ps 1.5 lc 'red' title 'alarm'
)";

}  // namespace adaptobs::examples
