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
#include <complex>
#include <cstdint>
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

/// `obj` as an array of `T`: in place when it already is one, else through
/// `numpy.asarray(obj, dtype)` once.
template <class ArrayType>
ArrayType as_array(nb::handle obj, std::string_view who, std::string_view name, const char* dtype,
                   std::string_view expected) {
  ArrayType array;
  if (nb::try_cast(obj, array, false)) return array;
  nb::object converted;
  try {
    converted = nb::module_::import_("numpy").attr("asarray")(obj, nb::arg("dtype") = dtype);
  } catch (nb::python_error&) {
    fail_type(who, name, obj, expected);
  }
  if (!nb::try_cast(converted, array, false)) fail_type(who, name, obj, expected);
  return array;
}

inline Array real_array(nb::handle obj, std::string_view who, std::string_view name) {
  return as_array<Array>(obj, who, name, "float64", "an array of real numbers");
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
  detail::fail_argument(who, name, std::string("must be ") + std::string(expected) + " (got " + shape_text(got) + ")");
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
  const auto a = as_array<ComplexArray>(obj, who, name, "complex128", "an array of numbers");
  if (a.ndim() > 1) fail_dimensions(who, name, "a vector (a 1-D array)", shape_of(a));
  const Index n = a.ndim() == 1 ? static_cast<Index>(a.shape(0)) : 1;
  const Index stride = a.ndim() == 1 ? static_cast<Index>(a.stride(0)) : 1;
  return Eigen::Map<const Eigen::VectorXcd, 0, Eigen::InnerStride<>>(a.data(), n, Eigen::InnerStride<>(stride));
}

/// A new float64 NumPy array of `shape`, C order, filled by the caller through `data`.
struct OutputArray {
  double* data = nullptr;
  nb::ndarray<nb::numpy, double> array;

  explicit OutputArray(std::vector<std::size_t> shape) {
    std::size_t size = 1;
    for (std::size_t n : shape) size *= n;
    data = new double[size > 0 ? size : 1];
    nb::capsule owner(data, [](void* p) noexcept { delete[] static_cast<double*>(p); });
    array = nb::ndarray<nb::numpy, double>(data, shape.size(), shape.data(), owner);
  }
};

/// A new int8 NumPy array (the status of each sample).
struct StatusArray {
  std::int8_t* data = nullptr;
  nb::ndarray<nb::numpy, std::int8_t> array;

  explicit StatusArray(std::size_t n) {
    data = new std::int8_t[n > 0 ? n : 1];
    nb::capsule owner(data, [](void* p) noexcept { delete[] static_cast<std::int8_t*>(p); });
    const std::size_t shape[1] = {n};
    array = nb::ndarray<nb::numpy, std::int8_t>(data, 1, shape, owner);
  }
};

}  // namespace adaptobs::python
