#pragma once
/// \file
/// The filters of Dey & Bhasin (2022), eq. (8)–(13), for a MIMO
/// system in observable canonical form, computed through their Kronecker
/// structure instead of the n × (r + mn) matrix \f$S_t\f$.
///
/// Notation. A system of order r with q outputs and m inputs (n = rq states) in
/// observable canonical form (3)–(4) is \f$A = \bar A(a)\otimes I_q\f$,
/// \f$C = e_1^T\otimes I_q\f$, with \f$\bar A(a)\f$ the r × r companion matrix whose
/// first column is \f$a = -[a_1\ \dots\ a_r]^T\f$ (the paper's vector a: the
/// scalars of the first block column of A) and ones on the superdiagonal; the
/// design matrix (6) is \f$F = \bar F\otimes I_q\f$, \f$\bar F = \bar A(f)\f$. The
/// unknowns are \f$p = [(a - f)^T\ \mathrm{vec}(B)^T]^T \in \mathbb{R}^{r+mn}\f$
/// (vec column by column), and an n-vector is handled in *block layout*, the
/// q × r matrix whose column k is its k-th block \f$x^{(k)}\f$, in which
/// \f$(Fx)^{(k)} = f_kx^{(1)} + x^{(k+1)}\f$.
///
/// Structure. \f$\bar F\f$ is nonderogatory, so every matrix the filters (8)–(9)
/// produce is a polynomial of degree < r in \f$\bar F\f$ (Kronecker with
/// \f$I_q\f$), fixed by one r-vector. All of (8)–(9) is therefore carried by one
/// bank of q + m scalar filters of order r,
/// \f[ \Sigma_{t+1} = \bar F\Sigma_t + e_r\,[y_t^T\ u_t^T],\qquad \Sigma_0 = 0
///     \quad (r \times (q+m);\ \text{stored transposed, one filter per row}), \f]
/// from which, with \f$\Sigma = [\Sigma_y\ \Sigma_u]\f$ and
/// \f$\hat\Theta_j = [(\hat a_j - f_j)I_q\ \ \hat N_j]\f$ (\f$\hat N_j\f$ the j-th q × m block of \f$\hat B\f$),
/// \f[ S_t\hat p = \sum_{j=1}^{r}\hat\Theta_j\,(\bar F^{r-j}\Sigma_t)^T \ \text{(block layout)},\qquad
///     \varphi_t = S_t^TC^T:\ \ \varphi^T\hat p = \sum_{j=1}^r\hat\Theta_j\,(e_1^T\bar F^{r-j}\Sigma_t)^T. \f]
/// The first is evaluated by Horner's rule, \f$\bar F\f$ acting through the
/// companion structure; the rows \f$e_1^T\bar F^{r-j}\f$ are precomputed. Per
/// step: r(q + m) for the bank, \f$r^2(q+m)\f$ for φ, \f$qr^2(1+m)\f$ for
/// \f$S_t\hat p\f$ — against \f$n^2(r + mn)\f$ for the literal (8)–(11) and
/// r(q + m) numbers of memory instead of n(r + mn). Tests compare both.

#include <adaptobs/core/detail/products.hpp>
#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/validation.hpp>
#include <adaptobs/design/companion_matrix.hpp>
#include <adaptobs/design/schur_stability.hpp>

#include <Eigen/Core>

#include <string_view>
#include <utility>

namespace adaptobs {

/// Filters (8)–(11) of Dey & Bhasin (2022) for order `R`, `Q` outputs and `M` inputs (any may be `Eigen::Dynamic`).
template <typename S, int R, int Q, int M>
class CanonicalFormFilters {
 public:
  static constexpr int nx = product_of_sizes(R, Q);
  static constexpr int np = sum_of_sizes(R, product_of_sizes(M, nx));
  static constexpr int channels = sum_of_sizes(Q, M);
  using Scalar = S;
  /// Sizes of the observer: n states, m inputs, q outputs, r + mn parameters.
  using Dims = Dimensions<S, nx, M, Q, np>;
  using State = typename Dims::State;
  using Input = typename Dims::Input;
  using Output = typename Dims::Output;
  using Parameters = typename Dims::Parameters;
  using StateMatrix = typename Dims::StateMatrix;
  using InputMatrix = typename Dims::InputMatrix;
  using Coefficients = Eigen::Matrix<S, R, 1>;     ///< first-column entries a, f
  using Bank = Eigen::Matrix<S, channels, R>;      ///< \f$\Sigma^T\f$: row c is the state of filter c
  using Channels = Eigen::Matrix<S, channels, 1>;  ///< \f$[y^T\ u^T]^T\f$, what drives the bank
  using Blocks = Eigen::Matrix<S, Q, R>;           ///< an n-vector in block layout
  using Regressor = Eigen::Matrix<S, np, Q>;       ///< φ
  using FirstRows = Eigen::Matrix<S, R, R>;        ///< row j: \f$e_1^T\bar F^{r-1-j}\f$ (0-based)

  /// \param f first-column entries of F (the paper's vector f); \f$\bar F\f$ must be Schur stable.
  /// \param q, m output and input counts (read when `Q`, `M` are dynamic).
  CanonicalFormFilters(Coefficients f, Index q = Q, Index m = M)
      : f_(std::move(f)), q_(Q == Eigen::Dynamic ? q : Q), m_(M == Eigen::Dynamic ? m : M) {
    constexpr std::string_view who = "CanonicalFormFilters";
    require(f_.size() >= 1, who, "f", "must have at least one entry (the order r)");
    require_finite(f_, who, "f");
    require(q_ >= 1, who, "q", "must be at least 1");
    require(m_ >= 0, who, "m", "must be non-negative");
    require(is_schur_stable(companion_matrix(f_)), who, "f",
            "must make F Schur stable (eq. (6)): the roots of z^r - f_1 z^(r-1) - ... - f_r must lie in |z| < 1");
    const Index r = order();
    first_rows_.setZero(r, r);
    first_rows_(r - 1, 0) = Scalar(1);
    for (Index j = r - 1; j > 0; --j) {  // e_1ᵀF̄^{d+1} = (e_1ᵀF̄^d) F̄
      first_rows_(j - 1, 0) = first_rows_.row(j).dot(f_);
      first_rows_.row(j - 1).tail(r - 1) = first_rows_.row(j).head(r - 1);
    }
  }

  [[nodiscard]] Index order() const noexcept { return f_.size(); }
  [[nodiscard]] Index outputs() const noexcept { return q_; }
  [[nodiscard]] Index inputs() const noexcept { return m_; }
  [[nodiscard]] Index states() const noexcept { return order() * q_; }
  [[nodiscard]] Index parameters() const noexcept { return order() + m_ * states(); }
  [[nodiscard]] Sizes sizes() const noexcept { return {states(), m_, q_, parameters()}; }
  /// The paper's vector f (first-column entries of F).
  [[nodiscard]] const Coefficients& coefficients() const noexcept { return f_; }
  /// \f$F = \bar F\otimes I_q\f$ as a dense n × n matrix (for analysis; the filters never form it).
  [[nodiscard]] StateMatrix transition_matrix() const { return block_companion_matrix<Q>(f_, q_); }

  /// In place, every row w of `rows` becomes \f$(\bar Fw^T)^T\f$: \f$w_k \leftarrow f_kw_1 + w_{k+1}\f$.
  /// Applied to an n-vector in block layout this is \f$x \leftarrow Fx\f$.
  template <class Derived>
  void apply_transition(Eigen::MatrixBase<Derived>& rows) const {
    const Index r = order();
    for (Index l = 0; l < rows.rows(); ++l) {
      const Scalar first = rows(l, 0);
      for (Index k = 0; k + 1 < r; ++k) rows(l, k) = f_(k) * first + rows(l, k + 1);
      rows(l, r - 1) = f_(r - 1) * first;
    }
  }

  /// \f$x \leftarrow Fx\f$ for an n-vector.
  void apply_transition_to_state(State& x) const {
    Eigen::Map<Blocks> blocks(x.data(), q_, order());
    apply_transition(blocks);
  }

  /// (8)–(9): \f$\Sigma_{t+1} = \bar F\Sigma_t + e_r[y_t^T\ u_t^T]\f$, with `drive` = \f$[y_t; u_t]\f$.
  void advance(Bank& bank, const Channels& drive) const {
    apply_transition(bank);
    bank.col(order() - 1) += drive;
  }

  /// \f$\varphi_t = S_t^TC^T\f$ (12): rows 1..r hold \f$e_1^T\bar F^{r-j}\Sigma_y\f$, and the
  /// row of \f$\hat B_{(k-1)q+l,\,i}\f$ holds \f$e_1^T\bar F^{r-k}\sigma_{u_i}\f$ in column l.
  void regressor(const Bank& bank, Regressor& phi) const {
    const Index r = order(), q = q_, n = states();
    detail::set_product(phi.template block<R, Q>(0, 0, r, q), first_rows_,
                        bank.template block<Q, R>(0, 0, q, r).transpose());
    phi.bottomRows(m_ * n).setZero();
    for (Index i = 0; i < m_; ++i)
      for (Index j = 0; j < r; ++j) {
        const Scalar value = first_rows_.row(j).dot(bank.row(q + i));
        for (Index l = 0; l < q; ++l) phi(r + i * n + j * q + l, l) = value;
      }
  }

  /// \f$x = S_tp + \text{free}\f$ (13), e.g. free = \f$F^t\hat x_0\f$.
  void state(const Bank& bank, const Parameters& p, const State& free, State& x) const {
    const Index r = order(), q = q_, m = m_;
    const auto sy = bank.template block<Q, R>(0, 0, q, r);
    const auto su = bank.template block<M, R>(q, 0, m, r);
    const Eigen::Map<const InputMatrix> b(p.data() + r, states(), m);
    Eigen::Map<Blocks> x_blocks(x.data(), q, r);
    // Horner: X = ((Θ̂_1Σᵀ)F̄ᵀ + Θ̂_2Σᵀ)F̄ᵀ + ... + Θ̂_rΣᵀ, Θ̂_jΣᵀ = (â_j − f_j)Σ_yᵀ + N̂_jΣ_uᵀ.
    for (Index j = 0; j < r; ++j) {
      if (j == 0) {
        x_blocks = p(0) * sy;
      } else {
        apply_transition(x_blocks);
        x_blocks += p(j) * sy;
      }
      detail::add_product(x_blocks, b.template block<Q, M>(j * q, 0, q, m), su);
    }
    x += free;
  }

  /// One-step prediction with the model of parameters p (from (7)):
  /// \f$x^+ = Fx + (I_r\otimes y)(\hat a - f) + \hat Bu\f$; with \f$x = S_t\hat p + F^t\hat x_0\f$ it
  /// equals \f$S_{t+1}\hat p + F^{t+1}\hat x_0\f$.
  template <class Y, class U>
  void predict(const State& x, const Parameters& p, const Eigen::MatrixBase<Y>& y, const Eigen::MatrixBase<U>& u,
               State& next) const {
    const Index r = order();
    next = x;
    Eigen::Map<Blocks> next_blocks(next.data(), q_, r);
    apply_transition(next_blocks);
    detail::add_product(next_blocks, y.derived(), p.template head<R>(r).transpose());
    const Eigen::Map<const InputMatrix> b(p.data() + r, states(), m_);
    detail::add_product(next, b, u.derived());
  }

  /// Its fields for `snapshot` and `restore` (core/snapshot.hpp): f and the
  /// rows derived from it; q and m are settings.
  template <class Self, class Archive>
  static void visit_state(Self& self, Archive& archive) {
    archive.setting("q", self.q_);
    archive.setting("m", self.m_);
    archive("f", self.f_);
    archive("first_rows", self.first_rows_);
  }

 private:
  Coefficients f_;
  Index q_;
  Index m_;
  FirstRows first_rows_;
};

}  // namespace adaptobs
