#pragma once
/// \file
/// The vertex LMIs of theorems 1 and 2 of Srinivasarengan et al. (2018)
/// (eq. (29)–(30), (55), (71)), assembled numerically from a candidate solution
/// \f$(P_0, P_1, R_i, F_i, \lambda_m, \Gamma^j)\f$, and the check that the solution
/// satisfies them. Eigen only: this is the independent verification of what an
/// SDP solver returns (see `design/lmi/takagi_sugeno_synthesis.hpp`), and it
/// also checks gains designed elsewhere.
///
/// **Error model.** With \f$e_x = x - \hat x\f$, \f$e_\Theta = \Theta - \hat\Theta\f$,
/// \f$e_a = (e_x, e_\Theta)\f$ and the perturbation \f$\tilde u = (x, u, \Theta, \Delta\Theta)\f$
/// (theorem 1) or \f$\tilde u = (x, u)\f$ (theorem 2), the errors obey (34)
/// \f$e_{a,k+1} = \sum_i\hat h_i(\Phi_ie_{a,k} + \Psi_k\tilde u_k)\f$ with
/// \f[ \Phi_i = \begin{bmatrix} A_i - L_iC & 0 \\ -K_{y,i}C & \Phi_{22}\end{bmatrix},\qquad
///     \Psi_k = \begin{bmatrix} \Delta A_k & \Delta B_k & 0 & 0 \\ 0 & 0 & G_\theta & I\end{bmatrix}, \f]
/// \f$\Delta A_k = \sum_i(h_i - \hat h_i)A_i = \mathcal{A}\Sigma_{A,k}E_A\f$ (23)–(24), likewise \f$\Delta B_k\f$.
/// The blocks \f$\Phi_{22}, G_\theta\f$ of the parameter error are where the printed
/// derivation and the printed observers disagree (`ParameterErrorModel`):
///
/// | | as printed | exact for the observer as printed |
/// |---|---|---|
/// | theorem 2, observer (65) | \f$\Phi_{22} = 0\f$ (66) | \f$\Phi_{22} = I\f$ |
/// | theorem 1, observer (21) | \f$\Phi_{22} = -K_\theta\f$, \f$G_\theta = I + K_\theta\f$ (32)–(33) | \f$\Phi_{22} = I - K_\theta\f$, \f$G_\theta = K_\theta\f$ |
///
/// For observer (65), \f$e_{\Theta,k+1} = e_{\Theta,k} - \sum_i\hat h_iK_{y,i}Ce_{x,k}\f$: the exact
/// \f$\Phi_{22} = I\f$ makes theorem 2 infeasible for every \f$Q_e\f$ (the principal submatrix on
/// the \f$e_\Theta\f$ rows of blocks 1 and 3 is \f$[[Q_\theta - P_1, P_1], [P_1, -P_1]]\f$, whose Schur
/// complement is \f$Q_\theta \succ 0\f$). The printed \f$\Phi_{22} = 0\f$ is feasible; it certifies
/// the state-error part, and \f$K_{y,i}\f$ must then be imposed (Remark 6): the
/// LMI alone is at least as feasible with \f$K_{y,i} = 0\f$.
///
/// **The LMI of vertex i** (re-derived from the proof: Schur complement (39) of
/// the bounded-real inequality (38) with \f$V = e_a^TPe_a\f$, \f$P = \mathrm{diag}(P_0, P_1)\f$,
/// \f$R_i = P_0L_i\f$, \f$F_i = P_1K_{y,i}\f$ (40), the four uses of Lemma 2 (49)–(51) and the
/// Schur complements (54)), with the blocks of sizes
/// \f$n_x + n_\theta \mid n_{\tilde u} \mid n_x + n_\theta \mid n_x + n_\theta \mid 2r(n_x + n_u)\f$:
/// \f[ M_i = \begin{bmatrix}
///   Q_e - P & Q_{A,i} & \Phi_i^TP & 0 & T_{1,i}
///   \\ * & T_{22} & 0 & Q_B & 0
///   \\ * & * & -P & 0 & 0
///   \\ * & * & * & -P & T_4
///   \\ * & * & * & * & \Lambda \end{bmatrix} \prec 0, \f]
/// \f$P_{0,i} = A_i^TP_0 - C^TR_i^T\f$ (41),
/// \f$\Phi_i^TP = \begin{bmatrix} P_{0,i} & -C^TF_i^T \\ 0 & \Phi_{22}^TP_1\end{bmatrix}\f$,
/// \f$Q_{A,i} = \begin{bmatrix} 0 & 0 & -C^TF_i^TG_\theta & -C^TF_i^T \\ 0 & 0 & \Phi_{22}^TP_1G_\theta & \Phi_{22}^TP_1\end{bmatrix}\f$,
/// \f$Q_B = \begin{bmatrix} 0 & 0 \\ 0 & 0 \\ 0 & G_\theta^TP_1 \\ 0 & P_1\end{bmatrix}\f$ (30), (43),
/// \f$T_{22} = \mathrm{diag}(-\Gamma^x + r(\lambda_1 + \lambda_2)I, -\Gamma^u + r(\lambda_3 + \lambda_4)I, -\Gamma^\theta, -\Gamma^{\Delta\theta})\f$
/// (\f$E_A^TE_A = rI\f$),
/// \f$T_{1,i} = \begin{bmatrix} P_{0,i}\mathcal{A} & P_{0,i}\mathcal{B} & 0 & 0 \\ 0 & 0 & 0 & 0\end{bmatrix}\f$,
/// \f$T_4 = \begin{bmatrix} 0 & 0 & P_0\mathcal{A} & P_0\mathcal{B} \\ 0 & 0 & 0 & 0\end{bmatrix}\f$ (the printed
/// \f$T_{\mathcal{AB},i}\f$ of (55), whose rows belong to blocks 1 and 4),
/// \f$\Lambda = \mathrm{diag}(-\lambda_1I_{n_xr}, -\lambda_3I_{n_ur}, -\lambda_2I_{n_xr}, -\lambda_4I_{n_ur})\f$.
/// Theorem 2 (71) drops the Θ and ΔΘ columns (\f$Q_{A,i} = 0\f$, \f$Q_B = 0\f$, no
/// \f$\Gamma^\theta, \Gamma^{\Delta\theta}\f$). \f$Q_e = \mathrm{diag}(Q_x, Q_\theta)\f$ replaces the theorems'
/// \f$I\f$ as Remark 4 allows (§6 uses \f$Q_x = 10^{-3}I\f$, \f$Q_\theta = 0.1I\f$). With (28)/(69)–(70):
/// \f$P_0, P_1 \succ 0\f$, \f$\lambda_m > 0\f$, \f$\Gamma^j \succ 0\f$; the gains are \f$L_i = P_0^{-1}R_i\f$,
/// \f$K_{y,i} = P_1^{-1}F_i\f$ (31). Corollary 1 minimises β with \f$\beta I \succeq \Gamma^j\f$ (56)–(57).
///
/// Readings of damaged print: (1,1) is "−P + I" (= \f$Q_e - P\f$ with \f$Q_e = I\f$); \f$Q_B\f$ has
/// four block rows (x, u, Θ, ΔΘ), not five; "\f$T_{22}^{11}\f$" twice in theorem 2 means
/// \f$T_{22}^{11}\f$ and \f$T_{22}^{22}\f$; "\f$\Phi_i^IP\f$" in (71) is \f$\Phi_i^TP\f$; \f$\mathcal{B}\f$ is
/// \f$n_x \times n_ur\f$; vertices run over \f$i = 1, \dots, 2^{n_z+n_\theta}\f$.

#include <adaptobs/core/symmetric_eigenvalues.hpp>
#include <adaptobs/core/validation.hpp>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string_view>
#include <vector>

namespace adaptobs {

/// Which observer the LMIs certify.
enum class TakagiSugenoTheorem {
  constant_parameters,      ///< theorem 2, observer (65): \f$\tilde u = (x, u)\f$
  time_varying_parameters,  ///< theorem 1, observer (21) with \f$K_\theta\f$: \f$\tilde u = (x, u, \Theta, \Delta\Theta)\f$
};

/// Which recursion of the parameter error \f$e_\Theta\f$ the LMIs are written for (see the file comment).
enum class ParameterErrorModel {
  as_printed,  ///< eq. (66) / (32)–(33): \f$\Phi_{22} = 0\f$ / \f$-K_\theta\f$, \f$G_\theta = I + K_\theta\f$
  exact,  ///< the recursion of observer (65) / (21): \f$\Phi_{22} = I\f$ / \f$I - K_\theta\f$, \f$G_\theta = K_\theta\f$
};

/// Problem data of the LMIs (double precision, sizes at run time).
struct TakagiSugenoLmiData {
  std::vector<Eigen::MatrixXd> A;  ///< \f$A_i\f$, \f$n_x\times n_x\f$
  std::vector<Eigen::MatrixXd> B;  ///< \f$B_i\f$, \f$n_x\times n_u\f$
  Eigen::MatrixXd C;               ///< \f$n_y\times n_x\f$
  Eigen::MatrixXd Q_x;             ///< \f$n_x\times n_x\f$, \f$Q_e = \mathrm{diag}(Q_x, Q_\theta)\f$ (Remark 4)
  Eigen::MatrixXd Q_theta;         ///< \f$n_\theta\times n_\theta\f$
  TakagiSugenoTheorem theorem = TakagiSugenoTheorem::constant_parameters;
  ParameterErrorModel error_model = ParameterErrorModel::as_printed;
  Eigen::MatrixXd K_theta;  ///< \f$K_\theta\f$, theorem 1 only

  [[nodiscard]] Index vertex_count() const noexcept { return static_cast<Index>(A.size()); }
  [[nodiscard]] Index nx() const noexcept { return C.cols(); }
  [[nodiscard]] Index nu() const noexcept { return B.empty() ? 0 : B.front().cols(); }
  [[nodiscard]] Index ny() const noexcept { return C.rows(); }
  [[nodiscard]] Index np() const noexcept { return Q_theta.rows(); }
  /// Size of \f$\tilde u\f$: \f$n_x + n_u\f$ (theorem 2) or \f$n_x + n_u + 2n_\theta\f$ (theorem 1).
  [[nodiscard]] Index perturbation_size() const noexcept {
    return nx() + nu() + (theorem == TakagiSugenoTheorem::time_varying_parameters ? 2 * np() : 0);
  }
  /// Size of each \f$M_i\f$: \f$3(n_x + n_\theta) + n_{\tilde u} + 2r(n_x + n_u)\f$.
  [[nodiscard]] Index vertex_lmi_size() const noexcept {
    return 3 * (nx() + np()) + perturbation_size() + 2 * vertex_count() * (nx() + nu());
  }
  /// \f$\mathcal{A} = [A_1 \cdots A_r]\f$ and \f$\mathcal{B} = [B_1 \cdots B_r]\f$ (24)–(25).
  [[nodiscard]] Eigen::MatrixXd stacked_A() const {
    Eigen::MatrixXd s(nx(), nx() * vertex_count());
    for (Index i = 0; i < vertex_count(); ++i) s.middleCols(i * nx(), nx()) = A[static_cast<std::size_t>(i)];
    return s;
  }
  [[nodiscard]] Eigen::MatrixXd stacked_B() const {
    Eigen::MatrixXd s(nx(), nu() * vertex_count());
    for (Index i = 0; i < vertex_count(); ++i) s.middleCols(i * nu(), nu()) = B[static_cast<std::size_t>(i)];
    return s;
  }
};

/// \f$\Phi_{22}\f$ and \f$G_\theta\f$ of the error model (33) / (66) (see the table in the file comment).
struct ParameterErrorBlocks {
  Eigen::MatrixXd Phi22;
  Eigen::MatrixXd G_theta;  ///< theorem 1 only (empty for theorem 2)
};

[[nodiscard]] inline ParameterErrorBlocks parameter_error_blocks(const TakagiSugenoLmiData& data) {
  const Index np = data.np();
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(np, np);
  const bool exact = data.error_model == ParameterErrorModel::exact;
  if (data.theorem == TakagiSugenoTheorem::constant_parameters) {
    return {exact ? I : Eigen::MatrixXd::Zero(np, np), Eigen::MatrixXd()};
  }
  if (exact) return {I - data.K_theta, data.K_theta};
  return {-data.K_theta, I + data.K_theta};
}

/// Decision variables of theorems 1–2 at one point (a candidate solution).
struct TakagiSugenoCertificate {
  Eigen::MatrixXd P0;              ///< \f$n_x\times n_x\f$
  Eigen::MatrixXd P1;              ///< \f$n_\theta\times n_\theta\f$
  std::vector<Eigen::MatrixXd> R;  ///< \f$R_i = P_0L_i\f$, \f$n_x\times n_y\f$
  std::vector<Eigen::MatrixXd> F;  ///< \f$F_i = P_1K_{y,i}\f$, \f$n_\theta\times n_y\f$
  std::array<double, 4> lambda{};  ///< \f$\lambda_1, \dots, \lambda_4\f$
  Eigen::MatrixXd Gamma_x;         ///< \f$\Gamma_2^x\f$
  Eigen::MatrixXd Gamma_u;         ///< \f$\Gamma_2^u\f$
  Eigen::MatrixXd Gamma_theta;     ///< \f$\Gamma_2^\theta\f$ (theorem 1)
  Eigen::MatrixXd Gamma_dtheta;    ///< \f$\Gamma_2^{\Delta\theta}\f$ (theorem 1)
};

namespace detail {
inline void validate_lmi_data(const TakagiSugenoLmiData& data, std::string_view who) {
  const Index r = data.vertex_count();
  require(r > 0, who, "data.A", "must hold at least one vertex");
  require(data.B.size() == data.A.size(), who, "data.B", "must hold one matrix per vertex of data.A");
  // n_x is C's column count: C is checked against A first, so that a C of the
  // wrong width is named, not every A.
  require_square(data.A.front(), who, "data.A");
  require_finite_shape(data.C, data.C.rows(), data.A.front().rows(), who, "data.C");
  const Index nx = data.nx(), nu = data.nu();
  for (std::size_t i = 0; i < data.A.size(); ++i) {
    require_finite_shape(data.A[i], nx, nx, who, "data.A");
    require_finite_shape(data.B[i], nx, nu, who, "data.B");
  }
  require_shape(data.Q_x, nx, nx, who, "data.Q_x");
  require_positive_semidefinite(data.Q_x, who, "data.Q_x");
  require_shape(data.Q_theta, data.Q_theta.rows(), data.Q_theta.rows(), who, "data.Q_theta");
  require_positive_semidefinite(data.Q_theta, who, "data.Q_theta");
  if (data.theorem == TakagiSugenoTheorem::time_varying_parameters) {
    require_finite_shape(data.K_theta, data.np(), data.np(), who, "data.K_theta");
  }
}

/// Largest eigenvalue of the symmetric part of m; +∞ when m holds a NaN or Inf.
[[nodiscard]] inline double largest_symmetric_eigenvalue(const Eigen::MatrixXd& m) {
  if (m.size() == 0) return -std::numeric_limits<double>::infinity();
  if (!m.allFinite()) return std::numeric_limits<double>::infinity();
  const Eigen::MatrixXd s = 0.5 * (m + m.transpose());
  return symmetric_eigenvalues(s).maxCoeff();
}
/// Smallest eigenvalue of a decision matrix of the theorems (P0, P1, a Γ), which
/// they require symmetric: −∞ when m holds a NaN or Inf, or is not symmetric
/// (`is_symmetric`). A non-symmetric candidate proves nothing, whatever its
/// symmetric part: the Lyapunov function \f$e^TP_0e\f$ and the gains
/// \f$L_i = P_0^{-1}R_i\f$ are derived for a symmetric \f$P_0\f$.
[[nodiscard]] inline double smallest_eigenvalue_if_symmetric(const Eigen::MatrixXd& m) {
  if (m.size() == 0) return std::numeric_limits<double>::infinity();
  if (!is_symmetric(m)) return -std::numeric_limits<double>::infinity();  // non-finite too
  return symmetric_eigenvalues(m).minCoeff();
}

/// The candidate's blocks have the sizes the data give them.
inline void validate_certificate(const TakagiSugenoLmiData& data, const TakagiSugenoCertificate& s,
                                 std::string_view who) {
  const Index r = data.vertex_count(), nx = data.nx(), nu = data.nu(), ny = data.ny(), np = data.np();
  require_shape(s.P0, nx, nx, who, "certificate.P0");
  require_shape(s.P1, np, np, who, "certificate.P1");
  require(static_cast<Index>(s.R.size()) == r, who, "certificate.R", "must hold one matrix per vertex");
  require(static_cast<Index>(s.F.size()) == r, who, "certificate.F", "must hold one matrix per vertex");
  for (const auto& m : s.R) require_shape(m, nx, ny, who, "certificate.R");
  for (const auto& m : s.F) require_shape(m, np, ny, who, "certificate.F");
  require_shape(s.Gamma_x, nx, nx, who, "certificate.Gamma_x");
  require_shape(s.Gamma_u, nu, nu, who, "certificate.Gamma_u");
  if (data.theorem == TakagiSugenoTheorem::time_varying_parameters) {
    require_shape(s.Gamma_theta, np, np, who, "certificate.Gamma_theta");
    require_shape(s.Gamma_dtheta, np, np, who, "certificate.Gamma_dtheta");
  }
}

}  // namespace detail

/// \f$M_i\f$ of (29) / (71) at a candidate solution, vertex i (0-based), assembled block by block.
[[nodiscard]] inline Eigen::MatrixXd takagi_sugeno_vertex_lmi(const TakagiSugenoLmiData& data,
                                                              const TakagiSugenoCertificate& s, Index i) {
  constexpr std::string_view who = "takagi_sugeno_vertex_lmi";
  detail::validate_lmi_data(data, who);
  detail::validate_certificate(data, s, who);
  require(i >= 0 && i < data.vertex_count(), who, "i", "must be a vertex index in [0, data.A.size())");

  const Index r = data.vertex_count(), nx = data.nx(), nu = data.nu(), np = data.np();
  const Index n1 = nx + np, nut = data.perturbation_size(), n5 = 2 * r * (nx + nu);
  const bool theorem1 = data.theorem == TakagiSugenoTheorem::time_varying_parameters;
  const ParameterErrorBlocks pe = parameter_error_blocks(data);
  const Eigen::MatrixXd calA = data.stacked_A(), calB = data.stacked_B();
  const auto& Ai = data.A[static_cast<std::size_t>(i)];
  const auto& Ri = s.R[static_cast<std::size_t>(i)];
  const auto& Fi = s.F[static_cast<std::size_t>(i)];

  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(n1, n1);
  P.topLeftCorner(nx, nx) = s.P0;
  P.bottomRightCorner(np, np) = s.P1;
  Eigen::MatrixXd Qe = Eigen::MatrixXd::Zero(n1, n1);
  Qe.topLeftCorner(nx, nx) = data.Q_x;
  Qe.bottomRightCorner(np, np) = data.Q_theta;
  const Eigen::MatrixXd P0i = Ai.transpose() * s.P0 - data.C.transpose() * Ri.transpose();  // (41)
  const Eigen::MatrixXd CtFt = data.C.transpose() * Fi.transpose();                         // n_x × n_θ

  // Offsets of the five block rows/columns.
  const Index o1 = 0, o2 = n1, o3 = n1 + nut, o4 = 2 * n1 + nut, o5 = 3 * n1 + nut;
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(o5 + n5, o5 + n5);
  // (1,1) Q_e − P
  M.block(o1, o1, n1, n1) = Qe - P;
  // (1,2) Q_{A,i} (theorem 1)
  if (theorem1) {
    M.block(o1, o2 + nx + nu, nx, np) = -CtFt * pe.G_theta;
    M.block(o1, o2 + nx + nu + np, nx, np) = -CtFt;
    M.block(o1 + nx, o2 + nx + nu, np, np) = pe.Phi22.transpose() * s.P1 * pe.G_theta;
    M.block(o1 + nx, o2 + nx + nu + np, np, np) = pe.Phi22.transpose() * s.P1;
  }
  // (1,3) Φ_iᵀP = [[P_{0,i}, −CᵀF_iᵀ], [0, Φ22ᵀP1]]
  M.block(o1, o3, nx, nx) = P0i;
  M.block(o1, o3 + nx, nx, np) = -CtFt;
  M.block(o1 + nx, o3 + nx, np, np) = pe.Phi22.transpose() * s.P1;
  // (1,5) T_{1,i} = [[P_{0,i}𝒜, P_{0,i}ℬ, 0, 0], [0, 0, 0, 0]]
  M.block(o1, o5, nx, nx * r) = P0i * calA;
  M.block(o1, o5 + nx * r, nx, nu * r) = P0i * calB;
  // (2,2) T22
  M.block(o2, o2, nx, nx) = -s.Gamma_x + double(r) * (s.lambda[0] + s.lambda[1]) * Eigen::MatrixXd::Identity(nx, nx);
  M.block(o2 + nx, o2 + nx, nu, nu) =
      -s.Gamma_u + double(r) * (s.lambda[2] + s.lambda[3]) * Eigen::MatrixXd::Identity(nu, nu);
  if (theorem1) {
    M.block(o2 + nx + nu, o2 + nx + nu, np, np) = -s.Gamma_theta;
    M.block(o2 + nx + nu + np, o2 + nx + nu + np, np, np) = -s.Gamma_dtheta;
    // (2,4) Q_B = [[0, 0], [0, 0], [0, G_θᵀP1], [0, P1]]
    M.block(o2 + nx + nu, o4 + nx, np, np) = pe.G_theta.transpose() * s.P1;
    M.block(o2 + nx + nu + np, o4 + nx, np, np) = s.P1;
  }
  // (3,3), (4,4) −P
  M.block(o3, o3, n1, n1) = -P;
  M.block(o4, o4, n1, n1) = -P;
  // (4,5) T4 = [[0, 0, P0𝒜, P0ℬ], [0, 0, 0, 0]]
  M.block(o4, o5 + (nx + nu) * r, nx, nx * r) = s.P0 * calA;
  M.block(o4, o5 + (2 * nx + nu) * r, nx, nu * r) = s.P0 * calB;
  // (5,5) Λ = diag(−λ1 I, −λ3 I, −λ2 I, −λ4 I)
  M.block(o5, o5, n5, n5).diagonal() << Eigen::VectorXd::Constant(nx * r, -s.lambda[0]),
      Eigen::VectorXd::Constant(nu * r, -s.lambda[2]), Eigen::VectorXd::Constant(nx * r, -s.lambda[1]),
      Eigen::VectorXd::Constant(nu * r, -s.lambda[3]);
  // Lower triangle from the upper one.
  M.triangularView<Eigen::StrictlyLower>() = M.transpose().eval();
  return M;
}

/// Outcome of checking a candidate solution against theorem 1 or 2.
struct TakagiSugenoCertificateCheck {
  double max_vertex_eigenvalue = std::numeric_limits<double>::infinity();  ///< \f$\max_i\lambda_{\max}(M_i)\f$
  double min_eigenvalue_P0 =
      -std::numeric_limits<double>::infinity();  ///< \f$\lambda_{\min}(P_0)\f$; −∞ unless symmetric
  double min_eigenvalue_P1 =
      -std::numeric_limits<double>::infinity();  ///< \f$\lambda_{\min}(P_1)\f$; −∞ unless symmetric
  double min_lambda = -std::numeric_limits<double>::infinity();
  double min_eigenvalue_Gamma =
      -std::numeric_limits<double>::infinity();  ///< smallest over the \f$\Gamma^j\f$; −∞ unless each is symmetric
  /// Every \f$M_i \prec 0\f$ and \f$P_0, P_1, \lambda_m, \Gamma^j \succ 0\f$ (strictly).
  [[nodiscard]] bool holds() const noexcept {
    return max_vertex_eigenvalue < 0 && min_eigenvalue_P0 > 0 && min_eigenvalue_P1 > 0 && min_lambda > 0 &&
           min_eigenvalue_Gamma > 0;
  }
};

/// Rebuilds every \f$M_i\f$ from the candidate and returns its largest eigenvalue, with the
/// smallest eigenvalues of \f$P_0, P_1, \Gamma^j\f$ and the smallest \f$\lambda_m\f$ (28), (69)–(71).
[[nodiscard]] inline TakagiSugenoCertificateCheck check_takagi_sugeno_certificate(const TakagiSugenoLmiData& data,
                                                                                  const TakagiSugenoCertificate& s) {
  constexpr std::string_view who = "check_takagi_sugeno_certificate";
  detail::validate_lmi_data(data, who);
  detail::validate_certificate(data, s, who);
  const Index r = data.vertex_count();
  const bool theorem1 = data.theorem == TakagiSugenoTheorem::time_varying_parameters;

  TakagiSugenoCertificateCheck check;
  check.max_vertex_eigenvalue = -std::numeric_limits<double>::infinity();
  for (Index i = 0; i < r; ++i)
    check.max_vertex_eigenvalue = std::max(check.max_vertex_eigenvalue,
                                           detail::largest_symmetric_eigenvalue(takagi_sugeno_vertex_lmi(data, s, i)));
  check.min_eigenvalue_P0 = detail::smallest_eigenvalue_if_symmetric(s.P0);
  check.min_eigenvalue_P1 = detail::smallest_eigenvalue_if_symmetric(s.P1);
  check.min_lambda = std::numeric_limits<double>::infinity();
  for (const double l : s.lambda)
    check.min_lambda = std::isfinite(l) ? std::min(check.min_lambda, l) : -std::numeric_limits<double>::infinity();
  check.min_eigenvalue_Gamma = std::min(detail::smallest_eigenvalue_if_symmetric(s.Gamma_x),
                                        detail::smallest_eigenvalue_if_symmetric(s.Gamma_u));
  if (theorem1) {
    check.min_eigenvalue_Gamma =
        std::min({check.min_eigenvalue_Gamma, detail::smallest_eigenvalue_if_symmetric(s.Gamma_theta),
                  detail::smallest_eigenvalue_if_symmetric(s.Gamma_dtheta)});
  }
  return check;
}

}  // namespace adaptobs
