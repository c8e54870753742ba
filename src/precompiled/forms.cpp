// adaptobs::precompiled: what the continuous-time observers of Zhang (2005) are designed
// with: the canonical forms of Algorithms 1-3 and their static transform, polynomials
// and transfer functions, the exact SPR test, the SPR sweep and the KYP certificate.
#include <adaptobs/design/care.hpp>
#include <adaptobs/design/dense_eigenvalues.hpp>
#include <adaptobs/design/lyapunov.hpp>
#include <adaptobs/design/observability.hpp>
#include <adaptobs/design/schur_stability.hpp>

#include "define_instances.hpp"

#include <adaptobs/core/static_transform.hpp>
#include <adaptobs/design/canonical_forms.hpp>
#include <adaptobs/design/polynomial.hpp>
#include <adaptobs/design/positive_real.hpp>
#include <adaptobs/design/spr_test.hpp>
