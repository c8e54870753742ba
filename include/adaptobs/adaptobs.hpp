#pragma once
/// \file
/// Umbrella header of what runs in the loop: sizes and models, the Observer
/// concept, the observers, their baselines and the adaptation laws.
///
/// Gain synthesis and design-time checks are in <adaptobs/design.hpp>, and
/// plants, the simulation runner and CSV output in <adaptobs/simulation.hpp>:
/// a translation unit that only runs an observer does not compile them.

// Core: sizes, models, the Observer concept, per-step numerics.
#include <adaptobs/core/continuous_model.hpp>
#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/discrete_model.hpp>
#include <adaptobs/core/dynamic_transform.hpp>
#include <adaptobs/core/health.hpp>
#include <adaptobs/core/observer.hpp>
#include <adaptobs/core/runge_kutta.hpp>
#include <adaptobs/core/sampled_integration.hpp>
#include <adaptobs/core/spectral_norm.hpp>
#include <adaptobs/core/static_transform.hpp>
#include <adaptobs/core/status.hpp>
#include <adaptobs/core/symmetric_eigenvalues.hpp>
#include <adaptobs/core/validation.hpp>

// Paper-family models.
#include <adaptobs/models/takagi_sugeno_model.hpp>

// Per-step diagnostics computed inside the updates.
#include <adaptobs/diagnostics/excitation_monitor.hpp>

// Adaptation laws: parameter estimators for a regression linear in the parameters.
#include <adaptobs/adaptation/adaptation_law.hpp>
#include <adaptobs/adaptation/covariance_resetting.hpp>
#include <adaptobs/adaptation/exponential_forgetting.hpp>
#include <adaptobs/adaptation/gradient_law.hpp>
#include <adaptobs/adaptation/normalized_gradient.hpp>
#include <adaptobs/adaptation/recursive_least_squares.hpp>
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
