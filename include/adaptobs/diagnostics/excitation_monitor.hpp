#pragma once
/// \file
/// Windowed persistent-excitation monitor.
///
/// Keeps the average of the last L positive semidefinite contributions
/// \f$\Phi_i^T\Phi_i\f$ (e.g. \f$\mu_i\Upsilon_i^T C_i^T C_i\Upsilon_i\f$ for
/// assumption 3 of Guyader & Zhang (2003), eq. (4)) and reports its smallest eigenvalue,
/// the largest α for which \f$\frac1L\sum_{i=k}^{k+L-1}\Phi_i^T\Phi_i \ge \alpha I\f$
/// holds on that window. A value that stays away from zero says the unknown
/// parameters are identifiable from the data; a value near zero says some
/// direction of θ is not excited.
///
/// A contribution too large for the floating-point range (a Φ beyond about
/// 10^154) cannot enter the average: while it is in the window the level is
/// unavailable (`available()` false, `level()` NaN), and it comes back once the
/// window has moved past it.
///
/// The sum is kept by adding the new term and subtracting the one that leaves,
/// O(p²) per sample. It is rebuilt from the window, O(Lp²), once per window and
/// whenever the subtracted terms outweigh what remains, so that a large term
/// leaving, or excitation dying out, cannot leave its rounding in the level.

#include <adaptobs/core/detail/finite.hpp>
#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/symmetric_eigenvalues.hpp>
#include <adaptobs/core/validation.hpp>

#include <Eigen/Core>

#include <cmath>
#include <limits>
#include <string_view>
#include <vector>

namespace adaptobs {

template <typename Scalar, int NP>
class ExcitationMonitor {
 public:
  using Gramian = Eigen::Matrix<Scalar, NP, NP>;

  /// \param window number L of samples averaged (≥ 1), \param np parameter count (p; with a
  /// compile-time NP it must be NP).
  explicit ExcitationMonitor(Index window, Index np = NP) : window_(window) {
    require(window >= 1, "ExcitationMonitor", "window", "must be at least 1");
    require_size<NP>(np, "ExcitationMonitor", "np");
    ring_.assign(static_cast<std::size_t>(window), Gramian::Zero(np, np));
    sum_.setZero(np, np);
  }

  /// Adds the contribution \f$w\,\Phi^T\Phi\f$ of one sample (Φ is m × p).
  /// A Φ with other than p columns, a non-finite entry, or a weight that is
  /// negative or not finite throws a `ConfigurationError` and adds nothing.
  /// Φ is read more than once: an expression without storage (`Ones()`, a sum) is
  /// evaluated once first, into a temporary that allocates when its size is
  /// dynamic; a matrix, a block or a map is used in place.
  template <class Derived>
  void add(const Eigen::MatrixBase<Derived>& phi, Scalar weight = Scalar(1)) {
    if constexpr (Derived::Flags & Eigen::DirectAccessBit) {
      add_stored(phi, weight);
    } else {
      add_stored(phi.eval(), weight);
    }
  }

  /// Number of samples averaged so far (at most the window length).
  [[nodiscard]] Index count() const noexcept { return count_; }
  [[nodiscard]] Index window() const noexcept { return window_; }
  [[nodiscard]] bool full() const noexcept { return count_ == window_; }

  /// \f$\frac1L\sum\Phi_i^T\Phi_i\f$ over the last L samples (fewer before the window fills).
  [[nodiscard]] Gramian average() const { return count_ == 0 ? Gramian(sum_) : Gramian(sum_ / Scalar(count_)); }

  /// False while a contribution in the window, or their sum, exceeded the floating-point range.
  [[nodiscard]] bool available() const { return adds_since_overflow_ >= window_ && detail::all_finite(sum_); }

  /// Smallest eigenvalue of `average()`: the excitation level α; NaN while not `available()`.
  [[nodiscard]] Scalar level() const {
    if (sum_.size() == 0) return Scalar(0);
    if (!available()) return std::numeric_limits<Scalar>::quiet_NaN();
    return symmetric_eigenvalues(average())(0);
  }

  /// Its fields for `snapshot` and `restore` (core/snapshot.hpp): the window of
  /// contributions and the running sum; the window length a setting.
  using SnapshotScalar = Scalar;
  static constexpr std::string_view snapshot_type = "ExcitationMonitor";
  static constexpr int snapshot_version = 1;
  template <class Self, class Archive>
  static void visit_state(Self& self, Archive& archive) {
    archive.setting("window", self.window_);
    archive("ring", self.ring_);
    archive("sum", self.sum_);
    archive("removed_trace", self.removed_trace_);
    archive("next", self.next_);
    archive("count", self.count_);
    archive("adds_since_overflow", self.adds_since_overflow_);
    if constexpr (Archive::reading)
      require(self.next_ < self.ring_.size() && self.count_ >= 0 && self.count_ <= self.window_, "restore", "snapshot",
              "holds an excitation window position outside the window");
  }

  void reset() {
    for (Gramian& g : ring_) g.setZero();
    adds_since_overflow_ = window_;
    sum_.setZero();
    removed_trace_ = Scalar(0);
    next_ = 0;
    count_ = 0;
  }

 private:
  template <class Derived>
  void add_stored(const Eigen::MatrixBase<Derived>& phi, Scalar weight) {
    constexpr std::string_view who = "ExcitationMonitor::add";
    require_finite_shape(phi, phi.rows(), sum_.cols(), who, "phi");
    require(weight >= Scalar(0) && std::isfinite(weight), who, "weight", "must be non-negative and finite");
    Gramian& slot = ring_[next_];
    sum_ -= slot;
    // The sum carries a rounding error of about ε times the terms it ever held;
    // once the terms removed outweigh what remains (a huge Φ leaving, or
    // excitation dying out), that error is no longer small beside the sum.
    // A sum that overflowed stays infinite under subtraction: rebuild it too.
    removed_trace_ += slot.trace();
    const Scalar remaining = sum_.trace();
    const bool cancelled = removed_trace_ > Scalar(4) * remaining || !std::isfinite(remaining);
    // (wΦ)ᵀΦ entry by entry, (wφ_i)ᵀφ_j: w first, so that a tiny w keeps a huge Φ
    // from overflowing. Eigen's product kernels (dynamic sizes) would take w out
    // of the product and apply it after the sum.
    for (Index j = 0; j < slot.cols(); ++j)
      for (Index i = 0; i < slot.rows(); ++i) slot(i, j) = (weight * phi.col(i)).dot(phi.col(j));
    if (detail::all_finite(slot)) {
      if (adds_since_overflow_ < window_) ++adds_since_overflow_;
    } else {
      slot.setZero();  // kept out of the sum; the level is unavailable until it leaves the window
      adds_since_overflow_ = 0;
    }
    sum_ += slot;
    next_ = (next_ + 1) % ring_.size();
    if (count_ < window_) ++count_;
    // Rebuild the sum from the window once per window, and whenever the
    // subtractions have cancelled most of it.
    if (next_ == 0 || cancelled) {
      sum_.setZero();
      for (const Gramian& g : ring_) sum_ += g;
      removed_trace_ = Scalar(0);
    }
  }

  std::vector<Gramian> ring_;
  Gramian sum_;
  Scalar removed_trace_ = Scalar(0);  // traces of the terms subtracted from sum_ since it was last rebuilt
  std::size_t next_ = 0;
  Index count_ = 0;
  Index window_;
  Index adds_since_overflow_ = window_;  // the last overflowing contribution left the window at window_
};

}  // namespace adaptobs
