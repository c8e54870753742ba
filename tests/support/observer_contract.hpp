#pragma once
// The contract every observer and baseline keeps, written once against the
// concepts of core/observer.hpp and instantiated per observer with a factory:
//
//   struct GuyaderZhangContract {
//     using Observer = ...;                            // the type under test
//     static Observer make();                          // at its initial estimates
//     static std::vector<typename Observer::Sample> samples();  // a valid run, at least 20
//     static auto readings(const Observer&);           // everything a user can read, a std::tuple
//     static Output expected_output_error(const Observer& before, const Observer& after,
//                                         const Sample&);  // what output_error() must read
//     // Optional, with their defaults:
//     static constexpr const char* name = "double";    // the instance's name: its scalar
//     static constexpr auto poisonable = std::tuple{&Sample::u, &Sample::y, ...};  // u, y (and Ψ)
//     static Sample overflowing(Sample);               // finite, but the step overflows:
//                                                      // every poisonable vector at the largest value
//     static std::vector<Sample> more_poisoned(const Sample&);  // bad samples the member pointers
//                                                                // cannot reach (none)
//   };
//   ADAPTOBS_OBSERVER_CONTRACT(GuyaderZhang, GuyaderZhangContract<float>, GuyaderZhangContract<double>);
//
// at global scope, with the factories of one family; CTest then lists
// `<Family>/ObserverContract/<name>.<promise>`.
//
// The promises checked (core/observer.hpp and core/status.hpp state them):
// - the `Observer` and `DiagnosableObserver` concepts;
// - a NaN, +Inf or −Inf in any entry of any field listed in `poisonable` (or in
//   `more_poisoned`), or of a known input term `f` of nx entries when the sample
//   has one, is rejected with `nonfinite_input`, and every reading stays the same
//   bit for bit; a known input term of neither nx entries nor none throws
//   `ConfigurationError` naming `sample.f`, and changes nothing; one of nx zeros
//   is no term; so is a continuous-time sample not after the last
//   accepted one, with `nonincreasing_time`; with a mask, a NaN in an absent
//   channel is never read (`update_finite_outputs` finds that mask);
// - a finite sample whose step would overflow is rejected with
//   `nonfinite_result`, every reading unchanged;
// - after a rejection the run carries on as if the sample had never come;
// - `reset(x0, θ0)` after a run equals a fresh construction at (x0, θ0), bit
//   for bit, on the same samples; a non-finite θ0 (and, for the discrete
//   observers, a negative start step, named) throws `ConfigurationError` and
//   changes nothing;
// - `output_error()` is zero before the first update and after a reset, is the
//   factory's formula after each accepted update, and is zero in an absent channel;
// - with fixed sizes, neither the updates of the run (also with a known input
//   term of nx entries, when the sample has one) nor the readings allocate
//   (support/allocation_counter.hpp counts operator new and malloc and its kin).
//
// A float factory that names its double twin (`using InDouble = ...;`) also
// runs `FloatFollowsDouble`, and a factory of `Eigen::Dynamic` sizes that names
// its fixed-size twin (`using InFixed = ...;`) runs `DynamicFollowsFixed`
// (ADAPTOBS_TWIN_CONTRACT): after the same run, every reading agrees with the
// twin's, to 1e-4 and 1e-12 relative (`float_tolerance` and `dynamic_tolerance`
// override them); the dynamic twin also gives the fixed one's verdict on the
// factory's `overflowing` sample (its `overflowing` must take its own sample type).

#include "support/allocation_counter.hpp"
#include "support/eigen_testing.hpp"

#include <adaptobs/core/observer.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

namespace adaptobs::testing {

// ------------------------------------------------------------ bitwise sameness

template <class T>
bool same_bits(const T& a, const T& b);

namespace contract_detail {

template <class T>
struct IsOptional : std::false_type {};
template <class T>
struct IsOptional<std::optional<T>> : std::true_type {};

template <class T>
struct IsTuple : std::false_type {};
template <class... T>
struct IsTuple<std::tuple<T...>> : std::true_type {};

}  // namespace contract_detail

/// Equality of every bit of a reading: Eigen matrices entry by entry, floating
/// point values by their representation (so NaN equals the same NaN and 0 is not
/// −0), optionals and tuples member by member, anything else by ==.
template <class T>
bool same_bits(const T& a, const T& b) {
  if constexpr (std::is_base_of_v<Eigen::MatrixBase<T>, T>) {
    return bitwise_equal(a, b);
  } else if constexpr (std::is_floating_point_v<T>) {
    return std::memcmp(&a, &b, sizeof(T)) == 0;
  } else if constexpr (contract_detail::IsOptional<T>::value) {
    return a.has_value() == b.has_value() && (!a || same_bits(*a, *b));
  } else if constexpr (contract_detail::IsTuple<T>::value) {
    return std::apply(
        [&](const auto&... x) { return std::apply([&](const auto&... y) { return (same_bits(x, y) && ...); }, b); }, a);
  } else {
    return a == b;
  }
}

/// Closeness of a reading to its twin's (float to double, dynamic to fixed
/// sizes): Eigen matrices and floating-point values within `tolerance` of the twin's,
/// relative to max(1, its largest magnitude); optionals and tuples member by
/// member; anything else (counters, flags) equal.
template <class F, class D>
bool close_in_precision(const F& f, const D& d, double tolerance) {
  if constexpr (std::is_base_of_v<Eigen::MatrixBase<F>, F>) {
    if (f.rows() != d.rows() || f.cols() != d.cols()) return false;
    if (f.size() == 0) return true;
    const Eigen::MatrixXd twin = d.template cast<double>();
    const double scale = std::max(1.0, twin.cwiseAbs().maxCoeff());
    return (f.template cast<double>() - twin).cwiseAbs().maxCoeff() <= tolerance * scale;
  } else if constexpr (std::is_floating_point_v<F>) {
    return std::abs(double(f) - double(d)) <= tolerance * std::max(1.0, std::abs(double(d)));
  } else if constexpr (contract_detail::IsOptional<F>::value) {
    return f.has_value() == d.has_value() && (!f || close_in_precision(*f, *d, tolerance));
  } else if constexpr (contract_detail::IsTuple<F>::value) {
    static_assert(std::tuple_size_v<F> == std::tuple_size_v<D>);
    return [&]<std::size_t... I>(std::index_sequence<I...>) {
      return (close_in_precision(std::get<I>(f), std::get<I>(d), tolerance) && ...);
    }(std::make_index_sequence<std::tuple_size_v<F>>{});
  } else {
    return f == d;
  }
}

// ------------------------------------------------------------ factory helpers

/// The first `count` samples of a plant's run, converted to the observer's
/// sample type by `convert` (by default the plant's sample as it is).
template <class Sample, class Plant, class Convert>
std::vector<Sample> first_samples(Plant plant, int count, Convert convert) {
  std::vector<Sample> run;
  for (int k = 0; k < count; ++k, plant.advance()) run.push_back(convert(plant.sample()));
  return run;
}
template <class Sample, class Plant>
std::vector<Sample> first_samples(Plant plant, int count) {
  return first_samples<Sample>(std::move(plant), count, [](const Sample& s) { return s; });
}

/// "float" or "double": an instance name for a factory templated on its scalar.
template <class S>
inline constexpr const char* scalar_name = std::is_same_v<S, float> ? "float" : "double";

// ------------------------------------------------------------ the contract

template <class Factory>
class ObserverContract : public ::testing::Test {
 public:
  using Observer = typename Factory::Observer;
  using Sample = typename Observer::Sample;
  using Scalar = typename Observer::Scalar;

  /// Every reading of the factory, and the output error.
  static auto readings(const Observer& o) {
    return std::tuple_cat(Factory::readings(o), std::make_tuple(typename Observer::Dims::Output(o.output_error())));
  }

  /// The observer after the first `count` samples of the run, all accepted.
  static Observer after(const std::vector<Sample>& run, std::size_t count) {
    Observer o = Factory::make();
    for (std::size_t k = 0; k < count; ++k) EXPECT_EQ(o.update(run[k]), UpdateStatus::accepted) << "k = " << k;
    return o;
  }

  /// The factory's `poisonable`, by default u, y and (when the sample has one) Ψ.
  static constexpr auto poisonable() {
    if constexpr (requires { Factory::poisonable; })
      return Factory::poisonable;
    else if constexpr (requires { &Sample::Psi; })
      return std::tuple{&Sample::u, &Sample::y, &Sample::Psi};
    else
      return std::tuple{&Sample::u, &Sample::y};
  }

  /// The factory's `overflowing(s)`, by default `s` with every poisonable vector at
  /// the largest finite value.
  static Sample overflowing(Sample s) {
    if constexpr (requires { Factory::overflowing(s); }) {
      return Factory::overflowing(std::move(s));
    } else {
      std::apply([&](auto... field) { ((s.*field).setConstant(std::numeric_limits<Scalar>::max()), ...); },
                 poisonable());
      return s;
    }
  }

  /// One copy of `valid` per entry of each poisonable field and per bad value.
  static std::vector<Sample> poisoned(const Sample& valid) {
    std::vector<Sample> out;
    const Scalar bad[] = {std::numeric_limits<Scalar>::quiet_NaN(), std::numeric_limits<Scalar>::infinity(),
                          -std::numeric_limits<Scalar>::infinity()};
    std::apply(
        [&](auto... field) {
          (
              [&](auto member) {
                using Field = std::remove_cvref_t<decltype(valid.*member)>;
                if constexpr (std::is_floating_point_v<Field>) {
                  for (const Scalar b : bad) {
                    out.push_back(valid);
                    out.back().*member = b;
                  }
                } else {
                  for (Index i = 0; i < (valid.*member).size(); ++i)
                    for (const Scalar b : bad) {
                      out.push_back(valid);
                      (out.back().*member).data()[i] = b;
                    }
                }
              }(field),
              ...);
        },
        poisonable());
    if constexpr (requires { valid.f; }) {
      Sample with_term = with_zero_known_input(valid);
      for (Index i = 0; i < with_term.f.size(); ++i)
        for (const Scalar b : bad) {
          out.push_back(with_term);
          out.back().f(i) = b;
        }
    }
    if constexpr (requires { Factory::more_poisoned(valid); })
      for (auto& sample : Factory::more_poisoned(valid)) out.push_back(std::move(sample));
    return out;
  }

  /// `s` with a known input term of nx zeros (a sample that has the field `f`).
  static Sample with_zero_known_input(Sample s) {
    s.f.setZero(Factory::make().sizes().nx);
    return s;
  }
};

TYPED_TEST_SUITE_P(ObserverContract);

TYPED_TEST_P(ObserverContract, SatisfiesTheObserverConcept) {
  using O = typename TestFixture::Observer;
  static_assert(Observer<O>);
  static_assert(std::is_copy_constructible_v<O> && std::is_move_constructible_v<O>);
  const auto run = TypeParam::samples();
  ASSERT_GE(run.size(), 20u);
  O observer = TypeParam::make();
  for (const auto& sample : run) ASSERT_EQ(observer.update(sample), UpdateStatus::accepted);
  // The run moved the estimates, or the checks below could not see a change.
  EXPECT_FALSE(same_bits(TestFixture::readings(observer), TestFixture::readings(TypeParam::make())));
}

TYPED_TEST_P(ObserverContract, NonFiniteSamplesAreRejectedAndChangeNothing) {
  const auto run = TypeParam::samples();
  const std::size_t half = run.size() / 2;
  auto observer = TestFixture::after(run, half);
  const auto before = TestFixture::readings(observer);
  const auto bad = TestFixture::poisoned(run[half]);
  ASSERT_FALSE(bad.empty());
  for (std::size_t i = 0; i < bad.size(); ++i) {
    EXPECT_EQ(observer.update(bad[i]), UpdateStatus::nonfinite_input) << "poisoned sample " << i;
    ASSERT_TRUE(same_bits(TestFixture::readings(observer), before)) << "poisoned sample " << i;
  }
  // A continuous-time sample not after the last accepted one.
  if constexpr (requires { run[half].t; }) {
    auto stale = run[half];
    stale.t = run[half - 1].t;
    EXPECT_EQ(observer.update(stale), UpdateStatus::nonincreasing_time);
    ASSERT_TRUE(same_bits(TestFixture::readings(observer), before));
  }
  // With a mask, a bad entry of an absent channel is never read: the step equals
  // that of the clean sample under the same mask, and update_finite_outputs
  // finds that mask itself.
  if constexpr (PartialOutputObserver<typename TestFixture::Observer>) {
    using Mask = OutputMask<typename TestFixture::Observer::Dims>;
    const Index ny = observer.sizes().ny;
    Mask without_first = Mask::Constant(ny, true);
    without_first(0) = false;
    auto glitch = run[half];
    glitch.y(0) = std::numeric_limits<typename TestFixture::Scalar>::quiet_NaN();
    EXPECT_EQ(observer.update(glitch, Mask::Constant(ny, true)), UpdateStatus::nonfinite_input);
    ASSERT_TRUE(same_bits(TestFixture::readings(observer), before));
    auto masked = observer, clean = observer, finite = observer;
    EXPECT_EQ(masked.update(glitch, without_first), UpdateStatus::accepted);
    EXPECT_EQ(clean.update(run[half], without_first), UpdateStatus::accepted);
    EXPECT_EQ(update_finite_outputs(finite, glitch), UpdateStatus::accepted);
    EXPECT_TRUE(same_bits(TestFixture::readings(masked), TestFixture::readings(clean)));
    EXPECT_TRUE(same_bits(TestFixture::readings(finite), TestFixture::readings(clean)));
  }
  // A known input term of neither nx entries nor none is refused by name; one of
  // nx zeros is no term (equal values: x + 0 may turn a −0 into +0).
  if constexpr (requires { run[half].f; }) {
    const Index nx = observer.sizes().nx;
    auto short_term = run[half];
    short_term.f.setOnes(nx - 1);
    EXPECT_CONFIGURATION_ERROR_NAMES((void)observer.update(short_term), "sample.f");
    if constexpr (decltype(short_term.f)::MaxRowsAtCompileTime == Eigen::Dynamic) {
      auto long_term = run[half];
      long_term.f.setOnes(nx + 1);
      EXPECT_CONFIGURATION_ERROR_NAMES((void)observer.update(long_term), "sample.f");
    }
    ASSERT_TRUE(same_bits(TestFixture::readings(observer), before));
    auto zeros = observer, none = observer;
    EXPECT_EQ(zeros.update(TestFixture::with_zero_known_input(run[half])), UpdateStatus::accepted);
    EXPECT_EQ(none.update(run[half]), UpdateStatus::accepted);
    EXPECT_TRUE(close_in_precision(TestFixture::readings(zeros), TestFixture::readings(none), 0.0));
  }
  // The run carries on as if the bad samples had never come.
  auto reference = TestFixture::after(run, half);
  for (std::size_t k = half; k < run.size(); ++k) {
    ASSERT_EQ(observer.update(run[k]), UpdateStatus::accepted);
    (void)reference.update(run[k]);
  }
  EXPECT_TRUE(same_bits(TestFixture::readings(observer), TestFixture::readings(reference)));
}

TYPED_TEST_P(ObserverContract, AnOverflowingStepIsRejectedAndChangesNothing) {
  const auto run = TypeParam::samples();
  const std::size_t half = run.size() / 2;
  auto observer = TestFixture::after(run, half);
  const auto before = TestFixture::readings(observer);
  EXPECT_EQ(observer.update(TestFixture::overflowing(run[half])), UpdateStatus::nonfinite_result);
  EXPECT_TRUE(same_bits(TestFixture::readings(observer), before));
  EXPECT_EQ(observer.update(run[half]), UpdateStatus::accepted);
}

// One overflowing sample is a bad sample; a run of them is divergence, which
// health() reports from the first of them on, until a reset.
TYPED_TEST_P(ObserverContract, ARunOfOverflowingStepsIsReportedAsDivergence) {
  const auto run = TypeParam::samples();
  const std::size_t half = run.size() / 2;
  auto observer = TestFixture::after(run, half);
  const Index first_refused = observer.step();
  EXPECT_EQ(observer.update(TestFixture::overflowing(run[half])), UpdateStatus::nonfinite_result);
  EXPECT_EQ(observer.update(run[half]), UpdateStatus::accepted);
  const auto bad = TestFixture::overflowing(run[half + 1]);  // a continuous-time sample must be later
  EXPECT_EQ(observer.health().state, Health::healthy) << observer.health().message;
  constexpr Index refusals = HealthRecord<typename TestFixture::Scalar>::divergence_refusals;
  for (Index i = 0; i < refusals; ++i) {
    EXPECT_EQ(observer.health().state, Health::healthy) << "after " << i << " refusals";
    EXPECT_EQ(observer.update(bad), UpdateStatus::nonfinite_result);
  }
  const HealthReport diverged = observer.health();
  EXPECT_EQ(diverged.state, Health::diverged);
  EXPECT_EQ(diverged.step, first_refused + 1);
  EXPECT_NE(diverged.message.find("from step " + std::to_string(first_refused + 1)), std::string::npos)
      << diverged.message;
  // Kept while the run goes on (a caller that checks at the end still sees it), and in a copy.
  EXPECT_EQ(observer.update(run[half + 1]), UpdateStatus::accepted);
  EXPECT_EQ(observer.health().state, Health::diverged);
  observer.reset(TypeParam::make().state(), TypeParam::make().parameters());
  EXPECT_EQ(observer.health().state, Health::healthy);
  EXPECT_EQ(observer.health().step, -1);
}

TYPED_TEST_P(ObserverContract, ResetEqualsAFreshConstruction) {
  const auto run = TypeParam::samples();
  const auto fresh = TypeParam::make();
  auto observer = TestFixture::after(run, run.size());
  observer.reset(fresh.state(), fresh.parameters());
  EXPECT_TRUE(same_bits(TestFixture::readings(observer), TestFixture::readings(fresh)));
  auto reference = fresh;
  for (const auto& sample : run) {
    ASSERT_EQ(observer.update(sample), UpdateStatus::accepted);
    ASSERT_EQ(reference.update(sample), UpdateStatus::accepted);
  }
  EXPECT_TRUE(same_bits(TestFixture::readings(observer), TestFixture::readings(reference)));
}

TYPED_TEST_P(ObserverContract, ResetRefusesBadArgumentsAndChangesNothing) {
  using O = typename TestFixture::Observer;
  const auto run = TypeParam::samples();
  auto observer = TestFixture::after(run, run.size() / 2);
  const auto before = TestFixture::readings(observer);
  const typename O::State x0 = observer.state();
  typename O::Parameters theta0 = observer.parameters();
  theta0(0) = std::numeric_limits<typename O::Scalar>::quiet_NaN();
  EXPECT_NE(configuration_error_of([&] { observer.reset(x0, theta0); }), "<no exception>");
  // The discrete observers restart at a step k of a time-varying model.
  if constexpr (requires { observer.reset(x0, theta0, Index(0)); }) {
    EXPECT_CONFIGURATION_ERROR_NAMES(observer.reset(x0, observer.parameters(), Index(-1)), "start_step");
  }
  EXPECT_TRUE(same_bits(TestFixture::readings(observer), before));
}

TYPED_TEST_P(ObserverContract, OutputErrorIsTheErrorOfTheLastAcceptedUpdate) {
  using O = typename TestFixture::Observer;
  static_assert(DiagnosableObserver<O>);
  {
    using Output = typename O::Dims::Output;
    // The factory's formula may round differently (another coordinate system, another order).
    const double tolerance = std::max(1e-12, 100.0 * std::numeric_limits<typename O::Scalar>::epsilon());
    const auto run = TypeParam::samples();
    O observer = TypeParam::make();
    EXPECT_TRUE(observer.output_error().isZero(0));
    double largest = 0;
    for (std::size_t k = 0; k < run.size(); ++k) {
      const O before = observer;
      ASSERT_EQ(observer.update(run[k]), UpdateStatus::accepted);
      const Output expected = TypeParam::expected_output_error(before, observer, run[k]);
      EXPECT_MATRIX_NEAR(observer.output_error(), expected, tolerance, tolerance) << "k = " << k;
      largest = std::max(largest, static_cast<double>(expected.cwiseAbs().maxCoeff()));
    }
    // Errors the formula could get wrong: not all zero.
    EXPECT_GT(largest, 1e-6);
    if constexpr (PartialOutputObserver<O>) {
      const Index ny = observer.sizes().ny;
      OutputMask<typename O::Dims> present = OutputMask<typename O::Dims>::Constant(ny, true);
      present(0) = false;
      auto next = run.back();
      if constexpr (requires { next.t; }) next.t += run.back().t - run[run.size() - 2].t;  // time must advance
      ASSERT_EQ(observer.update(next, present), UpdateStatus::accepted);
      EXPECT_EQ(observer.output_error()(0), 0);
      if (ny >= 2) {
        EXPECT_NE(observer.output_error()(1), 0);
      }
    }
    observer.reset(observer.state(), observer.parameters());
    EXPECT_TRUE(observer.output_error().isZero(0));
  }
}

TYPED_TEST_P(ObserverContract, FixedSizeUpdatesAndReadingsDoNotAllocate) {
  using O = typename TestFixture::Observer;
  if constexpr (!O::Dims::is_fixed) {
    GTEST_SKIP() << "run-time sizes allocate their workspaces at construction";
  } else {
    const auto run = TypeParam::samples();
    O observer = TypeParam::make();
    int rejected = 0;
    EXPECT_EQ(allocations_during([&] {
                for (const auto& sample : run) {
                  rejected += observer.update(sample) != UpdateStatus::accepted;
                  (void)TestFixture::readings(observer);
                }
              }),
              0);
    EXPECT_EQ(rejected, 0);
    // A known input term is stored in the sample, in place: its updates do not allocate either.
    if constexpr (requires { run[0].f; }) {
      std::vector<typename TestFixture::Sample> with_term;
      for (const auto& sample : run) with_term.push_back(TestFixture::with_zero_known_input(sample));
      EXPECT_EQ(allocations_during([&] {
                  for (const auto& sample : with_term) rejected += observer.update(sample) != UpdateStatus::accepted;
                }),
                0);
      EXPECT_EQ(rejected, 0);
    }
  }
}

// ------------------------------------------------------------ twins

/// Runs a factory and its twin (the same observer, plant and run in another
/// scalar, or with other size parameters) and expects every reading of the one,
/// output error included, within `tolerance` of the other's, relative to
/// max(1, the twin's largest magnitude). The run must have moved the twin's
/// readings by more than 1e-2, or the comparison would be empty.
template <class Factory, class Twin>
void expect_readings_follow_the_twin(double tolerance) {
  using Instance = ObserverContract<Factory>;
  using Reference = ObserverContract<Twin>;
  const auto run = Factory::samples();
  const auto twin_run = Twin::samples();
  ASSERT_EQ(run.size(), twin_run.size());
  const auto observer = Instance::after(run, run.size());
  const auto twin = Reference::after(twin_run, twin_run.size());
  const auto readings = Instance::readings(observer);
  const auto twin_readings = Reference::readings(twin);
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    (
        [&] {
          EXPECT_TRUE(close_in_precision(std::get<I>(readings), std::get<I>(twin_readings), tolerance))
              << "reading " << I << " of the factory's readings() (the last is output_error())";
        }(),
        ...);
  }(std::make_index_sequence<std::tuple_size_v<decltype(readings)>>{});
  EXPECT_FALSE(close_in_precision(Reference::readings(twin), Reference::readings(Twin::make()), 1e-2));
}

/// The single-precision instance of an observer follows its double-precision
/// twin: a float factory names its twin `InDouble`, and after the run every
/// reading agrees to 1e-4 relative (or the factory's `float_tolerance`). The
/// satellite and waste-water runs agree to 1e-5; a float-only slip as small as a
/// step size 1 % off in float fails.
template <class Factory>
class FloatFollowsDouble : public ::testing::Test {};

TYPED_TEST_SUITE_P(FloatFollowsDouble);

TYPED_TEST_P(FloatFollowsDouble, ReadingsAfterTheRunAgreeToSinglePrecision) {
  static_assert(std::is_same_v<typename TypeParam::Observer::Scalar, float> &&
                std::is_same_v<typename TypeParam::InDouble::Observer::Scalar, double>);
  double tolerance = 1e-4;
  if constexpr (requires { TypeParam::float_tolerance; }) tolerance = TypeParam::float_tolerance;
  expect_readings_follow_the_twin<TypeParam, typename TypeParam::InDouble>(tolerance);
}

REGISTER_TYPED_TEST_SUITE_P(FloatFollowsDouble, ReadingsAfterTheRunAgreeToSinglePrecision);

/// The `Eigen::Dynamic` instance of an observer follows its fixed-size twin: a
/// factory of run-time sizes names its twin `InFixed`, and after the run every
/// reading agrees to 1e-12 relative (or the factory's `dynamic_tolerance`). Only
/// the order of roundings may differ (vectorized fixed-size products against the
/// dynamic kernels).
template <class Factory>
class DynamicFollowsFixed : public ::testing::Test {};

TYPED_TEST_SUITE_P(DynamicFollowsFixed);

TYPED_TEST_P(DynamicFollowsFixed, ReadingsAfterTheRunAgreeToRounding) {
  static_assert(!TypeParam::Observer::Dims::is_fixed && TypeParam::InFixed::Observer::Dims::is_fixed);
  double tolerance = 1e-12;
  if constexpr (requires { TypeParam::dynamic_tolerance; }) tolerance = TypeParam::dynamic_tolerance;
  expect_readings_follow_the_twin<TypeParam, typename TypeParam::InFixed>(tolerance);
}

// The overflow paths: a finite sample whose step overflows (the factory's
// `overflowing`, as in `AnOverflowingStepIsRejectedAndChangesNothing`) gets the
// same verdict from both twins, and the run after it ends at the same readings.
// A step that guards against overflow by scaling (the normalized step of
// Guyader–Zhang) is checked by a factory whose run takes that path, accepted.
TYPED_TEST_P(DynamicFollowsFixed, AnOverflowingSampleGetsTheSameVerdict) {
  using Fixed = typename TypeParam::InFixed;
  double tolerance = 1e-12;
  if constexpr (requires { TypeParam::dynamic_tolerance; }) tolerance = TypeParam::dynamic_tolerance;
  const auto run = TypeParam::samples();
  const auto fixed_run = Fixed::samples();
  ASSERT_EQ(run.size(), fixed_run.size());
  const std::size_t half = run.size() / 2;
  auto observer = ObserverContract<TypeParam>::after(run, half);
  auto twin = ObserverContract<Fixed>::after(fixed_run, half);
  const auto before = ObserverContract<TypeParam>::readings(observer);
  const UpdateStatus verdict = twin.update(ObserverContract<Fixed>::overflowing(fixed_run[half]));
  EXPECT_EQ(verdict, UpdateStatus::nonfinite_result);
  EXPECT_EQ(observer.update(ObserverContract<TypeParam>::overflowing(run[half])), verdict);
  EXPECT_TRUE(same_bits(ObserverContract<TypeParam>::readings(observer), before));
  for (std::size_t k = half; k < run.size(); ++k) {
    ASSERT_EQ(twin.update(fixed_run[k]), UpdateStatus::accepted) << "k = " << k;
    ASSERT_EQ(observer.update(run[k]), UpdateStatus::accepted) << "k = " << k;
  }
  EXPECT_TRUE(close_in_precision(ObserverContract<TypeParam>::readings(observer),
                                 ObserverContract<Fixed>::readings(twin), tolerance));
}

REGISTER_TYPED_TEST_SUITE_P(DynamicFollowsFixed, ReadingsAfterTheRunAgreeToRounding,
                            AnOverflowingSampleGetsTheSameVerdict);

// A test executable whose observers have no such twin does not instantiate its suite.
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(FloatFollowsDouble);
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(DynamicFollowsFixed);

/// Names each instance by its factory's `name`, by default its scalar
/// ("GuyaderZhang/ObserverContract/float.…").
struct ContractName {
  template <class Factory>
  static std::string GetName(int) {
    if constexpr (requires { Factory::name; })
      return Factory::name;
    else
      return scalar_name<typename Factory::Observer::Scalar>;
  }
};

REGISTER_TYPED_TEST_SUITE_P(ObserverContract, SatisfiesTheObserverConcept, NonFiniteSamplesAreRejectedAndChangeNothing,
                            ARunOfOverflowingStepsIsReportedAsDivergence, AnOverflowingStepIsRejectedAndChangesNothing,
                            ResetEqualsAFreshConstruction, ResetRefusesBadArgumentsAndChangesNothing,
                            OutputErrorIsTheErrorOfTheLastAcceptedUpdate, FixedSizeUpdatesAndReadingsDoNotAllocate);

}  // namespace adaptobs::testing

/// Runs the contract on the factories given, one family: at global scope.
#define ADAPTOBS_OBSERVER_CONTRACT(Family, ...)                                                      \
  namespace adaptobs::testing {                                                                      \
  using Family##ContractFactories = ::testing::Types<__VA_ARGS__>;                                   \
  INSTANTIATE_TYPED_TEST_SUITE_P(Family, ObserverContract, Family##ContractFactories, ContractName); \
  }                                                                                                  \
  static_assert(true, "")

/// Runs a twin suite, `FloatFollowsDouble` or `DynamicFollowsFixed`, on the
/// factories given (each naming its twin): at global scope.
#define ADAPTOBS_TWIN_CONTRACT(Family, Suite, ...)                                       \
  namespace adaptobs::testing {                                                          \
  using Family##Suite##Factories = ::testing::Types<__VA_ARGS__>;                        \
  INSTANTIATE_TYPED_TEST_SUITE_P(Family, Suite, Family##Suite##Factories, ContractName); \
  }                                                                                      \
  static_assert(true, "")
