#pragma once
/// \file
/// Configuration checks shared by every model, observer and design routine.
///
/// Bad configuration fails where it is given (a constructor or a design
/// function) with a `ConfigurationError` whose message names the component and
/// the offending argument, e.g. `GuyaderZhangObserver: argument 'mu' must be
/// positive and finite (got -1)`. The argument checks are public, so that a
/// model or observer written for the library's concepts refuses its bad
/// configuration in the same terms.

#include <adaptobs/core/detail/cholesky.hpp>
#include <adaptobs/core/detail/finite.hpp>
#include <adaptobs/core/detail/message.hpp>
#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/symmetric_eigenvalues.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>

namespace adaptobs {

/// Invalid configuration: wrong sizes, non-positive gains, indefinite covariances, ...
class ConfigurationError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// \name Argument checks
/// The checks every constructor and design routine of the library makes of its
/// arguments, for a model, observer or design routine of one's own that is to
/// fail as the library's do: each throws `ConfigurationError` with the message
/// "<who>: argument '<argument>' <problem>", e.g.
/// `require_positive(mu, "MyObserver", "mu")` for mu = −1 gives
/// `MyObserver: argument 'mu' must be positive and finite (got -1)`.
/// \{

/// Throws `ConfigurationError` "<who>: argument '<argument>' <problem>".
[[noreturn]] inline void fail_argument(std::string_view who, std::string_view argument, std::string_view problem) {
  std::string message;
  message.reserve(who.size() + argument.size() + problem.size() + 16);
  message.append(who).append(": argument '").append(argument).append("' ").append(problem);
  throw ConfigurationError(message);
}

/// `fail_argument(who, argument, problem)` unless `condition` holds.
inline void require(bool condition, std::string_view who, std::string_view argument, std::string_view problem) {
  if (!condition) fail_argument(who, argument, problem);
}

namespace detail {

// The failures of the shape checks format their message outside the templates, so
// that a translation unit compiles each once rather than once per matrix type.
[[noreturn]] inline void fail_not_square(Index rows, Index cols, std::string_view who, std::string_view argument) {
  Message os;
  os << "must be square (got " << rows << "x" << cols << ")";
  fail_argument(who, argument, os.str());
}

[[noreturn]] inline void fail_shape(Index rows, Index cols, Index got_rows, Index got_cols, std::string_view who,
                                    std::string_view argument, std::string_view because = {}) {
  Message os;
  os << "must be " << rows << "x" << cols << " (got " << got_rows << "x" << got_cols << ")";
  if (!because.empty()) os << ": " << because;
  fail_argument(who, argument, os.str());
}

/// Whether an Eigen expression of type `Derived` can be assigned to a matrix
/// of compile-time size R × C: every dimension fixed on both sides agrees.
template <class Derived, int R, int C>
inline constexpr bool fits_size =
    (Derived::RowsAtCompileTime == Eigen::Dynamic || R == Eigen::Dynamic || Derived::RowsAtCompileTime == R) &&
    (Derived::ColsAtCompileTime == Eigen::Dynamic || C == Eigen::Dynamic || Derived::ColsAtCompileTime == C);

/// `m` as a `Target` when its compile-time size fits, else an empty `Target`:
/// a constructor's `static_assert` on `fits_size` then names the argument, and
/// is the only error (not Eigen's, deep inside the conversion).
template <class Target, class Derived>
[[nodiscard]] Target fitted(const Eigen::MatrixBase<Derived>& m) {
  if constexpr (fits_size<Derived, Target::RowsAtCompileTime, Target::ColsAtCompileTime>)
    return Target(m);
  else
    return Target();
}

/// A list argument (one matrix per vertex, per mode, ...) of the wrong length:
/// "must hold <what> (<expected>, got <got>)".
[[noreturn]] inline void fail_count(Index expected, std::size_t got, std::string_view what, std::string_view who,
                                    std::string_view argument) {
  Message os;
  os << "must hold " << what << " (" << expected << ", got " << got << ")";
  fail_argument(who, argument, os.str());
}

/// "list[index]", element `index` of a list argument as an error names it.
[[nodiscard]] inline std::string element_name(std::string_view list, std::size_t index) {
  Message name;
  name << list << "[" << index << "]";
  return name.str();
}

/// A finite scalar of the sign `what` names ("positive", "non-negative").
template <typename Scalar>
void require_finite_with_sign(bool sign_holds, Scalar value, std::string_view who, std::string_view argument,
                              std::string_view what) {
  if (!sign_holds || !std::isfinite(value)) {
    Message os;
    os << "must be " << what << " and finite (got " << value << ")";
    fail_argument(who, argument, os.str());
  }
}

/// True when the symmetric `m` (lower triangle read) is positive definite: `cholesky_in_place` on a copy.
template <class Derived>
[[nodiscard]] bool cholesky_succeeds(const Eigen::MatrixBase<Derived>& m) {
  Eigen::Matrix<typename Derived::Scalar, Derived::RowsAtCompileTime, Derived::ColsAtCompileTime> l = m;
  return cholesky_in_place(l);
}

}  // namespace detail

/// A positive, finite scalar (a gain, a period, a forgetting horizon).
template <typename Scalar>
void require_positive(Scalar value, std::string_view who, std::string_view argument) {
  detail::require_finite_with_sign(value > Scalar(0), value, who, argument, "positive");
}

/// A non-negative, finite scalar (a noise level, a margin).
template <typename Scalar>
void require_non_negative(Scalar value, std::string_view who, std::string_view argument) {
  detail::require_finite_with_sign(value >= Scalar(0), value, who, argument, "non-negative");
}

/// A matrix of `rows` × `cols` (the check that keeps a run-time-sized argument
/// from being multiplied with the wrong sizes).
template <class Derived>
void require_shape(const Eigen::EigenBase<Derived>& m, Index rows, Index cols, std::string_view who,
                   std::string_view argument) {
  if (m.rows() != rows || m.cols() != cols) detail::fail_shape(rows, cols, m.rows(), m.cols(), who, argument);
}

/// A square matrix.
template <class Derived>
void require_square(const Eigen::EigenBase<Derived>& m, std::string_view who, std::string_view argument) {
  if (m.rows() != m.cols()) detail::fail_not_square(m.rows(), m.cols(), who, argument);
}

/// One row or one column, whatever the type (a 1 × n `MatrixXd` is a vector).
template <class Derived>
void require_vector(const Eigen::EigenBase<Derived>& m, std::string_view who, std::string_view argument) {
  if (m.rows() != 1 && m.cols() != 1) fail_argument(who, argument, "must be a vector (one row or one column)");
}

/// Only finite entries (no infinity, no NaN).
template <class Derived>
void require_finite(const Eigen::DenseBase<Derived>& m, std::string_view who, std::string_view argument) {
  if (!detail::all_finite(m)) fail_argument(who, argument, "must contain only finite numbers");
}

/// The shape check, then the finiteness check, of one argument: the pair that
/// nearly every matrix argument gets.
template <class Derived>
void require_finite_shape(const Eigen::DenseBase<Derived>& m, Index rows, Index cols, std::string_view who,
                          std::string_view argument) {
  require_shape(m, rows, cols, who, argument);
  require_finite(m, who, argument);
}

/// `require_finite_shape` of element `index` of the list `list`, named
/// `list[index]`; the name is formatted only when the check fails.
template <class Derived>
void require_finite_shape(const Eigen::DenseBase<Derived>& m, Index rows, Index cols, std::string_view who,
                          std::string_view list, std::size_t index) {
  if (m.rows() != rows || m.cols() != cols || !detail::all_finite(m))
    require_finite_shape(m, rows, cols, who, detail::element_name(list, index));
}

/// A size given at run time for a dimension of compile-time size `N`:
/// non-negative, and N itself unless N is `Eigen::Dynamic` (another size would
/// contradict the fixed-size types it is used with).
template <int N>
void require_size(Index n, std::string_view who, std::string_view argument) {
  require(n >= 0, who, argument, "must be non-negative");
  if constexpr (N != Eigen::Dynamic) require(n == N, who, argument, "must equal the compile-time size");
}

/// The matrices (A, B, C) of a state-space system, discrete or continuous: A
/// square, B with A's rows, C with A's columns, every entry finite.
template <class System>
void validate_state_space(const System& s, std::string_view who) {
  require_square(s.A, who, "A");
  require_finite(s.A, who, "A");
  // A fixes nx: B and C are measured against it, and their refusal says so.
  const auto fail_against_a = [&](std::string_view argument, Index rows, Index cols, const auto& m) {
    detail::Message from_a;
    from_a << "nx = " << s.A.rows() << " is the order of A";
    detail::fail_shape(rows, cols, m.rows(), m.cols(), who, argument, from_a.str());
  };
  if (s.B.rows() != s.A.rows()) fail_against_a("B", s.A.rows(), s.B.cols(), s.B);
  require_finite(s.B, who, "B");
  if (s.C.cols() != s.A.rows()) fail_against_a("C", s.C.rows(), s.A.rows(), s.C);
  require_finite(s.C, who, "C");
}

/// The matrices a time-varying model's callable returned, checked against the
/// model's sizes at every call when they are dynamic (fixed sizes are checked
/// by the type): with `Eigen::Dynamic` sizes nothing else would stop an
/// observer or a plant from writing past its vectors. `callable` names the
/// callable and its argument, e.g. "matrices_at(t)".
template <class System>
void require_system_sizes(const System& s, const Sizes& sizes, std::string_view who, std::string_view callable) {
  if (s.A.rows() == sizes.nx && s.A.cols() == sizes.nx && s.B.rows() == sizes.nx && s.B.cols() == sizes.nu &&
      s.C.rows() == sizes.ny && s.C.cols() == sizes.nx)
    return;
  detail::Message os;
  os << "returns A " << s.A.rows() << "x" << s.A.cols() << ", B " << s.B.rows() << "x" << s.B.cols() << ", C "
     << s.C.rows() << "x" << s.C.cols() << " where the model's sizes give A " << sizes.nx << "x" << sizes.nx << ", B "
     << sizes.nx << "x" << sizes.nu << ", C " << sizes.ny << "x" << sizes.nx;
  fail_argument(who, callable, os.str());
}

/// The initial estimates of an observer (or the initial true values of a
/// simulated plant): a finite state column of nx entries and a finite
/// parameter column of np entries, named in the error as given.
template <class X, class Theta>
void require_initial_estimates(const Eigen::DenseBase<X>& x0, Index nx, const Eigen::DenseBase<Theta>& theta0, Index np,
                               std::string_view who, std::string_view x_name = "x0",
                               std::string_view theta_name = "theta0") {
  require_finite_shape(x0, nx, 1, who, x_name);
  require_finite_shape(theta0, np, 1, who, theta_name);
}

/// Square, finite and symmetric to a relative tolerance of 100 ulp of its largest entry.
template <class Derived>
[[nodiscard]] bool is_symmetric(const Eigen::MatrixBase<Derived>& m) {
  using Scalar = typename Derived::Scalar;
  if (m.rows() != m.cols() || !detail::all_finite(m)) return false;
  if (m.size() == 0) return true;
  const Scalar scale = m.cwiseAbs().maxCoeff();
  const Scalar tol = Scalar(100) * std::numeric_limits<Scalar>::epsilon() * (scale > Scalar(0) ? scale : Scalar(1));
  return (m - m.transpose()).cwiseAbs().maxCoeff() <= tol;
}

/// Symmetric to a relative tolerance of 100 ulp of its largest entry.
template <class Derived>
void require_symmetric(const Eigen::MatrixBase<Derived>& m, std::string_view who, std::string_view argument) {
  require_square(m, who, argument);
  if (!is_symmetric(m)) fail_argument(who, argument, "must be symmetric");
}

/// Symmetric positive definite (a Cholesky factorization exists).
template <class Derived>
void require_positive_definite(const Eigen::MatrixBase<Derived>& m, std::string_view who, std::string_view argument) {
  require_finite(m, who, argument);
  require_symmetric(m, who, argument);
  if (!detail::cholesky_succeeds(m)) fail_argument(who, argument, "must be positive definite");
}

/// Symmetric positive semidefinite: no eigenvalue below −100 n ε max|λ| (round-off
/// of a rank-deficient product such as GᵀG is accepted).
template <class Derived>
void require_positive_semidefinite(const Eigen::MatrixBase<Derived>& m, std::string_view who,
                                   std::string_view argument) {
  using Scalar = typename Derived::Scalar;
  require_finite(m, who, argument);
  require_symmetric(m, who, argument);
  if (m.size() == 0) return;
  // On a dynamic copy: one instantiation per scalar type.
  const Eigen::Matrix<Scalar, Eigen::Dynamic, 1> lambda =
      symmetric_eigenvalues(Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>(m));
  const Scalar tol = Scalar(100) * Scalar(m.rows()) * std::numeric_limits<Scalar>::epsilon() *
                     std::max(std::abs(lambda(0)), std::abs(lambda(lambda.size() - 1)));
  if (!(lambda(0) >= -tol)) fail_argument(who, argument, "must be positive semidefinite");
}

/// \}

namespace detail {

/// The data of an observability question: A square and finite, C finite with
/// A's columns (`output_matrix` names C). Returns the order n.
template <class DA, class DC>
Index require_output_pair(const Eigen::DenseBase<DA>& A, const Eigen::DenseBase<DC>& C, std::string_view who,
                          std::string_view output_matrix = "C") {
  require_square(A, who, "A");
  require_finite(A, who, "A");
  require_finite_shape(C, C.rows(), A.rows(), who, output_matrix);
  return A.rows();
}

/// A single-output pair (A, c): `require_output_pair` with c one row. Returns
/// the order n, which the design routines of SISO systems go on with.
template <class DA, class DC>
Index require_single_output_pair(const Eigen::DenseBase<DA>& A, const Eigen::DenseBase<DC>& c, std::string_view who) {
  const Index n = require_output_pair(A, c, who, "c");
  require_shape(c, 1, n, who, "c");
  return n;
}

/// A single-input single-output triple (A, b, c): A square, b one column and
/// c one row of its order, all finite. Returns the order n.
template <class DA, class DB, class DC>
Index require_siso_triple(const Eigen::DenseBase<DA>& A, const Eigen::DenseBase<DB>& b, const Eigen::DenseBase<DC>& c,
                          std::string_view who) {
  const Index n = require_single_output_pair(A, c, who);
  require_finite_shape(b, n, 1, who, "b");
  return n;
}

/// Throws `ConfigurationError` when a run-time-sized output mask does not have ny entries.
template <StateSpace D>
void require_mask_size(const OutputMask<D>& present, Index ny, std::string_view who) {
  require(present.size() == ny, who, "present", "must have one entry per output channel");
}

}  // namespace detail
}  // namespace adaptobs
