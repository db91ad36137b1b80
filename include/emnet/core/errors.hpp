// Error types shared by every layer.
//
// Three kinds of error (docs/model.md, Kinds of error): assert for invariants; InputError for bad
// user input, naming the file, line and key (OptionError, emnet/core/option_error.hpp, for an
// option of a library call, naming its Options field); a status in each analysis Result for
// numerical failure or cancellation.
#pragma once

#include <stdexcept>
#include <string>

namespace emnet {

// Bad user input: a scene file, an override of one or an option of a library call.
// `where` is "file:line" (or "file", or "override" for a value an override wrote, or the called
// function: "set_parameter"), `key` the dotted key concerned.
class InputError : public std::runtime_error {
 public:
  InputError(std::string where, std::string key, const std::string& message)
      : std::runtime_error(format(where, key, message)),
        where_(std::move(where)),
        key_(std::move(key)) {}
  const std::string& where() const { return where_; }
  const std::string& key() const { return key_; }

 private:
  static std::string format(const std::string& where, const std::string& key,
                            const std::string& message) {
    std::string text = where.empty() ? std::string() : where + ": ";
    if (!key.empty()) text += "key '" + key + "': ";
    return text + message;
  }
  std::string where_;
  std::string key_;
};

/// What an outcome is, for a caller to act on without reading the message.
enum class StatusCode {
  ok,         ///< computed
  numerical,  ///< the method could not compute it (no convergence, a singular system, a file
              ///< that cannot be written): the message says why and what to change
  cancelled,  ///< stopped by its Progress's cancellation (emnet/core/progress.hpp)
};

/// Outcome of an analysis: a code and, when it is not ok, the reason. Numerical failure and
/// cancellation are reported here, never thrown.
struct Status {
  StatusCode code = StatusCode::ok;
  std::string message;  ///< empty when ok

  bool ok() const { return code == StatusCode::ok; }
  bool cancelled() const { return code == StatusCode::cancelled; }

  static Status success() { return {}; }
  /// A numerical failure, `why` saying what failed and what to change.
  static Status failure(std::string why) { return {StatusCode::numerical, std::move(why)}; }

  /// The same outcome, its message after `context` ("static operating point: ") when not ok.
  Status with_context(const std::string& context) const {
    return ok() ? *this : Status{code, context + message};
  }
};

}  // namespace emnet
