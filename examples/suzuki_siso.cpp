// SISO comparison of Dey & Bhasin (2022) §5 (figures 4–5): the Dey–Bhasin observer
// (RLS with covariance resetting, k0 = 1e4, R = 1, kmin = 1e-4) against the
// observer of Suzuki, Nakamura & Koga (1980) — the same filters with RLS and
// exponential forgetting, weighting factor √0.5 taken as the forgetting factor
// λ — on A = [1.52 1; −0.6 0], B = [0.43; −0.35], F = [1.49 1; −0.55 0],
// x₀ = x̂₀ = 0, Â₀ = [0 1; 0 0], B̂₀ = 0, u_t = sin(0.2t): a regressor that is not
// persistently exciting.
//
// What happens to the baseline: Γ⁻¹ forgets the directions the sine does not
// reach, so Γ grows by 1/λ = √2 per step (1e13 at t = 100, 1e148 at t = 1000)
// until it overflows double precision near t ≈ 2050; from then on the raw law
// produces inf and NaN. The library's observers never commit a non-finite step:
// the `SuzukiObserver` reports `nonfinite_result` from that step on and keeps its
// last estimates (column status_suzuki). To show the law itself, the columns
// *_suzuki are those of the raw recursion, fed with the same regressor and
// committed unconditionally, so the CSV holds `inf`/`nan` after the overflow.
// Before it, its estimates do not visibly drift in double precision: the
// start-up transient (x₀ = 0, the sine starting at t = 0) excites every direction.
//
// Usage: suzuki_siso [--out DIR] [--steps 3000] [--lambda 0.7071067811865476]
// Writes suzuki_siso.csv (t,u_1,y_1,x_*,xhat_*,theta_*,thetahat_*,xhat_suzuki_*,
// thetahat_suzuki_*,thetahat_norm_*,thetahat_norm_suzuki_*,xerr_norm,
// xerr_norm_suzuki,gamma_max,gamma_max_suzuki,status_suzuki,resets); row t
// holds p̂_t and x̂_t = S_t p̂_t + F^t x̂_0 (eq. (13)). Then suzuki_siso.png.

#include <adaptobs/adaptobs.hpp>
#include <adaptobs/simulation.hpp>

#include "common/example_support.hpp"
#include "models/dey_bhasin.hpp"

#include <cmath>
#include <limits>
#include <string>

namespace siso = adaptobs::examples::dey_bhasin::siso;
namespace db = adaptobs::examples::dey_bhasin;
using adaptobs::examples::print_text;
using adaptobs::examples::print_value;

namespace {

// The system, its parameter vector p, the initial estimate and the laws' settings.
void print_problem(const Eigen::Vector4d& p, const Eigen::Vector4d& phat0, double lambda) {
  print_value("A", Eigen::Matrix2d(adaptobs::companion_matrix(siso::a())));
  print_value("F", Eigen::Matrix2d(adaptobs::companion_matrix(siso::f())));
  print_value("B", siso::B().transpose());
  print_value("p", p.transpose());
  print_value("phat0", phat0.transpose());
  print_value("k0", siso::k0);
  print_value("kmin", siso::kmin);
  print_value("lambda", lambda);
}

// The step at which something first happened, or "none" (a negative step).
void print_step(const std::string& name, adaptobs::Index step) {
  if (step >= 0)
    print_value(name, double(step));
  else
    print_text(name, "none");
}

// The exponential-forgetting recursion of Suzuki et al. in plain IEEE
// arithmetic: fed the resetting observer's regressor and committed
// unconditionally, with the first steps at which its covariance and its
// estimates stop being finite.
struct RawForgettingLaw {
  adaptobs::ExponentialForgettingRls<double, 4, 1> law;
  adaptobs::Index covariance_nonfinite = -1, estimate_nonfinite = -1;
  double gamma_max = 0, last_finite_gamma = 0;  // largest |Γ| entry: now, and when last finite

  // Step t with the regressor and measurement the observer used (none at t = 0).
  template <class Observer>
  void step(adaptobs::Index t, const Observer& observer) {
    if (t > 0) {
      (void)law.propose(observer.regressor(), observer.measurement());
      law.commit();
    }
    gamma_max = law.covariance().cwiseAbs().template maxCoeff<Eigen::PropagateNaN>();
    if (covariance_nonfinite < 0 && !law.covariance().allFinite()) covariance_nonfinite = t;
    if (covariance_nonfinite < 0) last_finite_gamma = gamma_max;
    if (estimate_nonfinite < 0 && !law.parameters().allFinite()) estimate_nonfinite = t;
  }
};

// The figure; `overflow` (when not negative) is the step at which the
// forgetting law's covariance stops being finite, marked on every panel.
void write_figure(const adaptobs::SeriesTable& table, const adaptobs::examples::Arguments& args,
                  adaptobs::Index overflow) {
  const std::string marker =
      overflow >= 0 ? adaptobs::examples::time_marker(double(overflow), "forgetting overflows") : "";
  adaptobs::examples::write_outputs(table, args.out_dir(), "suzuki_siso",
                                    std::string(adaptobs::examples::log_floor_function) + marker + R"(
set multiplot layout 3,2 title 'Covariance resetting against exponential forgetting, SISO example (Dey and Bhasin 2022, section 5; no units)'
set grid
set xlabel 't (samples)'
# Autoscaled, with a margin: the start-up transient is part of the figure.
set offsets 0, 0, graph 0.05, graph 0.05
set ylabel 'estimate / true value (1: exact)'
set key bottom right
set title 'Figure 4(a): normalized estimates, Suzuki et al. (forgetting, lambda = sqrt 0.5)'
plot for [i=1:4] csv using 't':(column(sprintf('thetahat_norm_suzuki_%d', i))) with lines lw 1.5 title sprintf('theta %d', i)
set title 'Figure 4(b): normalized estimates, covariance resetting'
plot for [i=1:4] csv using 't':(column(sprintf('thetahat_norm_%d', i))) with lines lw 1.5 title sprintf('theta %d', i)
set offsets 0, 0, 0, 0
set logscale y
set format y '10^{%T}'
set ylabel '||x - xhat|| (log; 0 drawn at 10^{-16})'
set title 'Figure 5(a): 2-norm of the state estimation error (0 at t = 0, 1), Suzuki et al.'
plot csv using 't':(floored(column('xerr_norm_suzuki'), 1e-16)) with lines lw 1.5 title '||x - xhat||'
set title 'Figure 5(b): 2-norm of the state estimation error (0 at t = 0, 1), resetting'
plot csv using 't':(floored(column('xerr_norm'), 1e-16)) with lines lw 1.5 title '||x - xhat||'
set title 'Why: largest covariance entry (forgetting overflows, resetting stays in [kmin, k0])'
set ylabel 'largest |Gamma| entry (no unit, log)'
set key top left
set yrange [1e-6:1e308]
plot csv using 't':'gamma_max_suzuki' with lines lw 1.5 title 'forgetting', \
     csv using 't':'gamma_max' with lines lw 1.5 title 'resetting'
unset logscale y
set autoscale y
set format y '%g'
set ylabel 'u, y (no unit)'
set key top right opaque
set title 'Input and output (first 300 samples)'
set xrange [0:300]
plot csv using 't':'u_1' with lines title 'u', csv using 't':'y_1' with lines title 'y'
unset multiplot)");
}

}  // namespace

int main(int argc, char** argv) try {
  const adaptobs::examples::Arguments args(
      argc, argv, "suzuki_siso",
      {{"steps", "3000", "samples of the run", "", adaptobs::examples::integer_in(10, 1e7)},
       {"lambda", std::to_string(siso::lambda), "forgetting factor of the Suzuki et al. observer", "",
        adaptobs::examples::real_in(0, 1, "(]")}});
  const auto steps = static_cast<adaptobs::Index>(args.integer("steps"));
  const double lambda = args.number("lambda");

  auto resetting = siso::make_observer();
  auto suzuki = siso::make_suzuki(lambda);
  RawForgettingLaw raw{
      adaptobs::ExponentialForgettingRls<double, 4, 1>(resetting.parameters(), siso::suzuki_options(lambda))};
  auto plant = siso::make_plant();
  const Eigen::Vector4d p = resetting.parameters_of(siso::a(), siso::B());
  print_problem(p, resetting.parameters(), lambda);

  adaptobs::SeriesTable table;
  adaptobs::Index first_rejected = -1;
  double state_error = 0;
  for (adaptobs::Index t = 0; t < steps; ++t) {
    const auto& sample = plant.sample();
    if (resetting.update(sample) != adaptobs::UpdateStatus::accepted) print_value("resetting_rejected_step", double(t));
    const adaptobs::UpdateStatus status = suzuki.update(sample);
    if (status != adaptobs::UpdateStatus::accepted && first_rejected < 0) first_rejected = t;
    raw.step(t, resetting);
    const Eigen::Vector2d x_raw = resetting.state_with(raw.law.parameters());
    state_error = (plant.state() - resetting.current_state()).norm();  // x_t − x̂_t
    const Eigen::Vector2d a_raw = raw.law.parameters().head<2>() + siso::f();
    const Eigen::Vector2d b_raw = raw.law.parameters().tail<2>();

    table.begin_row()
        .add("t", double(t))
        .add("u", sample.u)
        .add("y", sample.y)
        .add("x", plant.state())
        .add("xhat", resetting.current_state())
        .add("theta", p)
        .add("thetahat", resetting.parameters())
        .add("xhat_suzuki", x_raw)
        .add("thetahat_suzuki", raw.law.parameters())
        .add("thetahat_norm", db::normalized_estimates(resetting, siso::a(), siso::B()))
        .add("thetahat_norm_suzuki", db::normalized_estimates(a_raw, b_raw, siso::a(), siso::B()))
        .add("xerr_norm", state_error)
        .add("xerr_norm_suzuki", (plant.state() - x_raw).norm())
        .add("gamma_max", resetting.law().covariance().cwiseAbs().maxCoeff())
        .add("gamma_max_suzuki", raw.gamma_max)
        .add("status_suzuki", status == adaptobs::UpdateStatus::accepted ? 1.0 : 0.0)
        .add("resets", double(resetting.law().reset_count()));
    plant.advance();
  }

  print_value("resets", double(resetting.law().reset_count()));
  print_value("thetahat_norm_final", db::normalized_estimates(resetting, siso::a(), siso::B()).transpose());
  print_value("xerr_norm_final", state_error);
  print_value("suzuki_gamma_max_last_finite", raw.last_finite_gamma);
  print_step("suzuki_covariance_nonfinite_step", raw.covariance_nonfinite);
  print_step("suzuki_estimates_nonfinite_step", raw.estimate_nonfinite);
  print_step("suzuki_observer_first_rejected_step", first_rejected);
  print_value("thetahat_norm_suzuki_observer_final",
              db::normalized_estimates(suzuki, siso::a(), siso::B()).transpose());

  write_figure(table, args, raw.covariance_nonfinite);
  return 0;
} catch (...) {
  return adaptobs::examples::failure("suzuki_siso");
}
