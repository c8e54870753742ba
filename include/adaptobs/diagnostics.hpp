#pragma once
/// \file
/// Umbrella header of fault detection on the estimates: the χ² test on output
/// errors, the CUSUM and windowed GLR on parameter estimates, their design from fault-free runs,
/// and the monitor that runs the three on any `DiagnosableObserver`. The Monte-Carlo
/// evaluator of a detector is in <adaptobs/simulation.hpp>.

#include <adaptobs/diagnostics/calibration.hpp>
#include <adaptobs/diagnostics/chi_square_distribution.hpp>
#include <adaptobs/diagnostics/chi_square_test.hpp>
#include <adaptobs/diagnostics/cusum.hpp>
#include <adaptobs/diagnostics/fault_monitor.hpp>
#include <adaptobs/diagnostics/glr.hpp>
