#pragma once
/// \file
/// The whole internal state of an observer, model or detector as named fields,
/// and its restoration, bit for bit.
///
/// A checkpointing stream processor, `copy.deepcopy` and `pickle` in Python,
/// and a controller that resumes after a power cycle all need the same thing:
/// every number the next update reads — model, gains, estimates, filtered
/// regressors, covariances, counters, the windows of the monitors — written out
/// and read back so that the restored object continues exactly like the
/// original. A class opts in with two constants and one member template that
/// lists its fields once, for writing and for reading (the `Archive` is a
/// `SnapshotWriter` or a `SnapshotReader`):
///
/// \code
///   static constexpr std::string_view snapshot_type = "GuyaderZhangObserver";
///   static constexpr int snapshot_version = 1;
///   template <class Self, class Archive>
///   static void visit_state(Self& self, Archive& archive) {
///     archive("x", self.x_);                // a matrix, a scalar, a counter or a flag
///     archive.setting("window", w);        // configuration: must agree to restore
///     archive.object("model", self.model_);  // a member with a visit_state of its own
///   }
/// \endcode
///
/// `snapshot(object)` gives a `Snapshot`; `restore(object, snapshot)` reads one
/// back into an object of the same class, version and configuration (sizes and
/// settings), or throws `ConfigurationError` naming the first field that
/// disagrees, with the object unchanged (the fields are read into a copy,
/// which then replaces the object). A class may check the values it reads as
/// well (`Archive::reading`). Scratch space is not part of the state: it is overwritten before
/// it is read.

#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/validation.hpp>

#include <Eigen/Core>

#include <concepts>
#include <cstdint>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

namespace adaptobs {

/// One floating-point field of a snapshot: a matrix in column-major order (a
/// scalar is 1 × 1).
template <typename Scalar>
struct SnapshotMatrix {
  std::string name;
  Index rows = 0;
  Index cols = 0;
  std::vector<Scalar> values;
};

/// One integer field: a counter, an index, a flag (0 or 1) or a setting.
struct SnapshotInteger {
  std::string name;
  std::int64_t value = 0;
};

/// The state of one object: its class, the version of its field list, and the fields.
template <typename Scalar>
struct Snapshot {
  std::string type;
  int version = 0;
  std::vector<SnapshotMatrix<Scalar>> matrices;
  std::vector<SnapshotInteger> integers;

  [[nodiscard]] const SnapshotMatrix<Scalar>* find_matrix(std::string_view name) const {
    for (const auto& m : matrices)
      if (m.name == name) return &m;
    return nullptr;
  }
  [[nodiscard]] const SnapshotInteger* find_integer(std::string_view name) const {
    for (const auto& i : integers)
      if (i.name == name) return &i;
    return nullptr;
  }
};

namespace detail {
// The scalar of a snapshottable class: its `SnapshotScalar` where its
// template parameter is itself named `Scalar`, else its `Scalar`.
template <class T>
struct snapshot_scalar {
  using type = typename T::Scalar;
};
template <class T>
  requires requires { typename T::SnapshotScalar; }
struct snapshot_scalar<T> {
  using type = typename T::SnapshotScalar;
};
}  // namespace detail

template <class T>
using snapshot_scalar_t = typename detail::snapshot_scalar<T>::type;

/// A class whose state `snapshot` and `restore` can write and read.
template <class T>
concept Snapshottable = requires {
  { T::snapshot_type } -> std::convertible_to<std::string_view>;
  { T::snapshot_version } -> std::convertible_to<int>;
};

namespace detail {

template <class T>
concept SnapshotEigen = std::derived_from<T, Eigen::PlainObjectBase<T>>;

template <class T>
concept SnapshotIntegral = std::integral<T> || std::is_enum_v<T>;

// Field names of a nested object carry its prefix: "excitation.sum".
class SnapshotArchiveBase {
 public:
  explicit SnapshotArchiveBase(std::string prefix) : prefix_(std::move(prefix)) {}

 protected:
  [[nodiscard]] std::string full_name(std::string_view name) const {
    std::string full = prefix_;
    full.append(name);
    return full;
  }
  [[nodiscard]] std::string nested_prefix(std::string_view name) const { return full_name(name) + "."; }

 private:
  std::string prefix_;
};

}  // namespace detail

/// The archive a `visit_state` is shown by `snapshot`: writes every field it
/// is shown into a snapshot.
template <typename Scalar>
class SnapshotWriter : public detail::SnapshotArchiveBase {
 public:
  explicit SnapshotWriter(Snapshot<Scalar>& out, std::string prefix = {})
      : SnapshotArchiveBase(std::move(prefix)), out_(out) {}

  /// Writes `field` (a matrix, a scalar, a counter, a flag or an enumerator) as `name`.
  template <class T>
  void operator()(std::string_view name, const T& field) {
    if constexpr (detail::SnapshotEigen<T>) {
      SnapshotMatrix<Scalar> m{full_name(name), field.rows(), field.cols(), {}};
      m.values.resize(static_cast<std::size_t>(field.size()));
      Eigen::Map<T>(m.values.data(), field.rows(), field.cols()) = field;
      out_.matrices.push_back(std::move(m));
    } else if constexpr (std::floating_point<T>) {
      out_.matrices.push_back({full_name(name), 1, 1, {static_cast<Scalar>(field)}});
    } else if constexpr (detail::SnapshotIntegral<T>) {
      add_integer(full_name(name), static_cast<std::int64_t>(field));
    } else {
      static_assert(sizeof(T) == 0, "adaptobs: a snapshot field must be a matrix, a scalar or an integer");
    }
  }

  /// A list of matrices: its length as a setting, then each element as "name[i]".
  template <class T>
  void operator()(std::string_view name, const std::vector<T>& list) {
    add_integer(full_name(name) + ".size", static_cast<std::int64_t>(list.size()));
    for (std::size_t i = 0; i < list.size(); ++i) (*this)(detail::element_name(name, i), list[i]);
  }

  /// Configuration that fixes the shape of the rest (a window length, an option).
  void setting(std::string_view name, std::int64_t value) { add_integer(full_name(name), value); }

  /// The archive for the fields of a member object, named "name.field".
  [[nodiscard]] SnapshotWriter nested(std::string_view name) const { return SnapshotWriter(out_, nested_prefix(name)); }

  /// The fields of a member object with a `visit_state` of its own, under "name.".
  template <class T>
  void object(std::string_view name, const T& member) {
    SnapshotWriter archive = nested(name);
    T::visit_state(member, archive);
  }

  /// False: nothing is read, so a `visit_state` has nothing to check.
  static constexpr bool reading = false;

 private:
  void add_integer(std::string full, std::int64_t value) { out_.integers.push_back({std::move(full), value}); }
  Snapshot<Scalar>& out_;
};

/// The archive a `visit_state` is shown by `restore`: reads the fields back,
/// each checked to exist with the object's shape, and the settings to agree.
template <typename Scalar>
class SnapshotReader : public detail::SnapshotArchiveBase {
 public:
  explicit SnapshotReader(const Snapshot<Scalar>& in, std::string prefix = {})
      : SnapshotArchiveBase(std::move(prefix)), in_(in) {}

  /// Reads the field `name` into `field`, which keeps its shape.
  template <class T>
  void operator()(std::string_view name, T& field) {
    const std::string full = full_name(name);
    if constexpr (detail::SnapshotEigen<T>) {
      const SnapshotMatrix<Scalar>& m = matrix(full);
      if (m.rows != field.rows() || m.cols != field.cols() || static_cast<Index>(m.values.size()) != m.rows * m.cols)
        fail_field_shape(full, m.rows, m.cols, field.rows(), field.cols());
      field = Eigen::Map<const T>(m.values.data(), m.rows, m.cols);
    } else if constexpr (std::floating_point<T>) {
      const SnapshotMatrix<Scalar>& m = matrix(full);
      if (m.rows != 1 || m.cols != 1 || m.values.size() != 1) fail_field_shape(full, m.rows, m.cols, 1, 1);
      field = static_cast<T>(m.values.front());
    } else if constexpr (detail::SnapshotIntegral<T>) {
      field = static_cast<T>(integer(full));
    } else {
      static_assert(sizeof(T) == 0, "adaptobs: a snapshot field must be a matrix, a scalar or an integer");
    }
  }

  /// A list of matrices, of the length it already has.
  template <class T>
  void operator()(std::string_view name, std::vector<T>& list) {
    check_setting(full_name(name) + ".size", static_cast<std::int64_t>(list.size()));
    for (std::size_t i = 0; i < list.size(); ++i) (*this)(detail::element_name(name, i), list[i]);
  }

  /// Configuration, which must agree with the snapshot's.
  void setting(std::string_view name, std::int64_t value) { check_setting(full_name(name), value); }

  /// Whether the snapshot holds the field `name`: for fields that a later
  /// version writes only when an option is on, so that earlier snapshots still restore.
  [[nodiscard]] bool contains(std::string_view name) const {
    const std::string full = full_name(name);
    return in_.find_matrix(full) != nullptr || in_.find_integer(full) != nullptr;
  }

  /// The archive for the fields of a member object, named "name.field".
  [[nodiscard]] SnapshotReader nested(std::string_view name) const { return SnapshotReader(in_, nested_prefix(name)); }

  /// The fields of a member object with a `visit_state` of its own, under "name.".
  template <class T>
  void object(std::string_view name, T& member) {
    SnapshotReader archive = nested(name);
    T::visit_state(member, archive);
  }

  /// True: the fields have just been read, and a `visit_state` may check them.
  static constexpr bool reading = true;

 private:
  const SnapshotMatrix<Scalar>& matrix(const std::string& full) const {
    const SnapshotMatrix<Scalar>* m = in_.find_matrix(full);
    if (!m) fail_argument("restore", "snapshot", "has no field '" + full + "'");
    return *m;
  }
  std::int64_t integer(const std::string& full) const {
    const SnapshotInteger* i = in_.find_integer(full);
    if (!i) fail_argument("restore", "snapshot", "has no field '" + full + "'");
    return i->value;
  }
  [[noreturn]] void fail_field_shape(const std::string& full, Index rows, Index cols, Index own_rows,
                                     Index own_cols) const {
    detail::Message os;
    os << "holds field '" << full << "' of " << rows << "x" << cols << " where this " << in_.type << " has " << own_rows
       << "x" << own_cols;
    fail_argument("restore", "snapshot", os.str());
  }
  void check_setting(const std::string& full, std::int64_t value) const {
    const std::int64_t stored = integer(full);
    if (stored != value) {
      detail::Message os;
      os << "holds '" << full << "' = " << stored << " where this " << in_.type << " has " << value
         << ": restore into an object built with the same configuration";
      fail_argument("restore", "snapshot", os.str());
    }
  }
  const Snapshot<Scalar>& in_;
};

/// The state of `object`, every field the next update reads.
template <Snapshottable T>
[[nodiscard]] Snapshot<snapshot_scalar_t<T>> snapshot(const T& object) {
  Snapshot<snapshot_scalar_t<T>> out;
  out.type = std::string(T::snapshot_type);
  out.version = T::snapshot_version;
  SnapshotWriter<snapshot_scalar_t<T>> writer(out);
  T::visit_state(object, writer);
  return out;
}

namespace detail {
/// Refuses a snapshot of another class than T, or of another version of its fields.
template <Snapshottable T>
void require_snapshot_type(const Snapshot<snapshot_scalar_t<T>>& state) {
  if (state.type != T::snapshot_type)
    fail_argument("restore", "snapshot", "is of a " + state.type + ", not of a " + std::string(T::snapshot_type));
  if (state.version != T::snapshot_version) {
    Message os;
    os << "is version " << state.version << " of " << state.type << "; this build reads version "
       << T::snapshot_version;
    fail_argument("restore", "snapshot", os.str());
  }
}
}  // namespace detail

/// Makes `object` continue exactly as the object `state` was taken from: its
/// model, gains and estimates are all replaced. Throws `ConfigurationError`,
/// leaving `object` unchanged, for a snapshot of another class or version, a
/// missing field, or a field whose shape or setting differs from `object`'s
/// (restore into an object constructed with the same sizes and options).
template <Snapshottable T>
void restore(T& object, const Snapshot<snapshot_scalar_t<T>>& state) {
  detail::require_snapshot_type<T>(state);
  // Read into a copy, so that a failure at any field leaves `object` as it was.
  T candidate(object);
  SnapshotReader<snapshot_scalar_t<T>> reader(state);
  T::visit_state(candidate, reader);
  object = std::move(candidate);
}

}  // namespace adaptobs
