// adaptobs::precompiled: observability, pole placement and the designs built on it
// (Guiro gains and their convergence check, the power bound). One unit: the Guiro gain
// design instantiates the pole placer and its decompositions, which the other routines
// share, so that this unit costs the compiler little more than that design alone.
#include <adaptobs/design/dense_eigenvalues.hpp>
#include <adaptobs/design/schur_stability.hpp>

#include "define_instances.hpp"

#include <adaptobs/design/guiro_convergence.hpp>
#include <adaptobs/design/guiro_gains.hpp>
#include <adaptobs/design/observability.hpp>
#include <adaptobs/design/pole_placement.hpp>
#include <adaptobs/design/power_bound.hpp>
