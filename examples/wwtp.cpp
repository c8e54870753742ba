// Waste water treatment plant, Srinivasarengan et al. (2018), §6: joint
// estimation of the biomass and substrate (x1, x2) and of the growth-rate error
// θ (a = 0.5 + θ) with the Takagi–Sugeno adaptive observer (65), once with the
// printed gains and once with gains designed here by theorem 2 with DSDP.
//
// Usage: wwtp [--out DIR] [--theta 0.1] [--steps 500] [--drop 0] [--outage none|K0,K1]
//             [--seed 1]
// With --drop P each output sample is lost with probability P, with --outage
// none arrives for k in [K0, K1]; both observers then take the time update.
// Writes wwtp.csv (t,u_1,y_1,y_available,x_*,xhat_*,theta_1,thetahat_1 for the printed gains,
// xhat_lmi_*,thetahat_lmi_1 for the LMI gains, h_1..h_8 the weights of the
// printed-gain observer) and wwtp.png (figures 1–5 of the paper: x1, x2, θ̂,
// input, weights).
//
// Input: the dilution rate u_k = 0.225 + 0.05 sin(2πk/100) ∈ [0.175, 0.275] ⊂ [0, 0.4].
// It keeps the plant inside its sector (76) for θ ∈ [−0.225, 0.3] (at a constant
// rate u the plant washes out, x1 → 0, as u approaches a = 0.5 + θ); at its mean
// the printed gains meet the 300-sample criterion for θ in [−0.125, 0.1], centred
// on the nominal θ = 0, and converge later beyond 0.1 (models/wwtp.hpp); the sine
// keeps the plant moving.
//
// LMI design: theorem 2 with the error model as printed in (66), K_i = 0.03
// imposed (Remark 6), Q_e = diag(1e-3, 1e-3, 0.1) (Remark 6), minimising β
// (corollary 1), on the input sector [0.05, 0.4] instead of [0, 0.4]: the input
// never goes below 0.175, and the u = 0 vertex (A_1, a pure integrator next to a
// mode at 0.99976 seen only through A_1(1,2) = 5.9e-4) drives β* from 537 to
// about 4.6e7, beyond DSDP's accuracy. The paper's own sectors are feasible too,
// shown by the largest-margin formulation with Γ = 1e8 (printed below).

#include <adaptobs/adaptobs.hpp>
#include <adaptobs/design/lmi/takagi_sugeno_synthesis.hpp>
#include <adaptobs/design/stability.hpp>
#include <adaptobs/simulation.hpp>

#include "common/example_support.hpp"
#include "models/wwtp.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

namespace wwtp = adaptobs::examples::wwtp;
using adaptobs::examples::print_text;
using adaptobs::examples::print_value;

namespace {

adaptobs::TakagiSugenoLmiOptions remark6_options() {
  adaptobs::TakagiSugenoLmiOptions options;
  options.Q_x = 1e-3 * Eigen::MatrixXd::Identity(2, 2);
  options.Q_theta = Eigen::MatrixXd::Constant(1, 1, 0.1);
  options.parameter_gain = Eigen::MatrixXd::Constant(1, 1, 0.03);
  return options;
}

template <class Gains>
void print_gains(const std::string& prefix, const Gains& gains) {
  for (std::size_t i = 0; i < gains.L.size(); ++i) {
    print_value(prefix + "L_" + std::to_string(i + 1), gains.L[i]);
  }
  print_value(prefix + "K_1", gains.K.front());
}

// First sample from which |θ̂ − θ| < 0.01 and ‖x − x̂‖∞ < 1e-3 hold to the end (−1: never).
int settled_from(const adaptobs::SeriesTable& table, const std::string& suffix) {
  const std::string x = suffix.empty() ? "xhat" : "xhat_" + suffix;
  const std::string t = suffix.empty() ? "thetahat" : "thetahat_" + suffix;
  int first = -1;
  for (std::size_t r = 0; r < table.rows(); ++r) {
    const bool ok = std::abs(table.at(r, t + "_1") - table.at(r, "theta_1")) < 0.01 &&
                    std::abs(table.at(r, x + "_1") - table.at(r, "x_1")) < 1e-3 &&
                    std::abs(table.at(r, x + "_2") - table.at(r, "x_2")) < 1e-3;
    if (!ok)
      first = -1;
    else if (first < 0)
      first = int(r);
  }
  return first;
}

// The eight vertices from the quasi-LPV factorization, against the printed ones.
template <class Model>
void compare_printed_vertices(const Model& model) {
  const auto printed = wwtp::printed_vertex_matrices();
  double worst_printed = 0;
  for (adaptobs::Index i = 0; i < model.vertex_count(); ++i) {
    Eigen::Matrix2d p;
    for (int e = 0; e < 4; ++e) p(e / 2, e % 2) = printed[std::size_t(i)][std::size_t(e)].value;
    const std::string n = std::to_string(i + 1);
    print_value("A_" + n, Eigen::Matrix2d(model.A(i)));
    print_value("A_" + n + "_printed", p);
    worst_printed = std::max(worst_printed, (Eigen::Matrix2d(model.A(i)) - p).cwiseAbs().maxCoeff());
  }
  print_value("B_i", Eigen::Vector2d(model.B(0)));
  print_value("max_abs_A_minus_printed", worst_printed);
}

// The printed gains: A_i − L_i C is not Schur at four vertices, so no common
// Lyapunov matrix (theorem 2) can exist for them.
template <class Model, class Gains>
void print_printed_gains(const Model& model, const Gains& paper) {
  print_gains("paper_", paper);
  Eigen::Matrix<double, 1, 8> radii;
  for (adaptobs::Index i = 0; i < 8; ++i)
    radii(i) = adaptobs::spectral_radius(Eigen::Matrix2d(model.A(i) - paper.L[std::size_t(i)] * model.C()));
  print_value("paper_spectral_radius_A_i_minus_L_i_C", radii);
}

// LMI design (theorem 2, corollary 1) on the input sector [0.05, 0.4]; false
// when it found no gains.
template <class Design>
bool print_lmi_design(const Design& design) {
  print_text("lmi", adaptobs::to_string(design.status));
  print_text("lmi_solver", design.message);
  print_value("lmi_beta", design.beta);
  print_value("lmi_solve_seconds", design.solver.seconds);
  print_value("lmi_max_eigenvalue", design.check.max_vertex_eigenvalue);
  if (!design.gains) {
    std::cerr << "wwtp: the LMI design failed: " << design.message << '\n';
    return false;
  }
  print_value("lmi_P0", design.certificate.P0);
  print_gains("lmi_", *design.gains);
  return true;
}

// The paper's sectors [0, 0.4]: feasible, shown with the largest-margin objective.
template <class Model>
void print_paper_sector_design(const Model& model) {
  auto margin_options = remark6_options();
  margin_options.objective = adaptobs::TakagiSugenoObjective::maximize_margin;
  margin_options.fixed_gamma = 1e8;
  const auto paper_sectors = adaptobs::synthesize_takagi_sugeno_gains(model, margin_options);
  print_text("lmi_paper_sectors", adaptobs::to_string(paper_sectors.status));
  print_value("lmi_paper_sectors_margin", paper_sectors.margin);
  print_value("lmi_paper_sectors_solve_seconds", paper_sectors.solver.seconds);
}

void write_figure(const adaptobs::SeriesTable& table, const adaptobs::examples::Arguments& args,
                  const adaptobs::OutputLoss& loss) {
  adaptobs::examples::write_outputs(table, args.out_dir(), "wwtp",
                                    adaptobs::examples::gap_shading(table, loss.options()) + R"(
set multiplot layout 3,2 title 'Takagi-Sugeno adaptive observer, waste water treatment plant (Srinivasarengan et al. 2018, section 6; the paper gives no units)'
set grid
set xlabel 'k (samples, T_s = 1)'
# Autoscaled, with a margin, so that neither the start nor the true value lies on a border.
set offsets 0, 0, graph 0.05, graph 0.05
set title 'Figure 1: estimation of x_1, the biomass (measured, y = x_1)'
set ylabel 'biomass x_1'
plot csv using 't':'x_1' with lines lw 2 lc 'black' title 'plant', \
     csv using 't':'xhat_1' with lines lw 1.5 title 'printed gains', \
     csv using 't':'xhat_lmi_1' with lines lw 1.5 dt 2 title 'LMI gains'
set title 'Figure 2: estimation of x_2, the substrate (not measured)'
set ylabel 'substrate x_2'
plot csv using 't':'x_2' with lines lw 2 lc 'black' title 'plant', \
     csv using 't':'xhat_2' with lines lw 1.5 title 'printed gains', \
     csv using 't':'xhat_lmi_2' with lines lw 1.5 dt 2 title 'LMI gains'
set title 'Figure 3: estimation of theta, the growth-rate error (a = 0.5 + theta)'
set ylabel 'theta (no unit)'
plot csv using 't':'theta_1' with lines lw 2 lc 'black' title 'true', \
     csv using 't':'thetahat_1' with lines lw 1.5 title 'printed gains', \
     csv using 't':'thetahat_lmi_1' with lines lw 1.5 dt 2 title 'LMI gains'
set title 'Figure 4: input, the dilution rate (its sector [0, 0.4])'
set ylabel 'dilution rate u (1/T_s)'
set offsets 0, 0, 0, 0
set yrange [0:0.4]
plot csv using 't':'u_1' with lines lw 1.5 title 'u'
set title 'Figure 5: weights h_i (printed-gain observer)'
set ylabel 'weight h_i (no unit)'
set yrange [0:1]
plot for [i=1:8] csv using 't':(column(sprintf('h_%d', i))) with lines lw 1.5 title sprintf('h_%d', i)
unset multiplot)");
}

}  // namespace

int main(int argc, char** argv) try {
  const adaptobs::examples::Arguments args(
      argc, argv, "wwtp",
      adaptobs::examples::with_output_loss(
          {{"theta", "0.1", "growth-rate error of the plant, a = 0.5 + theta (the input keeps it in its sector)", "",
            adaptobs::examples::real_in(-0.225, 0.3)},
           {"steps", "500", "samples of the run", "", adaptobs::examples::integer_in(10, 1e7)},
           adaptobs::examples::seed_option("1", "seed of the lost samples")},
          "samples"));
  const double theta = args.number("theta");
  const auto steps = static_cast<adaptobs::Index>(args.integer("steps"));
  adaptobs::OutputLoss loss(
      adaptobs::examples::output_loss_options(args, static_cast<std::uint64_t>(args.integer("seed")), double(steps)));

  const auto model = wwtp::model<double>();
  compare_printed_vertices(model);
  const auto paper = wwtp::paper_gains<double>();
  print_printed_gains(model, paper);
  const auto lmi_model = wwtp::model<double>(0.05);
  const auto design = adaptobs::synthesize_takagi_sugeno_gains(lmi_model, remark6_options());
  if (!print_lmi_design(design)) return 1;
  print_paper_sector_design(model);

  // Both observers on the same plant and input.
  auto plant = wwtp::make_plant<double>(theta);
  adaptobs::TakagiSugenoObserver observer(model, paper, wwtp::initial_state_estimate<double>(),
                                          wwtp::initial_parameter_estimate<double>());
  adaptobs::TakagiSugenoObserver lmi_observer(lmi_model, *design.gains, wwtp::initial_state_estimate<double>(),
                                              wwtp::initial_parameter_estimate<double>());
  print_text("input", "u_k = 0.225 + 0.05 sin(2 pi k / 100)");
  print_value("x0", wwtp::initial_state<double>());
  print_value("xhat0", wwtp::initial_state_estimate<double>());
  print_value("thetahat0", wwtp::initial_parameter_estimate<double>());

  adaptobs::SeriesTable table;
  std::vector<std::string> weight_columns;
  for (adaptobs::Index i = 0; i < model.vertex_count(); ++i) weight_columns.push_back("h_" + std::to_string(i + 1));
  const auto report = adaptobs::simulate(
      plant, steps, table, loss,
      [&](adaptobs::SeriesTable& row, const auto&) {
        // Weights ĥ_i of the printed-gain observer at this step (figure 5).
        const auto h = model.weights(model.premises(observer.state(), plant.sample().u, observer.parameters()),
                                     observer.parameters());
        for (adaptobs::Index i = 0; i < h.size(); ++i) row.add(weight_columns[std::size_t(i)], h(i));
      },
      adaptobs::track(observer), adaptobs::track(lmi_observer, "lmi"));

  print_value("steps", double(report.steps));
  print_value("rejected", double(report.rejected[0] + report.rejected[1]));
  print_value("theta", plant.parameters());
  print_value("thetahat", observer.parameters());
  print_value("thetahat_lmi", lmi_observer.parameters());
  print_value("state_error", (observer.state() - plant.state()).cwiseAbs().maxCoeff());
  print_value("state_error_lmi", (lmi_observer.state() - plant.state()).cwiseAbs().maxCoeff());
  print_value("settled_from_sample", settled_from(table, ""));
  print_value("settled_from_sample_lmi", settled_from(table, "lmi"));

  write_figure(table, args, loss);
  return 0;
} catch (...) {
  return adaptobs::examples::failure("wwtp");
}
