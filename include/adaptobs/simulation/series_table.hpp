#pragma once
/// \file
/// Column table of simulated series, written as CSV.
///
/// Rows are built with `begin_row()` followed by `add(...)` calls; the first
/// row fixes the columns (a vector added as `"xhat"` becomes `xhat_1..xhat_n`,
/// 1-based), every later row must add the same columns in the same order.
/// Numbers are written in shortest round-trip form; non-finite values as
/// `nan`, `inf` and `-inf`.

#include <Eigen/Core>

#include <charconv>
#include <cstddef>
#include <fstream>
#include <limits>
#include <ostream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace adaptobs {

class SeriesTable {
 public:
  /// Starts a new row; the previous one must be complete.
  SeriesTable& begin_row() {
    if (rows_ > 0 && cursor_ != names_.size())
      throw std::logic_error("SeriesTable: row " + std::to_string(rows_ - 1) + " has " + std::to_string(cursor_) +
                             " values, the header has " + std::to_string(names_.size()));
    ++rows_;
    cursor_ = 0;
    return *this;
  }

  /// Adds one value under column `name`.
  SeriesTable& add(std::string_view name, double value) {
    push(name, value);
    return *this;
  }

  /// Adds a vector (or matrix, column-major) under columns `name_1`, `name_2`, ...
  template <class Derived>
  SeriesTable& add(std::string_view name, const Eigen::DenseBase<Derived>& values) {
    const auto& v = values.derived();
    // Built by resize and append: GCC 12 reports a false -Wrestrict on
    // std::string::assign(string_view) once this loop is inlined.
    std::string column(name);
    column += '_';
    const std::size_t stem = column.size();
    for (Eigen::Index i = 0; i < v.size(); ++i) {
      column.resize(stem);
      column += std::to_string(i + 1);
      push(column, static_cast<double>(v.reshaped()(i)));
    }
    return *this;
  }

  [[nodiscard]] std::size_t rows() const noexcept { return rows_; }
  [[nodiscard]] std::size_t columns() const noexcept { return names_.size(); }
  [[nodiscard]] const std::vector<std::string>& names() const noexcept { return names_; }

  /// Value of `column` in `row`; throws `std::out_of_range` if the column does
  /// not exist or the row is not a complete one.
  [[nodiscard]] double at(std::size_t row, std::string_view column) const {
    const std::size_t c = index_of(column);
    if (row >= complete_rows())
      throw std::out_of_range("SeriesTable: no row " + std::to_string(row) + " (" + std::to_string(complete_rows()) +
                              " complete rows)");
    return values_[row * names_.size() + c];
  }

  /// All values of one column.
  [[nodiscard]] std::vector<double> column(std::string_view name) const {
    const std::size_t c = index_of(name);
    std::vector<double> out;
    out.reserve(rows_);
    for (std::size_t r = 0; r < complete_rows(); ++r) out.push_back(values_[r * names_.size() + c]);
    return out;
  }

  void write_csv(std::ostream& os) const {
    for (std::size_t c = 0; c < names_.size(); ++c) os << (c ? "," : "") << names_[c];
    os << '\n';
    char buffer[64];
    for (std::size_t r = 0; r < complete_rows(); ++r) {
      for (std::size_t c = 0; c < names_.size(); ++c) {
        if (c) os << ',';
        os << format(values_[r * names_.size() + c], buffer);
      }
      os << '\n';
    }
  }

  void write_csv(const std::string& path) const {
    std::ofstream file(path);
    if (!file) throw std::runtime_error("SeriesTable: cannot open '" + path + "' for writing");
    write_csv(file);
    file.close();  // flushes: a full disk shows here, not in a destructor that cannot report it
    if (!file) throw std::runtime_error("SeriesTable: failed writing '" + path + "'");
  }

 private:
  void push(std::string_view name, double value) {
    if (rows_ == 0) throw std::logic_error("SeriesTable: add() before begin_row()");
    if (rows_ == 1) {
      // A name the CSV header cannot hold as one field, or one already taken,
      // would shift or hide columns.
      if (name.empty() || name.find_first_of(",\"\r\n") != std::string_view::npos)
        throw std::invalid_argument("SeriesTable: column name '" + std::string(name) +
                                    "' must be non-empty, without comma, quote or line break");
      for (const std::string& taken : names_)
        if (taken == name)
          throw std::invalid_argument("SeriesTable: column '" + std::string(name) +
                                      "' appears twice in the header (give each series its own name)");
      names_.emplace_back(name);
    } else if (cursor_ >= names_.size() || names_[cursor_] != name) {
      throw std::logic_error("SeriesTable: column '" + std::string(name) + "' does not match the header at position " +
                             std::to_string(cursor_));
    }
    values_.push_back(value);
    ++cursor_;
  }

  [[nodiscard]] std::size_t complete_rows() const noexcept {
    if (names_.empty()) return 0;
    return values_.size() / names_.size();
  }

  [[nodiscard]] std::size_t index_of(std::string_view name) const {
    for (std::size_t c = 0; c < names_.size(); ++c)
      if (names_[c] == name) return c;
    throw std::out_of_range("SeriesTable: no column '" + std::string(name) + "'");
  }

  static std::string_view format(double v, char (&buffer)[64]) {
    if (v != v) return "nan";
    if (v == std::numeric_limits<double>::infinity()) return "inf";
    if (v == -std::numeric_limits<double>::infinity()) return "-inf";
    const auto result = std::to_chars(buffer, buffer + sizeof(buffer), v);
    return {buffer, static_cast<std::size_t>(result.ptr - buffer)};
  }

  std::vector<std::string> names_;
  std::vector<double> values_;
  std::size_t rows_ = 0;
  std::size_t cursor_ = 0;
};

}  // namespace adaptobs
