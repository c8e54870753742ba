// Included by each translation unit of adaptobs::precompiled (see
// include/adaptobs/core/precompiled.hpp) between two groups of headers. Before it
// come the headers whose instances other units compile: their ADAPTOBS_INSTANTIATE
// lines are explicit instantiation declarations (`extern template`). After it come
// the headers whose instances this unit compiles: there the lines are definitions.
// A header after it must therefore include no header with ADAPTOBS_INSTANTIATE lines
// that is neither before it nor after it in the same unit, or its instances would
// be compiled twice.
#ifndef ADAPTOBS_PRECOMPILED
#error "src/precompiled/*.cpp are compiled with ADAPTOBS_PRECOMPILED defined (target adaptobs_precompiled)"
#endif
#undef ADAPTOBS_INSTANTIATE
#define ADAPTOBS_INSTANTIATE template
