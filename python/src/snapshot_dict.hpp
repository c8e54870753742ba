#pragma once
// A C++ `Snapshot` (core/snapshot.hpp) as a Python dict and back:
//   {"type": str, "version": int, "matrices": {name: 2-D float64 array}, "integers": {name: int}}
// Plain Python and NumPy objects only, so that pickle, npz and any checkpoint
// store can hold it.

#include "arrays.hpp"

#include <adaptobs/core/snapshot.hpp>

#include <nanobind/nanobind.h>
#include <nanobind/stl/string.h>

#include <cstdint>
#include <string>

namespace adaptobs::python {

inline nb::dict to_dict(const Snapshot<double>& s) {
  nb::dict matrices;
  for (const auto& m : s.matrices) {
    OutputArray out({static_cast<std::size_t>(m.rows), static_cast<std::size_t>(m.cols)});
    // The snapshot is column-major, the array C order.
    for (Index i = 0; i < m.rows; ++i)
      for (Index j = 0; j < m.cols; ++j) out.data[i * m.cols + j] = m.values[static_cast<std::size_t>(j * m.rows + i)];
    matrices[m.name.c_str()] = out.array;
  }
  nb::dict integers;
  for (const auto& i : s.integers) integers[i.name.c_str()] = i.value;
  nb::dict d;
  d["type"] = s.type;
  d["version"] = s.version;
  d["matrices"] = matrices;
  d["integers"] = integers;
  return d;
}

inline Snapshot<double> from_dict(nb::handle obj) {
  constexpr std::string_view who = "restore";
  if (!nb::isinstance<nb::dict>(obj)) fail_type(who, "state", obj, "a dict made by snapshot()");
  const nb::dict d = nb::borrow<nb::dict>(obj);
  for (const char* key : {"type", "version", "matrices", "integers"})
    if (!d.contains(key)) adaptobs::fail_argument(who, "state", std::string("has no key '") + key + "'");
  // Each entry of the wrong type is a TypeError naming its key.
  const auto entry = [&](nb::handle value, const std::string& key, auto& out, std::string_view expected) {
    if (!nb::try_cast(value, out)) fail_type(who, "state['" + key + "']", value, expected);
  };
  Snapshot<double> s;
  entry(d["type"], "type", s.type, "a str");
  entry(d["version"], "version", s.version, "an int");
  for (const char* key : {"matrices", "integers"})
    if (!nb::isinstance<nb::dict>(d[key])) fail_type(who, std::string("state['") + key + "']", d[key], "a dict");
  for (auto [key, value] : nb::borrow<nb::dict>(d["matrices"])) {
    std::string name;
    entry(key, "matrices", name, "str keys");
    const MatrixView m = view(real_array(value, who, name), who, name);
    SnapshotMatrix<double> field{name, m.rows(), m.cols(), {}};
    field.values.resize(static_cast<std::size_t>(m.size()));
    Eigen::Map<Eigen::MatrixXd>(field.values.data(), m.rows(), m.cols()) = m;
    s.matrices.push_back(std::move(field));
  }
  for (auto [key, value] : nb::borrow<nb::dict>(d["integers"])) {
    SnapshotInteger field;
    entry(key, "integers", field.name, "str keys");
    entry(value, field.name, field.value, "an int");
    s.integers.push_back(std::move(field));
  }
  return s;
}

}  // namespace adaptobs::python
