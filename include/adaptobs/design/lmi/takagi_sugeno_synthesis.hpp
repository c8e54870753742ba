#pragma once
/// \file
/// LMI synthesis of the gains of `TakagiSugenoObserver` by theorem 2 (constant
/// parameters, observer (65)) or theorem 1 (time-varying parameters, observer
/// (21)), optionally minimising the \f$\ell_2\f$ gain β of corollary 1
/// (Srinivasarengan et al. (2018)), solved with DSDP. Part of the optional
/// `adaptobs::lmi` component.
///
/// The LMIs are those of `design/takagi_sugeno_lmi.hpp` (see there for every
/// block and for the readings of the printed text), written over the decision
/// variables \f$P_0, P_1, R_i, F_i, \lambda_{1..4}, \Gamma^j\f$ (and β). Every point DSDP returns
/// is verified independently: the certificate is read back, each \f$M_i\f$ is
/// rebuilt numerically with `takagi_sugeno_vertex_lmi` and its largest eigenvalue
/// must be negative, with \f$P_0, P_1, \lambda_m, \Gamma^j \succ 0\f$. Only a verified point
/// yields gains \f$L_i = P_0^{-1}R_i\f$, \f$K_{y,i} = P_1^{-1}F_i\f$ (31); anything else comes back
/// as a status without gains.
///
/// Choices a user makes (all in `TakagiSugenoLmiOptions`):
/// - \f$Q_e = \mathrm{diag}(Q_x, Q_\theta)\f$ in place of the theorems' \f$I\f$ (Remark 4; §6 uses
///   \f$10^{-3}I\f$ and \f$0.1\f$);
/// - the parameter gain: imposed (\f$F_i = P_1K\f$, Remark 6 — needed with the printed error
///   model of theorem 2, under which \f$K_{y,i} = 0\f$ is always at least as feasible),
///   bounded below (scalar case, \f$F_i \succeq \kappa P_1\f$, i.e. \f$K_{y,i} \ge \kappa\f$; Remark 3 (62) has
///   \f$\kappa = \rho k_\theta\f$), or free;
/// - fixed \f$\lambda_m\f$ and \f$\Gamma^j = \gamma I\f$ (Remark 7);
/// - the objective: minimise β (corollary 1), maximise a margin t with \f$M_i \preceq -tI\f$
///   (for ill-conditioned problems, with Γ fixed), or plain feasibility.

#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/validation.hpp>
#include <adaptobs/design/lmi/dsdp.hpp>
#include <adaptobs/design/lmi/lmi_problem.hpp>
#include <adaptobs/design/takagi_sugeno_lmi.hpp>
#include <adaptobs/models/takagi_sugeno_model.hpp>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace adaptobs {

/// What the SDP optimises over the LMIs.
enum class TakagiSugenoObjective {
  minimize_beta,  ///< corollary 1 (56)–(57): \f$\min\beta\f$, \f$\beta I \succeq \Gamma^j\f$, \f$M_i \preceq -\varepsilon I\f$
  maximize_margin,  ///< \f$\max t \le 1\f$ with \f$M_i \preceq -tI\f$ and \f$P_0, P_1, \lambda_m \succeq tI\f$ (needs fixed Γ)
  feasibility,  ///< \f$M_i \preceq -\varepsilon I\f$, minimising \f$\mathrm{tr}\,P_0\f$ only to keep the point bounded
};

struct TakagiSugenoLmiOptions {
  TakagiSugenoTheorem theorem = TakagiSugenoTheorem::constant_parameters;
  /// The parameter-error recursion the LMIs are written for. Empty: the reading under
  /// which the theorem is feasible and certifies the observer as implemented —
  /// `as_printed` (\f$\Phi_{22} = 0\f$) for theorem 2, whose `exact` form is infeasible for
  /// every \f$Q_e\f$, and `exact` (\f$\Phi_{22} = I - K_\theta\f$, \f$G_\theta = K_\theta\f$) for theorem 1, whose
  /// printed form describes the update \f$\hat\Theta_{k+1} = \sum_i\hat h_i(K_{y,i}(y_k - \hat y_k) - K_\theta\hat\Theta_k)\f$
  /// rather than (21).
  std::optional<ParameterErrorModel> error_model;
  Eigen::MatrixXd Q_x;      ///< \f$n_x\times n_x\f$, empty: \f$I\f$ (the theorems' "+I")
  Eigen::MatrixXd Q_theta;  ///< \f$n_\theta\times n_\theta\f$, empty: \f$I\f$
  Eigen::MatrixXd K_theta;  ///< \f$K_\theta\f$ of observer (21), theorem 1 only
  /// \f$K_{y,i} = K\f$ at every vertex, imposed as \f$F_i = P_1K\f$ (Remark 6); empty: \f$F_i\f$ free.
  Eigen::MatrixXd parameter_gain;
  /// \f$K_{y,i} \ge \kappa\f$ as \f$F_i \succeq \kappa P_1\f$ (scalar θ and y; Remark 3 (62) with \f$\kappa = \rho k_\theta\f$);
  /// unused when `parameter_gain` is set or when empty.
  std::optional<double> min_parameter_gain;
  std::optional<std::array<double, 4>> fixed_lambda;  ///< \f$\lambda_1..\lambda_4\f$ fixed (Remark 7)
  std::optional<double> fixed_gamma;                  ///< \f$\Gamma^j = \gamma I\f$ fixed (Remark 7)
  TakagiSugenoObjective objective = TakagiSugenoObjective::minimize_beta;
  double margin = 1e-7;  ///< ε of the strict inequalities (not used by `maximize_margin`)
  lmi::DsdpOptions solver;
};

/// The LMI problem of theorem 1 or 2 and the expressions of its variables.
struct TakagiSugenoLmiProblem {
  lmi::LmiProblem problem;
  TakagiSugenoLmiData data;
  lmi::AffineMatrix P0, P1, Gamma_x, Gamma_u, Gamma_theta, Gamma_dtheta;
  std::vector<lmi::AffineMatrix> R, F;
  std::array<lmi::AffineMatrix, 4> lambda;
  std::optional<lmi::AffineMatrix> beta;       ///< corollary 1
  std::optional<lmi::AffineMatrix> t;          ///< margin variable
  std::vector<lmi::AffineMatrix> vertex_lmis;  ///< \f$M_i\f$, i = 0..r−1, as in (29) / (71)

  /// The decision variables at a point y.
  [[nodiscard]] TakagiSugenoCertificate certificate(const Eigen::VectorXd& y) const {
    TakagiSugenoCertificate s;
    s.P0 = P0.value(y);
    s.P1 = P1.value(y);
    for (const auto& r : R) s.R.push_back(r.value(y));
    for (const auto& f : F) s.F.push_back(f.value(y));
    for (std::size_t m = 0; m < 4; ++m) s.lambda[m] = lambda[m].value(y)(0, 0);
    s.Gamma_x = Gamma_x.value(y);
    s.Gamma_u = Gamma_u.value(y);
    if (!Gamma_theta.empty()) s.Gamma_theta = Gamma_theta.value(y);
    if (!Gamma_dtheta.empty()) s.Gamma_dtheta = Gamma_dtheta.value(y);
    return s;
  }
};

namespace detail {
inline void validate_lmi_options(const TakagiSugenoLmiData& data, const TakagiSugenoLmiOptions& o,
                                 std::string_view who) {
  const Index ny = data.ny(), np = data.np();
  require(std::isfinite(o.margin) && o.margin >= 0, who, "options.margin", "must be finite and non-negative");
  if (o.parameter_gain.size() > 0) {
    require_finite_shape(o.parameter_gain, np, ny, who, "options.parameter_gain");
  }
  if (o.min_parameter_gain) {
    require(np == 1 && ny == 1, who, "options.min_parameter_gain", "needs a scalar parameter and a scalar output");
    require(std::isfinite(*o.min_parameter_gain), who, "options.min_parameter_gain", "must be finite");
  }
  if (o.fixed_lambda) {
    for (double l : *o.fixed_lambda) require_positive(l, who, "options.fixed_lambda");
  }
  if (o.fixed_gamma) require_positive(*o.fixed_gamma, who, "options.fixed_gamma");
  require(!(o.objective == TakagiSugenoObjective::minimize_beta && o.fixed_gamma), who, "options.objective",
          "cannot minimise beta with options.fixed_gamma set (choose maximize_margin or feasibility)");
  require(!(o.objective == TakagiSugenoObjective::maximize_margin && !o.fixed_gamma), who, "options.fixed_gamma",
          "must be set for the maximize_margin objective (it normalizes the homogeneous LMIs)");
}
}  // namespace detail

/// Builds the LMIs of theorem 1 / 2 for `data` (vertices, C, \f$Q_e\f$, reading) and `options`.
[[nodiscard]] inline TakagiSugenoLmiProblem build_takagi_sugeno_lmis(TakagiSugenoLmiData data,
                                                                     const TakagiSugenoLmiOptions& options) {
  using Eigen::MatrixXd;
  using lmi::AffineMatrix;
  constexpr std::string_view who = "build_takagi_sugeno_lmis";
  detail::validate_lmi_data(data, who);
  detail::validate_lmi_options(data, options, who);

  TakagiSugenoLmiProblem out;
  auto& pb = out.problem;
  const Index r = data.vertex_count(), nx = data.nx(), nu = data.nu(), ny = data.ny(), np = data.np();
  const bool theorem1 = data.theorem == TakagiSugenoTheorem::time_varying_parameters;
  const bool with_margin = options.objective == TakagiSugenoObjective::maximize_margin;
  const double eps = with_margin ? 0.0 : options.margin;
  const ParameterErrorBlocks pe = parameter_error_blocks(data);
  const MatrixXd calA = data.stacked_A(), calB = data.stacked_B();
  const MatrixXd Ct = data.C.transpose();

  // Decision variables (28) / (69)–(70), with R_i = P0 L_i and F_i = P1 K_{y,i} (40).
  out.P0 = pb.symmetric("P0", nx);
  out.P1 = pb.symmetric("P1", np);
  for (Index i = 0; i < r; ++i) out.R.push_back(pb.full("R" + std::to_string(i + 1), nx, ny));
  for (Index i = 0; i < r; ++i) {
    out.F.push_back(options.parameter_gain.size() > 0 ? out.P1 * options.parameter_gain
                                                      : pb.full("F" + std::to_string(i + 1), np, ny));
  }
  for (std::size_t m = 0; m < 4; ++m) {
    out.lambda[m] = options.fixed_lambda ? AffineMatrix(MatrixXd::Constant(1, 1, (*options.fixed_lambda)[m]))
                                         : pb.scalar("lambda" + std::to_string(m + 1));
  }
  const auto gamma = [&](const std::string& name, Index n) {
    return options.fixed_gamma ? AffineMatrix(*options.fixed_gamma * MatrixXd::Identity(n, n)) : pb.symmetric(name, n);
  };
  out.Gamma_x = gamma("Gamma_x", nx);
  out.Gamma_u = gamma("Gamma_u", nu);
  if (theorem1) {
    out.Gamma_theta = gamma("Gamma_theta", np);
    out.Gamma_dtheta = gamma("Gamma_dtheta", np);
  }
  if (options.objective == TakagiSugenoObjective::minimize_beta) out.beta = pb.scalar("beta");
  if (with_margin) out.t = pb.scalar("t");

  // Every constraint G ⪯ −εI is written G + tI ⪯ 0 under the margin objective.
  const auto negative = [&](const std::string& name, const AffineMatrix& G) {
    if (out.t) {
      pb.require_negative_definite(name, G + out.t->times_identity(G.rows()));
    } else {
      pb.require_negative_definite(name, G, eps);
    }
  };
  const auto positive = [&](const std::string& name, const AffineMatrix& G) { negative(name, -G); };

  positive("P0 > 0", out.P0);
  positive("P1 > 0", out.P1);
  if (!options.fixed_lambda)
    for (std::size_t m = 0; m < 4; ++m) positive("lambda" + std::to_string(m + 1) + " > 0", out.lambda[m]);
  if (!options.fixed_gamma) {
    positive("Gamma_x > 0", out.Gamma_x);
    positive("Gamma_u > 0", out.Gamma_u);
    if (theorem1) {
      positive("Gamma_theta > 0", out.Gamma_theta);
      positive("Gamma_dtheta > 0", out.Gamma_dtheta);
    }
  }
  if (out.beta) {  // (57): βI ⪰ Γ^j
    pb.require_positive_definite("beta I - Gamma_x >= 0", out.beta->times_identity(nx) - out.Gamma_x);
    pb.require_positive_definite("beta I - Gamma_u >= 0", out.beta->times_identity(nu) - out.Gamma_u);
    if (theorem1) {
      pb.require_positive_definite("beta I - Gamma_theta >= 0", out.beta->times_identity(np) - out.Gamma_theta);
      pb.require_positive_definite("beta I - Gamma_dtheta >= 0", out.beta->times_identity(np) - out.Gamma_dtheta);
    }
  }
  if (options.min_parameter_gain && options.parameter_gain.size() == 0) {  // (62): F_i ⪰ κ P1
    for (Index i = 0; i < r; ++i)
      pb.require_positive_definite("F" + std::to_string(i + 1) + " >= kappa P1",
                                   out.F[static_cast<std::size_t>(i)] - *options.min_parameter_gain * out.P1);
  }
  if (out.t) pb.require_positive_definite("t <= 1", AffineMatrix(MatrixXd::Ones(1, 1)) - *out.t);

  // Blocks shared by every vertex (see design/takagi_sugeno_lmi.hpp).
  const Index n1 = nx + np, nut = data.perturbation_size();
  const AffineMatrix P = lmi::blocks({{out.P0, AffineMatrix()}, {AffineMatrix(), out.P1}});
  MatrixXd Qe = MatrixXd::Zero(n1, n1);
  Qe.topLeftCorner(nx, nx) = data.Q_x;
  Qe.bottomRightCorner(np, np) = data.Q_theta;
  const AffineMatrix& l1 = out.lambda[0];
  const AffineMatrix& l2 = out.lambda[1];
  const AffineMatrix& l3 = out.lambda[2];
  const AffineMatrix& l4 = out.lambda[3];
  // T22 = diag(−Γx + (λ1+λ2) E_AᵀE_A, −Γu + (λ3+λ4) E_BᵀE_B [, −Γθ, −ΓΔθ]), E_AᵀE_A = r I.
  std::vector<std::vector<AffineMatrix>> t22_grid;
  t22_grid.push_back({-out.Gamma_x + double(r) * (l1 + l2).times_identity(nx), AffineMatrix()});
  t22_grid.push_back({AffineMatrix(), -out.Gamma_u + double(r) * (l3 + l4).times_identity(nu)});
  if (theorem1) {
    for (auto& row : t22_grid) row.resize(4);
    t22_grid.push_back({AffineMatrix(), AffineMatrix(), -out.Gamma_theta, AffineMatrix()});
    t22_grid.push_back({AffineMatrix(), AffineMatrix(), AffineMatrix(), -out.Gamma_dtheta});
  }
  const AffineMatrix T22 = lmi::blocks(t22_grid);
  // Λ = diag(−λ1 I_{n_x r}, −λ3 I_{n_u r}, −λ2 I_{n_x r}, −λ4 I_{n_u r}).
  const AffineMatrix Lambda = lmi::blocks({{-l1.times_identity(nx * r), {}, {}, {}},
                                           {{}, -l3.times_identity(nu * r), {}, {}},
                                           {{}, {}, -l2.times_identity(nx * r), {}},
                                           {{}, {}, {}, -l4.times_identity(nu * r)}});
  // T4 = [[0, 0, P0𝒜, P0ℬ], [0, 0, 0, 0]] (rows: e_x, e_Θ).
  const AffineMatrix T4 =
      lmi::blocks({{AffineMatrix::zero(nx, nx * r), AffineMatrix::zero(nx, nu * r), out.P0 * calA, out.P0 * calB},
                   {AffineMatrix::zero(np, nx * r), {}, {}, AffineMatrix::zero(np, nu * r)}});
  // Q_B = [[0, 0], [0, 0], [0, G_θᵀP1], [0, P1]] (theorem 1).
  AffineMatrix QB;
  if (theorem1) {
    QB = lmi::blocks({{AffineMatrix::zero(nx, nx), AffineMatrix::zero(nx, np)},
                      {AffineMatrix::zero(nu, nx), {}},
                      {{}, MatrixXd(pe.G_theta.transpose()) * out.P1},
                      {{}, out.P1}});
  }
  const AffineMatrix Phi22tP1 = MatrixXd(pe.Phi22.transpose()) * out.P1;

  for (Index i = 0; i < r; ++i) {
    const auto& Ai = data.A[static_cast<std::size_t>(i)];
    const AffineMatrix P0i =
        MatrixXd(Ai.transpose()) * out.P0 - Ct * out.R[static_cast<std::size_t>(i)].transpose();  // (41)
    const AffineMatrix CtFt = Ct * out.F[static_cast<std::size_t>(i)].transpose();
    // Φ_iᵀP = [[P_{0,i}, −CᵀF_iᵀ], [0, Φ22ᵀP1]].
    const AffineMatrix PhiTP = lmi::blocks({{P0i, -CtFt}, {AffineMatrix::zero(np, nx), Phi22tP1}});
    // T_{1,i} = [[P_{0,i}𝒜, P_{0,i}ℬ, 0, 0], [0, 0, 0, 0]].
    const AffineMatrix T1 =
        lmi::blocks({{P0i * calA, P0i * calB, AffineMatrix::zero(nx, nx * r), AffineMatrix::zero(nx, nu * r)},
                     {AffineMatrix::zero(np, nx * r), {}, {}, {}}});
    // Q_{A,i} = [[0, 0, −CᵀF_iᵀG_θ, −CᵀF_iᵀ], [0, 0, Φ22ᵀP1G_θ, Φ22ᵀP1]] (theorem 1), 0 (theorem 2).
    AffineMatrix QA;
    if (theorem1) {
      QA = lmi::blocks({{AffineMatrix::zero(nx, nx), AffineMatrix::zero(nx, nu), -CtFt * pe.G_theta, -CtFt},
                        {AffineMatrix::zero(np, nx), {}, Phi22tP1 * pe.G_theta, Phi22tP1}});
    }
    const AffineMatrix zero_block;  // sized by its row and column
    AffineMatrix M = lmi::symmetric_blocks({
        {Qe - P, QA.empty() ? AffineMatrix::zero(n1, nut) : QA, PhiTP, AffineMatrix::zero(n1, n1), T1},
        {{}, T22, AffineMatrix::zero(nut, n1), QB.empty() ? AffineMatrix::zero(nut, n1) : QB, zero_block},
        {{}, {}, -P, AffineMatrix::zero(n1, n1), zero_block},
        {{}, {}, {}, -P, T4},
        {{}, {}, {}, {}, Lambda},
    });
    negative("M" + std::to_string(i + 1) + " < 0", M);
    out.vertex_lmis.push_back(std::move(M));
  }

  switch (options.objective) {
    case TakagiSugenoObjective::minimize_beta: pb.minimize(*out.beta); break;
    case TakagiSugenoObjective::maximize_margin: pb.minimize(-*out.t); break;
    case TakagiSugenoObjective::feasibility: pb.minimize(lmi::trace(out.P0)); break;
  }
  out.data = std::move(data);
  return out;
}

/// The reading of the parameter error used when `TakagiSugenoLmiOptions::error_model` is empty.
[[nodiscard]] constexpr ParameterErrorModel default_error_model(TakagiSugenoTheorem theorem) noexcept {
  return theorem == TakagiSugenoTheorem::constant_parameters ? ParameterErrorModel::as_printed
                                                             : ParameterErrorModel::exact;
}

/// The problem data of a polytopic model for the LMIs: its vertices and C in double
/// precision, \f$Q_e\f$ and the theorem's choices from `options`.
template <TakagiSugenoSystem Model>
[[nodiscard]] TakagiSugenoLmiData takagi_sugeno_lmi_data(const Model& model,
                                                         const TakagiSugenoLmiOptions& options = {}) {
  constexpr std::string_view who = "takagi_sugeno_lmi_data";
  TakagiSugenoLmiData data;
  const Sizes s = model.sizes();
  if (options.Q_x.size() > 0) {
    require_shape(options.Q_x, s.nx, s.nx, who, "options.Q_x");
    require_positive_semidefinite(options.Q_x, who, "options.Q_x");
  }
  if (options.Q_theta.size() > 0) {
    require_shape(options.Q_theta, s.np, s.np, who, "options.Q_theta");
    require_positive_semidefinite(options.Q_theta, who, "options.Q_theta");
  }
  if (options.theorem == TakagiSugenoTheorem::time_varying_parameters) {
    require_finite_shape(options.K_theta, s.np, s.np, who, "options.K_theta");
  }
  for (Index i = 0; i < model.vertex_count(); ++i) {
    data.A.push_back(model.A(i).template cast<double>());
    data.B.push_back(model.B(i).template cast<double>());
  }
  data.C = model.C().template cast<double>();
  data.Q_x = options.Q_x.size() > 0 ? options.Q_x : Eigen::MatrixXd::Identity(s.nx, s.nx);
  data.Q_theta = options.Q_theta.size() > 0 ? options.Q_theta : Eigen::MatrixXd::Identity(s.np, s.np);
  data.theorem = options.theorem;
  data.error_model = options.error_model.value_or(default_error_model(options.theorem));
  data.K_theta = options.K_theta;
  return data;
}

/// Outcome of a synthesis.
enum class SynthesisStatus {
  feasible,  ///< the returned point was verified: every \f$M_i \prec 0\f$, \f$P_0, P_1, \lambda, \Gamma \succ 0\f$
  /// DSDP reports the LMIs infeasible (DSDP_INFEASIBLE, r > 0), or the largest margin is ≤ 0.
  /// This is DSDP's claim, not re-checked: on badly conditioned problems it can be
  /// wrong (corollary 1 on the §6 plant's own sectors, β* ≈ 4.6e7, is reported
  /// infeasible; the `maximize_margin` objective solves that problem).
  infeasible,
  not_verified,   ///< DSDP did not prove infeasibility, but its point fails the independent check
  solver_failed,  ///< a DSDP call failed
};

[[nodiscard]] constexpr std::string_view to_string(SynthesisStatus s) noexcept {
  switch (s) {
    case SynthesisStatus::feasible: return "feasible";
    case SynthesisStatus::infeasible: return "infeasible";
    case SynthesisStatus::not_verified: return "not verified";
    case SynthesisStatus::solver_failed: return "solver failed";
  }
  return "unknown";
}

/// Result of `synthesize_takagi_sugeno_gains`: gains only when the point was verified.
template <StateSpace D>
struct TakagiSugenoSynthesis {
  SynthesisStatus status = SynthesisStatus::solver_failed;
  std::optional<TakagiSugenoGains<D>>
      gains;  ///< \f$L_i = P_0^{-1}R_i\f$, \f$K_{y,i} = P_1^{-1}F_i\f$ (31), and \f$K_\theta\f$
  TakagiSugenoCertificate certificate;  ///< the point DSDP returned (for diagnosis, also when not verified)
  TakagiSugenoCertificateCheck check;   ///< the independent eigenvalue check of that point
  double beta = std::numeric_limits<double>::quiet_NaN();    ///< corollary 1: the minimised β
  double margin = std::numeric_limits<double>::quiet_NaN();  ///< the margin t of `maximize_margin`
  lmi::SdpSolution solver;                                   ///< what DSDP said (status, r, iterations, time)
  std::string message;                                       ///< one line on the outcome

  [[nodiscard]] bool feasible() const noexcept { return status == SynthesisStatus::feasible; }
};

/// Designs the gains of `TakagiSugenoObserver` for `model` by theorem 2 (or theorem 1
/// with \f$K_\theta\f$), solving the LMIs with DSDP and verifying the solution independently.
///
/// Bad options throw `ConfigurationError`; an infeasible, unverified or failed
/// solve returns its status with no gains.
template <TakagiSugenoSystem Model>
[[nodiscard]] TakagiSugenoSynthesis<typename Model::Dims> synthesize_takagi_sugeno_gains(
    const Model& model, const TakagiSugenoLmiOptions& options = {}) {
  using Dims = typename Model::Dims;
  using Scalar = typename Dims::Scalar;
  const TakagiSugenoLmiProblem lmis = build_takagi_sugeno_lmis(takagi_sugeno_lmi_data(model, options), options);
  TakagiSugenoSynthesis<Dims> result;
  result.solver = lmi::solve_with_dsdp(lmis.problem, options.solver);
  std::ostringstream message;
  message << "DSDP: " << lmi::to_string(result.solver.status) << " (" << result.solver.stop_reason << ", "
          << result.solver.iterations << " iterations, r = " << result.solver.infeasibility << ")";
  if (result.solver.status == lmi::SdpStatus::error) {
    result.status = SynthesisStatus::solver_failed;
    result.message = message.str() + ": " + result.solver.message;
    return result;
  }
  const Eigen::VectorXd& y = result.solver.y;
  result.certificate = lmis.certificate(y);
  result.check = check_takagi_sugeno_certificate(lmis.data, result.certificate);
  if (lmis.beta) result.beta = lmis.beta->value(y)(0, 0);
  if (lmis.t) result.margin = lmis.t->value(y)(0, 0);
  message << "; largest eigenvalue of the vertex LMIs " << result.check.max_vertex_eigenvalue;

  if (!result.check.holds()) {
    const bool proved_infeasible = result.solver.status == lmi::SdpStatus::infeasible ||
                                   (lmis.t && result.solver.status == lmi::SdpStatus::feasible && !(result.margin > 0));
    result.status = proved_infeasible ? SynthesisStatus::infeasible : SynthesisStatus::not_verified;
    result.message = message.str();
    return result;
  }

  // A verified certificate proves feasibility whatever DSDP's own classification.
  const Eigen::LLT<Eigen::MatrixXd> p0(result.certificate.P0), p1(result.certificate.P1);
  TakagiSugenoGains<Dims> gains;
  for (Index i = 0; i < model.vertex_count(); ++i) {
    const auto k = static_cast<std::size_t>(i);
    gains.L.push_back(p0.solve(result.certificate.R[k]).template cast<Scalar>());
    gains.K.push_back(p1.solve(result.certificate.F[k]).template cast<Scalar>());
  }
  if (options.theorem == TakagiSugenoTheorem::time_varying_parameters)
    gains.K_theta = options.K_theta.template cast<Scalar>();
  result.gains = std::move(gains);
  result.status = SynthesisStatus::feasible;
  result.message = message.str();
  return result;
}

}  // namespace adaptobs
