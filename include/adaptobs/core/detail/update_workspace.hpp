#pragma once
/// \file
/// The scratch of one observer update, and the dispatch of an update with an
/// output mask: written once for every observer that has them.

#include <adaptobs/core/detail/products.hpp>
#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/validation.hpp>

#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>

namespace adaptobs::detail {

/// Where an update computes before it commits. With `on_stack` (fixed sizes)
/// nothing is stored: each step builds its workspace on the stack, where the
/// compiler can keep it in registers. Otherwise (run-time sizes) the observer
/// keeps one, sized at construction, so that an update never allocates.
template <class Workspace, bool on_stack>
class UpdateWorkspace {
 public:
  /// Sizes the kept workspace (`Workspace::resize(args...)`); nothing on the stack.
  template <class... Args>
  void resize(const Args&... args) {
    if constexpr (!on_stack) work_.resize(args...);
  }

  /// `step(workspace)`, on a fresh stack workspace or the kept one.
  template <class Step>
  decltype(auto) run(Step&& step) {
    if constexpr (on_stack) {
      Workspace w;
      return std::forward<Step>(step)(w);
    } else {
      return std::forward<Step>(step)(work_);
    }
  }

 private:
  [[no_unique_address]] std::conditional_t<on_stack, std::monostate, Workspace> work_;
};

/// The mask an update with `present` hands its step: null when every channel is
/// present (the plain update, bit for bit), after checking a run-time-sized mask
/// against the ny outputs (`who` names the caller in the error).
template <StateSpace D>
[[nodiscard]] const OutputMask<D>* partial_mask(const OutputMask<D>& present, Index ny, std::string_view who) {
  if constexpr (D::ny == Eigen::Dynamic) require_mask_size<D>(present, ny, who);
  return present.all() ? nullptr : &present;
}

/// Zeroes the rows of `m` whose output channel is absent (nothing for a null mask).
template <StateSpace D, class Derived>
void zero_absent_rows(Eigen::MatrixBase<Derived>& m, const OutputMask<D>* present) {
  if (!present) return;
  for (Index i = 0; i < m.rows(); ++i)
    if (!(*present)(i))
      for (Index j = 0; j < m.cols(); ++j) m.coeffRef(i, j) = typename Derived::Scalar(0);
}

/// \f$\bar R = DRD + (I - D)\f$, D = diag(present), into `out`: the measurement
/// covariance of the present channels, decoupled from unit noise on the absent
/// ones, so that a gain \f$P\bar C^T\bar R^{-1}\f$ with \f$\bar C = DC\f$ has zero
/// columns for them. Positive definite with R.
template <StateSpace D, class Square>
void masked_covariance(const Square& r, const OutputMask<D>& present, Square& out) {
  out = r;
  for (Index i = 0; i < out.rows(); ++i) {
    if (present(i)) continue;
    out.row(i).setZero();
    out.col(i).setZero();
    out(i, i) = typename Square::Scalar(1);
  }
}

/// The output `y` over an interval in which only the channels in `measured` are
/// measured: their measured values, and the prediction \f$(C\hat x)_i\f$ of the others.
template <StateSpace D, class OutputMatrix, class X>
const typename D::Output& predict_unmeasured(const OutputMatrix& c, const X& x, const typename D::Output& measured_y,
                                             const OutputMask<D>& measured, typename D::Output& y) {
  set_product(y, c, x);
  for (Index i = 0; i < y.size(); ++i)
    if (measured(i)) y(i) = measured_y(i);
  return y;
}

}  // namespace adaptobs::detail
