// `evaluate_detection` on the satellite's thruster fault over two threads: each
// scenario builds its plant and observer (matrix exponentials of the sampled
// model), designs nothing, and runs the CUSUM of a monitor designed beforehand.
// ThreadSanitizer must see no data race, and the summary must equal the
// one-thread summary exactly. Built with -fsanitize=thread by this directory's
// CMakeLists.txt; exits non-zero on a mismatch, and ThreadSanitizer exits
// non-zero on a race (TSAN_OPTIONS=halt_on_error=1 in scripts/test.sh).

#include <adaptobs/simulation/detection_evaluation.hpp>

#include "models/satellite_fault.hpp"

#include <cstdio>

namespace satellite = adaptobs::examples::satellite;

int main() {
  // A short design (6 fault-free runs of 1600 s) keeps the instrumented run to seconds.
  const satellite::MonitorDesign design = satellite::design_monitor(1e4, 1.0, 6, 1600);
  const satellite::ThrusterFault fault{};
  const auto scenario = [&](std::uint64_t seed, bool faulty) {
    return satellite::monitored_run(design, adaptobs::examples::Detector::cusum, fault, seed, faulty, fault.time + 100);
  };
  const adaptobs::FaultDescription description{.time = fault.time, .parameter = fault.parameter};
  const adaptobs::DetectionSummary one = adaptobs::evaluate_detection(scenario, description, 100, 4, 1);
  const adaptobs::DetectionSummary two = adaptobs::evaluate_detection(scenario, description, 100, 4, 2);
  const bool same = one.delays == two.delays && one.false_alarms == two.false_alarms &&
                    one.detection_rate == two.detection_rate && one.detection_rate > 0;
  std::printf("evaluate_detection on 1 and 2 threads: detection rate %g and %g, %s\n", one.detection_rate,
              two.detection_rate, same ? "the same summary" : "DIFFERENT summaries");
  return same ? 0 : 1;
}
