// The library adaptobs::precompiled: the double-precision instances (and the
// float matrix exponential) of the design routines that end in an
// ADAPTOBS_INSTANTIATE line, compiled once (see include/adaptobs/core/precompiled.hpp). Here the line is an explicit
// instantiation definition; in a program that links this library it is a
// declaration, and the program calls these instead of compiling its own.
#define ADAPTOBS_INSTANTIATE template

#include <adaptobs/core/matrix_exponential.hpp>
#include <adaptobs/core/static_transform.hpp>
#include <adaptobs/design/canonical_forms.hpp>
#include <adaptobs/design/care.hpp>
#include <adaptobs/design/dare.hpp>
#include <adaptobs/design/dense_eigenvalues.hpp>
#include <adaptobs/design/guiro_convergence.hpp>
#include <adaptobs/design/guiro_gains.hpp>
#include <adaptobs/design/lyapunov.hpp>
#include <adaptobs/design/pole_placement.hpp>
#include <adaptobs/design/positive_real.hpp>
#include <adaptobs/design/power_bound.hpp>
#include <adaptobs/design/schur_stability.hpp>
#include <adaptobs/design/spr_test.hpp>
#include <adaptobs/design/stein.hpp>

#ifndef ADAPTOBS_PRECOMPILED
#error "src/precompiled.cpp is compiled with ADAPTOBS_PRECOMPILED defined (target adaptobs_precompiled)"
#endif
