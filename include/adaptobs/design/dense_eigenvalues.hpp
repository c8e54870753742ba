#pragma once
/// \file
/// Eigenvalues of a dynamic-size matrix: the one instantiation of Eigen's
/// `EigenSolver` that the design routines share (compiled once for `double`
/// where `adaptobs::precompiled` is linked; see core/precompiled.hpp).

#include <adaptobs/core/detail/dynamic_copy.hpp>
#include <adaptobs/core/precompiled.hpp>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include <limits>

namespace adaptobs::detail {

/// Eigenvalues of a square matrix (real Schur form, no eigenvectors), in the
/// solver's order; every entry NaN when the solver fails (a non-finite `m`),
/// whose eigenvalue storage is then never written.
template <typename Scalar>
[[nodiscard]] ComplexVector<Scalar> dense_eigenvalues(const DynamicMatrix<Scalar>& m) {
  const Eigen::EigenSolver<DynamicMatrix<Scalar>> solver(m, /*computeEigenvectors=*/false);
  if (solver.info() != Eigen::Success)
    return ComplexVector<Scalar>::Constant(m.rows(), std::numeric_limits<Scalar>::quiet_NaN());
  return solver.eigenvalues();
}
#ifdef ADAPTOBS_PRECOMPILED
ADAPTOBS_INSTANTIATE ComplexVector<double> dense_eigenvalues<double>(const DynamicMatrix<double>&);
#endif

}  // namespace adaptobs::detail
