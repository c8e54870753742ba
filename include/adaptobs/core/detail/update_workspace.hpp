#pragma once
/// \file
/// The scratch of one observer update, and the dispatch of an update with an
/// output mask: written once for every observer that has them.

#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/discrete_model.hpp>
#include <adaptobs/core/status.hpp>
#include <adaptobs/core/validation.hpp>

#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>

namespace adaptobs::detail {

/// Where an update computes before it commits. With `on_stack` (fixed sizes)
/// nothing is stored: each step builds its workspace on the stack, where the
/// compiler can keep it in registers. Otherwise (run-time sizes) the observer
/// keeps one, sized at construction, so that an update never allocates.
template <class Workspace, bool on_stack>
class UpdateWorkspace {
 public:
  /// Sizes the kept workspace (`Workspace::resize(args...)`); nothing on the stack.
  template <class... Args>
  void resize(const Args&... args) {
    if constexpr (!on_stack) work_.resize(args...);
  }

  /// `step(workspace)`, on a fresh stack workspace or the kept one.
  template <class Step>
  decltype(auto) run(Step&& step) {
    if constexpr (on_stack) {
      Workspace w;
      return std::forward<Step>(step)(w);
    } else {
      return std::forward<Step>(step)(work_);
    }
  }

 private:
  [[no_unique_address]] std::conditional_t<on_stack, std::monostate, Workspace> work_;
};

/// The mask an update with `present` hands its step: null when every channel is
/// present (the plain update, bit for bit), after checking a run-time-sized mask
/// against the ny outputs (`who` names the caller in the error).
template <StateSpace D>
[[nodiscard]] const OutputMask<D>* partial_mask(const OutputMask<D>& present, Index ny, std::string_view who) {
  if constexpr (D::ny == Eigen::Dynamic) require_mask_size<D>(present, ny, who);
  return present.all() ? nullptr : &present;
}

/// The public update of a discrete-time observer with a model, written once
/// (CRTP): `update(sample)`, its masked form and `sizes()`, with the run-time
/// size checks of the sample and the mask. The observer supplies
/// `step_with(sample, mask)` (mask null: every channel present), `model_`, and
/// `Observer::name_update`, the name its size errors give.
template <class Observer, StateSpace Dims, template <StateSpace> class SampleOf>
class DiscreteUpdate : public SizedBy<Dims> {
 public:
  using Sample = SampleOf<Dims>;

  /// One step of the observer's law with the sample (its `step_with` cites the
  /// equations). Returns `UpdateStatus::accepted`, or the reason the sample
  /// was rejected (`nonfinite_input` for a NaN/Inf in it, `nonfinite_result`
  /// when the step would produce one, ...); a rejected step leaves the observer
  /// exactly as it was. With run-time sizes, a sample of the wrong shape throws
  /// `ConfigurationError` naming it, before anything is read.
  [[nodiscard]] UpdateStatus update(const Sample& sample) { return checked_step(sample, nullptr); }

  /// The same with only the output channels in `present` measured (the
  /// observer's file comment, "Missing and partial outputs"); absent entries of
  /// `sample.y` are ignored (they may be NaN or Inf). All channels present is
  /// `update(sample)`, bit for bit; none is the time update alone.
  [[nodiscard]] UpdateStatus update(const Sample& sample, const OutputMask<Dims>& present) {
    return checked_step(sample, partial_mask<Dims>(present, sizes().ny, Observer::name_update));
  }

  /// Run-time sizes (nx, nu, ny, np).
  [[nodiscard]] Sizes sizes() const noexcept { return self().model_.sizes(); }

 private:
  UpdateStatus checked_step(const Sample& sample, const OutputMask<Dims>* present) {
    if constexpr (!Dims::is_fixed) require_sample_sizes(sample, sizes(), Observer::name_update);
    return self().step_with(sample, present);
  }

  Observer& self() noexcept { return static_cast<Observer&>(*this); }
  const Observer& self() const noexcept { return static_cast<const Observer&>(*this); }
};

}  // namespace adaptobs::detail
