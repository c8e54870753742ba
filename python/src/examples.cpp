// adaptobs.examples: the paper systems, their matrices and their simulated
// data from the same C++ plants and seeds as the C++ examples, so that a
// Python replay can be compared with the examples' CSV to the last digit.

#include "arrays.hpp"

#include "models/dey_bhasin.hpp"
#include "models/guiro.hpp"
#include "models/periodic_mimo.hpp"
#include "models/satellite.hpp"
#include "models/siso_third_order.hpp"

#include <nanobind/eigen/dense.h>
#include <nanobind/stl/string.h>

#include <cstdint>
#include <limits>

namespace adaptobs::python {

namespace {

namespace satellite = adaptobs::examples::satellite;

nb::dict satellite_system() {
  const auto zoh = satellite::discretized<double>();
  nb::dict d;
  d["A"] = Eigen::MatrixXd(zoh.Ad);
  d["B"] = Eigen::MatrixXd(Eigen::MatrixXd::Zero(4, 2));
  d["C"] = Eigen::MatrixXd(satellite::output_matrix<double>());
  d["H"] = Eigen::MatrixXd(zoh.Bd);
  d["K"] = Eigen::MatrixXd(satellite::paper_gain<double>());
  d["mu"] = satellite::mu;
  d["Ts"] = satellite::sampling_period;
  d["theta"] = Eigen::VectorXd(satellite::true_parameters<double>());
  d["x0"] = Eigen::VectorXd(satellite::initial_state<double>());
  d["x0_estimate"] = Eigen::VectorXd(satellite::initial_state_estimate<double>());
  d["theta0_estimate"] = Eigen::VectorXd(satellite::initial_parameter_estimate<double>());
  return d;
}

// N samples of the satellite: U (N x 2), Y (N x 2), Psi (N x 4 x 2) and the true states X (N x 4).
nb::dict simulate_satellite(Index steps, double noise, std::uint64_t seed) {
  adaptobs::require(steps >= 0, "examples.simulate_satellite", "steps", "must be non-negative");
  adaptobs::require(noise >= 0 && std::isfinite(noise), "examples.simulate_satellite", "noise",
                    "must be non-negative and finite");
  auto plant = satellite::make_plant<double>(noise, seed);
  const auto n = static_cast<std::size_t>(steps);
  OutputArray u({n, 2}), y({n, 2}), psi({n, 4, 2}), x({n, 4});
  for (Index k = 0; k < steps; ++k) {
    const auto& sample = plant.sample();
    for (Index i = 0; i < 2; ++i) {
      u.data[k * 2 + i] = sample.u(i);
      y.data[k * 2 + i] = sample.y(i);
    }
    for (Index i = 0; i < 4; ++i) {
      x.data[k * 4 + i] = plant.state()(i);
      for (Index j = 0; j < 2; ++j) psi.data[(k * 4 + i) * 2 + j] = sample.Psi(i, j);
    }
    plant.advance();
  }
  nb::dict d;
  d["U"] = u.array;
  d["Y"] = y.array;
  d["Psi"] = psi.array;
  d["X"] = x.array;
  return d;
}

namespace guiro = adaptobs::examples::guiro;

nb::dict guiro_system() {
  const auto model = guiro::model<double>();
  nb::dict d;
  d["E"] = Eigen::MatrixXd(model.system().A);
  d["B"] = Eigen::MatrixXd(model.system().B);
  d["C"] = Eigen::MatrixXd(model.system().C);
  d["T"] = guiro::period;
  d["theta"] = Eigen::VectorXd(Eigen::VectorXd::Constant(1, guiro::theta));
  d["x0"] = Eigen::VectorXd(guiro::initial_state<double>());
  d["z0"] = Eigen::VectorXd(guiro::initial_state_estimate<double>());
  d["theta0"] = Eigen::VectorXd(guiro::initial_parameter_estimate<double>());
  d["H0"] = Eigen::MatrixXd(guiro::closed_form_H<double>(0));
  d["Hbar"] = Eigen::MatrixXd(guiro::limit_H<double>());
  d["poles"] = Eigen::VectorXd(guiro::requested_poles());
  d["printed_K"] = Eigen::VectorXd(guiro::printed_K());
  d["printed_Gamma"] = guiro::corrected_printed_Gamma;
  return d;
}

// `samples` samples of the paper's example, regular period T: Y, Psi (Psi_k = E H_k, N x 2 x 1) and X.
nb::dict simulate_guiro(Index samples) {
  adaptobs::require(samples >= 0, "examples.simulate_guiro", "samples", "must be non-negative");
  auto plant = guiro::make_plant();
  const auto n = static_cast<std::size_t>(samples);
  OutputArray y({n, 1}), psi({n, 2, 1}), x({n, 2});
  for (Index k = 0; k < samples; ++k, plant.advance()) {
    y.data[k] = plant.sample().y(0);
    psi.data[2 * k] = plant.sample().Psi(0, 0);
    psi.data[2 * k + 1] = plant.sample().Psi(1, 0);
    x.data[2 * k] = plant.state()(0);
    x.data[2 * k + 1] = plant.state()(1);
  }
  nb::dict d;
  d["Y"] = y.array;
  d["Psi"] = psi.array;
  d["X"] = x.array;
  return d;
}

namespace mimo = adaptobs::examples::dey_bhasin::mimo;
namespace siso = adaptobs::examples::siso;

nb::dict siso_system() {
  nb::dict d;
  d["A"] = Eigen::MatrixXd(siso::dynamics<double>());
  d["B"] = Eigen::MatrixXd(siso::input_matrix<double>());
  d["C"] = Eigen::MatrixXd(siso::output_matrix<double>());
  d["theta"] = Eigen::VectorXd(siso::true_parameters<double>());
  d["x0"] = Eigen::VectorXd(siso::initial_state<double>());
  return d;
}

// `steps` samples of a continuous plant made by make_plant(options), every
// `period` from t = 0: t, U, Y, the signals at the midpoint of the interval
// ending at each sample (row 0: NaN) and the true states X.
template <class MakePlant>
nb::dict simulate_continuous(MakePlant make_plant, Index steps, double period, double noise, std::uint64_t seed,
                             std::string_view who) {
  adaptobs::require(steps >= 1, who, "steps", "must be at least 1");
  adaptobs::require_positive(period, who, "period");
  adaptobs::require(noise >= 0 && std::isfinite(noise), who, "noise", "must be non-negative and finite");
  auto plant = make_plant(ContinuousPlantOptions<double>{.period = period, .output_noise = noise, .seed = seed});
  const Sizes s = plant.model().sizes();
  const auto n = static_cast<std::size_t>(steps);
  const auto nx = static_cast<std::size_t>(s.nx), nu = static_cast<std::size_t>(s.nu),
             ny = static_cast<std::size_t>(s.ny);
  OutputArray t({n}), u({n, nu}), y({n, ny}), u_mid({n, nu}), y_mid({n, ny}), x({n, nx});
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (Index k = 0; k < steps; ++k) {
    if (k > 0) plant.advance();
    const auto& sample = plant.sample();
    t.data[k] = sample.t;
    Eigen::Map<Eigen::VectorXd>(u.data + k * s.nu, s.nu) = sample.u;
    Eigen::Map<Eigen::VectorXd>(y.data + k * s.ny, s.ny) = sample.y;
    if (sample.midpoint) {
      Eigen::Map<Eigen::VectorXd>(u_mid.data + k * s.nu, s.nu) = sample.midpoint->u;
      Eigen::Map<Eigen::VectorXd>(y_mid.data + k * s.ny, s.ny) = sample.midpoint->y;
    } else {
      Eigen::Map<Eigen::VectorXd>(u_mid.data + k * s.nu, s.nu).setConstant(nan);
      Eigen::Map<Eigen::VectorXd>(y_mid.data + k * s.ny, s.ny).setConstant(nan);
    }
    Eigen::Map<Eigen::VectorXd>(x.data + k * s.nx, s.nx) = plant.state();
  }
  nb::dict d;
  d["t"] = t.array;
  d["U"] = u.array;
  d["Y"] = y.array;
  d["U_mid"] = u_mid.array;
  d["Y_mid"] = y_mid.array;
  d["X"] = x.array;
  return d;
}

nb::dict simulate_siso(Index steps, double period, double noise, std::uint64_t seed) {
  return simulate_continuous([](auto options) { return siso::make_plant<double>(options); }, steps, period, noise, seed,
                             "examples.simulate_siso");
}

namespace periodic = adaptobs::examples::periodic;

nb::dict periodic_system() {
  nb::dict d;
  d["matrices_at"] = nb::cpp_function(
      [](double t) {
        const auto s = periodic::system<double>(t);
        return nb::make_tuple(Eigen::MatrixXd(s.A), Eigen::MatrixXd(s.B), Eigen::MatrixXd(s.C));
      },
      nb::arg("t"), "(A(t), B(t), C(t)) of the periodic plant");
  d["Phi"] = nb::cpp_function([](double t) { return Eigen::MatrixXd(periodic::Regressor{}(t)); }, nb::arg("t"),
                              "Phi(t) of the periodic plant");
  d["period"] = periodic::period;
  d["T"] = Eigen::MatrixXd(periodic::coordinate_change<double>());
  d["K1"] = Eigen::MatrixXd(2.0 * Eigen::MatrixXd::Identity(2, 2));
  d["gamma"] = Eigen::MatrixXd(10.0 * Eigen::MatrixXd::Identity(2, 2));
  d["K"] = Eigen::MatrixXd(periodic::zhang_gain<double>());
  d["theta"] = Eigen::VectorXd(periodic::true_parameters<double>());
  d["x0"] = Eigen::VectorXd(periodic::initial_state<double>());
  return d;
}

nb::dict simulate_periodic(Index steps, double period, double noise, std::uint64_t seed) {
  return simulate_continuous([](auto options) { return periodic::make_plant<double>(options); }, steps, period, noise,
                             seed, "examples.simulate_periodic");
}

nb::dict dey_bhasin_mimo_system() {
  nb::dict d;
  d["a"] = Eigen::VectorXd(mimo::a());
  d["B"] = Eigen::MatrixXd(mimo::B());
  d["f"] = Eigen::VectorXd(mimo::f());
  d["x0"] = Eigen::VectorXd(mimo::x0());
  d["x0_estimate"] = Eigen::VectorXd(mimo::x_hat0());
  d["a0_estimate"] = Eigen::VectorXd(mimo::a_hat0());
  d["B0_estimate"] = Eigen::MatrixXd(mimo::B_hat0());
  d["k0"] = mimo::k0;
  d["kmin"] = mimo::kmin;
  d["R"] = Eigen::MatrixXd(Eigen::MatrixXd::Identity(mimo::outputs, mimo::outputs));
  return d;
}

// `steps` samples of a plant of the canonical form of Dey & Bhasin (2022),
// noise free: U, Y and the true states X, sample k in row k.
template <class Plant>
nb::dict record_canonical(Plant plant, Index steps, Index nu, Index ny, Index nx) {
  const auto n = static_cast<std::size_t>(steps);
  OutputArray u({n, static_cast<std::size_t>(nu)}), y({n, static_cast<std::size_t>(ny)}),
      x({n, static_cast<std::size_t>(nx)});
  for (Index k = 0; k < steps; ++k, plant.advance()) {
    Eigen::Map<Eigen::VectorXd>(u.data + k * nu, nu) = plant.sample().u;
    Eigen::Map<Eigen::VectorXd>(y.data + k * ny, ny) = plant.sample().y;
    Eigen::Map<Eigen::VectorXd>(x.data + k * nx, nx) = plant.state();
  }
  nb::dict d;
  d["U"] = u.array;
  d["Y"] = y.array;
  d["X"] = x.array;
  return d;
}

// The MIMO plant of §5 under the rich input u = (sin 0.3t + sin 1.3t,
// sin 0.7t + sin 2.1t) or the one that is not rich enough.
nb::dict simulate_dey_bhasin_mimo(Index steps, bool rich) {
  adaptobs::require(steps >= 0, "examples.simulate_dey_bhasin_mimo", "steps", "must be non-negative");
  const auto record = [steps](auto plant) {
    return record_canonical(std::move(plant), steps, mimo::inputs, mimo::outputs, mimo::states);
  };
  return rich ? record(mimo::make_plant(mimo::RichInput{})) : record(mimo::make_plant(mimo::NotRichInput{}));
}

namespace db_siso = adaptobs::examples::dey_bhasin::siso;

nb::dict dey_bhasin_siso_system() {
  nb::dict d;
  d["a"] = Eigen::VectorXd(db_siso::a());
  d["B"] = Eigen::MatrixXd(db_siso::B());
  d["f"] = Eigen::VectorXd(db_siso::f());
  d["x0"] = Eigen::VectorXd(db_siso::x0());
  d["x0_estimate"] = Eigen::VectorXd(db_siso::x0());
  d["a0_estimate"] = Eigen::VectorXd(db_siso::a_hat0());
  d["B0_estimate"] = Eigen::MatrixXd(db_siso::B_hat0());
  d["k0"] = db_siso::k0;
  d["kmin"] = db_siso::kmin;
  d["R"] = Eigen::MatrixXd(Eigen::MatrixXd::Identity(1, 1));
  d["lambda"] = db_siso::lambda;
  return d;
}

// The SISO plant of §5 under u_t = sin 0.2t, which is not persistently exciting.
nb::dict simulate_dey_bhasin_siso(Index steps) {
  adaptobs::require(steps >= 0, "examples.simulate_dey_bhasin_siso", "steps", "must be non-negative");
  return record_canonical(db_siso::make_plant(), steps, 1, 1, db_siso::order);
}

}  // namespace

void bind_examples(nb::module_& m) {
  nb::module_ examples = m.def_submodule("examples", "The paper systems and their simulated data.");
  examples.def("satellite", &satellite_system,
               "The controlled satellite of Guyader & Zhang (2003), section 4: A, B, C, H (Psi_k = H diag-(u_k)),\n"
               "the paper's gain K and mu, Ts, the true theta and the initial states and estimates.");
  examples.def("simulate_satellite", &simulate_satellite, nb::arg("steps") = 3000, nb::arg("noise") = 0.01,
               nb::arg("seed") = 2003,
               "`steps` samples of the satellite with output noise of standard deviation `noise` from `seed`\n"
               "(the C++ example's plant): a dict of U, Y, Psi and the true states X, sample k in row k.");
  examples.def("guiro", &guiro_system,
               "The example of Guiro, Iggidr, Ngom & Toure (2008): x1' = theta phi(t), x2' = x1, y = x2 sampled\n"
               "every T = 1, phi(t) = (t + 1)/(t + 2), theta = 5; the sampled E, B, C, the regressor H0 of the first\n"
               "interval and its limit Hbar,\n"
               "the requested poles and the printed gains (Gamma with its decimal point corrected).");
  examples.def("simulate_guiro", &simulate_guiro, nb::arg("samples") = 60,
               "`samples` noise-free samples: Y, Psi (Psi_k = E H_k, the regressor of each interval as the\n"
               "observer takes it) and the true states X.");
  examples.def("siso", &siso_system,
               "The third-order SISO plant of the unified formulation's examples (Zhang 2005 prints none):\n"
               "A, B, C, the true theta = (2, -1) and eta(0); Phi(t) = [[sin t, 0], [cos 1.7t, 1], [0, sin 0.6t]]\n"
               "and u = 1 + sin 0.3t.");
  examples.def("simulate_siso", &simulate_siso, nb::arg("steps") = 10001, nb::arg("period") = 0.01,
               nb::arg("noise") = 0.0, nb::arg("seed") = 1,
               "`steps` samples of it every `period` from t = 0 (the C++ plant, RK4): t, U, Y, U_mid and Y_mid\n"
               "(the signals at the midpoint of the interval ending at each sample; row 0 NaN) and X.");
  examples.def("periodic", &periodic_system,
               "The periodic MIMO plant of the Besancon and Zhang examples (n = 4, m = 2, p = 2, period 2 pi):\n"
               "matrices_at(t) -> (A(t), B(t), C(t)) and Phi(t) (C++ functions, for a ContinuousLtvModel), the\n"
               "coordinate change T to the form (8), the examples' K1, gamma and Zhang gain K, theta = (1, -2)\n"
               "and eta(0); u = sin 0.4t.");
  examples.def("simulate_periodic", &simulate_periodic, nb::arg("steps") = 4001, nb::arg("period") = 0.01,
               nb::arg("noise") = 0.0, nb::arg("seed") = 1,
               "`steps` samples of it every `period` from t = 0 (the C++ plant, RK4), as simulate_siso.");
  examples.def("dey_bhasin_mimo", &dey_bhasin_mimo_system,
               "The MIMO system of Dey & Bhasin (2022), section 5 (r = 3, q = 2, m = 2): the true a and B, the\n"
               "filter coefficients f, the initial state and estimates, k0, kmin and R of the observer.");
  examples.def("simulate_dey_bhasin_mimo", &simulate_dey_bhasin_mimo, nb::arg("steps") = 300, nb::arg("rich") = true,
               "`steps` noise-free samples of that system: U, Y and the true states X.");
  examples.def("dey_bhasin_siso", &dey_bhasin_siso_system,
               "The SISO comparison of Dey & Bhasin (2022), section 5, with the observer of Suzuki, Nakamura &\n"
               "Koga (1980): the true a and B, the filter coefficients f, the initial state and estimates, k0,\n"
               "kmin and R of the resetting observer and the forgetting factor lambda = sqrt(0.5) of the baseline.");
  examples.def("simulate_dey_bhasin_siso", &simulate_dey_bhasin_siso, nb::arg("steps") = 3000,
               "`steps` noise-free samples under u_t = sin 0.2t: U, Y and the true states X.");
}

}  // namespace adaptobs::python
