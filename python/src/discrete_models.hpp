#pragma once
// The model a discrete observer holds in Python. One C++ type carries both of
// the Python models, so that each observer is one Python class whatever its
// model: a DiscreteLtiModel's (A, B, C) for every step, or a DiscreteLtvModel's
// (A_k, B_k, C_k) for steps 0 … N − 1, shared read-only by the model object
// and every observer built on it (no copy per observer or per step).

#include "arrays.hpp"
#include "snapshot_fields.hpp"

#include <adaptobs/core/discrete_model.hpp>
#include <adaptobs/core/snapshot.hpp>

#include <nanobind/nanobind.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace adaptobs::python {

using Dims = DynamicDimensions<double>;
using LtiModel = DiscreteLtiModel<Dims>;
using System = DiscreteSystem<Dims>;

class SharedDiscreteModel : public Dims {
 public:
  /// Either kind, known at run time (`is_time_invariant`).
  static constexpr bool time_invariant = false;
  using Systems = std::vector<System>;

  /// The model of a DiscreteLtiModel: its matrices at every step.
  explicit SharedDiscreteModel(const LtiModel& lti)
      : systems_(std::make_shared<const Systems>(Systems{lti.system()})), np_(lti.sizes().np), varying_(false) {}

  /// Steps 0 … systems.size() − 1, each validated (finite, sizes of step 0);
  /// `name(k, i)` is what an error calls matrix i (0: A, 1: B, 2: C) of step k.
  template <class Name>
  SharedDiscreteModel(Systems systems, Index np, std::string_view who, Name name) : np_(np), varying_(true) {
    if (systems.empty()) adaptobs::fail_argument(who, "steps", "must be at least 1");
    adaptobs::require(np >= 0, who, "np", "must be non-negative");
    const Sizes s = sizes_of(systems.front(), np);
    for (std::size_t k = 0; k < systems.size(); ++k) {
      adaptobs::require_finite_shape(systems[k].A, s.nx, s.nx, who, name(k, 0));
      adaptobs::require_finite_shape(systems[k].B, s.nx, s.nu, who, name(k, 1));
      adaptobs::require_finite_shape(systems[k].C, s.ny, s.nx, who, name(k, 2));
    }
    systems_ = std::make_shared<const Systems>(std::move(systems));
  }

  /// The names of per-step arrays: "A[k]", "B[k]", "C[k]".
  static std::string element_of_arrays(std::size_t k, int i) {
    return detail::element_name(i == 0 ? "A" : i == 1 ? "B" : "C", k);
  }

  /// (A_k, B_k, C_k). Beyond the last step a time-varying model has no
  /// matrices: the update refuses, naming the step, and changes nothing.
  [[nodiscard]] const System& at(Index k) const {
    if (!varying_) return systems_->front();
    if (k < 0 || k >= steps())
      adaptobs::fail_argument("DiscreteLtvModel", "steps",
                              "holds the matrices of steps 0 to " + std::to_string(steps() - 1) + "; step " +
                                  std::to_string(k) + " is beyond them");
    return (*systems_)[static_cast<std::size_t>(k)];
  }
  [[nodiscard]] Sizes sizes() const noexcept { return sizes_of(systems_->front(), np_); }
  [[nodiscard]] Index steps() const noexcept { return static_cast<Index>(systems_->size()); }
  [[nodiscard]] bool is_time_invariant() const noexcept { return !varying_; }
  [[nodiscard]] const Systems& systems() const noexcept { return *systems_; }

  /// Its fields: the matrices of every step side by side (A is nx × N·nx, and
  /// so on), N and np settings; a time-invariant model is N = 0 with one (A, B, C).
  static constexpr std::string_view snapshot_type = "DiscreteLtvModel";
  static constexpr int snapshot_version = 1;
  template <class Self, class Archive>
  static void visit_state(Self& self, Archive& archive) {
    archive.setting("steps", self.varying_ ? self.steps() : 0);
    archive.setting("np", self.np_);
    Stacked stacked = self.stacked();
    archive("A", stacked.A);
    archive("B", stacked.B);
    archive("C", stacked.C);
    if constexpr (Archive::reading) {
      adaptobs::require(detail::all_finite(stacked.A) && detail::all_finite(stacked.B) && detail::all_finite(stacked.C),
                        "restore", "snapshot", "holds model matrices that are not finite");
      self.systems_ = std::make_shared<const Systems>(stacked.unstacked(self.sizes()));
    }
  }

  /// The model a snapshot's fields under `prefix` ("model." in an observer's) describe.
  static SharedDiscreteModel of_snapshot(const Snapshot<double>& s, const std::string& prefix) {
    const Index steps = integer(s, prefix + "steps");
    const Index np = integer(s, prefix + "np");
    if (steps < 0) adaptobs::fail_argument("restore", "snapshot", "holds a negative number of model steps");
    const Stacked stacked{field(s, prefix + "A"), field(s, prefix + "B"), field(s, prefix + "C")};
    const Index nx = stacked.A.rows();
    const Index count = std::max<Index>(steps, 1);
    if (nx == 0 || stacked.A.cols() != count * nx || stacked.B.cols() % count != 0 || stacked.C.cols() != count * nx)
      adaptobs::fail_argument("restore", "snapshot",
                              "holds model matrices that are not " + std::to_string(count) + " steps of one size");
    const Sizes sizes{nx, stacked.B.cols() / count, stacked.C.rows(), np};
    if (steps == 0) return SharedDiscreteModel(LtiModel(stacked.A, stacked.B, stacked.C, np));
    return SharedDiscreteModel(stacked.unstacked(sizes), np, "restore", element_of_arrays);
  }

 private:
  struct Stacked {
    Eigen::MatrixXd A, B, C;
    [[nodiscard]] Systems unstacked(const Sizes& s) const {
      Systems systems;
      for (Index k = 0; k * s.nx < A.cols(); ++k)
        systems.push_back({A.middleCols(k * s.nx, s.nx), B.middleCols(k * s.nu, s.nu), C.middleCols(k * s.nx, s.nx)});
      return systems;
    }
  };

  [[nodiscard]] Stacked stacked() const {
    const Sizes s = sizes();
    const Index n = steps();
    Stacked out{Eigen::MatrixXd(s.nx, n * s.nx), Eigen::MatrixXd(s.nx, n * s.nu), Eigen::MatrixXd(s.ny, n * s.nx)};
    for (Index k = 0; k < n; ++k) {
      const System& system = (*systems_)[static_cast<std::size_t>(k)];
      out.A.middleCols(k * s.nx, s.nx) = system.A;
      out.B.middleCols(k * s.nu, s.nu) = system.B;
      out.C.middleCols(k * s.nx, s.nx) = system.C;
    }
    return out;
  }

  static Sizes sizes_of(const System& system, Index np) {
    return {system.A.rows(), system.B.cols(), system.C.rows(), np};
  }

  std::shared_ptr<const Systems> systems_;
  Index np_;
  bool varying_;
};

/// Refuses, before any sample, a run of `samples` from step `first` that would
/// go beyond the last step of a time-varying model.
inline void require_steps(const SharedDiscreteModel& model, Index first, Index samples, std::string_view who) {
  if (!model.is_time_invariant() && first + samples > model.steps())
    adaptobs::fail_argument(who, "Y",
                            "has " + std::to_string(samples) + " samples from step " + std::to_string(first) +
                                ", beyond the " + std::to_string(model.steps()) + " steps of the DiscreteLtvModel");
}

/// The model argument of a discrete observer: a DiscreteLtiModel or a DiscreteLtvModel.
inline SharedDiscreteModel discrete_model(nb::handle model, std::string_view who) {
  LtiModel* lti = nullptr;
  if (nb::try_cast<LtiModel*>(model, lti, false) && lti) return SharedDiscreteModel(*lti);
  return object_argument<SharedDiscreteModel>(model, who, "model", "an adaptobs.DiscreteLtiModel or DiscreteLtvModel");
}

void bind_discrete_models(nb::module_& m);

}  // namespace adaptobs::python
