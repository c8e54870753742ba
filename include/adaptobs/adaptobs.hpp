#pragma once
/// \file
/// Umbrella header: every public component of adaptobs.

// Core: sizes, models, the Observer concept, discretization.
#include <adaptobs/core/commit.hpp>
#include <adaptobs/core/continuous_model.hpp>
#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/discrete_model.hpp>
#include <adaptobs/core/discretization.hpp>
#include <adaptobs/core/dynamic_copy.hpp>
#include <adaptobs/core/dynamic_transform.hpp>
#include <adaptobs/core/matrix_exponential.hpp>
#include <adaptobs/core/observer.hpp>
#include <adaptobs/core/products.hpp>
#include <adaptobs/core/regressor_integral.hpp>
#include <adaptobs/core/runge_kutta.hpp>
#include <adaptobs/core/sampled_integration.hpp>
#include <adaptobs/core/sampled_model.hpp>
#include <adaptobs/core/segments.hpp>
#include <adaptobs/core/spectral_norm.hpp>
#include <adaptobs/core/static_transform.hpp>
#include <adaptobs/core/status.hpp>
#include <adaptobs/core/sylvester.hpp>
#include <adaptobs/core/takagi_sugeno_model.hpp>
#include <adaptobs/core/validation.hpp>

// Design: gains before the loop, and diagnostics.
#include <adaptobs/design/canonical_forms.hpp>
#include <adaptobs/design/care.hpp>
#include <adaptobs/design/dare.hpp>
#include <adaptobs/design/excitation_monitor.hpp>
#include <adaptobs/design/guiro_convergence.hpp>
#include <adaptobs/design/guiro_gains.hpp>
#include <adaptobs/design/ltv_stability.hpp>
#include <adaptobs/design/lyapunov.hpp>
#include <adaptobs/design/observability.hpp>
#include <adaptobs/design/pole_placement.hpp>
#include <adaptobs/design/polynomial.hpp>
#include <adaptobs/design/positive_real.hpp>
#include <adaptobs/design/power_bound.hpp>
#include <adaptobs/design/riccati_differential.hpp>
#include <adaptobs/design/riccati_recursion.hpp>
#include <adaptobs/design/stability.hpp>
#include <adaptobs/design/takagi_sugeno_lmi.hpp>
// Not included here: the LMI synthesis with DSDP, <adaptobs/design/lmi/takagi_sugeno_synthesis.hpp>,
// is the optional component adaptobs::lmi.

// Adaptation laws: parameter estimators for a regression linear in the parameters.
#include <adaptobs/adaptation/adaptation_law.hpp>
#include <adaptobs/adaptation/covariance_resetting.hpp>
#include <adaptobs/adaptation/exponential_forgetting.hpp>
#include <adaptobs/adaptation/normalized_gradient.hpp>
#include <adaptobs/adaptation/recursive_least_squares.hpp>
#include <adaptobs/adaptation/gradient_law.hpp>
#include <adaptobs/adaptation/rls_correction.hpp>

// Observers and the baselines they are compared with.
#include <adaptobs/baselines/augmented_kalman.hpp>
#include <adaptobs/baselines/kalman_bucy.hpp>
#include <adaptobs/observers/bastin_gevers.hpp>
#include <adaptobs/observers/besancon.hpp>
#include <adaptobs/observers/canonical_form_filters.hpp>
#include <adaptobs/observers/dey_bhasin.hpp>
#include <adaptobs/observers/guiro.hpp>
#include <adaptobs/observers/guyader_zhang.hpp>
#include <adaptobs/observers/marino_tomei.hpp>
#include <adaptobs/observers/takagi_sugeno.hpp>
#include <adaptobs/observers/unified_adaptive_observer.hpp>
#include <adaptobs/observers/zhang_continuous.hpp>

// Simulation and CSV output.
#include <adaptobs/simulation/continuous_plant.hpp>
#include <adaptobs/simulation/discrete_nonlinear_plant.hpp>
#include <adaptobs/simulation/discrete_plant.hpp>
#include <adaptobs/simulation/joint_integration.hpp>
#include <adaptobs/simulation/runner.hpp>
#include <adaptobs/simulation/series_table.hpp>
