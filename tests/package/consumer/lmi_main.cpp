// A project that uses the installed LMI component through find_package(adaptobs COMPONENTS lmi).
#include <adaptobs/design/lmi/dsdp.hpp>
#include <adaptobs/design/lmi/lmi_problem.hpp>

#include <cstdio>

int main() {
  // Lyapunov: find P ⪰ I with AᵀPA − P ⪯ −10⁻³ I for a Schur-stable A, minimising tr P.
  Eigen::MatrixXd a(2, 2);
  a << 0.9, 0.5, -0.2, 0.7;
  adaptobs::lmi::LmiProblem problem;
  const auto p = problem.symmetric("P", 2);
  problem.require_positive_definite("P >= I", p - Eigen::MatrixXd::Identity(2, 2));
  problem.require_negative_definite("A'PA - P < 0", Eigen::MatrixXd(a.transpose()) * p * a - p, 1e-3);
  problem.minimize(adaptobs::lmi::trace(p));
  const auto solution = adaptobs::lmi::solve_with_dsdp(problem);
  if (solution.status != adaptobs::lmi::SdpStatus::feasible || !(problem.largest_eigenvalue(solution.y) < 0)) return 1;
  std::puts("adaptobs lmi consumer ok");
  return 0;
}
