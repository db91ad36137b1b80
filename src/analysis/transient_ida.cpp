// Transient analysis with SUNDIALS IDA on the displacement form (index 1): sparse KLU
// Jacobian, exact stops at every source breakpoint, consistent restarts (own Newton iteration,
// IDACalcIC as the fallback).
#include <ida/ida.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>

#include "consistent_start.hpp"
#include "core/timed.hpp"
#include "displacement_form.hpp"
#include "emnet/analysis/analysis.hpp"
#include "emnet/analysis/transient.hpp"
#include "sundials_handles.hpp"
#include "transient_finite.hpp"

namespace emnet {

namespace {

std::string format_time(double t) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.9g", t);
  return buffer;
}

// The CSC pattern of ∂F/∂u + c_j·∂F/∂u' (the linear part and the nonlinear part at a generic
// state), fixed for the whole run, so that KLU's symbolic analysis stays valid from one Jacobian
// to the next; each Jacobian is scattered into the values in place instead of being assembled
// by setFromTriplets, which sorted every entry per call (3 % of the 3000-segment fin's run).
class JacobianPattern {
 public:
  JacobianPattern(int size, const std::vector<Eigen::Triplet<double>>& entries) : size_(size) {
    Eigen::SparseMatrix<double, Eigen::ColMajor, sunindextype> matrix(size, size);
    std::vector<Eigen::Triplet<double, sunindextype>> zeros;
    zeros.reserve(entries.size());
    for (const auto& e : entries) zeros.emplace_back(e.row(), e.col(), 0.0);
    matrix.setFromTriplets(zeros.begin(), zeros.end());
    matrix.makeCompressed();
    column_starts_.assign(matrix.outerIndexPtr(), matrix.outerIndexPtr() + size + 1);
    rows_.assign(matrix.innerIndexPtr(), matrix.innerIndexPtr() + matrix.nonZeros());
  }
  sunindextype nonzeros() const { return static_cast<sunindextype>(rows_.size()); }
  void write_structure(SUNMatrix matrix) const {
    std::copy(column_starts_.begin(), column_starts_.end(), SUNSparseMatrix_IndexPointers(matrix));
    std::copy(rows_.begin(), rows_.end(), SUNSparseMatrix_IndexValues(matrix));
  }
  // values = the sum of the entries (duplicates add up). The entries come in the same order
  // call after call, so each one's position is remembered and only checked; a new one is
  // found by bisection in its column. False (values undefined) for an entry outside the
  // pattern, whose place is then in `outside`.
  bool scatter(const std::vector<Eigen::Triplet<double>>& entries, realtype* values,
               Eigen::Triplet<double>& outside) {
    std::fill(values, values + rows_.size(), 0.0);
    if (positions_.size() < entries.size()) positions_.resize(entries.size(), -1);
    for (size_t k = 0; k < entries.size(); ++k) {
      const Eigen::Triplet<double>& entry = entries[k];
      sunindextype position = positions_[k];
      if (position < 0 || rows_[static_cast<size_t>(position)] != entry.row() ||
          !in_column(position, entry.col())) {
        position = find(entry.row(), entry.col());
        if (position < 0) {
          outside = entry;
          return false;
        }
        positions_[k] = position;
      }
      values[position] += entry.value();
    }
    return true;
  }

 private:
  bool in_column(sunindextype position, int column) const {
    return position >= column_starts_[static_cast<size_t>(column)] &&
           position < column_starts_[static_cast<size_t>(column) + 1];
  }
  sunindextype find(int row, int column) const {
    if (column < 0 || column >= size_) return -1;
    const auto begin = rows_.begin() + column_starts_[static_cast<size_t>(column)];
    const auto end = rows_.begin() + column_starts_[static_cast<size_t>(column) + 1];
    const auto it = std::lower_bound(begin, end, static_cast<sunindextype>(row));
    return it != end && *it == row ? static_cast<sunindextype>(it - rows_.begin()) : -1;
  }

  int size_;
  std::vector<sunindextype> column_starts_, rows_, positions_;
};

struct CallbackData {
  const DisplacementForm* form;
  double interval_begin = 0.0, interval_end = 0.0;
  JacobianPattern* pattern = nullptr;
  // Work space kept between calls (no allocation per residual or Jacobian).
  Eigen::VectorXd residual;
  std::vector<Eigen::Triplet<double>> entries;
  std::string last_error;
};

// Sources are evaluated strictly inside the current interval between breakpoints, so that a
// jump at either end (whose floating-point position may differ from the breakpoint's by a few
// ulps) is never seen on the wrong side. Inside, sources are smooth.
double source_time(const CallbackData& data, double t) {
  const double margin = 1e-9 * (data.interval_end - data.interval_begin);
  return std::clamp(t, data.interval_begin + margin, data.interval_end - margin);
}

// A callback's unrecoverable failure (IDA stops with the flag the call returns): its reason
// kept for the message; nothing thrown back into C.
int unrecoverable(CallbackData& data, const char* why) noexcept {
  try {
    data.last_error = why;
  } catch (...) {
  }
  return -1;
}

int residual_callback(realtype t, N_Vector yy, N_Vector yp, N_Vector rr, void* user) {
  auto& data = *static_cast<CallbackData*>(user);
  try {
    const int n = data.form->size();
    Eigen::Map<const Eigen::VectorXd> u(N_VGetArrayPointer(yy), n), up(N_VGetArrayPointer(yp), n);
    data.form->residual(source_time(data, t), u, up, data.residual);
    if (!data.residual.allFinite()) return 1;  // recoverable: IDA cuts the step
    Eigen::Map<Eigen::VectorXd>(N_VGetArrayPointer(rr), n) = data.residual;
    return 0;
  } catch (const std::exception& e) {
    return unrecoverable(data, e.what());
  } catch (...) {
    return unrecoverable(data, "unknown exception");
  }
}

int jacobian_callback(realtype /*t*/, realtype cj, N_Vector yy, N_Vector yp, N_Vector /*rr*/,
                      SUNMatrix jacobian, void* user, N_Vector, N_Vector, N_Vector) {
  auto& data = *static_cast<CallbackData*>(user);
  try {
    const int n = data.form->size();
    Eigen::Map<const Eigen::VectorXd> u(N_VGetArrayPointer(yy), n), up(N_VGetArrayPointer(yp), n);
    data.form->jacobian(cj, u, up, data.entries);
    // IDA zeroes the matrix, structure included, before every call (SUNMatZero).
    data.pattern->write_structure(jacobian);
    Eigen::Triplet<double> outside;
    if (!data.pattern->scatter(data.entries, SUNSparseMatrix_Data(jacobian), outside)) {
      data.last_error = "the Jacobian has an entry (row " + std::to_string(outside.row()) +
                        ", column " + std::to_string(outside.col()) +
                        ") outside its pattern taken at the start";
      return -1;
    }
    return 0;
  } catch (const std::exception& e) {
    return unrecoverable(data, e.what());
  } catch (...) {
    return unrecoverable(data, "unknown exception");
  }
}

// Called from C: nothing may throw out of it (an allocation failure keeps the last message).
void error_handler(int /*code*/, const char* /*module*/, const char* function, char* message,
                   void* user) {
  auto& data = *static_cast<CallbackData*>(user);
  try {
    data.last_error = std::string(function ? function : "IDA") + ": " + (message ? message : "");
  } catch (...) {
  }
}

// Per-unknown absolute tolerances: the relative tolerance times a scale of the unknown's kind
// (domain × across / through): the larger of its static value under the drive and its AC
// amplitude at the drive frequency (displacements: velocity amplitude / ω), so that a
// quantity that vanishes at rest (the shear force under a pure moment) still gets a
// physical scale.
Eigen::VectorXd absolute_tolerances(const DisplacementForm& form, const StaticResult& rest,
                                    double rtol, double frequency) {
  const System& system = form.system();
  const int n = system.size();
  // Six kinds (domain × across/through) and a seventh for the unknowns whose tolerance follows
  // the displacements' (Unknown::tolerance_per_displacement), kept out of the others' scales.
  constexpr int follows_displacement = 6;
  auto kind = [&](int k) {
    const Unknown& u = system.unknowns[static_cast<size_t>(k)];
    if (u.tolerance_per_displacement > 0.0) return follows_displacement;
    return static_cast<int>(u.domain) * 2 + (u.kind == Unknown::Kind::node_across ? 0 : 1);
  };
  double largest[7] = {0, 0, 0, 0, 0, 0, 0};
  if (rest.status.ok())
    for (int k = 0; k < n; ++k)
      largest[kind(k)] = std::max(largest[kind(k)], std::abs(rest.state[k]));
  const double omega = 2 * M_PI * frequency;
  if (system.b_ac().norm() > 0.0) {
    const Eigen::SparseMatrix<double> g =
        linearised_g(system, rest.status.ok() ? rest.operating_point : Eigen::VectorXd::Zero(n));
    const Eigen::VectorXcd y = small_signal_phasors(system, g, omega);
    if (y.size() == n) {
      for (int k = 0; k < n; ++k) {
        const bool displacement = form.mechanical(k);
        const double amplitude = std::abs(y[k]) / (displacement ? omega : 1.0);
        if (std::isfinite(amplitude)) largest[kind(k)] = std::max(largest[kind(k)], amplitude);
      }
    }
  }
  // A kind whose scale is rounding noise (e.g. 1e-19 A where no current flows in the static and
  // AC states) would get an absolute tolerance no step can meet: floor each kind at 1e-10 of
  // the largest scale in its domain (rounding is ~1e-16 of it).
  for (int domain = 0; domain < 3; ++domain) {
    const double floor = 1e-10 * std::max(largest[2 * domain], largest[2 * domain + 1]);
    for (int k = 2 * domain; k < 2 * domain + 2; ++k) largest[k] = std::max(largest[k], floor);
  }
  const double displacement = largest[static_cast<int>(Domain::translational) * 2];
  Eigen::VectorXd atol(form.size());
  for (int k = 0; k < n; ++k) {
    const double per_displacement =
        system.unknowns[static_cast<size_t>(k)].tolerance_per_displacement;
    const double kind_scale = kind(k) == follows_displacement
                                  ? (displacement > 0.0 ? displacement : 1.0) * per_displacement
                                  : largest[kind(k)];
    const double scale = kind_scale > 0.0 ? kind_scale : 1.0;
    atol[k] = rtol * scale;
    if (form.velocity_of(k) >= 0) atol[form.velocity_of(k)] = rtol * scale * omega;
  }
  return atol;
}

}  // namespace

namespace {

// One run of IDA over the transient (run_transient_ida): the displacement form, SUNDIALS' handles
// and the result, with a function per phase. Its construction may throw (no displacement form).
class IdaRun {
 public:
  IdaRun(const System& system, const std::vector<Probe>& probes, const TransientOptions& options,
         TransientResult& result)
      : system_(system),
        probes_(probes),
        options_(options),
        result_(result),
        form_(system),
        n_(form_.size()),
        yy_(n_, context_),
        yp_(n_, context_),
        id_(n_, context_),
        atol_(n_, context_),
        ida_(context_),
        mem_(ida_.get()) {
    data_.form = &form_;
  }

  // Start state, and a scale for the tolerances.
  Status set_start() {
    const StaticResult rest = solve_static(system_);
    Eigen::VectorXd u0 = Eigen::VectorXd::Zero(n_), up0 = Eigen::VectorXd::Zero(n_);
    if (options_.initial_state) {
      if (options_.initial_state->size() != n_)
        return Status::failure("initial state of the wrong size");
      u0 = *options_.initial_state;
    } else if (options_.start == StartState::static_) {
      if (!rest.status.ok()) return rest.status.with_context("static start state: ");
      u0 = form_.from_static(rest.state);
    }
    const double frequency = 1.0 / options_.end_time;
    double drive_frequency = frequency;
    for (const auto& w : system_.excitation().waveforms)
      if (w.period > 0.0) drive_frequency = std::max(drive_frequency, 1.0 / w.period);
    const Eigen::VectorXd atol_values =
        options_.absolute_tolerance > 0.0
            ? Eigen::VectorXd::Constant(n_, options_.absolute_tolerance)
            : absolute_tolerances(form_, rest, options_.relative_tolerance, drive_frequency);
    // Jacobian pattern: linear part plus the nonlinear part at a generic state.
    form_.jacobian(1.0, Eigen::VectorXd::Ones(n_), Eigen::VectorXd::Ones(n_), data_.entries);
    pattern_ = std::make_unique<JacobianPattern>(n_, data_.entries);
    data_.pattern = pattern_.get();
    Eigen::Map<Eigen::VectorXd>(yy_.data(), n_) = u0;
    Eigen::Map<Eigen::VectorXd>(yp_.data(), n_) = up0;
    Eigen::Map<Eigen::VectorXd>(atol_.data(), n_) = atol_values;
    for (int k = 0; k < n_; ++k)
      id_.data()[k] = form_.differential()[static_cast<size_t>(k)] ? 1.0 : 0.0;
    return Status::success();
  }

  // IDA's options, tolerances and its sparse KLU linear solver; false (failed_call_ says which
  // call) on failure.
  bool set_up() {
    if (!succeeded("IDASetErrHandlerFn", IDASetErrHandlerFn(mem_, error_handler, &data_)) ||
        !succeeded("IDAInit", IDAInit(mem_, residual_callback, 0.0, yy_, yp_)) ||
        !succeeded("IDASVtolerances", IDASVtolerances(mem_, options_.relative_tolerance, atol_)) ||
        !succeeded("IDASetUserData", IDASetUserData(mem_, &data_)) ||
        !succeeded("IDASetId", IDASetId(mem_, id_)) ||
        !succeeded("IDASetMaxNumSteps", IDASetMaxNumSteps(mem_, 100000)) ||  // per output interval
        (options_.max_step > 0.0 &&
         !succeeded("IDASetMaxStep", IDASetMaxStep(mem_, options_.max_step))))
      return false;
    jacobian_ = std::make_unique<sundials::Matrix>(SUNSparseMatrix(
        n_, n_, std::max<sunindextype>(pattern_->nonzeros(), 1), CSC_MAT, context_));
    solver_ = std::make_unique<sundials::LinearSolver>(SUNLinSol_KLU(yy_, *jacobian_, context_));
    return succeeded("IDASetLinearSolver", IDASetLinearSolver(mem_, *solver_, *jacobian_), true) &&
           succeeded("IDASetJacFn", IDASetJacFn(mem_, jacobian_callback), true);
  }
  Status setup_failure() const { return Status::failure("IDA setup: " + failed_call_); }

  // Intervals between breakpoints; outputs inside each.
  Status run() {
    const std::vector<double> stops = interval_ends(system_, options_.end_time);
    outputs_ = options_.output_times;
    std::sort(outputs_.begin(), outputs_.end());
    result_.times.reserve(outputs_.size());
    for (auto& series : result_.values) series.reserve(outputs_.size());
    ConsistentStart consistent_start(form_);
    double t = 0.0;
    for (double stop : stops) {
      if (stop <= t) continue;
      if (Status started = start_interval(consistent_start, t, stop); !started.ok()) return started;
      if (Status integrated = integrate_interval(t, stop); !integrated.ok()) return integrated;
      t = stop;
    }
    accumulate_statistics();
    result_.final_state = Eigen::Map<const Eigen::VectorXd>(yy_.data(), n_);
    if (Status finite = check_finite_outputs(result_, probes_, "IDA"); !finite.ok()) return finite;
    if (!result_.final_state.allFinite())
      return Status::failure(
          "IDA gave a non-finite state at t = " + format_time(options_.end_time) + " s");
    return Status::success();
  }

 private:
  // Every IDA call's flag is checked; the first failure names the call, its flag and IDA's
  // own message (error_handler), and ends the run as a numerical failure.
  bool succeeded(const char* call, int flag, bool linear_solver_interface = false) {
    if (flag == IDA_SUCCESS) return true;  // IDALS_SUCCESS is 0 as well
    failed_call_ = sundials::describe_flag(call, flag, linear_solver_interface);
    if (!data_.last_error.empty()) failed_call_ += ": " + data_.last_error;
    return false;
  }
  Status run_failure(double at) {
    accumulate_statistics();
    return Status::failure("IDA at t = " + format_time(at) + " s: " + failed_call_);
  }
  void record(double t) {
    const Eigen::Map<const Eigen::VectorXd> u(yy_.data(), n_), up(yp_.data(), n_);
    result_.times.push_back(t);
    for (size_t p = 0; p < probes_.size(); ++p) {
      const double value = form_.probe(probes_[p], u, up);
      result_.values[p].push_back(value);
    }
  }
  // The counters are only read (each getter fails only for a null memory, which the Ida
  // handle excludes); a getter that fails anyway adds nothing.
  void accumulate_statistics() {
    // The getter runs before its value is read: two statements, since the order in which a
    // call's arguments are evaluated is unspecified (GCC read `value` first, so every counter
    // showed the one before it).
    const auto add = [this](int (*getter)(void*, long*), long& total) {
      long value = 0;
      if (getter(mem_, &value) == IDA_SUCCESS) total += value;
    };
    IntegratorStatistics& statistics = result_.statistics;
    add(IDAGetNumSteps, statistics.steps);
    add(IDAGetNumResEvals, statistics.residual_evaluations);
    add(IDAGetNumJacEvals, statistics.jacobian_evaluations);
    add(IDAGetNumNonlinSolvIters, statistics.newton_iterations);
    add(IDAGetNumErrTestFails, statistics.error_test_failures);
    add(IDAGetNumNonlinSolvConvFails, statistics.convergence_failures);
  }

  // Consistent values at the start of the interval [t, stop]: algebraic unknowns and
  // derivatives follow the sources' new values; differential unknowns are continuous. Own
  // Newton iteration first (consistent_start.hpp); IDACalcIC only if it fails.
  Status start_interval(ConsistentStart& consistent_start, double t, double stop) {
    data_.interval_begin = t;
    data_.interval_end = stop;
    Eigen::VectorXd u_start = Eigen::Map<const Eigen::VectorXd>(yy_.data(), n_);
    Eigen::VectorXd up_start = Eigen::Map<const Eigen::VectorXd>(yp_.data(), n_);
    const Status consistent =
        consistent_start.make_consistent(source_time(data_, t), u_start, up_start);
    if (consistent.ok()) {
      Eigen::Map<Eigen::VectorXd>(yy_.data(), n_) = u_start;
      Eigen::Map<Eigen::VectorXd>(yp_.data(), n_) = up_start;
    }
    if (result_.statistics.restarts > 0) accumulate_statistics();
    if ((result_.statistics.restarts > 0 || consistent.ok()) &&
        !succeeded("IDAReInit", IDAReInit(mem_, t, yy_, yp_)))
      return run_failure(t);
    ++result_.statistics.restarts;
    if (!consistent.ok()) {
      const int ic = IDACalcIC(mem_, IDA_YA_YDP_INIT, t + 1e-3 * (stop - t));
      if (ic != IDA_SUCCESS)
        return Status::failure("consistent initial values at t = " + format_time(t) +
                               " s failed (" + consistent.message + "; then " + data_.last_error +
                               "); try a nonzero drive.rise_time or a start from the static state");
      if (!succeeded("IDAGetConsistentIC", IDAGetConsistentIC(mem_, yy_, yp_)))
        return run_failure(t);
    }
    return Status::success();
  }

  // IDA from t to stop, recording the outputs inside; t ends at the last time reached.
  Status integrate_interval(double& t, double stop) {
    // Where the interval begins, for a second attempt with the algebraic unknowns out of
    // the error test (below).
    const Eigen::VectorXd u_begin = Eigen::Map<const Eigen::VectorXd>(yy_.data(), n_);
    const Eigen::VectorXd up_begin = Eigen::Map<const Eigen::VectorXd>(yp_.data(), n_);
    const double t_begin = t;
    while (next_output_ < outputs_.size() && outputs_[next_output_] <= t) {
      if (outputs_[next_output_] == t) record(t);
      ++next_output_;
    }
    const size_t first_output = next_output_, recorded = result_.times.size();
    if (!succeeded("IDASetStopTime", IDASetStopTime(mem_, stop))) return run_failure(t);
    while (true) {
      const double target = next_output_ < outputs_.size() && outputs_[next_output_] < stop
                                ? outputs_[next_output_]
                                : stop;
      realtype reached = t;
      const int flag = IDASolve(mem_, target, &reached, yy_, yp_, IDA_NORMAL);
      if (flag < 0) {
        if (Status retried =
                retry_without_algebraic(reached, flag, stop, t_begin, u_begin, up_begin);
            !retried.ok())
          return retried;
        t = t_begin;
        next_output_ = first_output;
        result_.times.resize(recorded);
        for (auto& series : result_.values) series.resize(recorded);
        continue;
      }
      t = reached;
      if (next_output_ < outputs_.size() &&
          std::abs(t - outputs_[next_output_]) <= 1e-12 * std::max(1.0, t)) {
        record(t);
        ++next_output_;
      }
      if (!keep_going(options_.progress, static_cast<long>(next_output_),
                      static_cast<long>(outputs_.size()), "output times")) {
        accumulate_statistics();
        return cancelled_status();
      }
      if (t >= stop || flag == IDA_TSTOP_RETURN) break;
    }
    return Status::success();
  }

  // After IDASolve failed with `flag` at `reached`: the interval again from its start
  // (t_begin, u_begin, up_begin) with the algebraic unknowns out of the error test, unless they
  // already are (then the failure).
  Status retry_without_algebraic(double reached, int flag, double stop, double t_begin,
                                 const Eigen::VectorXd& u_begin, const Eigen::VectorXd& up_begin) {
    accumulate_statistics();
    char buffer[96];
    std::snprintf(buffer, sizeof buffer, "IDA failed at t = %.9g s (flag %d): ", reached, flag);
    const std::string failure = buffer + data_.last_error;
    if (suppress_algebraic_)
      return Status::failure(failure + "; try a looser rtol or atol, or a shorter end time");
    // The algebraic unknowns can pin the step size: right after an edge at N = 10 000
    // segments (the beam's forces leave the consistent start with rounding errors above
    // their absolute tolerance; the error test fails down to h = 1e-13 s), or in a fast
    // algebraic transient (a 1 ns RC loop beside a 0.2 s period). They follow the
    // differential unknowns exactly, so this interval is integrated again from its start
    // with them out of the error test, as is the rest of the run, and the method says
    // so. (Running the whole transient again made 2 periods of the 10 000-segment fin at
    // rtol 1e-6 take 17 s instead of 5 s.)
    result_.method_note = "algebraic unknowns out of the error test after: " + failure;
    suppress_algebraic_ = true;
    Eigen::Map<Eigen::VectorXd>(yy_.data(), n_) = u_begin;
    Eigen::Map<Eigen::VectorXd>(yp_.data(), n_) = up_begin;
    if (!succeeded("IDASetSuppressAlg", IDASetSuppressAlg(mem_, SUNTRUE)) ||
        !succeeded("IDAReInit", IDAReInit(mem_, t_begin, yy_, yp_)) ||
        !succeeded("IDASetStopTime", IDASetStopTime(mem_, stop)))
      return run_failure(t_begin);
    return Status::success();
  }

  const System& system_;
  const std::vector<Probe>& probes_;
  const TransientOptions& options_;
  TransientResult& result_;
  const DisplacementForm form_;
  const int n_;
  CallbackData data_;
  std::unique_ptr<JacobianPattern> pattern_;
  sundials::Context context_;
  sundials::Vector yy_, yp_, id_, atol_;
  sundials::Ida ida_;
  void* mem_;
  std::unique_ptr<sundials::Matrix> jacobian_;
  std::unique_ptr<sundials::LinearSolver> solver_;
  std::string failed_call_;
  std::vector<double> outputs_;
  size_t next_output_ = 0;
  bool suppress_algebraic_ = false;  // set after a failure (retry_without_algebraic)
};

TransientResult integrate(const System& system, const std::vector<Probe>& probes,
                          const TransientOptions& options) {
  Timed<TransientResult> timed;
  TransientResult& result = timed.result;
  result.method = Method::ida;
  result.values.assign(probes.size(), {});
  auto finish = [&](Status status) { return timed.finish(std::move(status)); };
  try {
    IdaRun run(system, probes, options, result);
    if (Status started = run.set_start(); !started.ok()) return finish(started);
    if (!run.set_up()) return finish(run.setup_failure());
    return finish(run.run());
  } catch (const std::exception& e) {
    return finish(Status::failure(std::string("transient: ") + e.what()));
  }
}

}  // namespace

TransientResult run_transient_ida(const System& system, const std::vector<Probe>& probes,
                                  const TransientOptions& options) {
  return integrate(system, probes, options);
}

}  // namespace emnet
