// Certificates and checks: Guiro's convergence conditions, the SPR tests,
// periodic stability, and the Monte-Carlo evaluation of a detector.

#include "arrays.hpp"

#include <nanobind/nanobind.h>

namespace adaptobs::python {

void bind_checks(nb::module_& /*m*/) {}

}  // namespace adaptobs::python
