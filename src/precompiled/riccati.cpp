// adaptobs::precompiled: the Lyapunov, Stein and Riccati solvers (CARE, DARE) and the
// Schur stability bound that certifies the DARE's closed loop.
#include <adaptobs/design/dense_eigenvalues.hpp>

#include "define_instances.hpp"

#include <adaptobs/design/care.hpp>
#include <adaptobs/design/dare.hpp>
#include <adaptobs/design/lyapunov.hpp>
#include <adaptobs/design/schur_stability.hpp>
#include <adaptobs/design/stein.hpp>
