// Diagonal equilibration: see equilibration.hpp.
#include "equilibration.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace emnet {

namespace {

double power_of_two(double value) {
  return std::isfinite(value) && value > 0.0 ? std::exp2(std::round(std::log2(value))) : 1.0;
}

// Sinkhorn–Knopp sweeps (the 1-norm form of Ruiz's iteration) on |a| + weight·|b| (b may be
// null), updating row and column in place until every row and column sum is within 2 % of 1
// (or after `sweeps`). Its limit, the doubly stochastic scaling, is unique for a matrix with
// total support, so the result does not depend on the units the matrix came in.
void sinkhorn(const Eigen::SparseMatrix<double>& a, const Eigen::SparseMatrix<double>* b,
              double weight, Eigen::VectorXd& row, Eigen::VectorXd& column, int sweeps) {
  const Eigen::Index rows = a.rows(), columns = a.cols();
  for (int sweep = 0; sweep <= sweeps; ++sweep) {
    Eigen::VectorXd row_sum = Eigen::VectorXd::Zero(rows),
                    column_sum = Eigen::VectorXd::Zero(columns);
    auto visit = [&](const Eigen::SparseMatrix<double>& m, double factor) {
      for (int col = 0; col < m.outerSize(); ++col)
        for (Eigen::SparseMatrix<double>::InnerIterator it(m, col); it; ++it) {
          const double value = std::abs(it.value()) * factor * row[it.row()] * column[col];
          row_sum[it.row()] += value;
          column_sum[col] += value;
        }
    };
    visit(a, 1.0);
    if (b) visit(*b, weight);
    // Every non-zero sum s within 2 %: |log s| < 0.02, tested without a logarithm.
    static const double low = std::exp(-0.02), high = std::exp(0.02);
    auto balanced = [](const Eigen::VectorXd& sums) {
      for (Eigen::Index k = 0; k < sums.size(); ++k)
        if (sums[k] > 0.0 && !(sums[k] > low && sums[k] < high)) return false;
      return true;
    };
    if ((balanced(row_sum) && balanced(column_sum)) || sweep == sweeps) break;
    for (Eigen::Index k = 0; k < rows; ++k)
      if (row_sum[k] > 0.0) row[k] /= std::sqrt(row_sum[k]);
    for (Eigen::Index k = 0; k < columns; ++k)
      if (column_sum[k] > 0.0) column[k] /= std::sqrt(column_sum[k]);
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

void round_to_powers_of_two(DiagonalScaling& scaling) {
  for (double& value : scaling.row) value = power_of_two(value);
  for (double& value : scaling.column) value = power_of_two(value);
  scaling.frequency = power_of_two(scaling.frequency);
}

}  // namespace

DiagonalScaling equilibrate(const Eigen::SparseMatrix<double>& matrix) {
  DiagonalScaling scaling;
  scaling.row = Eigen::VectorXd::Ones(matrix.rows());
  scaling.column = Eigen::VectorXd::Ones(matrix.cols());
  sinkhorn(matrix, nullptr, 0.0, scaling.row, scaling.column, 200);
  round_to_powers_of_two(scaling);
  return scaling;
}

DiagonalScaling equilibrate_pencil(const Eigen::SparseMatrix<double>& a,
                                   const Eigen::SparseMatrix<double>& b, double frequency) {
  if (frequency > 0.0) {
    DiagonalScaling scaling;
    scaling.row = Eigen::VectorXd::Ones(a.rows());
    scaling.column = Eigen::VectorXd::Ones(a.cols());
    scaling.frequency = frequency;
    sinkhorn(a, &b, frequency, scaling.row, scaling.column, 200);
    round_to_powers_of_two(scaling);
    return scaling;
  }
  DiagonalScaling scaling;
  scaling.row = Eigen::VectorXd::Ones(a.rows());
  scaling.column = Eigen::VectorXd::Ones(a.cols());
  // ω₀: the weight at which the non-zero entries of Â and ω₀·B̂ of the balanced pencil have
  // the same geometric mean, found by fixed-point steps from the ratio of the plain sums (each
  // Sinkhorn run warm-started).
  double weight = 1.0;
  {
    double sum_a = 0.0, sum_b = 0.0;
    for (int col = 0; col < a.outerSize(); ++col)
      for (Eigen::SparseMatrix<double>::InnerIterator it(a, col); it; ++it)
        sum_a += std::abs(it.value());
    for (int col = 0; col < b.outerSize(); ++col)
      for (Eigen::SparseMatrix<double>::InnerIterator it(b, col); it; ++it)
        sum_b += std::abs(it.value());
    if (sum_a > 0.0 && sum_b > 0.0) weight = sum_a / sum_b;
  }
  for (int round = 0; round < 40; ++round) {
    sinkhorn(a, &b, weight, scaling.row, scaling.column, 200);
    const double mean_a = geometric_mean(a, scaling.row, scaling.column);
    const double mean_b = geometric_mean(b, scaling.row, scaling.column) * weight;
    if (!(mean_a > 0.0 && mean_b > 0.0)) break;
    const double ratio = mean_a / mean_b;
    weight *= ratio;
    if (std::abs(std::log(ratio)) < 0.05) break;
  }
  scaling.frequency = weight;
  round_to_powers_of_two(scaling);
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

double sparse_one_norm(const Eigen::SparseMatrix<double>& m) {
  double largest = 0.0;
  for (int col = 0; col < m.outerSize(); ++col) {
    double sum = 0.0;
    for (Eigen::SparseMatrix<double>::InnerIterator it(m, col); it; ++it)
      sum += std::abs(it.value());
    largest = std::max(largest, sum);
  }
  return largest;
}

}  // namespace emnet
