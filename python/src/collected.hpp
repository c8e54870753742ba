#pragma once
// Cyclic garbage collection of the bound objects that hold Python objects (a
// model's regressor, matrices or premise function, and so every observer on
// it). A function defined at module level holds that module's globals, where
// the object may itself be stored. Python breaks such a cycle only if the C++
// object reports the references it holds (tp_traverse) and drops them on
// request (tp_clear); otherwise it lives until exit, when nanobind reports it.

#include <nanobind/nanobind.h>

namespace adaptobs::python {

/// The type slots of a bound type T. `GetModel{}(t)` is the model that holds the
/// references; `traverse_python(model, visit, arg)` and `clear_python(model)`,
/// found beside the model's type, visit and drop them.
template <class T, class GetModel>
struct CollectedReferences {
  static int traverse(PyObject* self, visitproc visit, void* arg) {
    Py_VISIT(Py_TYPE(self));
    if (!nanobind::inst_ready(self)) return 0;
    return traverse_python(GetModel{}(*nanobind::inst_ptr<T>(self)), visit, arg);
  }
  static int clear(PyObject* self) {
    if (nanobind::inst_ready(self)) clear_python(GetModel{}(*nanobind::inst_ptr<T>(self)));
    return 0;
  }
  static inline PyType_Slot slots[] = {{Py_tp_traverse, reinterpret_cast<void*>(&traverse)},
                                       {Py_tp_clear, reinterpret_cast<void*>(&clear)},
                                       {0, nullptr}};
};

/// GetModel of a model type itself, and of an observer's Python object.
struct ModelItself {
  template <class M>
  const M& operator()(const M& model) const {
    return model;
  }
};
struct ModelOfObserver {
  template <class B>
  const auto& operator()(const B& bound) const {
    return bound.observer.model();
  }
};

}  // namespace adaptobs::python
