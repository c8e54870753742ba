#pragma once
// How the Python package reads NumPy arguments, in one place.
//
// The rule (README, "Python"): a float64 array of any layout — C- or
// F-contiguous, or a strided view — is read in place, without a copy. Anything
// else (a list, a scalar, an integer or float32 array) is converted once by
// NumPy to float64; what NumPy cannot convert is a TypeError naming the
// argument. A wrong shape is `adaptobs.ConfigurationError` naming the argument
// and both shapes, in the library's own wording.

#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/validation.hpp>

#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <atomic>
#include <complex>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace adaptobs::python {

namespace nb = nanobind;

/// A float64 array of any shape and layout, as NumPy hands it over.
using Array = nb::ndarray<const double, nb::device::cpu>;
using BoolArray = nb::ndarray<const bool, nb::device::cpu>;
using ComplexArray = nb::ndarray<const std::complex<double>, nb::device::cpu>;

/// A read-only view of a 1-D or 2-D float64 array (a 1-D one as a column).
using MatrixView = Eigen::Map<const Eigen::MatrixXd, 0, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>>;

[[noreturn]] inline void fail_type(std::string_view who, std::string_view name, nb::handle obj,
                                   std::string_view expected) {
  std::string message(who);
  message.append(": argument '").append(name).append("' must be ").append(expected).append(" (got ");
  message.append(nb::type_name(obj.type()).c_str()).append(")");
  throw nb::type_error(message.c_str());
}

/// `obj` as an array of `T`: in place when it already is one, else converted
/// once by NumPy to `dtype`. Only the kinds of number in `kinds` (NumPy's
/// dtype.kind letters) convert: a complex array is not silently made real.
template <class ArrayType>
ArrayType as_array(nb::handle obj, std::string_view who, std::string_view name, const char* dtype,
                   std::string_view expected, std::string_view kinds) {
  ArrayType array;
  if (nb::try_cast(obj, array, false)) return array;
  nb::object converted;
  try {
    const nb::object numpy = nb::module_::import_("numpy");
    converted = numpy.attr("asarray")(obj);
    const std::string kind = nb::cast<std::string>(converted.attr("dtype").attr("kind"));
    if (kind.size() != 1 || kinds.find(kind[0]) == std::string_view::npos) fail_type(who, name, obj, expected);
    converted = numpy.attr("asarray")(converted, nb::arg("dtype") = dtype);
  } catch (nb::python_error&) {
    fail_type(who, name, obj, expected);
  }
  if (!nb::try_cast(converted, array, false)) fail_type(who, name, obj, expected);
  return array;
}

/// An argument that must be an object of a bound class (a model, a design):
/// anything else is a TypeError naming the argument, not nanobind's list of overloads.
template <class T>
T& object_argument(nb::handle obj, std::string_view who, std::string_view name, std::string_view expected) {
  T* object = nullptr;
  if (!nb::try_cast<T*>(obj, object, false) || object == nullptr) fail_type(who, name, obj, expected);
  return *object;
}

inline Array real_array(nb::handle obj, std::string_view who, std::string_view name) {
  return as_array<Array>(obj, who, name, "float64", "an array of real numbers", "biuf");
}

/// "4x2", "(3,)", "(10, 4, 2)": a shape as the errors print it.
inline std::string shape_text(const std::vector<std::size_t>& shape) {
  if (shape.size() == 2) return std::to_string(shape[0]) + "x" + std::to_string(shape[1]);
  std::string text = "(";
  for (std::size_t i = 0; i < shape.size(); ++i) text += (i ? ", " : "") + std::to_string(shape[i]);
  return text + (shape.size() == 1 ? ",)" : ")");
}

template <class A>
std::vector<std::size_t> shape_of(const A& a) {
  std::vector<std::size_t> shape(a.ndim());
  for (std::size_t i = 0; i < a.ndim(); ++i) shape[i] = a.shape(i);
  return shape;
}

[[noreturn]] inline void fail_dimensions(std::string_view who, std::string_view name, std::string_view expected,
                                         const std::vector<std::size_t>& got) {
  adaptobs::fail_argument(who, name,
                          std::string("must be ") + std::string(expected) + " (got " + shape_text(got) + ")");
}

/// The view of a 0-, 1- or 2-D array (a scalar 1 × 1, a vector a column).
inline MatrixView view(const Array& a, std::string_view who, std::string_view name) {
  if (a.ndim() > 2) fail_dimensions(who, name, "a matrix", shape_of(a));
  const Index rows = a.ndim() >= 1 ? static_cast<Index>(a.shape(0)) : 1;
  const Index cols = a.ndim() == 2 ? static_cast<Index>(a.shape(1)) : 1;
  const Index row_stride = a.ndim() >= 1 ? static_cast<Index>(a.stride(0)) : 1;
  const Index col_stride = a.ndim() == 2 ? static_cast<Index>(a.stride(1)) : std::max<Index>(rows, 1);
  return MatrixView(a.data(), rows, cols, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>(col_stride, row_stride));
}

/// A real scalar argument: a Python or NumPy number, or a 0-d array (not a bool).
inline double real_scalar(nb::handle obj, std::string_view who, std::string_view name) {
  if (PyBool_Check(obj.ptr())) fail_type(who, name, obj, "a real number");
  if (PyFloat_Check(obj.ptr())) return PyFloat_AsDouble(obj.ptr());
  const Array a = real_array(obj, who, name);
  if (a.ndim() != 0) fail_dimensions(who, name, "a scalar", shape_of(a));
  return *a.data();
}

/// An integer argument: a Python or NumPy integer (not a bool, not a float).
inline Index integer_argument(nb::handle obj, std::string_view who, std::string_view name) {
  if (PyBool_Check(obj.ptr()) || !PyIndex_Check(obj.ptr())) fail_type(who, name, obj, "an integer");
  const Py_ssize_t value = PyNumber_AsSsize_t(obj.ptr(), PyExc_OverflowError);
  if (value == -1 && PyErr_Occurred()) {
    PyErr_Clear();
    adaptobs::fail_argument(who, name, "is out of range");
  }
  return static_cast<Index>(value);
}

/// A flag argument: a Python bool or a NumPy bool.
inline bool flag_argument(nb::handle obj, std::string_view who, std::string_view name) {
  if (PyBool_Check(obj.ptr())) return obj.ptr() == Py_True;
  if (nb::hasattr(obj, "dtype") && nb::hasattr(obj, "ndim") && nb::cast<int>(obj.attr("ndim")) == 0 &&
      nb::cast<std::string>(obj.attr("dtype").attr("kind")) == "b")
    return PyObject_IsTrue(obj.ptr()) == 1;
  fail_type(who, name, obj, "a bool");
}

/// A matrix argument, copied into the Eigen matrix the library stores.
inline Eigen::MatrixXd matrix(nb::handle obj, std::string_view who, std::string_view name) {
  const Array a = real_array(obj, who, name);
  return view(a, who, name);
}

/// A vector argument: a 1-D array (or a scalar, of length 1).
inline Eigen::VectorXd vector(nb::handle obj, std::string_view who, std::string_view name) {
  const Array a = real_array(obj, who, name);
  if (a.ndim() > 1) fail_dimensions(who, name, "a vector (a 1-D array)", shape_of(a));
  return view(a, who, name);
}

/// Copies a vector argument of length `n` into `out` (allocated once, by the caller).
inline void read_vector(nb::handle obj, Index n, std::string_view who, std::string_view name, Eigen::VectorXd& out) {
  const Array a = real_array(obj, who, name);
  if (a.ndim() > 1 || (a.ndim() == 1 ? static_cast<Index>(a.shape(0)) : 1) != n)
    fail_dimensions(who, name, "(" + std::to_string(n) + ",)", shape_of(a));
  out = view(a, who, name);
}

/// Copies an rows × cols matrix argument into `out`.
inline void read_matrix(nb::handle obj, Index rows, Index cols, std::string_view who, std::string_view name,
                        Eigen::MatrixXd& out) {
  const Array a = real_array(obj, who, name);
  if (a.ndim() != 2 || static_cast<Index>(a.shape(0)) != rows || static_cast<Index>(a.shape(1)) != cols)
    fail_dimensions(who, name, std::to_string(rows) + "x" + std::to_string(cols), shape_of(a));
  out = view(a, who, name);
}

/// A complex vector (poles): real or complex input, converted once to complex128.
inline Eigen::VectorXcd complex_vector(nb::handle obj, std::string_view who, std::string_view name) {
  const auto a = as_array<ComplexArray>(obj, who, name, "complex128", "an array of numbers", "biufc");
  if (a.ndim() > 1) fail_dimensions(who, name, "a vector (a 1-D array)", shape_of(a));
  const Index n = a.ndim() == 1 ? static_cast<Index>(a.shape(0)) : 1;
  const Index stride = a.ndim() == 1 ? static_cast<Index>(a.stride(0)) : 1;
  return Eigen::Map<const Eigen::VectorXcd, 0, Eigen::InnerStride<>>(a.data(), n, Eigen::InnerStride<>(stride));
}

/// A new NumPy array of `shape`, C order, filled by the caller through `data`.
template <class T>
struct NewArray {
  T* data = nullptr;
  nb::ndarray<nb::numpy, T> array;

  explicit NewArray(std::vector<std::size_t> shape) {
    std::size_t size = 1;
    for (std::size_t n : shape) size *= n;
    data = new T[size > 0 ? size : 1];
    nb::capsule owner(data, [](void* p) noexcept { delete[] static_cast<T*>(p); });
    array = nb::ndarray<nb::numpy, T>(data, shape.size(), shape.data(), owner);
  }
};

using OutputArray = NewArray<double>;

/// The status of each sample (UpdateStatus values).
struct StatusArray : NewArray<std::int8_t> {
  explicit StatusArray(std::size_t n) : NewArray<std::int8_t>({n}) {}
};

/// A list of runs, each an N_r x n array (row k: the vector at sample k), as vectors.
inline std::vector<std::vector<Eigen::VectorXd>> vector_runs(nb::handle obj, std::string_view who,
                                                             std::string_view name) {
  if (!nb::isinstance<nb::sequence>(obj) || nb::isinstance<nb::str>(obj))
    fail_type(who, name, obj, "a list of arrays, one per run (N_r x n)");
  std::vector<std::vector<Eigen::VectorXd>> runs;
  std::size_t r = 0;
  for (nb::handle run : obj) {
    const std::string element = detail::element_name(name, r++);
    const Array a = real_array(run, who, element);
    if (a.ndim() != 2) fail_dimensions(who, element, "an N x n array", shape_of(a));
    const MatrixView m = view(a, who, element);
    std::vector<Eigen::VectorXd>& values = runs.emplace_back();
    values.reserve(static_cast<std::size_t>(m.rows()));
    for (Index k = 0; k < m.rows(); ++k) values.emplace_back(m.row(k).transpose());
  }
  return runs;
}

/// (nx, nu, ny, np), as the `sizes` properties give them.
inline nb::tuple sizes_tuple(const Sizes& s) { return nb::make_tuple(s.nx, s.nu, s.ny, s.np); }

/// The three matrices a Python function of a model returned, as the tuple (A, B, C).
inline std::array<nb::object, 3> system_tuple(const nb::object& result, std::string_view who, std::string_view name) {
  nb::tuple abc;
  if (!nb::try_cast(result, abc, false) || abc.size() != 3) fail_type(who, name, result, "a tuple (A, B, C)");
  return {abc[0], abc[1], abc[2]};
}

/// Runs `loop` on `object`; if it throws (a Python function it calls raised),
/// `object` is put back as it was before, and the exception goes on.
template <class T, class Loop>
void all_or_nothing(T& object, Loop&& loop) {
  T before = object;
  try {
    loop();
  } catch (...) {
    object = std::move(before);
    throw;
  }
}

/// Column j of a 2-D array, as a view.
inline nb::object column(nb::handle array, std::size_t j) {
  return array[nb::make_tuple(nb::slice(nb::none(), nb::none(), nb::none()), j)];
}

/// Marks an object in use by a call that runs with the GIL released: another
/// thread's call on the same object is then a RuntimeError rather than a data
/// race. Held by every call that changes the object.
class InUse {
 public:
  InUse(std::atomic<bool>& flag, std::string_view who) : flag_(flag) {
    if (flag_.exchange(true)) {
      std::string message(who);
      message += ": the object is in use by a call on another thread (one object, one thread at a time)";
      throw std::runtime_error(message);
    }
  }
  InUse(const InUse&) = delete;
  InUse& operator=(const InUse&) = delete;
  ~InUse() { flag_ = false; }

 private:
  std::atomic<bool>& flag_;
};

/// The flag of `InUse`, which a copied or moved object does not inherit.
struct UseFlag {
  mutable std::atomic<bool> flag{false};
  UseFlag() = default;
  UseFlag(const UseFlag&) noexcept {}
  UseFlag& operator=(const UseFlag&) noexcept { return *this; }
};

}  // namespace adaptobs::python
