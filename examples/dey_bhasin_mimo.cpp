// MIMO example of Dey & Bhasin (2022) §5 (Dey & Bhasin): q = 2 outputs, m = 2 inputs,
// order r = 3 (n = 6 states), every entry of A and B unknown, RLS with
// covariance resetting (k0 = 1000, R = I, kmin = 1e-4), two runs:
//   - an input that is not sufficiently rich, u = [sin 0.2t, sin 0.5t]:
//     the estimates settle at wrong but bounded values (theorem 5);
//   - a sufficiently rich one, u = [sin 0.3t + sin 1.3t, sin 0.7t + sin 2.1t]:
//     every entry of A and B is identified and the state error vanishes (theorem 6).
//
// Reading of the printed example (see examples/models/dey_bhasin.hpp): the first
// block of A is printed `4 I2`, which makes the plant unstable (pole 4.0455) so
// that the state overflows under the prescribed bounded inputs; it is read as
// `0.4 I2` (poles 0.8962, −0.2481 ± 0.5227i). B is the transpose of the printed
// 2 × 6 array. Normalized estimates are â_k/a_k and b̂_j/b_j (p's first entry
// a₁ − f₁ is 0, so p̂/p is undefined); a zero true entry would be written `nan`.
//
// Usage: dey_bhasin_mimo [--out DIR] [--steps 1000] [--drop 0] [--outage none|T0,T1]
//                        [--channel 0] [--seed 1]
// With --drop P each output sample is lost with probability P, with --outage
// none arrives for t in [T0, T1]; --channel c (1 or 2) loses only that output
// channel, as a partial update, instead of the whole sample.
// Writes dey_bhasin_mimo_nonpe.csv and dey_bhasin_mimo_pe.csv (t,u_*,y_*,y_available,x_*,
// xhat_*,theta_*,thetahat_*,thetahat_norm_*,xerr_norm,resets), where row t holds
// the paper's estimates at time t: p̂_t and x̂_t = S_t p̂_t + F^t x̂_0 (eq. (13));
// theta = p = [a − f; vec(B)]. Then dey_bhasin_mimo.png (figures 1–3).

#include <adaptobs/adaptobs.hpp>
#include <adaptobs/design/stability.hpp>
#include <adaptobs/simulation.hpp>

#include "common/example_support.hpp"
#include "models/dey_bhasin.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

namespace mimo = adaptobs::examples::dey_bhasin::mimo;
namespace db = adaptobs::examples::dey_bhasin;
using adaptobs::examples::print_text;
using adaptobs::examples::print_value;

namespace {

struct RunResult {
  adaptobs::SeriesTable table;
  double max_parameter_error = 0;
  double beta_phi = 0;           // sup ‖φ_t‖₂
  double beta_w = 0;             // sup ‖W_t‖₂
  double final_state_error = 0;  // ‖x_T − x̂_T‖ at the last sample T
};

template <class Input>
RunResult run(Input input, adaptobs::Index steps, const std::string& name, adaptobs::OutputLoss loss) {
  auto observer = mimo::make_observer();
  auto plant = mimo::make_plant(input);
  const Eigen::Matrix<double, 15, 1> p = observer.parameters_of(mimo::a(), mimo::B());
  RunResult result;
  adaptobs::Index rejected = 0;
  Eigen::Matrix<double, 15, 15> previous_gamma = observer.law().covariance();
  for (adaptobs::Index t = 0; t < steps; ++t) {
    const auto& sample = plant.sample();
    const auto present = loss.channels_at<typename decltype(observer)::Dims>(double(t), sample.y.size());
    if (observer.update(sample, present) != adaptobs::UpdateStatus::accepted) ++rejected;
    const auto& phi = observer.regressor();
    result.beta_phi = std::max(result.beta_phi, adaptobs::spectral_norm(phi));
    if (t > 0) {
      const Eigen::Matrix2d w = (Eigen::Matrix2d::Identity() + phi.transpose() * previous_gamma * phi).inverse();
      result.beta_w = std::max(result.beta_w, adaptobs::spectral_norm(w));
    }
    previous_gamma = observer.law().covariance();
    result.max_parameter_error = std::max(result.max_parameter_error, (p - observer.parameters()).norm());
    result.final_state_error = (plant.state() - observer.current_state()).norm();
    result.table.begin_row()
        .add("t", double(t))
        .add("u", sample.u)
        .add("y", sample.y)
        .add("y_available", adaptobs::channel_bits(present))
        .add("x", plant.state())
        .add("xhat", observer.current_state())
        .add("theta", p)
        .add("thetahat", observer.parameters())
        .add("thetahat_norm", db::normalized_estimates(observer, mimo::a(), mimo::B()))
        .add("xerr_norm", result.final_state_error)
        .add("resets", double(observer.law().reset_count()));
    plant.advance();
  }
  print_value("rejected_" + name, double(rejected));
  print_value("resets_" + name, double(observer.law().reset_count()));
  print_value("cholesky_reset_tests_" + name, double(observer.law().reset_tests_run()));
  print_value("thetahat_norm_final_" + name, db::normalized_estimates(observer, mimo::a(), mimo::B()).transpose());
  print_value("xerr_norm_final_" + name, result.final_state_error);
  print_value("A_hat_" + name, observer.A_hat());
  print_value("B_hat_" + name, observer.B_hat());
  return result;
}

// Gnuplot body of dey_bhasin_mimo.png, after the shading of the lost samples:
// figures 1–3 of the paper, without and with a rich input.
constexpr const char* figure_script = R"(
set multiplot layout 3,2 title 'Dey-Bhasin adaptive observer, MIMO example (Dey and Bhasin 2022, section 5; the paper gives no units)'
set grid
set xlabel 't (samples)'
set key off
# Autoscaled, with a margin: the start-up transient is part of the figure.
set offsets 0, 0, graph 0.05, graph 0.05
set title 'Figure 1(a): normalized estimates, input not sufficiently rich (15 entries of A and B)'
set ylabel 'estimate / true value (1: exact)'
plot for [i=1:15] nonpe using 't':(column(sprintf('thetahat_norm_%d', i))) with lines
set title 'Figure 1(b): normalized estimates, sufficiently rich input (15 entries of A and B)'
plot for [i=1:15] pe using 't':(column(sprintf('thetahat_norm_%d', i))) with lines
set offsets 0, 0, 0, 0
set logscale y
set format y '10^{%T}'
set key top right
set ylabel '||x - xhat|| (no unit, log)'
set title 'Figure 2(a): 2-norm of the state estimation error, input not sufficiently rich'
plot nonpe using 't':(floored(column('xerr_norm'), 1e-17)) with lines lw 1.5 title '||x - xhat|| (values below 10^{-17} drawn at 10^{-17})'
set title 'Figure 2(b): 2-norm of the state estimation error, sufficiently rich input'
plot pe using 't':(floored(column('xerr_norm'), 1e-17)) with lines lw 1.5 title '||x - xhat|| (values below 10^{-17} drawn at 10^{-17})'
unset logscale y
set format y '%g'
set ylabel 'input (no unit)'
set key opaque
set xrange [0:200]
set title 'Figure 3(a): input not sufficiently rich (first 200 samples)'
plot nonpe using 't':'u_1' with lines title 'u^1', nonpe using 't':'u_2' with lines title 'u^2'
set title 'Figure 3(b): sufficiently rich input (first 200 samples)'
plot pe using 't':'u_1' with lines title 'u^1', pe using 't':'u_2' with lines title 'u^2'
unset multiplot)";

}  // namespace

int main(int argc, char** argv) try {
  auto channel = adaptobs::examples::integer_in(0, mimo::outputs);
  channel.range = "0 (the whole sample) or an output channel, 1 or 2";
  const adaptobs::examples::Arguments args(
      argc, argv, "dey_bhasin_mimo",
      adaptobs::examples::with_output_loss(
          {{"steps", "1000", "samples of each run", "", adaptobs::examples::integer_in(10, 1e7)},
           {"channel", "0", "output channel that a lost sample loses, as a partial update (0: all of them)", "",
            channel},
           adaptobs::examples::seed_option("1", "seed of the lost samples")},
          "samples"));
  const auto steps = static_cast<adaptobs::Index>(args.integer("steps"));
  const auto loss =
      adaptobs::examples::output_loss_options(args, static_cast<std::uint64_t>(args.integer("seed")), double(steps),
                                              adaptobs::Index(args.integer("channel")) - 1);

  using Matrix6 = Eigen::Matrix<double, 6, 6>;
  const Matrix6 a_matrix = adaptobs::block_companion_matrix<2>(mimo::a());
  const Matrix6 f_matrix = adaptobs::block_companion_matrix<2>(mimo::f());
  print_text("reading",
             "first block of A = 0.4 I2 (printed 4 I2 gives an unstable plant); B = printed array transposed");
  print_value("spectral_radius_A", adaptobs::spectral_radius(a_matrix));
  print_value("spectral_radius_A_printed",
              adaptobs::spectral_radius(Matrix6(adaptobs::block_companion_matrix<2>(mimo::printed_a()))));
  print_value("spectral_radius_F", adaptobs::spectral_radius(f_matrix));
  print_value("A", a_matrix);
  print_value("B", mimo::B());
  print_value("F", f_matrix);
  print_value("k0", mimo::k0);
  print_value("kmin", mimo::kmin);
  const auto observer = mimo::make_observer();
  const Eigen::Matrix<double, 15, 1> p = observer.parameters_of(mimo::a(), mimo::B());
  print_value("p", p.transpose());
  print_value("phat0", observer.parameters().transpose());

  const RunResult nonpe = run(mimo::NotRichInput{}, steps, "nonpe", adaptobs::OutputLoss(loss));
  const RunResult pe = run(mimo::RichInput{}, steps, "pe", adaptobs::OutputLoss(loss));

  // Theorem 5 on the run without excitation: as printed, and corrected.
  const double initial_error = (p - observer.parameters()).norm();
  const Eigen::VectorXd x_tilde0 = mimo::x0() - mimo::x_hat0();
  const Eigen::MatrixXd c = db::canonical_output_matrix<double>(mimo::order, mimo::outputs);
  const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(2, 2);
  const double perturbation = db::output_free_response_sum(f_matrix, c, x_tilde0, identity);  // R = I
  print_value("max_parameter_error_nonpe", nonpe.max_parameter_error);
  print_value("theorem5_bound_paper_nonpe", initial_error + mimo::k0 * nonpe.beta_phi * nonpe.beta_w * perturbation);
  print_value("theorem5_bound_corrected_nonpe", initial_error + std::sqrt(mimo::k0) * perturbation);
  print_value("max_parameter_error_pe", pe.max_parameter_error);

  adaptobs::examples::write_outputs(
      {{nonpe.table, "dey_bhasin_mimo_nonpe", "nonpe"}, {pe.table, "dey_bhasin_mimo_pe", "pe"}}, args.out_dir(),
      "dey_bhasin_mimo",
      adaptobs::examples::gap_shading(pe.table, loss) + adaptobs::examples::log_floor_function + figure_script);
  return 0;
} catch (...) {
  return adaptobs::examples::failure("dey_bhasin_mimo");
}
