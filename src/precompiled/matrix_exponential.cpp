// adaptobs::precompiled_base: the matrix exponential (double, and float for sampled
// float models), which every sampled model calls. The library is split into units
// so that each compiler process stays small (docs/compile_time.md).
#include "define_instances.hpp"

#include <adaptobs/core/matrix_exponential.hpp>
