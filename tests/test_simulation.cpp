// Simulation runner and CSV table.

#include <adaptobs/baselines/augmented_kalman.hpp>
#include <adaptobs/observers/guyader_zhang.hpp>
#include <adaptobs/simulation/discrete_nonlinear_plant.hpp>
#include <adaptobs/simulation/runner.hpp>
#include <adaptobs/simulation/series_table.hpp>

#include "models/satellite.hpp"
#include "support/eigen_testing.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <limits>
#include <sstream>

namespace {

namespace satellite = adaptobs::examples::satellite;
using adaptobs::Index;
using adaptobs::testing::configuration_error_of;

TEST(SeriesTable, WritesHeaderAndNonFiniteValues) {
  adaptobs::SeriesTable table;
  table.begin_row().add("t", 0.0).add("x", Eigen::Vector2d(1.5, -2)).add("v", std::numeric_limits<double>::quiet_NaN());
  table.begin_row()
      .add("t", 0.1)
      .add("x", Eigen::Vector2d(0.1, 1e-300))
      .add("v", -std::numeric_limits<double>::infinity());
  std::ostringstream os;
  table.write_csv(os);
  EXPECT_EQ(os.str(), "t,x_1,x_2,v\n0,1.5,-2,nan\n0.1,0.1,1e-300,-inf\n");
  EXPECT_EQ(table.rows(), 2u);
  EXPECT_EQ(table.at(1, "x_2"), 1e-300);
  EXPECT_EQ(table.column("t"), (std::vector<double>{0.0, 0.1}));
}

TEST(SeriesTable, RoundTripsDoublesExactly) {
  adaptobs::SeriesTable table;
  const double value = 0.1 + 0.2;  // not representable in few digits
  table.begin_row().add("a", value);
  std::ostringstream os;
  table.write_csv(os);
  const std::string text = os.str();
  EXPECT_EQ(std::stod(text.substr(text.find('\n') + 1)), value);
}

TEST(SeriesTable, RejectsRowsThatDoNotMatchTheHeader) {
  adaptobs::SeriesTable table;
  table.begin_row().add("a", 1.0).add("b", 2.0);
  table.begin_row().add("a", 1.0);
  EXPECT_THROW(table.add("c", 3.0), std::logic_error);
  adaptobs::SeriesTable short_row;
  short_row.begin_row().add("a", 1.0).add("b", 2.0);
  short_row.begin_row().add("a", 1.0);
  EXPECT_THROW(short_row.begin_row(), std::logic_error);
}

// Names the CSV header could not hold as one field, or that repeat, are refused
// (a comma shifted every later column; a repeat hid the second series from
// `at`); a row past the complete ones is out of range, not another row's value.
TEST(SeriesTable, RefusesAmbiguousNamesAndRowsOutOfRange) {
  adaptobs::SeriesTable table;
  table.begin_row();
  EXPECT_THROW(table.add("x,y", 1.0), std::invalid_argument);
  EXPECT_THROW(table.add("line\nbreak", 1.0), std::invalid_argument);
  EXPECT_THROW(table.add("", 1.0), std::invalid_argument);
  table.add("a", 11.0);
  EXPECT_THROW(table.add("a", 2.0), std::invalid_argument);
  EXPECT_THROW(table.add("a", Eigen::Vector2d(1, 2)).add("a", Eigen::Vector2d(3, 4)), std::invalid_argument);
  table.begin_row().add("a", 12.0).add("a_1", 1.0).add("a_2", 2.0);
  EXPECT_EQ(table.at(1, "a"), 12.0);
  EXPECT_THROW((void)table.at(2, "a"), std::out_of_range);
  EXPECT_THROW((void)table.at(std::size_t(1) << 63, "a"), std::out_of_range);
  // A file that cannot take the data says so when written, not never.
  if (std::ofstream("/dev/full")) {
    EXPECT_THROW(table.write_csv(std::string("/dev/full")), std::runtime_error);
  }
}

// With dynamic sizes, what the plant's callables return is checked at every
// step: a time-varying model whose matrices change size, an input or a
// regressor of the wrong size is refused by name before anything is written.
TEST(DiscreteLinearPlant, WrongSizesFromItsCallablesAndNonFiniteStartsAreRefusedByName) {
  using DD = adaptobs::DynamicDimensions<double>;
  const auto matrices_at = [](Index k) {
    const Index n = k == 0 ? 2 : 40;  // grows after the first step
    return adaptobs::DiscreteSystem<DD>{0.5 * Eigen::MatrixXd::Identity(n, n), Eigen::MatrixXd::Ones(n, 1),
                                        Eigen::MatrixXd::Ones(1, n)};
  };
  const auto model = adaptobs::make_discrete_ltv_model<DD>(matrices_at, {2, 1, 1, 1});
  const auto input = [](Index) { return Eigen::VectorXd::Ones(1); };
  const auto regressor = [](Index, const Eigen::VectorXd&) { return Eigen::MatrixXd::Ones(2, 1); };
  const Eigen::VectorXd x0 = Eigen::VectorXd::Ones(2), theta = Eigen::VectorXd::Ones(1);
  adaptobs::DiscreteLinearPlant growing(model, x0, theta, input, regressor);
  EXPECT_CONFIGURATION_ERROR_NAMES(growing.advance(), "matrices_at(k)");
  EXPECT_TRUE(growing.state() == x0);
  EXPECT_CONFIGURATION_ERROR_NAMES(model.at(3), "matrices_at(k)");

  const auto steady = adaptobs::make_discrete_ltv_model<DD>(
      [](Index) {
        return adaptobs::DiscreteSystem<DD>{0.5 * Eigen::MatrixXd::Identity(2, 2), Eigen::MatrixXd::Ones(2, 1),
                                            Eigen::MatrixXd::Ones(1, 2)};
      },
      {2, 1, 1, 1});
  const auto wide_input = [](Index k) { return Eigen::VectorXd::Ones(k == 0 ? 1 : 50); };
  adaptobs::DiscreteLinearPlant wide(steady, x0, theta, wide_input, regressor);
  EXPECT_CONFIGURATION_ERROR_NAMES(wide.advance(), "input(k)");
  const auto tall_regressor = [](Index, const Eigen::VectorXd&) { return Eigen::MatrixXd::Ones(3, 1); };
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::DiscreteLinearPlant(steady, x0, theta, input, tall_regressor),
                                   "regressor(k, u)");

  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  EXPECT_CONFIGURATION_ERROR_NAMES(
      adaptobs::DiscreteLinearPlant(steady, x0, Eigen::VectorXd::Constant(1, nan), input, regressor), "theta");
  EXPECT_CONFIGURATION_ERROR_NAMES(
      adaptobs::DiscreteLinearPlant(steady, Eigen::VectorXd::Constant(2, inf), theta, input, regressor), "x0");
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::DiscreteLinearPlant(steady, x0, theta, input, regressor, {.output = inf}),
                                   "noise.output");
  EXPECT_CONFIGURATION_ERROR_NAMES(
      adaptobs::DiscreteLinearPlant(steady, x0, theta, input, regressor, {.parameter = -1}), "noise.parameter");
}

TEST(DiscreteNonlinearPlant, ATransitionOfAnotherSizeIsRefusedByName) {
  using DD = adaptobs::DynamicDimensions<double>;
  const auto transition = [](const Eigen::VectorXd& x, const Eigen::VectorXd&, const Eigen::VectorXd&) {
    return Eigen::VectorXd(Eigen::VectorXd::Constant(x(0) > 0.6 ? 3 : 2, 0.5 * x(0)));
  };
  auto plant = adaptobs::make_discrete_nonlinear_plant<DD>(
      transition, Eigen::MatrixXd::Ones(1, 2), Eigen::VectorXd::Ones(2), [](Index) { return Eigen::VectorXd::Ones(1); },
      [](Index) { return Eigen::VectorXd::Ones(1); });
  EXPECT_CONFIGURATION_ERROR_NAMES(plant.advance(), "transition(x, u, theta)");
  EXPECT_TRUE(plant.state() == Eigen::VectorXd::Ones(2));
  EXPECT_EQ(plant.step(), 0);
}

// The plant has no model to size u and θ: a run-time-sized input or
// parameter vector that changed size was stored as returned, and a throwing
// callable of step k + 1 left the state moved and the sample stale.
TEST(DiscreteNonlinearPlant, InputsAndParametersKeepTheirStepZeroSizes) {
  using DD = adaptobs::DynamicDimensions<double>;
  const auto transition = [](const Eigen::VectorXd& x, const Eigen::VectorXd& u, const Eigen::VectorXd& theta) {
    return Eigen::VectorXd(0.5 * x + Eigen::VectorXd::Constant(2, u(0) + theta(0)));
  };
  const auto sized_from = [](Index k_changed) {
    return [=](Index k) { return Eigen::VectorXd(Eigen::VectorXd::Ones(k >= k_changed ? 2 : 1)); };
  };
  const auto make = [&](auto input, auto parameters) {
    return adaptobs::make_discrete_nonlinear_plant<DD>(transition, Eigen::MatrixXd::Ones(1, 2),
                                                       Eigen::VectorXd::Ones(2), input, parameters);
  };
  auto growing_input = make(sized_from(2), sized_from(100));
  growing_input.advance();
  const Eigen::VectorXd x1 = growing_input.state();
  EXPECT_TRUE(x1.isApprox(Eigen::VectorXd::Constant(2, 2.5), 1e-15));
  EXPECT_CONFIGURATION_ERROR_NAMES(growing_input.advance(), "input(k)");
  EXPECT_EQ(growing_input.step(), 1);
  EXPECT_TRUE(growing_input.state() == x1);
  EXPECT_EQ(growing_input.sample().u.size(), 1);

  auto growing_theta = make(sized_from(100), sized_from(1));
  EXPECT_CONFIGURATION_ERROR_NAMES(growing_theta.advance(), "parameters_at(k)");
  EXPECT_EQ(growing_theta.step(), 0);
  EXPECT_TRUE(growing_theta.state() == Eigen::VectorXd::Ones(2));

  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_CONFIGURATION_ERROR_NAMES(
      make(sized_from(100), [=](Index) { return Eigen::VectorXd(Eigen::VectorXd::Constant(1, nan)); }),
      "parameters_at(k)");
}

TEST(Simulation, RecordsTruthAndEveryObserverInSchemaOrder) {
  auto plant = satellite::make_plant<double>();
  adaptobs::GuyaderZhangObserver observer(satellite::model<double>(), satellite::paper_gain<double>(), satellite::mu,
                                          satellite::initial_state_estimate<double>(),
                                          satellite::initial_parameter_estimate<double>());
  adaptobs::AugmentedKalmanCovariances<satellite::Dims<double>> cov{
      Eigen::Matrix<double, 6, 6>::Identity(), Eigen::Matrix<double, 6, 6>::Zero(), Eigen::Matrix2d::Identity() * 1e-4};
  adaptobs::AugmentedKalmanFilter akf(satellite::model<double>(), satellite::initial_state_estimate<double>(),
                                      satellite::initial_parameter_estimate<double>(), cov);
  adaptobs::SeriesTable table;
  int extra_calls = 0;
  const auto report = adaptobs::simulate(
      plant, 25, table,
      [&](adaptobs::SeriesTable& row, const auto& p) {
        ++extra_calls;
        row.add("step", double(p.step()));
      },
      adaptobs::track(observer), adaptobs::track(akf, "akf"));
  EXPECT_EQ(report.steps, 25);
  EXPECT_EQ(report.rejected[0], 0);
  EXPECT_EQ(report.rejected[1], 0);
  EXPECT_EQ(extra_calls, 25);
  const std::vector<std::string> expected = {"t",
                                             "u_1",
                                             "u_2",
                                             "y_1",
                                             "y_2",
                                             "x_1",
                                             "x_2",
                                             "x_3",
                                             "x_4",
                                             "xhat_1",
                                             "xhat_2",
                                             "xhat_3",
                                             "xhat_4",
                                             "theta_1",
                                             "theta_2",
                                             "thetahat_1",
                                             "thetahat_2",
                                             "xhat_akf_1",
                                             "xhat_akf_2",
                                             "xhat_akf_3",
                                             "xhat_akf_4",
                                             "thetahat_akf_1",
                                             "thetahat_akf_2",
                                             "step"};
  EXPECT_EQ(table.names(), expected);
  // Row k holds the estimates before sample k: row 0 has the initial estimates.
  EXPECT_EQ(table.at(0, "thetahat_1"), 0.5);
  EXPECT_EQ(table.at(0, "xhat_1"), 0.9);
  EXPECT_DOUBLE_EQ(table.at(24, "t"), 2.4);
  EXPECT_EQ(table.at(24, "thetahat_akf_2"), table.at(24, "thetahat_akf_2"));
  // The last row's estimates are those after 24 updates.
  EXPECT_EQ(observer.step(), 25);
}

// With an output loss, the runner hands each observer the channels that
// arrived: a lost sample is the time update, a lost channel the partial update,
// recorded in y_available. The observer run by hand with the same masks ends
// bit-identical.
void expect_runner_matches_hand_loop(const adaptobs::OutputLossOptions& options) {
  using Mask = adaptobs::OutputMask<satellite::Dims<double>>;
  const auto make = [] {
    return adaptobs::GuyaderZhangObserver(satellite::model<double>(), satellite::paper_gain<double>(), satellite::mu,
                                          satellite::initial_state_estimate<double>(),
                                          satellite::initial_parameter_estimate<double>(), {.normalized_step = true});
  };
  auto simulated = make();
  auto by_hand = make();
  adaptobs::OutputLoss loss(options);
  adaptobs::SeriesTable table;
  auto plant = satellite::make_plant<double>(0.01, 3);
  const auto report = adaptobs::simulate(
      plant, 60, table, loss, [](adaptobs::SeriesTable&, const auto&) {}, adaptobs::track(simulated));
  EXPECT_EQ(report.rejected[0], 0);
  EXPECT_EQ(table.names()[5], "y_available");

  adaptobs::OutputLoss replay(options);
  auto twin = satellite::make_plant<double>(0.01, 3);
  Index lost = 0;
  for (Index k = 0; k < 60; ++k) {
    const Mask present = replay.channels_at<satellite::Dims<double>>(twin.time(), 2);
    EXPECT_EQ(table.at(std::size_t(k), "y_available"), double(present(0)) + 2 * double(present(1)));
    if (twin.time() >= 2.0 && twin.time() <= 3.0) {
      EXPECT_FALSE(present(1));
    }
    lost += present.all() ? 0 : 1;
    ASSERT_EQ(by_hand.update(twin.sample(), present), adaptobs::UpdateStatus::accepted);
    twin.advance();
  }
  EXPECT_GT(lost, 20);  // the 11 samples of the outage and about 30 % of the 49 others
  EXPECT_TRUE(adaptobs::testing::bitwise_equal(simulated.state(), by_hand.state()));
  EXPECT_TRUE(adaptobs::testing::bitwise_equal(simulated.parameters(), by_hand.parameters()));
  EXPECT_EQ(simulated.step(), 60);
}

TEST(Simulation, LostOutputsBecomeMaskedUpdatesAndAreRecorded) {
  SCOPED_TRACE("whole samples lost");
  expect_runner_matches_hand_loop({.drop = 0.3, .outage_begin = 2.0, .outage_end = 3.0, .seed = 5});
}

TEST(Simulation, ALostChannelBecomesAPartialUpdate) {
  expect_runner_matches_hand_loop({.drop = 0.3, .outage_begin = 2.0, .outage_end = 3.0, .channel = 1, .seed = 5});
}

TEST(OutputLoss, OneChannelLossAndBadConfiguration) {
  using Dims = adaptobs::Dimensions<double, 3, 0, 3, 1>;
  adaptobs::OutputLoss second({.drop = 0.5, .channel = 1, .seed = 2});
  Index partial = 0;
  for (int k = 0; k < 100; ++k) {
    const auto present = second.channels_at<Dims>(double(k), 3);
    EXPECT_TRUE(present(0) && present(2));
    partial += present(1) ? 0 : 1;
    EXPECT_EQ(adaptobs::channel_bits(present), present(1) ? 7.0 : 5.0);
  }
  EXPECT_GT(partial, 30);
  EXPECT_LT(partial, 70);
  EXPECT_TRUE(adaptobs::OutputLoss().lossless());
  EXPECT_NE(configuration_error_of([] { adaptobs::OutputLoss l({.drop = 1.0}); }).find("'drop'"), std::string::npos);
  EXPECT_NE(configuration_error_of([] { adaptobs::OutputLoss l({.drop = -0.1}); }).find("'drop'"), std::string::npos);
  EXPECT_NE(configuration_error_of([] { adaptobs::OutputLoss l({.channel = -2}); }).find("'channel'"),
            std::string::npos);
  adaptobs::OutputLoss beyond({.drop = 0.999, .channel = 3});
  EXPECT_NE(configuration_error_of([&] { (void)beyond.channels_at<Dims>(0.0, 3); }).find("'channel'"),
            std::string::npos);
}

// The runner's arguments are checked before the first row: a negative count,
// and a lost channel the plant does not have (once found only at the first
// loss, after rows were written, or never when no loss came).
TEST(Simulation, BadArgumentsAreRefusedBeforeAnyRow) {
  auto plant = satellite::make_plant<double>();
  adaptobs::GuyaderZhangObserver observer(satellite::model<double>(), satellite::paper_gain<double>(), satellite::mu,
                                          satellite::initial_state_estimate<double>(),
                                          satellite::initial_parameter_estimate<double>());
  adaptobs::SeriesTable table;
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::simulate(plant, -5, table, adaptobs::track(observer)), "steps");
  adaptobs::OutputLoss channel_seven({.drop = 0.001, .channel = 7});
  const auto no_columns = [](adaptobs::SeriesTable&, const auto&) {};
  EXPECT_CONFIGURATION_ERROR_NAMES(
      adaptobs::simulate(plant, 10, table, channel_seven, no_columns, adaptobs::track(observer)), "loss");
  EXPECT_EQ(table.rows(), 0u);
  EXPECT_EQ(plant.step(), 0);
  EXPECT_CONFIGURATION_ERROR_NAMES(adaptobs::record_samples(plant, -1), "n");
}

}  // namespace
