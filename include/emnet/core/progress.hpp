// Progress and cancellation of long analyses.
//
// An analysis that loops (the AC sweep over its frequencies, a transient over its output times,
// the sensitivity over its parameters) takes an optional Progress* in its options: after each
// step it calls report(done, total, what), and when cancelled() is true it stops at the next
// step and returns cancelled_status() (its code StatusCode::cancelled). A null pointer means no
// reports and no cancellation. report() is called on the analysis's own thread once per step, so an
// implementation only records the state (a program prints it at its own rate); cancelled() is a
// flag read, e.g. one that a SIGINT handler sets.
#pragma once

#include <string_view>

#include "emnet/core/errors.hpp"

namespace emnet {

/// Receives an analysis's progress reports and tells it when to stop (see above).
class Progress {
 public:
  virtual ~Progress() = default;
  /// `done` of `total` steps of `what` ("AC frequencies", "output times"); total 0: unknown.
  virtual void report(long done, long total, std::string_view what) = 0;
  /// Whether the analysis is to stop at its next step.
  virtual bool cancelled() const = 0;
};

/// Whether `progress` is non-null and cancelled.
inline bool cancel_requested(const Progress* progress) {
  return progress != nullptr && progress->cancelled();
}

/// Reports a step; false when the analysis is to stop (cancelled).
inline bool keep_going(Progress* progress, long done, long total, std::string_view what) {
  if (progress == nullptr) return true;
  progress->report(done, total, what);
  return !progress->cancelled();
}

/// Reports a phase with no count (a study's "building the model"); nothing when `progress` is null.
inline void report_phase(Progress* progress, std::string_view what) {
  if (progress != nullptr) progress->report(0, 0, what);
}

/// The Status of an analysis stopped by its Progress: code StatusCode::cancelled, message
/// "cancelled" (the one place that builds it).
inline Status cancelled_status() {
  return {StatusCode::cancelled, "cancelled"};
}

/// Forwards the cancellation of `outer` but drops reports: for analyses run inside one step of
/// another (the one-period IDA runs of a shooting solve), whose reports would replace the outer
/// analysis's.
class CancellationOnly : public Progress {
 public:
  explicit CancellationOnly(const Progress* outer) : outer_(outer) {}
  void report(long, long, std::string_view) override {}
  bool cancelled() const override { return cancel_requested(outer_); }

 private:
  const Progress* outer_;
};

}  // namespace emnet
