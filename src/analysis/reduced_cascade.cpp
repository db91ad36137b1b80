// The reduced cascade: ReducedPeriodicSolver for a network whose only nonlinearity is the DEAs'
// force d_j·u_j² (include/emnet/analysis/modal_reduction.hpp; the exact cascade's stages,
// periodic_cascade.hpp, on the kept poles, with the truncated poles' particular state exact
// through the full model's response at each exponent).
#include <Eigen/SparseLU>
#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

#include "core/timed.hpp"
#include "emnet/analysis/modal_reduction.hpp"
#include "emnet/core/stopwatch.hpp"
#include "emnet/core/units.hpp"
#include "exponential_series.hpp"
#include "periodic_cascade.hpp"
#include "reduced_periodic.hpp"
#include "static_operator.hpp"

namespace emnet {

Eigen::SparseMatrix<double> linearised_g(const System& system, const Eigen::VectorXd& y);

namespace {

using Complex = std::complex<double>;

// A pole a voltage carries: its weight max |g|·|β|/|λ| above this fraction of the largest
// (as square_exponents' 1e-12 of a voltage's scale).
constexpr double kCarried = 1e-12;
// A pole a DEA's force reaches: |β|·‖z‖/|λ| above this fraction of the largest (as the
// reduction's drop_unreached_poles).
constexpr double kReached = 1e-12;
// A pole that carries a voltage and is reached by a force couples the stages (as the exact
// cascade's 1e-9 of the product of the largest of each).
constexpr double kCoupled = 1e-9;

}  // namespace

struct ReducedPeriodicSolver::Cascade {
  struct Source {
    std::string name;
    Probe voltage;  // u_j on the static form's unknowns
  };
  std::vector<Source> sources;
  std::vector<std::shared_ptr<const Element>> elements;  // the DEAs (same_cascade)
  size_t first_input = 0;       // the sources' inputs follow the waveforms'
  Eigen::VectorXcd lambda;      // the kept poles, then the conjugates of the oscillatory ones
  std::vector<size_t> kept_of;  // [pole] → reduction.kept
  std::vector<bool> conjugate;  // [pole]
  Eigen::MatrixXcd beta;        // [pole][input]
  SquareExponents exponents;    // over lambda; kept: the poles the voltages carry
  // feed[j][m]: the truncated part's z(μ_m), z'(μ_m), z''(μ_m)/2 for source j's direction.
  std::vector<std::vector<std::array<Eigen::VectorXcd, 3>>> feed;

  // The probe's row of the modal coordinates: g_k = Σ c·v^z_k[index].
  Eigen::VectorXcd row(const ModalReduction& reduction, const Probe& probe) const {
    Eigen::VectorXcd g = Eigen::VectorXcd::Zero(lambda.size());
    for (const auto& [index, c] : probe.terms)
      for (Eigen::Index k = 0; k < lambda.size(); ++k) {
        const Complex v = reduction.kept[kept_of[static_cast<size_t>(k)]].z_vector[index];
        g[k] += c * (conjugate[static_cast<size_t>(k)] ? std::conj(v) : v);
      }
    return g;
  }
};

namespace {

using Cascade = ReducedPeriodicSolver::Cascade;

// The DEAs' squared sources of `system`, each one more input (its direction); a failed Status
// saying why the network is not such a cascade.
Status squared_sources(const System& system, Cascade& cascade,
                       std::vector<Eigen::VectorXcd>& inputs) {
  for (const auto& element : system.nonlinear_elements) {
    LinearTerms voltage, direction_terms;
    if (!element->squared_source(voltage, direction_terms))
      return not_a_squared_source(*element, "the reduced cascade");
    cascade.sources.push_back({element->name(), squared_voltage_probe(element->name(), voltage)});
    Eigen::VectorXcd direction = Eigen::VectorXcd::Zero(system.size());
    for (const auto& [row, value] : direction_terms) direction[row] += value;
    inputs.push_back(std::move(direction));
  }
  cascade.elements = system.nonlinear_elements;
  return Status::success();
}

// The kept poles with the conjugates of the oscillatory ones, and their β.
void expand_poles(const ModalReduction& reduction, Cascade& cascade) {
  std::vector<Complex> poles;
  for (size_t k = 0; k < reduction.kept.size(); ++k) {
    poles.push_back(reduction.kept[k].pole);
    cascade.kept_of.push_back(k);
    cascade.conjugate.push_back(false);
  }
  for (size_t k = 0; k < reduction.kept.size(); ++k)
    if (reduction.kept[k].oscillatory) {
      poles.push_back(std::conj(reduction.kept[k].pole));
      cascade.kept_of.push_back(k);
      cascade.conjugate.push_back(true);
    }
  const auto count = static_cast<Eigen::Index>(poles.size());
  const auto inputs = static_cast<Eigen::Index>(reduction.inputs.size());
  cascade.lambda = Eigen::Map<const Eigen::VectorXcd>(poles.data(), count);
  cascade.beta.resize(count, inputs);
  for (Eigen::Index k = 0; k < count; ++k)
    for (Eigen::Index j = 0; j < inputs; ++j) {
      const Complex b =
          reduction.beta[cascade.kept_of[static_cast<size_t>(k)]][static_cast<size_t>(j)];
      cascade.beta(k, j) = cascade.conjugate[static_cast<size_t>(k)] ? std::conj(b) : b;
    }
}

// The poles the voltages carry (the exponents of their squares), after checking that none of
// them is reached by a DEA's force (the stages apart).
Status carried_poles(const ModalReduction& reduction, Cascade& cascade) {
  const Eigen::Index count = cascade.lambda.size();
  const auto waveforms = static_cast<Eigen::Index>(cascade.first_input);
  const auto forces = cascade.beta.cols() - waveforms;
  Eigen::VectorXd carried = Eigen::VectorXd::Zero(count), reached = Eigen::VectorXd::Zero(count);
  for (const Cascade::Source& source : cascade.sources) {
    const Eigen::VectorXd g = cascade.row(reduction, source.voltage).cwiseAbs();
    for (Eigen::Index k = 0; k < count; ++k) {
      const double inverse = 1.0 / std::abs(cascade.lambda[k]);
      if (waveforms > 0)
        carried[k] = std::max(
            carried[k], g[k] * cascade.beta.row(k).head(waveforms).cwiseAbs().maxCoeff() * inverse);
      const double z = reduction.kept[cascade.kept_of[static_cast<size_t>(k)]].z_vector.norm();
      reached[k] = std::max(reached[k],
                            cascade.beta.row(k).tail(forces).cwiseAbs().maxCoeff() * z * inverse);
    }
  }
  const double carried_scale = carried.maxCoeff(), reached_scale = reached.maxCoeff();
  for (Eigen::Index k = 0; k < count; ++k) {
    if (!(carried[k] > kCarried * carried_scale)) continue;
    if (reached[k] > kCoupled * reached_scale)
      return Status::failure(
          "a pole that carries a DEA's voltage is also moved by the DEAs' forces (s = " +
          format_number("%.6g", cascade.lambda[k].real()) + " + " +
          format_number("%.6g", cascade.lambda[k].imag()) +
          "j 1/s): the stages of the cascade are coupled; the shooting method serves it");
    cascade.exponents.kept.push_back(k);
  }
  const auto kept = static_cast<Eigen::Index>(cascade.exponents.kept.size());
  cascade.exponents.mu.resize(1 + kept + kept * (kept + 1) / 2);
  Eigen::Index m = 0;
  cascade.exponents.mu[m++] = 0.0;
  for (Eigen::Index k : cascade.exponents.kept) cascade.exponents.mu[m++] = cascade.lambda[k];
  for (Eigen::Index p = 0; p < kept; ++p)
    for (Eigen::Index q = p; q < kept; ++q)
      cascade.exponents.mu[m++] = cascade.lambda[cascade.exponents.kept[static_cast<size_t>(p)]] +
                                  cascade.lambda[cascade.exponents.kept[static_cast<size_t>(q)]];
  return Status::success();
}

// The unknowns in the parts of the operator's sparsity graph (A₀ + A₁ + A₂) that the forces'
// directions touch: the beam and what is linearly tied to it, where the circuit's poles are not.
std::vector<Eigen::Index> reached_unknowns(const Eigen::SparseMatrix<double>& pattern,
                                           const std::vector<Eigen::VectorXcd>& directions) {
  const Eigen::Index n = pattern.rows();
  std::vector<Eigen::Index> parent(static_cast<size_t>(n));
  std::iota(parent.begin(), parent.end(), Eigen::Index{0});
  auto root = [&](Eigen::Index i) {
    while (parent[static_cast<size_t>(i)] != i)
      i = parent[static_cast<size_t>(i)] =
          parent[static_cast<size_t>(parent[static_cast<size_t>(i)])];
    return i;
  };
  for (Eigen::Index col = 0; col < pattern.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(pattern, col); it; ++it)
      parent[static_cast<size_t>(root(it.row()))] = root(col);
  std::vector<bool> touched(static_cast<size_t>(n), false);
  for (const Eigen::VectorXcd& d : directions)
    for (Eigen::Index i = 0; i < n; ++i)
      if (d[i] != 0.0) touched[static_cast<size_t>(root(i))] = true;
  std::vector<Eigen::Index> reached;
  for (Eigen::Index i = 0; i < n; ++i)
    if (touched[static_cast<size_t>(root(i))]) reached.push_back(i);
  return reached;
}

// `matrix` restricted to the rows and columns `index`.
Eigen::SparseMatrix<double> restricted(const Eigen::SparseMatrix<double>& matrix,
                                       const std::vector<Eigen::Index>& index) {
  std::vector<Eigen::Index> position(static_cast<size_t>(matrix.rows()), -1);
  for (size_t i = 0; i < index.size(); ++i)
    position[static_cast<size_t>(index[i])] = static_cast<Eigen::Index>(i);
  std::vector<Eigen::Triplet<double>> entries;
  for (Eigen::Index col = 0; col < matrix.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(matrix, col); it; ++it) {
      const Eigen::Index r = position[static_cast<size_t>(it.row())],
                         c = position[static_cast<size_t>(col)];
      if (r >= 0 && c >= 0) entries.emplace_back(r, c, it.value());
    }
  const auto size = static_cast<Eigen::Index>(index.size());
  Eigen::SparseMatrix<double> out(size, size);
  out.setFromTriplets(entries.begin(), entries.end());
  return out;
}

// The full model's operator A(μ) = A₀ + μ·A₁ + μ²·A₂ on the reached unknowns, factorised per
// exponent: in real arithmetic where μ is real (an RC loop's), its pattern analysed once.
class ReachedOperator {
 public:
  ReachedOperator(const std::array<Eigen::SparseMatrix<double>, 3>& a,
                  const std::vector<Eigen::Index>& reached)
      : reached_(reached) {
    for (size_t r = 0; r < 3; ++r) a_[r] = restricted(a[r], reached);
    real_lu_.analyzePattern(Eigen::SparseMatrix<double>(a_[0] + a_[1] + a_[2]));
  }

  // z(μ), z'(μ), z''(μ)/2 of the response to each direction, from A(μ)·z₀ = b, A·z₁ = −A'·z₀,
  // A·z₂ = −A'·z₁ − A₂·z₀ (zero outside the reached unknowns).
  Status taylor_at(Complex mu, const std::vector<Eigen::VectorXcd>& directions, Eigen::Index n,
                   std::vector<std::array<Eigen::VectorXcd, 3>>& taylor) {
    taylor.clear();
    if (mu.imag() == 0.0) return real_taylor_at(mu.real(), directions, n, taylor);
    const Eigen::SparseMatrix<Complex> a0 = a_[0].cast<Complex>(), a1 = a_[1].cast<Complex>(),
                                       a2 = a_[2].cast<Complex>();
    const Eigen::SparseMatrix<Complex> slope = a1 + (2.0 * mu) * a2;
    Eigen::SparseLU<Eigen::SparseMatrix<Complex>> lu;
    lu.compute(a0 + mu * a1 + (mu * mu) * a2);
    if (lu.info() != Eigen::Success) return singular_at(mu);
    for (const Eigen::VectorXcd& d : directions) {
      const Eigen::VectorXcd z0 = lu.solve(restrict(d));
      const Eigen::VectorXcd z1 = lu.solve(-(slope * z0));
      const Eigen::VectorXcd z2 = lu.solve(-(slope * z1) - a2 * z0);
      if (Status expanded = expand({z0, z1, z2}, mu, n, taylor); !expanded.ok()) return expanded;
    }
    return Status::success();
  }

 private:
  // The same for a real μ, the real and imaginary parts of each direction apart.
  Status real_taylor_at(double s, const std::vector<Eigen::VectorXcd>& directions, Eigen::Index n,
                        std::vector<std::array<Eigen::VectorXcd, 3>>& taylor) {
    real_lu_.factorize(Eigen::SparseMatrix<double>(a_[0] + s * a_[1] + (s * s) * a_[2]));
    if (real_lu_.info() != Eigen::Success) return singular_at(s);
    const Eigen::SparseMatrix<double> slope = a_[1] + (2.0 * s) * a_[2];
    for (const Eigen::VectorXcd& d : directions) {
      const Eigen::VectorXcd b = restrict(d);
      std::array<Eigen::VectorXcd, 3> parts;
      for (int part = 0; part < 2; ++part) {
        const Eigen::VectorXd rhs =
            part == 0 ? Eigen::VectorXd(b.real()) : Eigen::VectorXd(b.imag());
        const Eigen::VectorXd z0 = real_lu_.solve(rhs);
        const Eigen::VectorXd z1 = real_lu_.solve(-(slope * z0));
        const Eigen::VectorXd z2 = real_lu_.solve(-(slope * z1) - a_[2] * z0);
        const std::array<const Eigen::VectorXd*, 3> z{&z0, &z1, &z2};
        for (size_t r = 0; r < 3; ++r)
          parts[r] = part == 0
                         ? Eigen::VectorXcd(z[r]->cast<Complex>())
                         : Eigen::VectorXcd(parts[r] + Complex(0.0, 1.0) * z[r]->cast<Complex>());
      }
      if (Status expanded = expand(parts, s, n, taylor); !expanded.ok()) return expanded;
    }
    return Status::success();
  }
  Eigen::VectorXcd restrict(const Eigen::VectorXcd& full) const {
    Eigen::VectorXcd b(static_cast<Eigen::Index>(reached_.size()));
    for (size_t i = 0; i < reached_.size(); ++i)
      b[static_cast<Eigen::Index>(i)] = full[reached_[i]];
    return b;
  }
  // The parts on the reached unknowns as full vectors, appended to `taylor`.
  Status expand(const std::array<Eigen::VectorXcd, 3>& parts, Complex mu, Eigen::Index n,
                std::vector<std::array<Eigen::VectorXcd, 3>>& taylor) const {
    std::array<Eigen::VectorXcd, 3> full;
    for (size_t r = 0; r < 3; ++r) {
      if (!parts[r].allFinite())
        return Status::failure("the full model's response at the squared voltages' exponent s = " +
                               format_number("%.6g", mu.real()) + " 1/s is not finite");
      full[r] = Eigen::VectorXcd::Zero(n);
      for (size_t i = 0; i < reached_.size(); ++i)
        full[r][reached_[i]] = parts[r][static_cast<Eigen::Index>(i)];
    }
    taylor.push_back(std::move(full));
    return Status::success();
  }
  static Status singular_at(Complex mu) {
    return Status::failure(
        "the squared voltages' exponent s = " + format_number("%.6g", mu.real()) + " + " +
        format_number("%.6g", mu.imag()) +
        "j 1/s is a pole of the beam: its response there has no particular "
        "state (the shooting method serves it)");
  }

  std::vector<Eigen::Index> reached_;
  std::array<Eigen::SparseMatrix<double>, 3> a_;
  Eigen::SparseLU<Eigen::SparseMatrix<double>> real_lu_;
};

// feed[j][m]: the full model's Taylor coefficients at μ_m less the kept poles' (R/(s − λ) →
// R·g, −R·g², R·g³ with g = 1/(μ − λ)); a kept pole the force does not reach is left out (its
// β is the decomposition's rounding, and μ may be that very pole: a voltage's).
// `g_matrix`, `static_operator`: at rest, as the reduction's.
Status truncated_feed(const System& system, const Eigen::SparseMatrix<double>& g_matrix,
                      const StaticOperator& static_operator, const ModalReduction& reduction,
                      Cascade& cascade) {
  const auto [a1, a2] = expansion_matrices(system, g_matrix, static_operator);
  // The pattern of the entries that are not zero (the DEAs' Jacobians at u = 0 are stored zeros).
  Eigen::SparseMatrix<double> pattern =
      static_operator.matrix().cwiseAbs() + a1.cwiseAbs() + a2.cwiseAbs();
  pattern.prune([](Eigen::Index, Eigen::Index, double value) { return value != 0.0; });
  std::vector<Eigen::VectorXcd> directions(
      reduction.inputs.begin() + static_cast<std::ptrdiff_t>(cascade.first_input),
      reduction.inputs.end());
  const std::vector<Eigen::Index> reached = reached_unknowns(pattern, directions);
  ReachedOperator reached_operator({static_operator.matrix(), a1, a2}, reached);
  for (const Cascade::Source& source : cascade.sources)
    for (const auto& [index, c] : source.voltage.terms)
      if (std::binary_search(reached.begin(), reached.end(), index))
        return Status::failure("DEA " + source.name +
                               "'s voltage is linearly tied to the beam: the reduced cascade "
                               "needs the circuit apart from it");
  const Eigen::Index n = system.size(), poles = cascade.lambda.size();
  std::vector<double> weight(static_cast<size_t>(poles), 0.0);
  cascade.feed.assign(directions.size(), {});
  for (Eigen::Index m = 0; m < cascade.exponents.mu.size(); ++m) {
    const Complex mu = cascade.exponents.mu[m];
    std::vector<std::array<Eigen::VectorXcd, 3>> taylor;
    if (Status full = reached_operator.taylor_at(mu, directions, n, taylor); !full.ok())
      return full;
    for (size_t j = 0; j < directions.size(); ++j) {
      const auto input = static_cast<Eigen::Index>(cascade.first_input + j);
      double largest = 0.0;
      for (Eigen::Index k = 0; k < poles; ++k) {
        const KeptPole& pole = reduction.kept[cascade.kept_of[static_cast<size_t>(k)]];
        weight[static_cast<size_t>(k)] =
            std::abs(cascade.beta(k, input)) * pole.z_vector.norm() / std::abs(pole.pole);
        largest = std::max(largest, weight[static_cast<size_t>(k)]);
      }
      for (Eigen::Index k = 0; k < poles; ++k) {
        if (!(weight[static_cast<size_t>(k)] > kReached * largest)) continue;
        const KeptPole& pole = reduction.kept[cascade.kept_of[static_cast<size_t>(k)]];
        const bool conjugate = cascade.conjugate[static_cast<size_t>(k)];
        const Eigen::VectorXcd residue =
            (conjugate ? Eigen::VectorXcd(pole.z_vector.conjugate()) : pole.z_vector) *
            cascade.beta(k, input);
        const Complex g = reciprocal(mu - cascade.lambda[k]);
        taylor[j][0] -= residue * g;
        taylor[j][1] += residue * (g * g);
        taylor[j][2] -= residue * (g * g * g);
      }
      cascade.feed[j].push_back(taylor[j]);
    }
  }
  return Status::success();
}

}  // namespace

void ReducedPeriodicSolver::reduce_cascade(const System& system, const ReductionOptions& periodic,
                                           std::vector<Eigen::VectorXcd> inputs) {
  auto cascade = std::make_shared<Cascade>();
  cascade->first_input = inputs.size();
  if (Status sources = squared_sources(system, *cascade, inputs); !sources.ok()) {
    reduction_.status = sources;
    return;
  }
  const Eigen::VectorXd rest = Eigen::VectorXd::Zero(system.size());
  const Eigen::SparseMatrix<double> g_matrix = linearised_g(system, rest);
  const StaticOperator static_operator(system, g_matrix);
  reduction_ = reduce_modal(system, rest, g_matrix, static_operator, inputs, periodic);
  if (!reduction_.status.ok()) return;
  const Stopwatch stopwatch;
  for (const Cascade::Source& source : cascade->sources)
    for (const auto& [node, coefficient] : source.voltage.terms)
      if (reduction_.mechanical[static_cast<size_t>(node)]) {
        reduction_.status = Status::failure("element '" + source.name +
                                            "' squares a mechanical quantity: the cascade "
                                            "squares voltages only");
        return;
      }
  if (reduction_.kept.empty()) {
    reduction_.status = Status::failure(
        "the reduction keeps no pole below f_c = " + format_number("%.4g", reduction_.cutoff_hz) +
        " Hz, where the reduced cascade needs at least the circuit's: raise the cut-off (band, "
        "tolerance) or use the exact cascade");
    return;
  }
  expand_poles(reduction_, *cascade);
  Status prepared = carried_poles(reduction_, *cascade);
  if (prepared.ok())
    prepared = truncated_feed(system, g_matrix, static_operator, reduction_, *cascade);
  reduction_.seconds += stopwatch.seconds();
  if (!prepared.ok()) {
    reduction_.status = prepared;
    return;
  }
  cascade_ = std::move(cascade);
}

namespace {

// The probe's truncated feed-through on interval i: Σ_j the response to u_j²'s terms P(h)·e^{μh},
// (t₀·P + t₁·P' + t₂·P'') with t_r = probe·feed[j][m][r] (`rows`: [j·M + m][r]).
ExponentialSeries::ForcedTerms truncated_terms(
    const Eigen::MatrixXcd& rows,
    const std::vector<std::vector<ExponentialSeries::ForcedTerms>>& squares, size_t i,
    Eigen::Index terms) {
  ExponentialSeries::ForcedTerms out = ExponentialSeries::ForcedTerms::Zero(terms, 3);
  for (size_t j = 0; j < squares.size(); ++j)
    for (Eigen::Index m = 0; m < terms; ++m) {
      const auto& p = squares[j][i];
      const Eigen::Index row = static_cast<Eigen::Index>(j) * terms + m;
      const Complex t0 = rows(row, 0), t1 = rows(row, 1), t2 = rows(row, 2);
      out(m, 0) += t0 * p(m, 0) + t1 * p(m, 1) + 2.0 * t2 * p(m, 2);
      out(m, 1) += t0 * p(m, 1) + 2.0 * t1 * p(m, 2);
      out(m, 2) += t0 * p(m, 2);
    }
  return out;
}

// Re Σ_m (c₀ + c₁·h + c₂·h²)_m·e^{μ_m h}.
double forced_value(const ExponentialSeries::ForcedTerms& c, const Eigen::VectorXcd& mu, double h) {
  Complex sum = 0.0;
  for (Eigen::Index m = 0; m < mu.size(); ++m)
    sum += (c(m, 0) + h * (c(m, 1) + h * c(m, 2))) * std::exp(mu[m] * h);
  return sum.real();
}

// The first stage's pieces a probe's series is made of (solve_cascade).
struct LinearStage {
  const std::vector<double>& edges;
  const InputPieces& pieces;
  const std::vector<Eigen::VectorXcd>&particular, &slope, &homogeneous;
};

// A probe's series: the linear part, the kept poles' forced part and the truncated
// feed-through; `jumps` gets the latter's jump at each interval's start (with the inputs'
// static correction's), where the truncated transients start.
ExponentialSeries cascade_probe_series(
    const Cascade& cascade, const ModalReduction& reduction, const Probe& probe,
    const LinearStage& stage, const ForcedModalResponse& response,
    const std::vector<std::vector<ExponentialSeries::ForcedTerms>>& squares,
    std::vector<double>& jumps) {
  const std::vector<double>& edges = stage.edges;
  const InputPieces& pieces = stage.pieces;
  const size_t intervals = edges.size() - 1;
  const Eigen::Index forces = static_cast<Eigen::Index>(cascade.sources.size()),
                     terms = cascade.exponents.mu.size();
  const Eigen::VectorXcd g = cascade.row(reduction, probe);
  const std::vector<double> d = input_feed(reduction, probe, cascade.first_input);
  ExponentialSeries s =
      affine_series(g, d, pieces, stage.particular, stage.slope, stage.homogeneous);
  Eigen::MatrixXcd rows(forces * terms, 3);  // [j·M + m][r]: probe·feed[j][m][r]
  for (Eigen::Index j = 0; j < forces; ++j)
    for (Eigen::Index m = 0; m < terms; ++m)
      for (int r = 0; r < 3; ++r) {
        Complex t = 0.0;
        for (const auto& [index, c] : probe.terms)
          t += c * cascade.feed[static_cast<size_t>(j)][static_cast<size_t>(m)]
                               [static_cast<size_t>(r)][index];
        rows(j * terms + m, r) = t;
      }
  std::vector<double> truncated_start(intervals), truncated_end(intervals);
  for (size_t i = 0; i < intervals; ++i) {
    const double h = edges[i + 1] - edges[i];
    const ExponentialSeries::ForcedTerms truncated = truncated_terms(rows, squares, i, terms);
    truncated_start[i] = forced_value(truncated, cascade.exponents.mu, 0.0);
    truncated_end[i] = forced_value(truncated, cascade.exponents.mu, h);
    for (size_t w = 0; w < d.size(); ++w) {
      truncated_start[i] += d[w] * pieces.value[i][w];
      truncated_end[i] += d[w] * (pieces.value[i][w] + h * pieces.slope[i][w]);
    }
    const Eigen::RowVectorXcd through_modes = g.transpose() * response.coefficients[i];
    ExponentialSeries::ForcedTerms kept(terms, 3);
    for (Eigen::Index m = 0; m < terms; ++m)
      for (int r = 0; r < 3; ++r) kept(m, r) = through_modes[3 * m + r];
    s.forced.push_back(kept + truncated);
  }
  jumps.clear();
  for (size_t i = 0; i < intervals; ++i)
    jumps.push_back(std::abs(truncated_start[i] - truncated_end[(i + intervals - 1) % intervals]));
  return s;
}

// The truncated poles' transients left out, at the interval start where they add up most:
// Σ_j |δ_j|·e^{−r·(t_i − t_j)} over the edges j of a period (δ_j: the jump there), the periods
// before through 1/(1 − e^{−r·T}), r the largest kept |pole|. Every truncated pole is at least
// as large, so a real one decays at least this fast from its start, its largest value; an
// oscillatory one with less damping than that may ring longer (an estimate then).
double transients_left_out(const std::vector<double>& edges, const std::vector<double>& jumps,
                           double rate) {
  const double period = edges.back();
  const double per_period = std::exp(-rate * period);
  const double earlier = per_period < 0.999 ? 1.0 / (1.0 - per_period) : 1000.0;
  double worst = 0.0;
  for (size_t i = 0; i < jumps.size(); ++i) {
    double sum = 0.0;
    for (size_t j = 0; j < jumps.size(); ++j) {
      double gap = edges[i] - edges[j];
      if (gap < 0.0) gap += period;
      sum += jumps[j] * std::exp(-rate * gap);
    }
    worst = std::max(worst, sum * earlier);
  }
  return worst;
}

}  // namespace

PeriodicResult ReducedPeriodicSolver::solve_cascade(const System& system,
                                                    const std::vector<Probe>& probes, double period,
                                                    int samples) const {
  Timed<PeriodicResult> timed;
  PeriodicResult& result = timed.result;
  result.method = Method::reduced;
  result.period = period;
  auto finish = [&](Status status) { return timed.finish(std::move(status)); };
  const Cascade& cascade = *cascade_;
  if (!same_cascade(system.nonlinear_elements, cascade.elements))
    return finish(Status::failure("the network's DEAs differ from the reduced one's"));
  const std::vector<double> edges = constant_intervals(system, period);
  const size_t intervals = edges.size() - 1;
  const InputPieces pieces = input_pieces(system, waveforms_, edges);
  const auto waveforms = static_cast<Eigen::Index>(cascade.first_input);
  const Eigen::Index forces = cascade.beta.cols() - waveforms;

  // The first stage: the linear network's periodic state under the sources, the DEA voltages
  // and their squares.
  std::vector<Eigen::VectorXcd> particular, slope, linear_start;
  affine_particulars(cascade.lambda, cascade.beta.leftCols(waveforms), pieces, particular, slope);
  if (Status periodic = periodic_interval_starts(cascade.lambda, edges, particular, slope, {},
                                                 linear_start, result.periodicity_residual);
      !periodic.ok())
    return finish(periodic);
  std::vector<Eigen::VectorXcd> homogeneous(intervals);
  for (size_t i = 0; i < intervals; ++i) homogeneous[i] = linear_start[i] - particular[i];
  std::vector<std::vector<ExponentialSeries::ForcedTerms>> squares;
  for (const Cascade::Source& source : cascade.sources)
    squares.push_back(
        squared_terms(affine_series(cascade.row(reduction_, source.voltage),
                                    input_feed(reduction_, source.voltage, cascade.first_input),
                                    pieces, particular, slope, homogeneous),
                      cascade.exponents));

  // The second: the kept poles under the squares, periodic with the first stage's states.
  ForcedModalResponse response;
  if (Status forced =
          forced_modal_response(cascade.lambda, edges, cascade.exponents,
                                cascade.beta.rightCols(forces), squares, {}, false, response);
      !forced.ok())
    return finish(forced);
  std::vector<Eigen::VectorXcd> particular_start(intervals), particular_end(intervals), start_of;
  for (size_t i = 0; i < intervals; ++i) {
    const double h = edges[i + 1] - edges[i];
    particular_start[i] = particular[i] + response.start[i];
    particular_end[i] = particular[i] + response.end[i];
    if (!slope.empty()) particular_end[i] += h * slope[i];
  }
  if (Status periodic =
          periodic_starts_from_particulars(cascade.lambda, edges, particular_start, particular_end,
                                           {}, start_of, result.periodicity_residual);
      !periodic.ok())
    return finish(periodic);
  for (size_t i = 0; i < intervals; ++i)
    homogeneous[i] = start_of[i] - response.start[i] - particular[i];

  std::vector<ExponentialSeries> series;
  std::vector<std::vector<double>> jumps(probes.size());
  for (size_t p = 0; p < probes.size(); ++p)
    series.push_back(cascade_probe_series(cascade, reduction_, probes[p],
                                          {edges, pieces, particular, slope, homogeneous}, response,
                                          squares, jumps[p]));
  sample_periodic_series(cascade.lambda, edges, series, samples, result, cascade.exponents.mu);
  const double rate = moduli(cascade.lambda).maxCoeff();
  for (size_t p = 0; p < probes.size(); ++p) {
    const double scale = std::max(std::abs(result.minimum[p]), std::abs(result.maximum[p]));
    if (scale > 0.0)
      result.truncation_estimate =
          std::max(result.truncation_estimate, transients_left_out(edges, jumps[p], rate) / scale);
  }
  return finish(Status::success());
}

}  // namespace emnet
