#pragma once
/// \file
/// Takagi–Sugeno polytopic adaptive observer of Srinivasarengan, Ragot, Aubrun
/// and Maquin (2018, docs/references.md), eq. (65) for constant
/// parameters, eq. (21) with Remark 5 for time-varying ones.
///
/// For the polytopic model (64) \f$x_{k+1} = \sum_i h_i(z_k,\theta)(A_ix_k + B_iu_k)\f$,
/// \f$y_k = Cx_k\f$ (see `TakagiSugenoModel`) the observer runs on the weights
/// \f$\hat h_i = h_i(\hat z_k, \hat\theta_k)\f$, where \f$\hat z_k = z(\hat x_k, u_k, \hat\theta_k)\f$
/// is the premise vector at the estimates and both \f$\hat z_k\f$ and \f$\hat\theta_k\f$ are
/// clipped to their sectors before the memberships are formed:
/// \f[ \hat x_{k+1} = \sum_{i=1}^{r}\hat h_i\left[A_i\hat x_k + B_iu_k + L_i(y_k - C\hat x_k)\right], \f]
/// \f[ \hat\theta_{k+1} = \hat\theta_k + \sum_{i=1}^{r}\hat h_i\left[K_{y,i}(y_k - C\hat x_k) - K_\theta\hat\theta_k\right]. \f]
/// With no \f$K_\theta\f$ this is eq. (65) (constant θ); with \f$K_\theta\f$ it is eq. (21),
/// extended to state premises as in Remark 5 (time-varying θ).
///
/// Readings of the printed text:
/// - (65) prints \f$\hat y_k = Cx_k\f$; the output estimate is \f$C\hat x_k\f$ as in (21).
/// - θ̂ reaches the state prediction only through the weights: because the
///   model is affine in θ, \f$\sum_i\hat h_iA_i = A(\hat z, \hat\theta)\f$ inside the sectors.
///   The parameter law is an integrator of the output error (no regressor), so it
///   converges only where the sign and size of \f$K_{y,i}\f$ suit the sensitivity of y
///   to θ along the trajectory; the LMIs of theorems 1–2 certify the state-error
///   part (see `design/takagi_sugeno_lmi.hpp`).
/// - \f$K_\theta\f$ enters as printed in (21): \f$\hat\theta_{k+1} = (I - K_\theta)\hat\theta_k + \dots\f$,
///   a leakage that biases θ̂ toward 0 by a term of order \f$K_\theta/K_{y}\f$ (Remark 3).
///
/// **Missing and partial outputs.** The step runs with the output error
/// \f$D_k(y_k - C\hat x_k)\f$, \f$D_k = \mathrm{diag}(\text{present})\f$; the weights are those of
/// the full step. The LMIs certify nothing across a gap: a dwell-time condition
/// the observer does not check (derivation: docs/readings/takagi_sugeno.md).

#include <adaptobs/core/detail/commit.hpp>
#include <adaptobs/core/detail/dynamic_copy.hpp>
#include <adaptobs/core/detail/update_workspace.hpp>
#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/discrete_model.hpp>
#include <adaptobs/core/discrete_update.hpp>
#include <adaptobs/core/snapshot.hpp>
#include <adaptobs/core/status.hpp>
#include <adaptobs/core/validation.hpp>
#include <adaptobs/models/takagi_sugeno_model.hpp>

#include <Eigen/Core>

#include <iterator>
#include <optional>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

namespace adaptobs {

/// Takagi–Sugeno adaptive observer, eq. (65) (eq. (21) with \f$K_\theta\f$ set). Its
/// `output_error()` is \f$\varepsilon_k = D_k(y_k - C\hat x_k)\f$, the error that drives
/// both \f$L_i\f$ and \f$K_{y,i}\f$.
///
/// \copydoc takagi_sugeno.hpp
template <TakagiSugenoSystem Model>
class TakagiSugenoObserver
    : public DiscreteUpdate<TakagiSugenoObserver<Model>, typename Model::Dims, InputOutputSample> {
 public:
  ADAPTOBS_DISCRETE_UPDATE_INTERFACE(TakagiSugenoObserver, InputOutputSample);
  /// No condition is checked per step: the LMI its gains solve (design/takagi_sugeno_lmi.hpp) is its condition.
  static constexpr CheckedAssumption checked_assumption{};
  using Gains = TakagiSugenoGains<Dims>;
  using PremiseVector = typename Model::PremiseVector;
  using Weights = typename Model::Weights;
  static constexpr int vertices_at_compile_time = Model::vertices_at_compile_time;

  /// \param gains \f$L_i, K_{y,i}\f$ per vertex (and \f$K_\theta\f$ for eq. (21));
  /// \param x0, theta0 initial estimates \f$\hat x_0, \hat\theta_0\f$.
  TakagiSugenoObserver(Model model, const Gains& gains, State x0, Parameters theta0)
      : model_(std::move(model)), x_(std::move(x0)), theta_(std::move(theta0)) {
    constexpr std::string_view who = "TakagiSugenoObserver";
    const Sizes s = model_.sizes();
    require_initial_estimates(x_, s.nx, theta_, s.np, who);
    check_gains(gains, who);
    gains_ = gains;
    detail::zero_resize(weights_, model_.vertex_count());
    detail::zero_resize(premises_, model_.premise_count());
    detail::zero_resize(this->output_error_, s.ny);
    work_.resize(s, model_);
  }

  /// State estimate \f$\hat x_k\f$.
  [[nodiscard]] const State& state() const noexcept { return x_; }
  /// Weights \f$\hat h_i\f$ used by the last accepted update (zero before the first).
  [[nodiscard]] const Weights& weights() const noexcept { return weights_; }
  /// Premise variables \f$\hat z_k\f$ of the last accepted update, before clipping.
  [[nodiscard]] const PremiseVector& premises() const noexcept { return premises_; }
  /// False when the last accepted update had to clip \f$\hat z_k\f$ or \f$\hat\theta_k\f$ to its sector
  /// (the estimates left the region where the model is exact; Remark 8).
  [[nodiscard]] bool premises_in_sectors() const noexcept { return in_sectors_; }
  /// The gains the update runs on: \f$L_i\f$ and \f$K_{y,i}\f$ of vertex i, and \f$K_\theta\f$.
  [[nodiscard]] const Gains& gains() const noexcept { return gains_; }
  /// True for the time-varying-parameter observer (eq. (21), \f$K_\theta\f$ set).
  [[nodiscard]] bool has_leakage() const noexcept { return gains_.K_theta.has_value(); }

  /// Replaces the gains (checked as at construction) from the next update on;
  /// bad gains throw `ConfigurationError` naming the vertex (`gains.L[i]`) and
  /// change nothing.
  void set_gains(const Gains& gains) {
    check_gains(gains, "TakagiSugenoObserver::set_gains");
    gains_ = gains;
  }

  /// Its fields for `snapshot` and `restore` (core/snapshot.hpp): the model, the
  /// gains of eq. (65)/(21) as the per-vertex \f$L_i\f$ and \f$K_{y,i}\f$ (lists "L" and "K_y")
  /// and \f$K_\theta\f$, the estimates and the weights and premises of the last
  /// update. Reading checks the gains as `set_gains` does.
  /// Whether \f$K_\theta\f$ is set (eq. (21) rather than (65)) is a setting.
  static constexpr std::string_view snapshot_type = "TakagiSugenoObserver";
  static constexpr int snapshot_version = 1;
  template <class Self, class Archive>
    requires Snapshottable<Model>
  static void visit_state(Self& self, Archive& archive) {
    archive.object("model", self.model_);
    // A reading fills a copy of the current gains, whose shapes the snapshot's
    // must have, kept only once checked against the model just read.
    std::conditional_t<Archive::reading, Gains, const Gains&> gains = self.gains_;
    archive("L", gains.L);
    archive("K_y", gains.K);
    archive.setting("has_leakage", gains.K_theta ? 1 : 0);
    if (gains.K_theta) archive("K_theta", *gains.K_theta);
    if constexpr (Archive::reading) {
      self.check_gains(gains, "restore");
      self.gains_ = std::move(gains);
    }
    archive("x", self.x_);
    archive("theta", self.theta_);
    archive("weights", self.weights_);
    archive("premises", self.premises_);
    archive("premises_in_sectors", self.in_sectors_);
    TakagiSugenoObserver::visit_update_state(self, archive);
  }

 private:
  void check_gains(const Gains& gains, std::string_view who) const {
    const Sizes s = model_.sizes();
    const Index r = model_.vertex_count();
    if (std::ssize(gains.L) != r) detail::fail_count(r, gains.L.size(), "one matrix per vertex", who, "gains.L");
    if (std::ssize(gains.K) != r) detail::fail_count(r, gains.K.size(), "one matrix per vertex", who, "gains.K");
    for (std::size_t i = 0; i < gains.L.size(); ++i) {
      require_finite_shape(gains.L[i], s.nx, s.ny, who, "gains.L", i);
      require_finite_shape(gains.K[i], s.np, s.ny, who, "gains.K", i);
    }
    if (gains.K_theta) {
      require_finite_shape(*gains.K_theta, s.np, s.np, who, "gains.K_theta");
    }
  }

  // The rest of `reset`: no weights or premises yet.
  void restart(const State& x0, const Parameters& theta0) {
    x_ = x0;
    theta_ = theta0;
    weights_.setZero();
    premises_.setZero();
    in_sectors_ = true;
  }

  // Intermediate results of one step, committed only when all are finite.
  struct Workspace {
    PremiseVector z;
    Weights h;
    Output e;  // D_k(y_k − Cx̂_k)
    State x;
    Parameters theta;
    void resize(const Sizes& s, const Model& m) {
      detail::zero_resize(z, m.premise_count());
      detail::zero_resize(h, m.vertex_count());
      detail::zero_resize(e, s.ny);
      detail::zero_resize(x, s.nx);
      detail::zero_resize(theta, s.np);
    }
  };

  /// One step of eq. (65) (or (21) when \f$K_\theta\f$ is set) with the sample
  /// \f$(u_k, y_k)\f$; `nonfinite_input` for a NaN/Inf in the premise variables
  /// \f$\hat z_k\f$, `nonfinite_result` when the step would produce one; both
  /// change nothing.
  UpdateStatus advance(const Sample& sample, const OutputMask<Dims>* present, Workspace& w) {
    // Premise variables at the estimates, ẑ_k = z(x̂_k, u_k, θ̂_k) (they may use unmeasured states),
    // written into the workspace by a model that can (with run-time sizes, returning them allocates).
    if constexpr (requires { model_.premises(x_, sample.u, theta_, w.z); }) {
      model_.premises(x_, sample.u, theta_, w.z);
    } else {
      w.z = model_.premises(x_, sample.u, theta_);
    }
    if (!detail::all_finite(w.z)) return UpdateStatus::nonfinite_input;
    /// Weights \f$\hat h_i = h_i(\hat z_k, \hat\theta_k)\f$ with \f$\hat z_k, \hat\theta_k\f$ clipped to their sectors (10), Remark 1.
    model_.weights(w.z, theta_, w.h);

    // Every product is Eigen's coefficient-based lazyProduct: with run-time sizes
    // a plain product inside a sum allocates a temporary, and a noalias() one
    // dispatches to the general matrix-vector kernel, slow for these few entries.
    /// (65) third line, \f$\hat y_k = C\hat x_k\f$: the output error \f$e_k = D_k(y_k - C\hat x_k)\f$.
    w.e = sample.y - model_.C().lazyProduct(x_);
    if (present)
      for (Index j = 0; j < w.e.size(); ++j)
        if (!(*present)(j)) w.e(j) = Scalar(0);

    /// (65) first and second lines, summed vertex by vertex:
    /// \f$\hat x_{k+1} = \sum_i\hat h_i[A_i\hat x_k + B_iu_k + L_ie_k]\f$,
    /// \f$\hat\theta_{k+1} = \hat\theta_k + \sum_i\hat h_iK_{y,i}e_k\f$. (21) adds
    /// \f$-\sum_i\hat h_iK_\theta\hat\theta_k\f$ to the second, which is \f$-K_\theta\hat\theta_k\f$ since
    /// \f$\sum_i\hat h_i = 1\f$ (11).
    w.x.setZero();
    w.theta = theta_;
    if (gains_.K_theta) w.theta -= gains_.K_theta->lazyProduct(theta_);  // (21)
    for (Index i = 0; i < model_.vertex_count(); ++i) {
      const auto& A = model_.A(i);
      const auto& B = model_.B(i);
      const auto& L = gains_.L[static_cast<std::size_t>(i)];
      const auto& K = gains_.K[static_cast<std::size_t>(i)];
      w.x += w.h(i) * (A.lazyProduct(x_) + B.lazyProduct(sample.u) + L.lazyProduct(w.e));  // (65)
      w.theta += w.h(i) * K.lazyProduct(w.e);                                              // (65)
    }

    if (!detail::all_finite(w.x, w.theta)) return UpdateStatus::nonfinite_result;

    in_sectors_ = model_.premise_bounds().contains(w.z) && model_.parameter_bounds().contains(theta_);
    detail::commit(x_, w.x);
    detail::commit(theta_, w.theta);
    detail::commit(weights_, w.h);
    detail::commit(premises_, w.z);
    detail::commit(this->output_error_, w.e);
    return UpdateStatus::accepted;
  }

  Model model_;  // A_i, B_i, C of (64)
  Gains gains_;  // L_i, K_{y,i} of (65), and K_θ of (21) (empty for (65))
  State x_;
  Parameters theta_;
  Weights weights_;
  PremiseVector premises_;
  bool in_sectors_ = true;
  // A run-time number of vertices keeps its workspace even with fixed sizes.
  detail::UpdateWorkspace<Workspace, Dims::is_fixed && vertices_at_compile_time != Eigen::Dynamic> work_;
};

}  // namespace adaptobs
