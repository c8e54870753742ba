#pragma once
/// \file
/// Umbrella header of design time: discretization, gain synthesis (Riccati
/// equations, pole placement, canonical forms) and the checks of the papers'
/// assumptions, all run before the loop.
///
/// Not included here: the LMI synthesis with DSDP,
/// <adaptobs/design/lmi/takagi_sugeno_synthesis.hpp>, is the optional component adaptobs::lmi.

// Discretization and the matrix functions behind it.
#include <adaptobs/core/discretization.hpp>
#include <adaptobs/core/matrix_exponential.hpp>
#include <adaptobs/core/sampled_model.hpp>
#include <adaptobs/core/sylvester.hpp>
#include <adaptobs/models/regressor_integral.hpp>

// Gains, stability and excitation checks.
#include <adaptobs/design/canonical_forms.hpp>
#include <adaptobs/design/care.hpp>
#include <adaptobs/design/companion_matrix.hpp>
#include <adaptobs/design/dare.hpp>
#include <adaptobs/design/guiro_convergence.hpp>
#include <adaptobs/design/guiro_gains.hpp>
#include <adaptobs/design/guyader_zhang_tuning.hpp>
#include <adaptobs/design/ltv_stability.hpp>
#include <adaptobs/design/lyapunov.hpp>
#include <adaptobs/design/observability.hpp>
#include <adaptobs/design/pole_placement.hpp>
#include <adaptobs/design/polynomial.hpp>
#include <adaptobs/design/positive_real.hpp>
#include <adaptobs/design/power_bound.hpp>
#include <adaptobs/design/riccati_differential.hpp>
#include <adaptobs/design/riccati_recursion.hpp>
#include <adaptobs/design/schur_stability.hpp>
#include <adaptobs/design/spr_test.hpp>
#include <adaptobs/design/stability.hpp>
#include <adaptobs/design/takagi_sugeno_lmi.hpp>
