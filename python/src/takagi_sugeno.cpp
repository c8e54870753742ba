// The Takagi–Sugeno observer, its polytopic model and the LMI synthesis.

#include "arrays.hpp"

#include <nanobind/nanobind.h>

namespace adaptobs::python {

void bind_takagi_sugeno(nb::module_& /*m*/) {}

}  // namespace adaptobs::python
