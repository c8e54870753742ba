#pragma once
/// \file
/// Monte-Carlo evaluation of a fault detector: detection rate, delay,
/// isolation and false-alarm rate over many seeds, each run beside its
/// fault-free twin.
///
/// A scenario is any callable `scenario(seed, faulty)` returning the
/// `MonitoredRun` of one simulation: the plant, noise and observer seeded by
/// `seed`, the fault injected when `faulty` is true, the detector's alarms
/// recorded. The evaluator knows nothing of observers or detectors; the same
/// seed gives the same run on any number of threads, so a summary is
/// reproducible. The scenario is called concurrently and must not share
/// mutable state between calls; an exception it throws stops the evaluation
/// and is rethrown to the caller.

#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/validation.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <exception>
#include <limits>
#include <mutex>
#include <thread>
#include <vector>

namespace adaptobs {

/// One alarm: when, and which parameter it names (−1 for none).
struct Alarm {
  double time = 0;
  Index isolated = -1;
};

/// The alarms of one run, monitored over [start, end] (in any order: the
/// evaluator sorts them by time).
struct MonitoredRun {
  double start = 0;
  double end = 0;
  std::vector<Alarm> alarms;
};

/// The fault a scenario injects: from `time` on (a step, or the start of a
/// drift), on parameter `parameter` (0-based; −1 when isolation is not scored).
/// An alarm at `time` itself cannot come from the fault (a change of θ_k shows
/// in the samples after k): detections are alarms strictly after it.
struct FaultDescription {
  double time = 0;
  Index parameter = -1;
};

/// Outcome over all seeds.
struct DetectionSummary {
  Index seeds = 0;
  double detection_rate = 0;  ///< faulty runs with an alarm after the fault
  double mean_detection_delay =
      std::numeric_limits<double>::quiet_NaN();  ///< from the fault to the first alarm after it
  double p95_detection_delay =
      std::numeric_limits<double>::quiet_NaN();  ///< nearest-rank 95th percentile of the delays
  /// Detections whose first alarm names the faulty parameter (NaN when not scored).
  double isolation_rate = std::numeric_limits<double>::quiet_NaN();
  double quiet_before_fault_rate = 0;  ///< faulty runs without an alarm up to the fault's time
  Index false_alarms = 0;              ///< alarms of the fault-free twins
  double fault_free_time = 0;          ///< their monitored time
  /// false_alarms / fault_free_time; NaN when no fault-free time was monitored
  double false_alarm_rate = 0;
  std::vector<double> delays;  ///< per detected seed, in seed order
};

/// Runs `scenario(seed, true)` and `scenario(seed, false)` for `seeds` seeds
/// from `first_seed`, over `threads` threads (0: one per core).
template <class Scenario>
  requires std::invocable<const Scenario&, std::uint64_t, bool> &&
           std::same_as<std::invoke_result_t<const Scenario&, std::uint64_t, bool>, MonitoredRun>
[[nodiscard]] DetectionSummary evaluate_detection(const Scenario& scenario, const FaultDescription& fault,
                                                  std::uint64_t first_seed, Index seeds, unsigned threads = 0) {
  constexpr std::string_view who = "evaluate_detection";
  require(seeds >= 1, who, "seeds", "must be at least 1");
  // Both runs of every seed are kept until scoring: a count past what a
  // vector can hold would only fail later, as std::length_error.
  require(static_cast<std::size_t>(seeds) <= std::vector<MonitoredRun>().max_size(), who, "seeds",
          "must be at most std::vector<MonitoredRun>::max_size() (each seed's runs are kept for scoring)");
  require(std::isfinite(fault.time), who, "fault.time", "must be finite");
  require(fault.parameter >= -1, who, "fault.parameter", "must be -1 (not scored) or a parameter index");
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  threads = static_cast<unsigned>(std::min<Index>(threads, seeds));

  std::vector<MonitoredRun> faulty(static_cast<std::size_t>(seeds)), twins(static_cast<std::size_t>(seeds));
  std::atomic<Index> next{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  auto work = [&] {
    try {
      for (Index i = next++; i < seeds; i = next++) {
        const std::uint64_t seed = first_seed + static_cast<std::uint64_t>(i);
        faulty[static_cast<std::size_t>(i)] = scenario(seed, true);
        twins[static_cast<std::size_t>(i)] = scenario(seed, false);
      }
    } catch (...) {
      next = seeds;  // the others stop at their next seed
      const std::lock_guard lock(failure_mutex);
      if (!failure) failure = std::current_exception();
    }
  };
  {
    std::vector<std::jthread> pool;
    for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work);
    work();
  }  // joins
  if (failure) std::rethrow_exception(failure);  // the first scenario that threw
  // A run's interval and alarm times must be finite and in order: a NaN or an
  // alarm outside [start, end] would be scored as a detection or a quiet start.
  for (const std::vector<MonitoredRun>* runs : {&faulty, &twins})
    for (const MonitoredRun& run : *runs) {
      bool valid = std::isfinite(run.end - run.start) && run.start <= run.end;
      for (const Alarm& alarm : run.alarms) valid = valid && alarm.time >= run.start && alarm.time <= run.end;
      require(valid, who, "scenario",
              "must return runs with finite start <= end, a finite span, and every alarm time within [start, end]");
    }

  DetectionSummary summary;
  summary.seeds = seeds;
  Index detected = 0, isolated = 0, quiet = 0;
  for (MonitoredRun& run : faulty) {
    std::stable_sort(run.alarms.begin(), run.alarms.end(),
                     [](const Alarm& a, const Alarm& b) { return a.time < b.time; });
    const auto after =
        std::find_if(run.alarms.begin(), run.alarms.end(), [&](const Alarm& a) { return a.time > fault.time; });
    if (after == run.alarms.begin()) ++quiet;
    if (after == run.alarms.end()) continue;
    ++detected;
    summary.delays.push_back(after->time - fault.time);
    if (after->isolated == fault.parameter) ++isolated;
  }
  for (const MonitoredRun& run : twins) {
    summary.false_alarms += static_cast<Index>(run.alarms.size());
    summary.fault_free_time += run.end - run.start;
  }
  const auto n = static_cast<double>(seeds);
  summary.detection_rate = static_cast<double>(detected) / n;
  summary.quiet_before_fault_rate = static_cast<double>(quiet) / n;
  if (detected > 0) {
    if (fault.parameter >= 0) summary.isolation_rate = static_cast<double>(isolated) / static_cast<double>(detected);
    std::vector<double> sorted = summary.delays;
    std::sort(sorted.begin(), sorted.end());
    double total = 0;
    for (double d : sorted) total += d;
    summary.mean_detection_delay = total / static_cast<double>(detected);
    const auto rank = static_cast<std::size_t>(std::ceil(0.95 * static_cast<double>(sorted.size())));
    summary.p95_detection_delay = sorted[std::max<std::size_t>(rank, 1) - 1];
  }
  require(std::isfinite(summary.fault_free_time), who, "scenario",
          "must return fault-free runs whose monitored time sums to a finite number");
  summary.false_alarm_rate = summary.fault_free_time > 0
                                 ? static_cast<double>(summary.false_alarms) / summary.fault_free_time
                                 : std::numeric_limits<double>::quiet_NaN();
  return summary;
}

}  // namespace adaptobs
