#pragma once
// The fields of a snapshot that an observer's constructor needs, read when
// unpickling builds the observer that `restore` then fills.

#include <adaptobs/core/snapshot.hpp>
#include <adaptobs/core/validation.hpp>

#include <Eigen/Core>

#include <string>

namespace adaptobs::python {

inline Eigen::MatrixXd field(const Snapshot<double>& s, const std::string& name) {
  const SnapshotMatrix<double>* m = s.find_matrix(name);
  if (!m || static_cast<Index>(m->values.size()) != m->rows * m->cols)
    adaptobs::fail_argument("restore", "snapshot", "has no field '" + name + "'");
  return Eigen::Map<const Eigen::MatrixXd>(m->values.data(), m->rows, m->cols);
}

inline double scalar(const Snapshot<double>& s, const std::string& name) {
  const Eigen::MatrixXd m = field(s, name);
  if (m.size() != 1) adaptobs::fail_argument("restore", "snapshot", "field '" + name + "' must be a scalar");
  return m(0, 0);
}

inline Index integer(const Snapshot<double>& s, const std::string& name) {
  const SnapshotInteger* i = s.find_integer(name);
  if (!i) adaptobs::fail_argument("restore", "snapshot", "has no field '" + name + "'");
  return static_cast<Index>(i->value);
}

}  // namespace adaptobs::python
