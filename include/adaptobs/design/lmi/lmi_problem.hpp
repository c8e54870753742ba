#pragma once
/// \file
/// Linear matrix inequality problems for an SDP solver: decision variables,
/// matrices affine in them, constraints \f$G(y) \preceq -\varepsilon I\f$ and a linear
/// objective. Part of the optional `adaptobs::lmi` component.
///
/// A decision vector \f$y \in \mathbb{R}^m\f$ is declared piece by piece (scalars,
/// symmetric and full matrices); each piece is an `AffineMatrix`
/// \f$G(y) = G_0 + \sum_k y_kG_k\f$, and products with constant matrices, sums and
/// block matrices of such expressions stay affine, so LMIs are written as they
/// are printed.

#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/core/symmetric_eigenvalues.hpp>
#include <adaptobs/core/validation.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace adaptobs::lmi {

/// \f$G(y) = G_0 + \sum_k y_kG_k\f$: a constant part and one coefficient matrix per
/// decision variable it depends on (sorted by variable). A default-constructed
/// (0 × 0) expression stands for a zero block in `blocks` / `symmetric_blocks`.
class AffineMatrix {
 public:
  struct Term {
    Index variable;
    Eigen::MatrixXd coefficient;
  };

  AffineMatrix() = default;
  explicit AffineMatrix(Eigen::MatrixXd constant) : constant_(std::move(constant)) {}
  [[nodiscard]] static AffineMatrix zero(Index rows, Index cols) {
    return AffineMatrix(Eigen::MatrixXd::Zero(rows, cols));
  }
  [[nodiscard]] static AffineMatrix identity(Index n) { return AffineMatrix(Eigen::MatrixXd::Identity(n, n)); }
  /// The single decision variable k as a 1 × 1 expression, or with coefficient matrix E.
  [[nodiscard]] static AffineMatrix variable(Index k, Eigen::MatrixXd coefficient = Eigen::MatrixXd::Ones(1, 1)) {
    require(k >= 0, "AffineMatrix::variable", "k", "must be a non-negative variable index");
    AffineMatrix a(Eigen::MatrixXd::Zero(coefficient.rows(), coefficient.cols()));
    a.terms_.push_back({k, std::move(coefficient)});
    return a;
  }

  [[nodiscard]] Index rows() const noexcept { return constant_.rows(); }
  [[nodiscard]] Index cols() const noexcept { return constant_.cols(); }
  [[nodiscard]] bool empty() const noexcept { return constant_.size() == 0; }
  [[nodiscard]] const Eigen::MatrixXd& constant() const noexcept { return constant_; }
  [[nodiscard]] const std::vector<Term>& terms() const noexcept { return terms_; }

  /// \f$G(y)\f$ at a point; y needs an entry for every variable the expression uses.
  [[nodiscard]] Eigen::MatrixXd value(const Eigen::VectorXd& y) const {
    // The terms are sorted by variable: the last one has the largest index.
    require(terms_.empty() || terms_.back().variable < y.size(), "AffineMatrix::value", "y",
            "must have an entry for every variable of the expression");
    Eigen::MatrixXd m = constant_;
    for (const Term& t : terms_) m += y(t.variable) * t.coefficient;
    return m;
  }

  [[nodiscard]] AffineMatrix transpose() const {
    AffineMatrix a(constant_.transpose());
    a.terms_.reserve(terms_.size());
    for (const Term& t : terms_) a.terms_.push_back({t.variable, t.coefficient.transpose()});
    return a;
  }

  /// A 1 × 1 expression times \f$I_n\f$.
  [[nodiscard]] AffineMatrix times_identity(Index n) const {
    require(rows() == 1 && cols() == 1, "AffineMatrix::times_identity", "this", "must be 1 x 1");
    const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(n, n);
    AffineMatrix a(constant_(0, 0) * I);
    for (const Term& t : terms_) a.terms_.push_back({t.variable, t.coefficient(0, 0) * I});
    return a;
  }

  AffineMatrix& operator+=(const AffineMatrix& other) {
    check_same_shape(other, "+");
    constant_ += other.constant_;
    std::vector<Term> merged;
    merged.reserve(terms_.size() + other.terms_.size());
    auto a = terms_.begin();
    auto b = other.terms_.begin();
    while (a != terms_.end() || b != other.terms_.end()) {
      if (b == other.terms_.end() || (a != terms_.end() && a->variable < b->variable)) {
        merged.push_back(std::move(*a++));
      } else if (a == terms_.end() || b->variable < a->variable) {
        merged.push_back(*b++);
      } else {
        merged.push_back({a->variable, a->coefficient + b->coefficient});
        ++a;
        ++b;
      }
    }
    terms_ = std::move(merged);
    return *this;
  }
  AffineMatrix& operator*=(double s) {
    constant_ *= s;
    for (Term& t : terms_) t.coefficient *= s;
    return *this;
  }
  friend AffineMatrix operator+(AffineMatrix a, const AffineMatrix& b) { return a += b; }
  friend AffineMatrix operator-(AffineMatrix a) { return a *= -1.0; }
  friend AffineMatrix operator-(AffineMatrix a, const AffineMatrix& b) { return a += -b; }
  friend AffineMatrix operator+(AffineMatrix a, const Eigen::MatrixXd& b) { return a += AffineMatrix(b); }
  friend AffineMatrix operator-(AffineMatrix a, const Eigen::MatrixXd& b) { return a += AffineMatrix(-b); }
  friend AffineMatrix operator-(const Eigen::MatrixXd& a, const AffineMatrix& b) { return AffineMatrix(a) - b; }
  friend AffineMatrix operator*(double s, AffineMatrix a) { return a *= s; }
  /// Constant matrix times expression, and expression times constant matrix.
  friend AffineMatrix operator*(const Eigen::MatrixXd& m, const AffineMatrix& a) {
    require(m.cols() == a.rows(), "AffineMatrix", "operator*", "has mismatched inner dimensions");
    AffineMatrix out(m * a.constant_);
    out.terms_.reserve(a.terms_.size());
    for (const Term& t : a.terms_) out.terms_.push_back({t.variable, m * t.coefficient});
    return out;
  }
  friend AffineMatrix operator*(const AffineMatrix& a, const Eigen::MatrixXd& m) {
    require(a.cols() == m.rows(), "AffineMatrix", "operator*", "has mismatched inner dimensions");
    AffineMatrix out(a.constant_ * m);
    out.terms_.reserve(a.terms_.size());
    for (const Term& t : a.terms_) out.terms_.push_back({t.variable, t.coefficient * m});
    return out;
  }

  /// Adds `block` into the rectangle at (row, col) of this expression.
  void add_block(Index row, Index col, const AffineMatrix& block) {
    if (block.empty()) return;
    require(row >= 0 && col >= 0 && row + block.rows() <= rows() && col + block.cols() <= cols(),
            "AffineMatrix::add_block", "row, col", "must place the block inside the expression");
    constant_.block(row, col, block.rows(), block.cols()) += block.constant_;
    for (const Term& t : block.terms_) {
      auto it = std::lower_bound(terms_.begin(), terms_.end(), t.variable,
                                 [](const Term& x, Index v) { return x.variable < v; });
      if (it == terms_.end() || it->variable != t.variable)
        it = terms_.insert(it, Term{t.variable, Eigen::MatrixXd::Zero(rows(), cols())});
      it->coefficient.block(row, col, block.rows(), block.cols()) += t.coefficient;
    }
  }

 private:
  void check_same_shape(const AffineMatrix& other, const char* op) const {
    if (rows() != other.rows() || cols() != other.cols())
      fail_argument("AffineMatrix", op,
                    "needs operands of the same shape (" + std::to_string(rows()) + "x" + std::to_string(cols()) +
                        " and " + std::to_string(other.rows()) + "x" + std::to_string(other.cols()) + ")");
  }

  Eigen::MatrixXd constant_;
  std::vector<Term> terms_;
};

/// \f$\mathrm{tr}\,G(y)\f$ as a 1 × 1 expression.
[[nodiscard]] inline AffineMatrix trace(const AffineMatrix& g) {
  AffineMatrix out(Eigen::MatrixXd::Constant(1, 1, g.constant().trace()));
  for (const auto& t : g.terms())
    out += AffineMatrix::variable(t.variable, Eigen::MatrixXd::Constant(1, 1, t.coefficient.trace()));
  return out;
}

/// Block matrix from a grid of expressions; an empty (default) expression is a
/// zero block whose size comes from the other blocks of its row and column.
[[nodiscard]] inline AffineMatrix blocks(const std::vector<std::vector<AffineMatrix>>& grid) {
  constexpr const char* who = "lmi::blocks";
  const std::size_t nr = grid.size();
  const std::size_t nc = nr ? grid.front().size() : 0;
  std::vector<Index> heights(nr, -1), widths(nc, -1);
  for (std::size_t i = 0; i < nr; ++i) {
    require(grid[i].size() == nc, who, "grid", "must have rows of equal length");
    for (std::size_t j = 0; j < nc; ++j) {
      const AffineMatrix& b = grid[i][j];
      if (b.empty()) continue;
      require(heights[i] < 0 || heights[i] == b.rows(), who, "grid", "has blocks of unequal height in a row");
      require(widths[j] < 0 || widths[j] == b.cols(), who, "grid", "has blocks of unequal width in a column");
      heights[i] = b.rows();
      widths[j] = b.cols();
    }
  }
  Index rows = 0, cols = 0;
  for (Index h : heights) {
    require(h >= 0, who, "grid", "has a block row with no sized block");
    rows += h;
  }
  for (Index w : widths) {
    require(w >= 0, who, "grid", "has a block column with no sized block");
    cols += w;
  }
  AffineMatrix out = AffineMatrix::zero(rows, cols);
  Index row = 0;
  for (std::size_t i = 0; i < nr; ++i) {
    Index col = 0;
    for (std::size_t j = 0; j < nc; ++j) {
      out.add_block(row, col, grid[i][j]);
      col += widths[j];
    }
    row += heights[i];
  }
  return out;
}

/// Symmetric block matrix from its upper triangle (blocks (i, j), j ≥ i); the
/// entries below the diagonal of `upper` are ignored and filled with transposes.
[[nodiscard]] inline AffineMatrix symmetric_blocks(std::vector<std::vector<AffineMatrix>> upper) {
  for (std::size_t i = 0; i < upper.size(); ++i)
    for (std::size_t j = 0; j < i && j < upper[i].size(); ++j) upper[i][j] = upper[j][i].transpose();
  return blocks(upper);
}

/// Variables, LMI constraints and a linear objective to minimise.
class LmiProblem {
 public:
  /// \f$G(y) \preceq -\varepsilon I\f$ (negative definite with margin ε ≥ 0).
  struct Constraint {
    std::string name;
    AffineMatrix G;
    double margin;
  };

  /// A new scalar variable.
  [[nodiscard]] AffineMatrix scalar(const std::string& name) {
    names_.push_back(name);
    return AffineMatrix::variable(variable_count_++);
  }
  /// A new symmetric n × n matrix variable (n(n+1)/2 scalars).
  [[nodiscard]] AffineMatrix symmetric(const std::string& name, Index n) {
    AffineMatrix a = AffineMatrix::zero(n, n);
    for (Index r = 0; r < n; ++r) {
      for (Index c = 0; c <= r; ++c) {
        Eigen::MatrixXd e = Eigen::MatrixXd::Zero(n, n);
        e(r, c) = e(c, r) = 1.0;
        names_.push_back(name + "(" + std::to_string(r) + "," + std::to_string(c) + ")");
        a += AffineMatrix::variable(variable_count_++, std::move(e));
      }
    }
    return a;
  }
  /// A new full rows × cols matrix variable.
  [[nodiscard]] AffineMatrix full(const std::string& name, Index rows, Index cols) {
    AffineMatrix a = AffineMatrix::zero(rows, cols);
    for (Index r = 0; r < rows; ++r) {
      for (Index c = 0; c < cols; ++c) {
        Eigen::MatrixXd e = Eigen::MatrixXd::Zero(rows, cols);
        e(r, c) = 1.0;
        names_.push_back(name + "(" + std::to_string(r) + "," + std::to_string(c) + ")");
        a += AffineMatrix::variable(variable_count_++, std::move(e));
      }
    }
    return a;
  }

  /// \f$G(y) \preceq -\varepsilon I\f$; G must be square (it is symmetrized).
  void require_negative_definite(const std::string& name, const AffineMatrix& G, double margin = 0) {
    add(name, G, margin);
  }
  /// \f$G(y) \succeq \varepsilon I\f$.
  void require_positive_definite(const std::string& name, const AffineMatrix& G, double margin = 0) {
    add(name, -G, margin);
  }
  /// Minimise the 1 × 1 expression `objective` (its constant part is ignored).
  void minimize(const AffineMatrix& objective) {
    require(objective.rows() == 1 && objective.cols() == 1, "LmiProblem::minimize", "objective", "must be 1 x 1");
    objective_ = objective;
  }

  [[nodiscard]] Index variable_count() const noexcept { return variable_count_; }
  [[nodiscard]] const std::vector<std::string>& variable_names() const noexcept { return names_; }
  [[nodiscard]] const std::vector<Constraint>& constraints() const noexcept { return constraints_; }
  /// c of the objective \f$\min c^Ty\f$ (zero when none was set).
  [[nodiscard]] Eigen::VectorXd objective() const {
    Eigen::VectorXd c = Eigen::VectorXd::Zero(variable_count_);
    for (const auto& t : objective_.terms()) c(t.variable) = t.coefficient(0, 0);
    return c;
  }

  /// \f$\max_j \lambda_{\max}(G_j(y))\f$: negative iff y satisfies every constraint strictly (the
  /// margins ε only help a solver land strictly inside).
  [[nodiscard]] double largest_eigenvalue(const Eigen::VectorXd& y) const {
    require_shape(y, variable_count_, 1, "LmiProblem::largest_eigenvalue", "y");
    double worst = -std::numeric_limits<double>::infinity();
    for (const Constraint& c : constraints_) {
      const Eigen::MatrixXd g = c.G.value(y);
      if (!g.allFinite()) return std::numeric_limits<double>::infinity();
      const Eigen::MatrixXd s = 0.5 * (g + g.transpose());
      const double top = symmetric_eigenvalues(s).maxCoeff();
      worst = std::max(worst, top);
    }
    return worst;
  }

 private:
  void add(const std::string& name, const AffineMatrix& G, double margin) {
    constexpr const char* who = "LmiProblem";
    require(G.rows() == G.cols() && G.rows() > 0, who, "G", "must be a non-empty square matrix");
    require(std::isfinite(margin) && margin >= 0, who, "margin", "must be finite and non-negative");
    for (const auto& t : G.terms())
      require(t.variable >= 0 && t.variable < variable_count_, who, "G", "uses a variable of another problem");
    constraints_.push_back({name, G, margin});
  }

  Index variable_count_ = 0;
  std::vector<std::string> names_;
  std::vector<Constraint> constraints_;
  AffineMatrix objective_ = AffineMatrix::zero(1, 1);
};

}  // namespace adaptobs::lmi
