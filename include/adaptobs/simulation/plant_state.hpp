#pragma once
/// \file
/// What the simulated plants share: the check of what their callables return,
/// and the trajectory of a discrete-time plant with its accessors.

#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/validation.hpp>

#include <string_view>
#include <utility>

namespace adaptobs {

namespace detail {

/// What a user callable of a plant returned (an input, a regressor, a next
/// state), checked to be rows × cols before the plant stores or multiplies it:
/// with `Eigen::Dynamic` sizes nothing else would stop a wrong size from
/// writing past the plant's vectors. The error names the callable.
template <class Value>
Value&& require_returned_shape(Value&& value, Index rows, Index cols, std::string_view who, std::string_view callable) {
  require_shape(value, rows, cols, who, callable);
  return std::forward<Value>(value);
}

}  // namespace detail

/// Base of a simulated discrete-time plant, not used on its own: its state
/// \f$x_k\f$, parameters \f$\theta_k\f$, step k, sampling period and the sample
/// it measures at step k. The plant moves them on and fills the sample.
template <StateSpace D, class SampleType>
class DiscretePlantState : public D {
 public:
  using Sample = SampleType;

  /// Measured sample of the current step.
  [[nodiscard]] const Sample& sample() const noexcept { return sample_; }
  /// True state \f$x_k\f$ and parameters \f$\theta_k\f$.
  [[nodiscard]] const typename D::State& state() const noexcept { return x_; }
  [[nodiscard]] const typename D::Parameters& parameters() const noexcept { return theta_; }
  [[nodiscard]] Index step() const noexcept { return k_; }
  [[nodiscard]] double time() const noexcept { return static_cast<double>(k_) * static_cast<double>(period_); }

 protected:
  DiscretePlantState(typename D::State x0, typename D::Parameters theta, typename D::Scalar period)
      : x_(std::move(x0)), theta_(std::move(theta)), period_(period) {}
  /// For a plant that sets \f$\theta_k\f$ itself before each sample.
  DiscretePlantState(typename D::State x0, typename D::Scalar period) : x_(std::move(x0)), period_(period) {}

  typename D::State x_;
  typename D::Parameters theta_;
  typename D::Scalar period_;
  Sample sample_;
  Index k_ = 0;
};

}  // namespace adaptobs
