// adaptobs::precompiled_base: the double matrix exponential, which every sampled
// model calls. The float instance, for sampled float models, is a unit of its own
// (matrix_exponential_float.cpp): each costs half of this header's compile time,
// and neither the satellite demo nor the Python module (double only) calls it.
// The header's ADAPTOBS_INSTANTIATE lines declare both instances (`extern
// template`); the definition below follows its declaration, as the standard
// allows ([temp.explicit]).
#ifndef ADAPTOBS_PRECOMPILED
#error "src/precompiled/*.cpp are compiled with ADAPTOBS_PRECOMPILED defined (target adaptobs_precompiled)"
#endif
#include <adaptobs/core/matrix_exponential.hpp>

namespace adaptobs::detail {
template DynamicMatrix<double> matrix_exponential_dense<double>(const DynamicMatrix<double>&);
}  // namespace adaptobs::detail
