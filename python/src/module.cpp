// The extension module adaptobs._core: the C++ library with run-time sizes,
// double precision. The Python package (python/adaptobs) re-exports it.

#include "arrays.hpp"

#include <adaptobs/core/health.hpp>
#include <adaptobs/core/status.hpp>
#include <adaptobs/core/validation.hpp>

#include <nanobind/nanobind.h>
#include <nanobind/stl/string.h>

namespace adaptobs::python {
void bind_discrete_models(nb::module_& m);
void bind_discrete_observers(nb::module_& m);
void bind_design(nb::module_& m);
void bind_examples(nb::module_& m);
void bind_fault_detection(nb::module_& m);
void bind_filter_observers(nb::module_& m);
void bind_continuous_observers(nb::module_& m);
void bind_takagi_sugeno(nb::module_& m);
void bind_checks(nb::module_& m);
}  // namespace adaptobs::python

NB_MODULE(_core, m) {
  namespace nb = nanobind;
  using adaptobs::UpdateStatus;
  m.doc() = "adaptobs: adaptive observers, joint state and parameter estimation";

  // ConfigurationError is a ValueError carrying the C++ message, which names the argument.
  nb::exception<adaptobs::ConfigurationError>(m, "ConfigurationError", PyExc_ValueError);

  nb::enum_<UpdateStatus>(m, "UpdateStatus", nb::is_arithmetic(),
                          "What became of one sample; anything but `accepted` left the observer as it was.")
      .value("accepted", UpdateStatus::accepted)
      .value("nonfinite_input", UpdateStatus::nonfinite_input)
      .value("nonfinite_result", UpdateStatus::nonfinite_result)
      .value("nonincreasing_time", UpdateStatus::nonincreasing_time)
      .value("indefinite_covariance", UpdateStatus::indefinite_covariance)
      .value("interval_too_long", UpdateStatus::interval_too_long);

  nb::enum_<adaptobs::Health>(m, "Health", "The worst an observer's run has shown since construction or reset.")
      .value("healthy", adaptobs::Health::healthy)
      .value("assumption_violated", adaptobs::Health::assumption_violated)
      .value("diverged", adaptobs::Health::diverged);
  nb::class_<adaptobs::HealthReport>(m, "HealthReport", "An observer's health(): state, the step it began, message.")
      .def_ro("state", &adaptobs::HealthReport::state)
      .def_ro("step", &adaptobs::HealthReport::step, "the step at which the run entered `state` (-1 while healthy)")
      .def_ro("message", &adaptobs::HealthReport::message, "the cause and the remedy")
      .def("__repr__", [](const adaptobs::HealthReport& r) { return "<HealthReport " + r.message + ">"; });

  adaptobs::python::bind_discrete_models(m);
  adaptobs::python::bind_discrete_observers(m);
  adaptobs::python::bind_filter_observers(m);
  adaptobs::python::bind_continuous_observers(m);
  adaptobs::python::bind_design(m);
  adaptobs::python::bind_fault_detection(m);
  adaptobs::python::bind_examples(m);
  adaptobs::python::bind_takagi_sugeno(m);
  adaptobs::python::bind_checks(m);
}
