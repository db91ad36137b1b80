// First-order pole error bounds with extended-precision residuals: see pole_bounds.hpp.
#include "pole_bounds.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "dense_decompositions.hpp"
#include "left_eigenvector.hpp"

namespace emnet {

namespace {

using Complex = std::complex<double>;
using Wide = std::complex<long double>;

// ‖(Â + ŝÊ)·x‖₂ in extended precision plus the rounding of that evaluation (header).
long double extended_residual(const Eigen::SparseMatrix<double>& a,
                              const Eigen::SparseMatrix<double>& e, Complex s,
                              const Eigen::VectorXcd& x, long double rounding) {
  const Eigen::Index n = a.rows();
  std::vector<Wide> r(static_cast<size_t>(n), Wide(0.0L, 0.0L));
  std::vector<long double> terms(static_cast<size_t>(n), 0.0L);
  const Wide wide_s(s.real(), s.imag());
  const long double abs_s = std::abs(wide_s);
  auto add = [&](const Eigen::SparseMatrix<double>& m, Eigen::Index col, const Wide& factor,
                 long double abs_factor) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(m, col); it; ++it) {
      const long double value = static_cast<long double>(it.value());
      r[static_cast<size_t>(it.row())] += factor * value;
      terms[static_cast<size_t>(it.row())] += abs_factor * std::fabs(value);
    }
  };
  for (Eigen::Index col = 0; col < n; ++col) {
    const Wide xc(x[col].real(), x[col].imag());
    add(a, col, xc, std::abs(xc));
    add(e, col, wide_s * xc, abs_s * std::abs(xc));
  }
  long double norm = 0.0L, size = 0.0L;
  for (Eigen::Index i = 0; i < n; ++i) {
    norm += std::norm(r[static_cast<size_t>(i)]);
    size += terms[static_cast<size_t>(i)] * terms[static_cast<size_t>(i)];
  }
  return std::sqrt(norm) + rounding * std::sqrt(size);
}

long most_entries(const Eigen::SparseMatrix<double>& a, const Eigen::SparseMatrix<double>& e) {
  std::vector<long> per_row(static_cast<size_t>(a.rows()), 0);
  long largest = 0;
  for (Eigen::Index col = 0; col < a.outerSize(); ++col) {
    largest = std::max<long>(largest, a.col(col).nonZeros() + e.col(col).nonZeros());
    for (Eigen::SparseMatrix<double>::InnerIterator it(a, col); it; ++it)
      ++per_row[static_cast<size_t>(it.row())];
    for (Eigen::SparseMatrix<double>::InnerIterator it(e, col); it; ++it)
      ++per_row[static_cast<size_t>(it.row())];
  }
  for (long count : per_row) largest = std::max(largest, count);
  return largest;
}

// Groups of poles within `group_width` (relative) of each group's first pole.
std::vector<std::vector<size_t>> pole_groups(const std::vector<PoleEstimate>& poles,
                                             double group_width) {
  std::vector<std::vector<size_t>> groups;
  std::vector<bool> done(poles.size(), false);
  for (size_t first = 0; first < poles.size(); ++first) {
    if (done[first]) continue;
    const double width = group_width * std::abs(poles[first].pole);
    std::vector<size_t> group;
    for (size_t k = first; k < poles.size(); ++k)
      if (!done[k] && std::abs(poles[k].pole - poles[first].pole) <= width) group.push_back(k);
    for (size_t k : group) done[k] = true;
    groups.push_back(std::move(group));
  }
  return groups;
}

// An orthonormal basis of the columns; false when they are not independent (to 1e-8).
bool orthonormal(const Eigen::MatrixXcd& columns, Eigen::MatrixXcd& basis) {
  Eigen::ColPivHouseholderQR<Eigen::MatrixXcd> qr(columns);
  qr.setThreshold(1e-8);
  if (qr.rank() < columns.cols()) return false;
  basis = qr.householderQ() * Eigen::MatrixXcd::Identity(columns.rows(), columns.cols());
  return true;
}

}  // namespace

void span_repeated_poles(const Eigen::SparseMatrix<double>& a, const Eigen::SparseMatrix<double>& e,
                         std::vector<PoleEstimate>& poles, double group_width) {
  const Eigen::SparseMatrix<double> a_transposed = a.transpose(), e_transposed = e.transpose();
  // On the transposed pencil, once it is needed: one ordering for every group.
  std::optional<LeftEigenSolver> transposed_left;
  for (const std::vector<size_t>& group : pole_groups(poles, group_width)) {
    const Eigen::Index g = static_cast<Eigen::Index>(group.size());
    if (g < 2) continue;
    Eigen::MatrixXcd right(a.rows(), g), basis;
    for (Eigen::Index j = 0; j < g; ++j) right.col(j) = poles[group[static_cast<size_t>(j)]].right;
    if (orthonormal(right, basis)) continue;
    double residual = 0.0;
    std::string why;
    const Complex centre = poles[group.front()].pole;
    // Right vectors of Â + ŝÊ are left vectors of the transposed pencil at conj(ŝ), conjugated.
    if (!transposed_left)
      transposed_left.emplace(a_transposed, e_transposed,
                              equilibrate_pencil(a_transposed, e_transposed));
    if (!transposed_left->space(std::conj(centre), static_cast<int>(g), right, residual, why) ||
        !orthonormal(right.conjugate(), basis))
      continue;  // left as they are: bound_poles then calls the group defective
    for (Eigen::Index j = 0; j < g; ++j) poles[group[static_cast<size_t>(j)]].right = basis.col(j);
  }
}

void bound_poles(const Eigen::SparseMatrix<double>& a, const Eigen::SparseMatrix<double>& e,
                 const std::vector<TransposedEigenpair>& left_pairs,
                 std::vector<PoleEstimate>& poles, double group_width, double largest_bound) {
  const long double rounding =
      static_cast<long double>(most_entries(a, e) + 2) * std::ldexp(1.0L, -64);
  const Eigen::SparseMatrix<Complex> e_complex = e.cast<Complex>();
  std::optional<LeftEigenSolver> inverse_iteration;  // once it is needed, for every group
  for (const std::vector<size_t>& group : pole_groups(poles, group_width)) {
    const Complex centre = poles[group.front()].pole;
    const double width = group_width * std::abs(centre);
    const Eigen::Index g = static_cast<Eigen::Index>(group.size());
    auto fail = [&](const std::string& reason) {
      for (size_t k : group) {
        poles[k].bounded = false;
        poles[k].reason = reason;
      }
    };
    // Orthonormal bases of the group's right and left spaces (span_repeated_poles has made the
    // right vectors of a repeated pole independent where it could). Left vectors come from the
    // transposed pencil's eigenvectors at these poles, else from inverse iteration at the
    // group's first pole ŝ_c (LeftEigenSolver). Residuals are taken at ŝ_c, so that each exact
    // pole of the group lies within the bound of ŝ_c (Bauer–Fike on the projected pencil); a
    // member's own bound adds its distance to ŝ_c.
    Eigen::MatrixXcd right(a.rows(), g), right_basis;
    for (Eigen::Index j = 0; j < g; ++j) right.col(j) = poles[group[static_cast<size_t>(j)]].right;
    if (!orthonormal(right, right_basis)) {
      fail("a group of " + std::to_string(g) +
           " equal poles with fewer independent right vectors (defective)");
      continue;
    }
    std::vector<Eigen::VectorXcd> lefts;
    for (const TransposedEigenpair& pair : left_pairs)
      if (std::abs(pair.pole - centre) <= width) lefts.push_back(pair.vector.conjugate());
    Eigen::MatrixXcd left(a.rows(), g), left_basis;
    bool have_left = static_cast<Eigen::Index>(lefts.size()) == g;
    if (have_left) {
      for (Eigen::Index j = 0; j < g; ++j) left.col(j) = lefts[static_cast<size_t>(j)];
      have_left = orthonormal(left, left_basis);
    }
    std::string why;
    double iteration_residual = 0.0;
    if (!have_left && !inverse_iteration) inverse_iteration.emplace(a, e, equilibrate_pencil(a, e));
    if (!have_left &&
        !(inverse_iteration->space(centre, static_cast<int>(g), left, iteration_residual, why) &&
          orthonormal(left, left_basis))) {
      fail(g > 1 ? "a group of " + std::to_string(g) + " equal poles with fewer independent " +
                       "left vectors (defective)" + (why.empty() ? "" : ": " + why)
                 : "no left vector (" + why + ")");
      continue;
    }
    long double residual_squares = 0.0L;
    for (Eigen::Index j = 0; j < g; ++j) {
      const long double r = extended_residual(a, e, centre, right_basis.col(j), rounding);
      residual_squares += r * r;
    }
    const Eigen::MatrixXcd coupling = left_basis.adjoint() * (e_complex * right_basis);
    const double smallest = complex_jacobi_svd(coupling, 0).singular_values[g - 1];
    if (!(smallest > 0.0) || !std::isfinite(smallest)) {
      fail(g > 1 ? "a group of " + std::to_string(g) +
                       " equal poles whose left and right spaces are E-orthogonal (defective)"
                 : "a defective pole (its left and right vectors are E-orthogonal)");
      continue;
    }
    const double group_bound = static_cast<double>(std::sqrt(residual_squares)) / smallest;
    for (size_t k : group) {
      PoleEstimate& pole = poles[k];
      pole.bound = group_bound + std::abs(pole.pole - centre);
      const double relative = pole.bound / std::abs(pole.pole);
      pole.bounded = std::isfinite(relative) && relative <= largest_bound;
      if (!pole.bounded) {
        char buffer[160];
        std::snprintf(buffer, sizeof buffer,
                      "its first-order error bound %.2g (relative) is above %.2g: the pole is too "
                      "ill-conditioned here to be bounded",
                      relative, largest_bound);
        pole.reason = buffer;
      }
    }
  }
}

}  // namespace emnet
