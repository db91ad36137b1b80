// Diagonal equilibration: see equilibration.hpp.
#include "equilibration.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <optional>
#include <vector>

namespace emnet {

namespace {

double power_of_two(double value) {
  return std::isfinite(value) && value > 0.0 ? std::exp2(std::round(std::log2(value))) : 1.0;
}

// Sums within 2 % of 1: the balance every scaling is taken to.
constexpr double kBalanced = 0.02;

// Sinkhorn–Knopp sweeps (the 1-norm form of Ruiz's iteration) on |a| + weight·|b| (b may be
// null), updating row and column in place until every row and column sum is within `within`
// of 1 in log (or after `sweeps`). Its limit, the doubly stochastic scaling, is unique for a
// matrix with total support, so the result does not depend on the units the matrix came in.
void sinkhorn(const Eigen::SparseMatrix<double>& a, const Eigen::SparseMatrix<double>* b,
              double weight, Eigen::VectorXd& row, Eigen::VectorXd& column, int sweeps,
              double within = kBalanced) {
  const Eigen::Index rows = a.rows(), columns = a.cols();
  // |a_ij| and |b_ij|·weight once, column by column in the iterators' order: each sum takes the
  // same products in the same order as entry by entry through the iterators, so the same values,
  // at a fraction of the time (the fish fin at N = 10 000: hundreds of sweeps).
  struct Magnitudes {
    std::vector<int> start{0}, row;  // entries of column j: start[j] … start[j + 1]
    std::vector<double> value;
  };
  auto magnitudes = [](const Eigen::SparseMatrix<double>& m, double factor) {
    Magnitudes out;
    out.start.reserve(static_cast<size_t>(m.outerSize()) + 1);
    out.row.reserve(static_cast<size_t>(m.nonZeros()));
    out.value.reserve(static_cast<size_t>(m.nonZeros()));
    for (int col = 0; col < m.outerSize(); ++col) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(m, col); it; ++it) {
        out.row.push_back(static_cast<int>(it.row()));
        out.value.push_back(std::abs(it.value()) * factor);
      }
      out.start.push_back(static_cast<int>(out.row.size()));
    }
    return out;
  };
  std::vector<Magnitudes> parts{magnitudes(a, 1.0)};
  if (b) parts.push_back(magnitudes(*b, weight));
  Eigen::VectorXd row_sum(rows), column_sum(columns);  // made once, cleared each sweep
  for (int sweep = 0; sweep <= sweeps; ++sweep) {
    row_sum.setZero();
    column_sum.setZero();
    for (const Magnitudes& part : parts) {
      const int* start = part.start.data();
      const int* inner = part.row.data();
      const double* magnitude = part.value.data();
      for (Eigen::Index col = 0; col < columns; ++col) {
        const double scale = column[col];
        double sum = column_sum[col];
        for (int k = start[col]; k < start[col + 1]; ++k) {
          const double value = magnitude[k] * row[inner[k]] * scale;
          row_sum[inner[k]] += value;
          sum += value;
        }
        column_sum[col] = sum;
      }
    }
    // Every non-zero sum s within: |log s| < within, tested without a logarithm.
    const double low = std::exp(-within), high = std::exp(within);
    auto balanced = [low, high](const Eigen::VectorXd& sums) {
      for (Eigen::Index k = 0; k < sums.size(); ++k)
        if (sums[k] > 0.0 && !(sums[k] > low && sums[k] < high)) return false;
      return true;
    };
    if ((balanced(row_sum) && balanced(column_sum)) || sweep == sweeps) break;
    // Empty rows and columns divided by √1; the rest by √s, in Eigen's vectorised square root
    // and division (the same values as one by one, at a third of the time).
    for (Eigen::VectorXd* sums : {&row_sum, &column_sum})
      for (double& sum : *sums)
        if (!(sum > 0.0)) sum = 1.0;
    row.array() /= row_sum.array().sqrt();
    column.array() /= column_sum.array().sqrt();
  }
}

// What the geometric mean of diag(r)·m·diag(c)'s non-zero entries needs of m, gathered once:
// log(|m_ij|·r_i·c_j) = log|m_ij| + log r_i + log c_j, so the mean is Σ log|m_ij| plus each
// row's and column's count of entries times its log scale, over the count: n logarithms a
// round instead of one per entry (the fish fin at N = 10 000: 230 000 a round, 12 rounds).
struct LogProfile {
  double sum = 0.0;  // Σ log|m_ij| over the non-zero entries
  Eigen::VectorXd row_count, column_count;
  double count = 0.0;

  explicit LogProfile(const Eigen::SparseMatrix<double>& m)
      : row_count(Eigen::VectorXd::Zero(m.rows())), column_count(Eigen::VectorXd::Zero(m.cols())) {
    for (int col = 0; col < m.outerSize(); ++col)
      for (Eigen::SparseMatrix<double>::InnerIterator it(m, col); it; ++it)
        if (it.value() != 0.0) {
          sum += std::log(std::abs(it.value()));
          row_count[it.row()] += 1.0;
          column_count[col] += 1.0;
          count += 1.0;
        }
  }
  // exp(mean(log|entries|)) of diag(row)·m·diag(column) from the scalings' logarithms; 0 when
  // m has no non-zero entry.
  double geometric_mean(const Eigen::VectorXd& log_row, const Eigen::VectorXd& log_column) const {
    if (count == 0.0) return 0.0;
    return std::exp((sum + row_count.dot(log_row) + column_count.dot(log_column)) / count);
  }
};

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

namespace {

// The balancing of a pencil, as equilibrate_pencil returns it (not remembered).
DiagonalScaling balance_pencil(const Eigen::SparseMatrix<double>& a,
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
  // the same geometric mean, found by fixed-point steps from the ratio of the unscaled
  // matrices' geometric means, each Sinkhorn run warm-started. A step only steers ω₀, so its
  // run stops at sums within half the last step's |log ratio| (at most kSteering): finer than
  // the change it has to follow, coarser than kBalanced while ω₀ moves. Once ω₀ has settled, a
  // run balances to kBalanced and ω₀ is checked once more: the same criteria as balancing every
  // step to kBalanced, in about half the sweeps on a 35-segment beam.
  const LogProfile profile_a(a), profile_b(b);
  double weight = 1.0;
  {
    const Eigen::VectorXd unscaled_row = Eigen::VectorXd::Zero(a.rows()),
                          unscaled_column = Eigen::VectorXd::Zero(a.cols());
    const double mean_a = profile_a.geometric_mean(unscaled_row, unscaled_column),
                 mean_b = profile_b.geometric_mean(unscaled_row, unscaled_column);
    if (mean_a > 0.0 && mean_b > 0.0) weight = mean_a / mean_b;
  }
  constexpr double kSteering = 0.2;
  bool last_run = false, balanced = false;
  double within = kSteering;
  for (int round = 0; round < 40 && !balanced; ++round) {
    sinkhorn(a, &b, weight, scaling.row, scaling.column, 200, last_run ? kBalanced : within);
    balanced = last_run;
    const Eigen::VectorXd log_row = scaling.row.array().log(),
                          log_column = scaling.column.array().log();
    const double mean_a = profile_a.geometric_mean(log_row, log_column);
    const double mean_b = profile_b.geometric_mean(log_row, log_column) * weight;
    if (!(mean_a > 0.0 && mean_b > 0.0)) break;
    const double ratio = mean_a / mean_b;
    weight *= ratio;
    last_run = std::abs(std::log(ratio)) < 0.05;
    within = std::clamp(0.5 * std::abs(std::log(ratio)), kBalanced, kSteering);
    if (!last_run) balanced = false;
  }
  if (!balanced) sinkhorn(a, &b, weight, scaling.row, scaling.column, 200);
  scaling.frequency = weight;
  round_to_powers_of_two(scaling);
  return scaling;
}

// Entry by entry the same matrix (both compressed).
bool same_matrix(const Eigen::SparseMatrix<double>& x, const Eigen::SparseMatrix<double>& y) {
  if (x.rows() != y.rows() || x.cols() != y.cols() || x.nonZeros() != y.nonZeros()) return false;
  const auto entries = static_cast<size_t>(x.nonZeros());
  return std::equal(x.outerIndexPtr(), x.outerIndexPtr() + x.outerSize() + 1, y.outerIndexPtr()) &&
         std::equal(x.innerIndexPtr(), x.innerIndexPtr() + entries, y.innerIndexPtr()) &&
         std::equal(x.valuePtr(), x.valuePtr() + entries, y.valuePtr());
}

// A pencil balanced on this thread, kept with its scaling.
struct BalancedPencil {
  Eigen::SparseMatrix<double> a, b;
  double frequency = 0.0;
  DiagonalScaling scaling;
};

}  // namespace

// The last two pencils balanced on this thread are remembered: an AC study asks for the same
// (G + J_g, C) up to three times (a reduction's left vectors, its check against the full model,
// the validity's rotation peak), 0.37 s each for the fish fin at N = 10 000. A pencil is found
// again only when equal entry by entry, so a changed one is balanced afresh.
DiagonalScaling equilibrate_pencil(const Eigen::SparseMatrix<double>& a,
                                   const Eigen::SparseMatrix<double>& b, double frequency) {
  thread_local std::array<std::optional<BalancedPencil>, 2> remembered;
  Eigen::SparseMatrix<double> a_compressed = a, b_compressed = b;
  a_compressed.makeCompressed();
  b_compressed.makeCompressed();
  for (const std::optional<BalancedPencil>& pencil : remembered)
    if (pencil && pencil->frequency == frequency && same_matrix(pencil->a, a_compressed) &&
        same_matrix(pencil->b, b_compressed))
      return pencil->scaling;
  DiagonalScaling scaling = balance_pencil(a_compressed, b_compressed, frequency);
  remembered[1] = std::move(remembered[0]);
  remembered[0] =
      BalancedPencil{std::move(a_compressed), std::move(b_compressed), frequency, scaling};
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
