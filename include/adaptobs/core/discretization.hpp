#pragma once
/// \file
/// Zero-order-hold discretization through one matrix exponential (Van Loan).
///
/// For \f$\dot x = A x + B u\f$ with u held over each period \f$T_s\f$,
/// \f[ \exp\left(\begin{bmatrix} A & B \\ 0 & 0 \end{bmatrix} T_s\right)
///   = \begin{bmatrix} A_d & B_d \\ 0 & I \end{bmatrix},\quad
///   A_d = e^{A T_s},\; B_d = \int_0^{T_s} e^{A s}\,ds\; B \f]
/// (C. F. Van Loan, "Computing integrals involving the matrix exponential",
/// IEEE TAC 23(3), 1978). With \f$B = I\f$ the upper-right block is the matrix
/// \f$H = \int_0^{T_s} e^{As}ds\f$ that Guyader & Zhang (2003, §4) uses to bring the
/// satellite's unknown input gains into the form \f$\Psi_k\theta\f$.

#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/matrix_exponential.hpp>
#include <adaptobs/core/validation.hpp>

#include <Eigen/Core>

#include <string_view>

namespace adaptobs {

/// Discrete matrices of a continuous system sampled with a zero-order hold.
template <typename Scalar, int N, int M>
struct ZeroOrderHold {
  Eigen::Matrix<Scalar, N, N> Ad;  ///< \f$e^{A T_s}\f$
  Eigen::Matrix<Scalar, N, M> Bd;  ///< \f$\int_0^{T_s} e^{As}ds\,B\f$
};

/// Zero-order-hold discretization of \f$(A, B)\f$ with period `ts` (Van Loan block form).
/// Throws a `ConfigurationError` naming the argument for a non-square or
/// non-finite A, a B of other rows or non-finite, a `ts` not positive, and
/// naming `A, ts` when \f$A T_s\f$, \f$B T_s\f$ or \f$e^{A T_s}\f$ lies beyond the
/// floating-point range.
template <class DerivedA, class DerivedB>
[[nodiscard]] auto discretize_zoh(const Eigen::MatrixBase<DerivedA>& A, const Eigen::MatrixBase<DerivedB>& B,
                                  typename DerivedA::Scalar ts) {
  using Scalar = typename DerivedA::Scalar;
  constexpr int n = DerivedA::RowsAtCompileTime;
  constexpr int m = DerivedB::ColsAtCompileTime;
  constexpr int block = sum_of_sizes(n, m);
  constexpr std::string_view who = "discretize_zoh";
  require_square(A, who, "A");
  require_finite(A, who, "A");
  require_finite_shape(B, A.rows(), B.cols(), who, "B");
  require_positive(ts, who, "ts");

  const Index nn = A.rows();
  const Index mm = B.cols();
  Eigen::Matrix<Scalar, block, block> van_loan = Eigen::Matrix<Scalar, block, block>::Zero(nn + mm, nn + mm);
  van_loan.topLeftCorner(nn, nn) = A * ts;
  van_loan.topRightCorner(nn, mm) = B * ts;
  constexpr std::string_view too_long = "give a sampled system beyond the floating-point range: shorten ts";
  require(van_loan.allFinite(), who, "A, ts", too_long);
  Eigen::Matrix<Scalar, block, block> e;
  try {
    e = matrix_exponential(van_loan);
  } catch (const ConfigurationError&) {  // the only refusal left for a finite square argument: overflow
    fail_argument(who, "A, ts", too_long);
  }
  return ZeroOrderHold<Scalar, n, m>{e.topLeftCorner(nn, nn), e.topRightCorner(nn, mm)};
}

/// \f$\int_0^{T_s} e^{As}\,ds\f$: the zero-order-hold input matrix for \f$B = I\f$.
template <class DerivedA>
[[nodiscard]] auto integral_of_exponential(const Eigen::MatrixBase<DerivedA>& A, typename DerivedA::Scalar ts) {
  using Scalar = typename DerivedA::Scalar;
  constexpr int n = DerivedA::RowsAtCompileTime;
  const Index nn = A.rows();
  return discretize_zoh(A, Eigen::Matrix<Scalar, n, n>::Identity(nn, nn), ts).Bd;
}

}  // namespace adaptobs
