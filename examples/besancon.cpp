// Algorithm 3 of Zhang (2005, §III-C, Besançon) on the MIMO LTV plant of
// examples/models/periodic_mimo.hpp (n = 4, m = 2, p = 2, period 2π): the
// plant's output matrix is not [I 0]; the constant T of the model brings it to
// the form (8). The error e2 obeys ė2 = A22(t)e2 — exponentially stable
// (Floquet exponents printed), which frozen-time eigenvalues could not tell.
//
// Usage: besancon [--out DIR] [--seconds 40] [--noise 0] [--seed 1]
// Writes besancon.csv (t,u_1,y_*,x_*,xhat_*,theta_*,thetahat_*) and besancon.png.

#include <adaptobs/adaptobs.hpp>
#include <adaptobs/design/ltv_stability.hpp>
#include <adaptobs/simulation.hpp>

#include "common/continuous_example.hpp"
#include "common/example_support.hpp"
#include "models/unified_designs.hpp"

namespace periodic = adaptobs::examples::periodic;
namespace designs = adaptobs::examples::designs;
using adaptobs::examples::print_value;

int main(int argc, char** argv) try {
  const adaptobs::examples::Arguments args(argc, argv, "besancon", adaptobs::examples::continuous_options("40"));
  auto observer = designs::besancon_observer<double>({.sampling = designs::quadratic(), .excitation_window = 629});
  const auto& algorithm = observer.algorithm();
  print_value("T", algorithm.static_transform.T());
  print_value("C_o", observer.transformed_system(0.0).Co);
  print_value("K1", algorithm.K1);
  print_value("Gamma", observer.law().gamma());
  const auto a22 = [](double t) {
    return Eigen::Matrix2d(periodic::form8_dynamics<double>(t).bottomRightCorner(2, 2));
  };
  print_value("floquet_exponents_A22", adaptobs::floquet_exponents(a22, periodic::period).transpose());

  auto plant = periodic::make_plant<double>(
      {.output_noise = args.number("noise"), .seed = static_cast<std::uint64_t>(args.number("seed"))});
  adaptobs::SeriesTable table;
  adaptobs::examples::run_continuous(plant, args.number("seconds"), 0.01, 5, table, adaptobs::track(observer));
  adaptobs::examples::print_final_errors(plant, observer);
  print_value("excitation_level_Lambda", observer.excitation_level().value_or(0.0));

  adaptobs::examples::write_outputs(
      table, args.out_dir(), "besancon",
      adaptobs::examples::estimates_and_errors_figure(
          "Besancon adaptive observer (Zhang 2005, Algorithm 3) on a periodic MIMO plant", "1 and -2", 2, 4));
  return 0;
} catch (...) {
  return adaptobs::examples::failure("besancon");
}
