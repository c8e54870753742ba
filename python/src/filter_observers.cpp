// The observers of Dey & Bhasin (2022) in Python, with run-time sizes: the
// MIMO observer in observable canonical form with covariance-resetting RLS
// (eq. (3)-(13), (16), (20)-(23)) and the Suzuki baseline with exponential
// forgetting. Their samples are (u_k, y_k); all of A and B is estimated.

#include "discrete_observer.hpp"
#include "snapshot_fields.hpp"

#include <adaptobs/observers/dey_bhasin.hpp>

#include <nanobind/stl/optional.h>

namespace adaptobs::python {

namespace {
constexpr int X = Eigen::Dynamic;
}

using DeyBhasin = DeyBhasinObserver<double, X, X, X>;
using Suzuki = SuzukiObserver<double, X, X, X>;

template <>
struct Diagnostics<DeyBhasin> {
  static constexpr std::array<const char*, 1> names{"reset_count"};
  static void record(const DeyBhasin& o, double* out) { out[0] = static_cast<double>(o.law().reset_count()); }
};

namespace {

// The properties both observers share: the estimates of A and B and the regression (16).
template <class Observer>
void bind_canonical_form_properties(nb::class_<Bound<Observer>>& cls) {
  using B = Bound<Observer>;
  cls.def_prop_ro(
         "current_state", [](const B& b) { return Eigen::VectorXd(b.observer.current_state()); },
         "x_hat_t of (13); `state` is the prediction x_hat_{t+1|t}.")
      .def_prop_ro(
          "a_hat", [](const B& b) { return Eigen::VectorXd(b.observer.a_hat()); },
          "estimate of the first-column coefficients a of A")
      .def_prop_ro("A_hat", [](const B& b) { return Eigen::MatrixXd(b.observer.A_hat()); })
      .def_prop_ro("B_hat", [](const B& b) { return Eigen::MatrixXd(b.observer.B_hat()); })
      .def_prop_ro(
          "regressor", [](const B& b) { return Eigen::MatrixXd(b.observer.regressor()); },
          "phi_t of the regression z_t = phi_t^T p (16)")
      .def_prop_ro(
          "measurement", [](const B& b) { return Eigen::VectorXd(b.observer.measurement()); }, "z_t of (16)")
      .def_prop_ro(
          "covariance", [](const B& b) { return Eigen::MatrixXd(b.observer.law().covariance()); },
          "the RLS gain Gamma_t");
}

constexpr std::string_view canonical_form_doc =
    "x_{t+1} = A x_t + B u_t, y_t = C x_t in observable canonical form (A block companion with first\n"
    "column a, C = [I 0]), A and B unknown. `f` holds the first column of the stable filter matrix F,\n"
    "its length r the order; x0 (n = r q) the initial state estimate, a0 and B0 (n x m) the initial\n"
    "estimates.";

}  // namespace

void bind_filter_observers(nb::module_& m) {
  auto dey_bhasin = nb::class_<Bound<DeyBhasin>>(
      m, "DeyBhasinObserver",
      (std::string("Dey-Bhasin adaptive observer (Dey & Bhasin 2022, eq. (3)-(13), (16), (20)-(23)).\n") +
       std::string(canonical_form_doc) +
       "\nRLS with covariance resetting: Gamma_0 = k0 I, reset to k0 I when lambda_min falls below kmin;\n"
       "R weights the output error.")
          .c_str());
  dey_bhasin.def(
      "__init__",
      [](Bound<DeyBhasin>* self, nb::handle f, nb::handle x0, nb::handle a0, nb::handle B0, nb::handle k0,
         nb::handle kmin, nb::handle R, nb::handle screen_reset_test, nb::handle information,
         nb::handle excitation_window) {
        constexpr std::string_view who = "DeyBhasinObserver";
        new (self) Bound<DeyBhasin>(
            DeyBhasin(vector(f, who, "f"), vector(x0, who, "x0"), vector(a0, who, "a0"), matrix(B0, who, "B0"),
                      {.k0 = real_scalar(k0, who, "k0"),
                       .kmin = real_scalar(kmin, who, "kmin"),
                       .R = matrix(R, who, "R"),
                       .screen_reset_test = flag_argument(screen_reset_test, who, "screen_reset_test")},
                      {.information = flag_argument(information, who, "information"),
                       .excitation_window = integer_argument(excitation_window, who, "excitation_window")}));
      },
      nb::arg("f"), nb::arg("x0"), nb::arg("a0"), nb::arg("B0"), nb::kw_only(), nb::arg("k0"), nb::arg("kmin"),
      nb::arg("R"), nb::arg("screen_reset_test") = true, nb::arg("information") = false,
      nb::arg("excitation_window") = 0);
  bind_canonical_form_properties(dey_bhasin);
  dey_bhasin.def_prop_ro("reset_count", [](const Bound<DeyBhasin>& b) { return b.observer.law().reset_count(); })
      .def_prop_ro("reset_at_last_step",
                   [](const Bound<DeyBhasin>& b) { return b.observer.law().reset_at_last_step(); })
      .def_prop_ro(
          "information",
          [](const Bound<DeyBhasin>& b) -> std::optional<Eigen::MatrixXd> {
            if (!b.observer.information_level()) return std::nullopt;
            return Eigen::MatrixXd(b.observer.information());
          },
          "I_t = sum phi_i R^-1 phi_i^T (definition 1, (15)); None unless information=True")
      .def_prop_ro(
          "information_level", [](const Bound<DeyBhasin>& b) { return b.observer.information_level(); },
          "lambda_min(I_t), growing without bound under persistent excitation; None unless information=True")
      .def_prop_ro(
          "excitation_level", [](const Bound<DeyBhasin>& b) { return b.observer.excitation_level(); },
          "lambda_min of the average of phi_i R^-1 phi_i^T over the last excitation_window samples; None until "
          "the window is full")
      .def_prop_ro(
          "excitation_rank", [](const Bound<DeyBhasin>& b) { return b.observer.excitation_rank(); },
          "numerical rank of that average (eigenvalues above 1e3 n_p eps lambda_max); None until the window is "
          "full");
  bind_discrete_observer(dey_bhasin, [](const Snapshot<double>& s) {
    const Eigen::VectorXd f = field(s, "filters.f");
    const Eigen::VectorXd x0 = field(s, "x0");
    // The diagnostics' settings are in a snapshot only when they were on.
    const bool diagnostics = s.find_integer("information") != nullptr;
    return DeyBhasin(f, x0, f, Eigen::MatrixXd::Zero(x0.size(), integer(s, "filters.m")),
                     {.k0 = scalar(s, "law.k0"),
                      .kmin = scalar(s, "law.kmin"),
                      .R = field(s, "law.R"),
                      .screen_reset_test = integer(s, "law.screen_reset_test") != 0},
                     {.information = diagnostics && integer(s, "information") != 0,
                      .excitation_window = diagnostics ? integer(s, "excitation_window") : 0});
  });

  auto suzuki = nb::class_<Bound<Suzuki>>(
      m, "SuzukiObserver",
      (std::string("Baseline: the filters of DeyBhasinObserver with exponential-forgetting RLS\n"
                   "(Dey & Bhasin 2022, section 5, after Suzuki et al. 1980).\n") +
       std::string(canonical_form_doc) + "\nGamma_0 = gamma0, forgetting factor lambda_ in (0, 1], weight R.")
          .c_str());
  suzuki.def(
      "__init__",
      [](Bound<Suzuki>* self, nb::handle f, nb::handle x0, nb::handle a0, nb::handle B0, nb::handle gamma0,
         nb::handle R, nb::handle lambda) {
        constexpr std::string_view who = "SuzukiObserver";
        new (self) Bound<Suzuki>(Suzuki(vector(f, who, "f"), vector(x0, who, "x0"), vector(a0, who, "a0"),
                                        matrix(B0, who, "B0"),
                                        {.gamma0 = matrix(gamma0, who, "gamma0"),
                                         .R = matrix(R, who, "R"),
                                         .lambda = real_scalar(lambda, who, "lambda_")}));
      },
      nb::arg("f"), nb::arg("x0"), nb::arg("a0"), nb::arg("B0"), nb::kw_only(), nb::arg("gamma0"), nb::arg("R"),
      nb::arg("lambda_"));
  bind_canonical_form_properties(suzuki);
  bind_discrete_observer(suzuki, [](const Snapshot<double>& s) {
    const Eigen::VectorXd f = field(s, "filters.f");
    const Eigen::VectorXd x0 = field(s, "x0");
    return Suzuki(f, x0, f, Eigen::MatrixXd::Zero(x0.size(), integer(s, "filters.m")),
                  {.gamma0 = field(s, "law.gamma0"), .R = field(s, "law.R"), .lambda = scalar(s, "law.lambda")});
  });
}

}  // namespace adaptobs::python
