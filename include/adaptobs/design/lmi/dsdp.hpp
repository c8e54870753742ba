#pragma once
/// \file
/// Solves an `LmiProblem` with DSDP 5.8 (Benson & Ye's dual-scaling
/// interior-point SDP solver, Debian package `libdsdp-dev`). Part of the
/// optional `adaptobs::lmi` component, which links the DSDP library.
///
/// DSDP solves \f$\max_y b^Ty\f$ subject to \f$C_j - \sum_k y_kA_{jk} \succeq 0\f$ for every
/// block j. A constraint \f$G_0 + \sum_k y_kG_k \preceq -\varepsilon I\f$ is passed as
/// \f$C = -G_0 - \varepsilon I\f$, \f$A_k = G_k\f$, and \f$\min c^Ty\f$ as \f$b = -c\f$. Matrices go in
/// packed lower-triangular storage, row by row (entry (r, c), r ≥ c, at
/// \f$r(r+1)/2 + c\f$). What the solver returns is a claim, not a proof: callers
/// verify the point (see `synthesize_takagi_sugeno_gains`).
///
/// Facts about DSDP 5.8 this wrapper relies on:
/// - it keeps pointers to the index and value arrays until `DSDPDestroy`, so they
///   live in this function's scope until then;
/// - `DSDPGetSolutionType` is only meaningful after `DSDPComputeX`;
/// - the default bounds \f$|y_k| \le 10^7\f$ cap variables silently (a solution with a
///   variable at the bound is then reported feasible or infeasible wrongly), so
///   the bounds are set explicitly (`DsdpOptions::variable_bound`).

#include <adaptobs/core/validation.hpp>
#include <adaptobs/design/lmi/lmi_problem.hpp>

#include <dsdp5.h>

#include <Eigen/Core>

#include <chrono>
#include <cmath>
#include <deque>
#include <string>
#include <string_view>
#include <vector>

namespace adaptobs::lmi {

/// Settings of the DSDP solver.
struct DsdpOptions {
  double variable_bound = 1e12;  ///< \f$|y_k| \le\f$ bound (DSDP's own default, 1e7, is too tight for LMIs)
  double penalty = 1e10;         ///< penalty on the infeasibility variable r (DSDP default 1e8)
  double gap_tolerance = 1e-7;   ///< relative duality gap at which DSDP stops
  int max_iterations = 500;
  bool print_iterations = false;  ///< DSDP's own progress monitor on stdout
};

/// DSDP's classification of the problem it solved (after `DSDPComputeX`).
enum class SdpStatus {
  feasible,    ///< DSDP_PDFEASIBLE: primal and dual feasible and bounded
  infeasible,  ///< DSDP_INFEASIBLE: the LMIs (DSDP's dual) have no solution
  unbounded,   ///< DSDP_UNBOUNDED: the objective is unbounded over the LMIs
  unknown,     ///< DSDP_PDUNKNOWN: no conclusion (check the variable bound)
  error,       ///< a DSDP call failed; see `message`
};

[[nodiscard]] constexpr std::string_view to_string(SdpStatus s) noexcept {
  switch (s) {
    case SdpStatus::feasible: return "feasible";
    case SdpStatus::infeasible: return "infeasible";
    case SdpStatus::unbounded: return "unbounded";
    case SdpStatus::unknown: return "unknown";
    case SdpStatus::error: return "error";
  }
  return "unknown";
}

/// What DSDP returned.
struct SdpSolution {
  SdpStatus status = SdpStatus::error;
  Eigen::VectorXd y;         ///< the point (decision variables)
  double infeasibility = 0;  ///< DSDP's r ≥ 0: r > 0 at the end means the LMIs were not met
  double objective = 0;      ///< \f$c^Ty\f$ at y
  int iterations = 0;
  double seconds = 0;       ///< wall time of setup + solve
  std::string stop_reason;  ///< DSDP's termination reason
  std::string message;      ///< the failing call when status is `error`
};

namespace detail {

[[nodiscard]] inline std::string_view dsdp_stop_reason(DSDPTerminationReason r) noexcept {
  switch (r) {
    case DSDP_CONVERGED: return "converged";
    case DSDP_INFEASIBLE_START: return "infeasible start";
    case DSDP_SMALL_STEPS: return "small steps";
    case DSDP_INDEFINITE_SCHUR_MATRIX: return "indefinite Schur matrix";
    case DSDP_MAX_IT: return "maximum iterations";
    case DSDP_NUMERICAL_ERROR: return "numerical error";
    case DSDP_UPPERBOUND: return "objective upper bound";
    case DSDP_USER_TERMINATION: return "user termination";
    case CONTINUE_ITERATING: return "not stopped";
  }
  return "unknown";
}

/// Owns a DSDP solver object and the arrays it points into, and frees them in order.
class DsdpSession {
 public:
  explicit DsdpSession(int variables) { ok_ = DSDPCreate(variables, &solver_) == 0; }
  DsdpSession(const DsdpSession&) = delete;
  DsdpSession& operator=(const DsdpSession&) = delete;
  ~DsdpSession() {
    if (ok_) DSDPDestroy(solver_);  // before indices_/values_ go away
  }
  [[nodiscard]] bool created() const noexcept { return ok_; }
  [[nodiscard]] DSDP get() const noexcept { return solver_; }
  // Stable storage (deque: no reallocation) for the packed matrices DSDP points into.
  std::deque<std::vector<int>> indices;
  std::deque<std::vector<double>> values;

 private:
  DSDP solver_{};
  bool ok_ = false;
};

}  // namespace detail

/// Solves `problem` (minimise its objective subject to its LMIs) with DSDP.
/// Never throws on solver trouble: failures come back as `SdpStatus::error`.
[[nodiscard]] inline SdpSolution solve_with_dsdp(const LmiProblem& problem, const DsdpOptions& options = {}) {
  constexpr std::string_view who = "solve_with_dsdp";
  require(problem.variable_count() > 0, who, "problem", "has no decision variables");
  require(!problem.constraints().empty(), who, "problem", "has no constraints");
  require(std::isfinite(options.variable_bound) && options.variable_bound > 0, who, "options.variable_bound",
          "must be positive and finite");
  require(std::isfinite(options.penalty) && options.penalty > 0, who, "options.penalty", "must be positive and finite");
  require(std::isfinite(options.gap_tolerance) && options.gap_tolerance > 0, who, "options.gap_tolerance",
          "must be positive and finite");
  require(options.max_iterations > 0, who, "options.max_iterations", "must be positive");

  const auto start = std::chrono::steady_clock::now();
  SdpSolution result;
  const int m = static_cast<int>(problem.variable_count());
  result.y = Eigen::VectorXd::Zero(m);
  const auto finish = [&](SdpStatus status, std::string message = {}) {
    result.status = status;
    result.message = std::move(message);
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
  };

  detail::DsdpSession session(m);
  if (!session.created()) return finish(SdpStatus::error, "DSDPCreate failed");
  DSDP dsdp = session.get();
#define ADAPTOBS_DSDP_CALL(call) \
  if ((call) != 0) return finish(SdpStatus::error, #call " failed")

  const Eigen::VectorXd c = problem.objective();
  for (int k = 0; k < m; ++k) ADAPTOBS_DSDP_CALL(DSDPSetDualObjective(dsdp, k + 1, -c(k)));  // variables are 1-based

  const auto& constraints = problem.constraints();
  SDPCone cone{};
  ADAPTOBS_DSDP_CALL(DSDPCreateSDPCone(dsdp, static_cast<int>(constraints.size()), &cone));
  // Packs the symmetric part of `a` (lower triangle, row by row) and hands it to DSDP.
  const auto set_matrix = [&](int block, int variable, const Eigen::MatrixXd& a) -> int {
    const Index n = a.rows();
    std::vector<int> index;
    std::vector<double> value;
    for (Index r = 0; r < n; ++r) {
      for (Index col = 0; col <= r; ++col) {
        const double v = 0.5 * (a(r, col) + a(col, r));
        if (v != 0.0) {
          index.push_back(static_cast<int>(r * (r + 1) / 2 + col));
          value.push_back(v);
        }
      }
    }
    if (index.empty()) return 0;
    session.indices.push_back(std::move(index));
    session.values.push_back(std::move(value));
    return SDPConeSetASparseVecMat(cone, block, variable, static_cast<int>(n), 1.0, 0, session.indices.back().data(),
                                   session.values.back().data(), static_cast<int>(session.indices.back().size()));
  };
  for (int j = 0; j < static_cast<int>(constraints.size()); ++j) {
    const auto& con = constraints[static_cast<std::size_t>(j)];
    const Index n = con.G.rows();
    ADAPTOBS_DSDP_CALL(SDPConeSetBlockSize(cone, j, static_cast<int>(n)));
    ADAPTOBS_DSDP_CALL(SDPConeSetSparsity(cone, j, static_cast<int>(con.G.terms().size())));
    ADAPTOBS_DSDP_CALL(set_matrix(j, 0, -con.G.constant() - con.margin * Eigen::MatrixXd::Identity(n, n)));
    for (const auto& t : con.G.terms())
      ADAPTOBS_DSDP_CALL(set_matrix(j, static_cast<int>(t.variable) + 1, t.coefficient));
  }
  ADAPTOBS_DSDP_CALL(DSDPSetYBounds(dsdp, -options.variable_bound, options.variable_bound));
  ADAPTOBS_DSDP_CALL(DSDPSetPenaltyParameter(dsdp, options.penalty));
  ADAPTOBS_DSDP_CALL(DSDPSetGapTolerance(dsdp, options.gap_tolerance));
  ADAPTOBS_DSDP_CALL(DSDPSetMaxIts(dsdp, options.max_iterations));
  if (options.print_iterations) ADAPTOBS_DSDP_CALL(DSDPSetStandardMonitor(dsdp, 1));

  ADAPTOBS_DSDP_CALL(DSDPSetup(dsdp));
  ADAPTOBS_DSDP_CALL(DSDPSolve(dsdp));
  DSDPTerminationReason stop = CONTINUE_ITERATING;
  ADAPTOBS_DSDP_CALL(DSDPStopReason(dsdp, &stop));
  result.stop_reason = detail::dsdp_stop_reason(stop);
  ADAPTOBS_DSDP_CALL(DSDPGetY(dsdp, result.y.data(), m));
  ADAPTOBS_DSDP_CALL(DSDPGetR(dsdp, &result.infeasibility));
  ADAPTOBS_DSDP_CALL(DSDPGetIts(dsdp, &result.iterations));
  result.objective = c.dot(result.y);
  // The solution type is classified by DSDPComputeX; before it, DSDP reports a stale "feasible".
  ADAPTOBS_DSDP_CALL(DSDPComputeX(dsdp));
  DSDPSolutionType type = DSDP_PDUNKNOWN;
  ADAPTOBS_DSDP_CALL(DSDPGetSolutionType(dsdp, &type));
#undef ADAPTOBS_DSDP_CALL
  switch (type) {
    case DSDP_PDFEASIBLE: return finish(SdpStatus::feasible);
    case DSDP_INFEASIBLE: return finish(SdpStatus::infeasible);
    case DSDP_UNBOUNDED: return finish(SdpStatus::unbounded);
    case DSDP_PDUNKNOWN: break;
  }
  return finish(SdpStatus::unknown);
}

}  // namespace adaptobs::lmi
