// Diagonal equilibration: see equilibration.hpp.
#include "equilibration.hpp"

#include <algorithm>
#include <cmath>

namespace emnet {

namespace {

constexpr int ruiz_sweeps = 12;  // the largest row/column entry is within 2 of 1 after a few

double power_of_two(double value) {
  return std::isfinite(value) && value > 0.0 ? std::exp2(std::round(std::log2(value))) : 1.0;
}

// Ruiz sweeps on |a| + weight·|b| (b may be empty), updating row and column in place.
void ruiz(const Eigen::SparseMatrix<double>& a, const Eigen::SparseMatrix<double>* b, double weight,
          Eigen::VectorXd& row, Eigen::VectorXd& column) {
  const Eigen::Index rows = a.rows(), columns = a.cols();
  for (int sweep = 0; sweep < ruiz_sweeps; ++sweep) {
    Eigen::VectorXd row_max = Eigen::VectorXd::Zero(rows),
                    column_max = Eigen::VectorXd::Zero(columns);
    auto visit = [&](const Eigen::SparseMatrix<double>& m, double factor) {
      for (int col = 0; col < m.outerSize(); ++col)
        for (Eigen::SparseMatrix<double>::InnerIterator it(m, col); it; ++it) {
          const double value = std::abs(it.value()) * factor * row[it.row()] * column[col];
          row_max[it.row()] = std::max(row_max[it.row()], value);
          column_max[col] = std::max(column_max[col], value);
        }
    };
    visit(a, 1.0);
    if (b) visit(*b, weight);
    bool changed = false;
    for (Eigen::Index k = 0; k < rows; ++k) {
      const double factor = power_of_two(1.0 / std::sqrt(row_max[k]));
      changed = changed || factor != 1.0;
      row[k] *= factor;
    }
    for (Eigen::Index k = 0; k < columns; ++k) {
      const double factor = power_of_two(1.0 / std::sqrt(column_max[k]));
      changed = changed || factor != 1.0;
      column[k] *= factor;
    }
    if (!changed) break;
  }
}

// exp(mean(log|entries|)) of diag(row)·m·diag(column); 0 when m has no non-zero entry.
double geometric_mean(const Eigen::SparseMatrix<double>& m, const Eigen::VectorXd& row,
                      const Eigen::VectorXd& column) {
  double sum = 0.0;
  long count = 0;
  for (int col = 0; col < m.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(m, col); it; ++it)
      if (it.value() != 0.0) {
        sum += std::log(std::abs(it.value()) * row[it.row()] * column[col]);
        ++count;
      }
  return count > 0 ? std::exp(sum / static_cast<double>(count)) : 0.0;
}

}  // namespace

DiagonalScaling equilibrate(const Eigen::SparseMatrix<double>& matrix) {
  DiagonalScaling scaling;
  scaling.row = Eigen::VectorXd::Ones(matrix.rows());
  scaling.column = Eigen::VectorXd::Ones(matrix.cols());
  ruiz(matrix, nullptr, 0.0, scaling.row, scaling.column);
  return scaling;
}

DiagonalScaling equilibrate_pencil(const Eigen::SparseMatrix<double>& a,
                                   const Eigen::SparseMatrix<double>& b) {
  DiagonalScaling scaling;
  scaling.row = Eigen::VectorXd::Ones(a.rows());
  scaling.column = Eigen::VectorXd::Ones(a.cols());
  // Alternate: ω₀ from the current scaling, then Ruiz on |A| + ω₀|B|. Three rounds settle ω₀
  // to within a factor of two on the networks tried (beams of 1 to 2000 segments, DEAs).
  for (int round = 0; round < 3; ++round) {
    const double mean_a = geometric_mean(a, scaling.row, scaling.column);
    const double mean_b = geometric_mean(b, scaling.row, scaling.column);
    if (mean_a > 0.0 && mean_b > 0.0) scaling.frequency = power_of_two(mean_a / mean_b);
    ruiz(a, &b, scaling.frequency, scaling.row, scaling.column);
  }
  return scaling;
}

Eigen::SparseMatrix<double> scaled(const Eigen::SparseMatrix<double>& matrix,
                                   const DiagonalScaling& scaling, double factor) {
  Eigen::SparseMatrix<double> out = matrix;
  for (int col = 0; col < out.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(out, col); it; ++it)
      it.valueRef() *= scaling.row[it.row()] * scaling.column[col] * factor;
  return out;
}

}  // namespace emnet
