// adaptobs::precompiled: the float matrix exponential, for sampled float models
// (see matrix_exponential.cpp, which holds the double one).
#ifndef ADAPTOBS_PRECOMPILED
#error "src/precompiled/*.cpp are compiled with ADAPTOBS_PRECOMPILED defined (target adaptobs_precompiled)"
#endif
#include <adaptobs/core/matrix_exponential.hpp>

namespace adaptobs::detail {
template DynamicMatrix<float> matrix_exponential_dense<float>(const DynamicMatrix<float>&);
}  // namespace adaptobs::detail
