// Error types shared by every layer.
//
// Three kinds of error (docs/model.md, Kinds of error): assert for invariants; InputError for bad
// user input, naming the file, line and key; a status in each analysis Result for numerical
// failure.
#pragma once

#include <stdexcept>
#include <string>

namespace emnet {

// Bad user input: a scene file, a --set override or a command-line option.
// `where` is "file:line" (or "file", or "--set"), `key` the dotted key concerned.
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

// Outcome of an analysis. Numerical failure is reported here, never thrown.
struct Status {
  bool ok = true;
  std::string message;
  static Status success() { return {}; }
  static Status failure(std::string why) { return {false, std::move(why)}; }
};

}  // namespace emnet
