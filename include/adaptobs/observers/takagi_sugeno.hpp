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
#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/discrete_model.hpp>
#include <adaptobs/core/discrete_update.hpp>
#include <adaptobs/core/snapshot.hpp>
#include <adaptobs/core/status.hpp>
#include <adaptobs/models/takagi_sugeno_model.hpp>
#include <adaptobs/core/detail/update_workspace.hpp>
#include <adaptobs/core/validation.hpp>

#include <Eigen/Core>

#include <iterator>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

namespace adaptobs {

/// Takagi–Sugeno adaptive observer, eq. (65) (eq. (21) with \f$K_\theta\f$ set). Its
/// `output_error()` is \f$\varepsilon_k = D_k(y_k - C\hat x_k)\f$, the error that drives
/// both \f$L_i\f$ and \f$K_{y,i}\f$.
template <TakagiSugenoSystem Model>
class TakagiSugenoObserver
    : public DiscreteUpdate<TakagiSugenoObserver<Model>, typename Model::Dims, InputOutputSample> {
 public:
  ADAPTOBS_DISCRETE_UPDATE_INTERFACE(TakagiSugenoObserver, InputOutputSample);
  using Gains = TakagiSugenoGains<Dims>;
  using PremiseVector = typename Model::PremiseVector;
  using Weights = typename Model::Weights;
  static constexpr int vertices_at_compile_time = Model::vertices_at_compile_time;

  /// \param gains \f$L_i, K_{y,i}\f$ per vertex (and \f$K_\theta\f$ for eq. (21));
  /// \param x0, theta0 initial estimates \f$\hat x_0, \hat\theta_0\f$.
  TakagiSugenoObserver(Model model, const Gains& gains, State x0, Parameters theta0)
      : model_(std::move(model)), K_theta_(gains.K_theta), x_(std::move(x0)), theta_(std::move(theta0)) {
    constexpr std::string_view who = "TakagiSugenoObserver";
    const Sizes s = model_.sizes();
    detail::require_initial_estimates(x_, s.nx, theta_, s.np, who);
    check_gains(gains, who);
    fill_vertex_maps(gains);
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
  /// The gains in use, read back from the vertex maps \f$V_i\f$ the update runs on.
  /// Returned by value: the observer keeps no second copy of them, and a
  /// program that never asks compiles no copy of their vectors.
  [[nodiscard]] Gains gains() const {
    const Sizes s = model_.sizes();
    const Index r = model_.vertex_count(), nv = s.nx + s.nu + s.ny;
    Gains g;
    g.L.resize(static_cast<std::size_t>(r));
    g.K.resize(static_cast<std::size_t>(r));
    for (Index i = 0; i < r; ++i) {
      auto& L = g.L[static_cast<std::size_t>(i)];
      auto& K = g.K[static_cast<std::size_t>(i)];
      L.resize(s.nx, s.ny);
      K.resize(s.np, s.ny);
      const Index first = i * nv + s.nx + s.nu;
      for (Index j = 0; j < s.ny; ++j) {
        for (Index a = 0; a < s.nx; ++a) L(a, j) = vertex_maps_(a, first + j);
        for (Index a = 0; a < s.np; ++a) K(a, j) = vertex_maps_(s.nx + a, first + j);
      }
    }
    g.K_theta = K_theta_;
    return g;
  }
  /// True for the time-varying-parameter observer (eq. (21), \f$K_\theta\f$ set).
  [[nodiscard]] bool has_leakage() const noexcept { return K_theta_.has_value(); }

  /// Replaces the gains (checked as at construction) from the next update on;
  /// bad gains throw `ConfigurationError` naming the vertex (`gains.L[i]`) and
  /// change nothing.
  void set_gains(const Gains& gains) {
    check_gains(gains, "TakagiSugenoObserver::set_gains");
    K_theta_ = gains.K_theta;
    fill_vertex_maps(gains);
  }

  /// Its fields for `snapshot` and `restore` (core/snapshot.hpp): the model, the
  /// gains of eq. (65)/(21) as the per-vertex \f$L_i\f$ and \f$K_{y,i}\f$ (lists "L" and "K_y")
  /// and \f$K_\theta\f$, the estimates and the weights and premises of the last
  /// update. The gains are written as `gains()` gives them, not as the vertex maps
  /// the update runs on, so that a snapshot does not depend on how those are
  /// packed; reading checks them as `set_gains` does and packs them again.
  /// Whether \f$K_\theta\f$ is set (eq. (21) rather than (65)) is a setting.
  static constexpr std::string_view snapshot_type = "TakagiSugenoObserver";
  static constexpr int snapshot_version = 1;
  template <class Self, class Archive>
    requires Snapshottable<Model>
  static void visit_state(Self& self, Archive& archive) {
    archive.object("model", self.model_);
    // The current gains give the shapes a reading is checked against.
    Gains gains = self.gains();
    archive("L", gains.L);
    archive("K_y", gains.K);
    archive.setting("has_leakage", gains.K_theta ? 1 : 0);
    if (gains.K_theta) archive("K_theta", *gains.K_theta);
    if constexpr (Archive::reading) {
      // After the model: the vertex maps pack its A_i, B_i with the gains.
      self.check_gains(gains, "restore");
      self.K_theta_ = gains.K_theta;
      self.fill_vertex_maps(gains);
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
      detail::require_finite_shape(gains.L[i], s.nx, s.ny, who, "gains.L", i);
      detail::require_finite_shape(gains.K[i], s.np, s.ny, who, "gains.K", i);
    }
    if (gains.K_theta) {
      detail::require_finite_shape(*gains.K_theta, s.np, s.np, who, "gains.K_theta");
    }
  }

  void fill_vertex_maps(const Gains& gains) {
    const Sizes s = model_.sizes();
    const Index r = model_.vertex_count();
    // [V_1 … V_r], V_i = [[A_i, B_i, L_i], [0, 0, K_{y,i}]], so that
    // [x̂⁺; Δθ̂] = Σ ĥ_i V_i [x̂; u; y − Cx̂].
    // Read from the stacked [A_1 … A_r] and [B_1 … B_r], entry by entry: no block type per vertex.
    const auto& A = model_.vertex_state_matrices();
    const auto& B = model_.vertex_input_matrices();
    const Index nv = s.nx + s.nu + s.ny;
    detail::zero_resize(vertex_maps_, s.nx + s.np, nv * r);
    for (Index i = 0; i < r; ++i) {
      const Index first = i * nv;
      for (Index a = 0; a < s.nx; ++a) {
        for (Index j = 0; j < s.nx; ++j) vertex_maps_(a, first + j) = A(a, i * s.nx + j);
        for (Index j = 0; j < s.nu; ++j) vertex_maps_(a, first + s.nx + j) = B(a, i * s.nu + j);
      }
      detail::copy_entries(vertex_maps_, 0, first + s.nx + s.nu, gains.L[static_cast<std::size_t>(i)]);
      detail::copy_entries(vertex_maps_, s.nx, first + s.nx + s.nu, gains.K[static_cast<std::size_t>(i)]);
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

  static constexpr int nv_at_compile_time = sum_of_sizes(sum_of_sizes(Dims::nx, Dims::nu), Dims::ny);
  static constexpr int na_at_compile_time = sum_of_sizes(Dims::nx, Dims::np);
  using VertexMaps =
      Eigen::Matrix<Scalar, na_at_compile_time, product_of_sizes(nv_at_compile_time, vertices_at_compile_time)>;

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
    const Index nx = x_.rows(), ny = sample.y.rows(), np = theta_.rows();

    // Premise variables at the estimates, ẑ_k = z(x̂_k, u_k, θ̂_k) (they may use unmeasured states).
    w.z = model_.premises(x_, sample.u, theta_);
    if (!detail::all_finite(w.z)) return UpdateStatus::nonfinite_input;
    /// Weights \f$\hat h_i = h_i(\hat z_k, \hat\theta_k)\f$ with \f$\hat z_k, \hat\theta_k\f$ clipped to their sectors (10), Remark 1.
    model_.weights(w.z, theta_, w.h);

    // e = D_k(y_k − C x̂_k).
    for (Index i = 0; i < ny; ++i) {
      Scalar e = sample.y(i);
      for (Index j = 0; j < nx; ++j) e -= model_.C()(i, j) * x_(j);
      w.e(i) = (present && !(*present)(i)) ? Scalar(0) : e;
    }

    /// (65) \f$\hat x_{k+1} = \sum_i\hat h_i[A_i\hat x_k + B_iu_k + L_i(y_k - C\hat x_k)]\f$ and
    /// \f$\hat\theta_{k+1} = \hat\theta_k + \sum_i\hat h_iK_{y,i}(y_k - C\hat x_k)\f$ in one sum:
    /// \f$[\hat x_{k+1}; \hat\theta_{k+1} - \hat\theta_k] = \sum_i\hat h_i(V_iv)\f$ with
    /// \f$V_i = \begin{bmatrix} A_i & B_i & L_i \\ 0 & 0 & K_{y,i}\end{bmatrix}\f$.
    for (Index a = 0; a < nx; ++a) w.x(a) = weighted_vertex_row(a, w.h, sample.u, w.e);
    for (Index a = 0; a < np; ++a) w.theta(a) = theta_(a) + weighted_vertex_row(nx + a, w.h, sample.u, w.e);
    /// (21) adds the leakage \f$-\sum_i\hat h_iK_\theta\hat\theta_k = -K_\theta\hat\theta_k\f$ (\f$\sum_i\hat h_i = 1\f$).
    if (K_theta_)
      for (Index i = 0; i < np; ++i)
        for (Index j = 0; j < np; ++j) w.theta(i) -= (*K_theta_)(i, j) * theta_(j);

    if (!detail::all_finite(w.x, w.theta)) return UpdateStatus::nonfinite_result;

    in_sectors_ = model_.premise_bounds().contains(w.z) && model_.parameter_bounds().contains(theta_);
    detail::commit(x_, w.x);
    detail::commit(theta_, w.theta);
    detail::commit(weights_, w.h);
    detail::commit(premises_, w.z);
    detail::commit(this->output_error_, w.e);
    return UpdateStatus::accepted;
  }

  // Row a of Σ_i ĥ_i (V_i v), v = [x̂; u; e]. Plain loops over the stored entries:
  // they run as fast as Eigen's block expressions here (r small blocks of a few
  // entries each) and cost a fraction of their compile time.
  Scalar weighted_vertex_row(Index a, const Weights& h, const typename Dims::Input& u, const Output& e) const {
    const Index nx = x_.size(), nu = u.size(), ny = e.size(), nv = nx + nu + ny;
    Scalar sum(0);
    for (Index i = 0; i < h.size(); ++i) {
      const Index first = i * nv;
      Scalar row(0);
      for (Index j = 0; j < nx; ++j) row += vertex_maps_(a, first + j) * x_(j);
      for (Index j = 0; j < nu; ++j) row += vertex_maps_(a, first + nx + j) * u(j);
      for (Index j = 0; j < ny; ++j) row += vertex_maps_(a, first + nx + nu + j) * e(j);
      sum += h(i) * row;
    }
    return sum;
  }

  Model model_;
  std::optional<typename Dims::ParameterMatrix> K_theta_;  // K_θ of eq. (21), empty for (65)
  VertexMaps vertex_maps_;
  State x_;
  Parameters theta_;
  Weights weights_;
  PremiseVector premises_;
  bool in_sectors_ = true;
  // A run-time number of vertices keeps its workspace even with fixed sizes.
  detail::UpdateWorkspace<Workspace, Dims::is_fixed && vertices_at_compile_time != Eigen::Dynamic> work_;
};

}  // namespace adaptobs
