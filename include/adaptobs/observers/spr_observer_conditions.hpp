#pragma once
/// \file
/// The construction-time conditions that the two single-output SPR observers
/// of Zhang (2005), Bastin–Gevers (§III-A) and Marino–Tomei (§III-B), share:
/// the form of the transformed system, and the strictly positive real error
/// system their Lyapunov function needs.

#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/static_transform.hpp>
#include <adaptobs/core/validation.hpp>
#include <adaptobs/design/spr_test.hpp>

#include <Eigen/Core>

#include <string>
#include <string_view>

namespace adaptobs::detail {

/// One output, constant (A, c), and \f$c_o = CT^{-1} = e_1^T\f$: what both
/// forms (5) and (7) start from.
template <StateSpace D>
void require_single_output_spr_form(const TransformedSystem<D>& so, const Sizes& sizes, bool time_invariant,
                                    std::string_view name) {
  require(time_invariant, name, "model", "must be time invariant (the SPR condition is on a transfer function)");
  require(sizes.ny == 1, name, "model", "must have a single output");
  require(is_leading_identity(so.Co), name, "static_transform", "must give c_o = C T^-1 = e1^T");
}

/// \f$c_o(sI - A_o + kc_o)^{-1}\gamma\f$ strictly positive real (exact test of
/// `design/spr_test.hpp`); the error names k, and γ as `gamma_name`.
template <StateSpace D, class DGamma>
void require_spr_error_system(const TransformedSystem<D>& so, const typename D::GainMatrix& k,
                              const Eigen::MatrixBase<DGamma>& gamma, std::string_view gamma_name,
                              std::string_view name) {
  const typename D::StateMatrix closed = so.Ao - k * so.Co;
  // The transform and the gains are validated, so the triple's shapes hold; a closed
  // loop that overflows is refused by the test, naming its numerator.
  if (!strictly_positive_real(closed, gamma, so.Co))
    fail_argument(
        name, "k",
        std::string("must make c_o (sI - A_o + k c_o)^-1 ").append(gamma_name).append(" strictly positive real"));
}

}  // namespace adaptobs::detail
