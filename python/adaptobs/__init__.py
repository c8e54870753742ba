"""adaptobs: adaptive observers, recursive estimators of the state and the
unknown parameters of a dynamic system from its inputs and outputs.

The classes and functions are the C++ library's (``include/adaptobs``) with
run-time sizes and double precision. Arguments are NumPy arrays: a float64
array of any layout is read in place; other input is converted once to float64.
Bad configuration raises :class:`ConfigurationError` (a ``ValueError``) naming
the argument; a rejected sample is a returned :class:`UpdateStatus`, never an
exception, and leaves the observer exactly as it was.
"""

from ._core import (
    AugmentedKalmanFilter,
    CareSolution,
    ChiSquareTest,
    ConfigurationError,
    CusumCalibration,
    CusumDetector,
    DareSolution,
    DeyBhasinObserver,
    DiscreteLtiModel,
    FaultMonitor,
    FaultMonitorDesign,
    GlrDetector,
    GuiroGains,
    GuiroObserver,
    GuyaderZhangObserver,
    KalmanBucyGain,
    KalmanGain,
    OutputInjectionGain,
    RunResult,
    StateFeedbackGain,
    SuzukiObserver,
    UpdateStatus,
    ZeroOrderHold,
    calibrate_cusum,
    design_fault_monitor,
    design_guiro_gains,
    discretize_zoh,
    examples,
    is_hurwitz_stable,
    is_schur_stable,
    kalman_bucy_gain,
    place_output_injection,
    place_state_feedback,
    solve_care,
    solve_dare,
    steady_state_kalman_gain,
)

__version__ = "0.1.0"

__all__ = [
    "AugmentedKalmanFilter",
    "CareSolution",
    "ChiSquareTest",
    "ConfigurationError",
    "CusumCalibration",
    "CusumDetector",
    "DareSolution",
    "DeyBhasinObserver",
    "DiscreteLtiModel",
    "FaultMonitor",
    "FaultMonitorDesign",
    "GlrDetector",
    "GuiroGains",
    "GuiroObserver",
    "GuyaderZhangObserver",
    "KalmanBucyGain",
    "KalmanGain",
    "OutputInjectionGain",
    "RunResult",
    "StateFeedbackGain",
    "SuzukiObserver",
    "UpdateStatus",
    "ZeroOrderHold",
    "calibrate_cusum",
    "design_fault_monitor",
    "design_guiro_gains",
    "discretize_zoh",
    "examples",
    "is_hurwitz_stable",
    "is_schur_stable",
    "kalman_bucy_gain",
    "place_output_injection",
    "place_state_feedback",
    "solve_care",
    "solve_dare",
    "steady_state_kalman_gain",
]
