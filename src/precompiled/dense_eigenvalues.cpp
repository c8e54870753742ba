// adaptobs::precompiled_base: the dense eigenvalues (Eigen's EigenSolver), which the
// stability checks of every observer's construction and the design routines call.
#include "define_instances.hpp"

#include <adaptobs/design/dense_eigenvalues.hpp>
