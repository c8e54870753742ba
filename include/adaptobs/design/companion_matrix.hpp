#pragma once
/// \file
/// Companion matrices: the state matrices of the observable canonical form, as
/// used to build plants and the filters of Dey & Bhasin (2022), eq. (3) and (6).

#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/validation.hpp>

#include <Eigen/Core>

#include <string_view>

namespace adaptobs {

/// \f$\bar A(a)\f$: the r × r companion matrix with first column a and ones on the superdiagonal.
template <class Derived>
[[nodiscard]] auto companion_matrix(const Eigen::MatrixBase<Derived>& a) {
  using Scalar = typename Derived::Scalar;
  constexpr int R = Derived::SizeAtCompileTime;
  require_vector(a, "companion_matrix", "a");
  const Index r = a.size();
  Eigen::Matrix<Scalar, R, R> m = Eigen::Matrix<Scalar, R, R>::Zero(r, r);
  for (Index i = 0; i < r; ++i) m(i, 0) = a(i);
  if (r > 1) m.topRightCorner(r - 1, r - 1).setIdentity();
  return m;
}

/// \f$\bar A(a)\otimes I_q\f$: the state matrix (3) of the observable canonical form (or F of (6)).
/// q is the block size: at least 1, and Q when Q is fixed.
template <int Q = Eigen::Dynamic, class Derived>
[[nodiscard]] auto block_companion_matrix(const Eigen::MatrixBase<Derived>& a, Index q = Q) {
  using Scalar = typename Derived::Scalar;
  constexpr int N = product_of_sizes(Derived::SizeAtCompileTime, Q);
  constexpr std::string_view who = "block_companion_matrix";
  require_vector(a, who, "a");
  require(q >= 1 && (Q == Eigen::Dynamic || q == Q), who, "q",
          Q == Eigen::Dynamic ? "must be at least 1" : "must be the fixed block size Q");
  const Index r = a.size();
  const Index n = r * q;
  Eigen::Matrix<Scalar, N, N> m = Eigen::Matrix<Scalar, N, N>::Zero(n, n);
  for (Index i = 0; i < r; ++i) {
    m.block(i * q, 0, q, q).diagonal().setConstant(a(i));
    if (i + 1 < r) m.block(i * q, (i + 1) * q, q, q).setIdentity();
  }
  return m;
}

}  // namespace adaptobs
