// Errors about an option of a library call, named by the library's own field, never by a
// front-end's word (docs/architecture.md, Conventions).
#pragma once

#include <functional>
#include <string>

#include "emnet/core/errors.hpp"

namespace emnet {

/// The name a front-end gives an Options field ("samples" → "--samples" on the command line,
/// "samples" in Python); a field it does not name keeps its own.
using FieldNamer = std::function<std::string(const std::string& field)>;

/// Bad value of an Options field of a library call (SwitchingSweepOptions::samples, a probe
/// text): names the field by its C++ name, dotted for a nested one ("reduction.tolerance"),
/// never by a front-end's word. A front-end words it in its own terms with message_with (the
/// command line's flags, Python's keyword arguments); what(), where() and key() use the fields'
/// own names.
///
/// Its message reads "<field>: key '<key>': <reason>": `key` is the field itself unless the
/// error names a key the option gave (a probe's text, a varied scene key) or another field;
/// `location` replaces the field before the key when the value came from a file the option
/// named ("variants.csv:3"). A reason that mentions another field writes it "{field}" (e.g.
/// "{reduce} replaces the exact method"), rendered by the front-end's names.
class OptionError : public InputError {
 public:
  /// @param field the Options field ("samples", "reduction.tolerance")
  /// @param reason what is wrong, other fields written "{field}"
  /// @param key the scene key or text the option gave ("u_A"); empty: the field itself
  OptionError(std::string field, std::string reason, std::string key = {});

  /// An error about the field `field` whose key is another field, `key_field`; `where`, when
  /// given, replaces the field before the key and is written with fields ("{from}/{to}").
  static OptionError between(std::string field, std::string key_field, std::string reason,
                             std::string where = {});
  /// An error in a file the field named, at `location` ("variants.csv:3"), about `key` (empty:
  /// the field itself).
  static OptionError in_file(std::string field, std::string location, std::string key,
                             std::string reason);

  const std::string& field() const { return field_; }
  /// The reason (the message after "where: key '…': ") with the fields' own names.
  std::string reason() const;
  /// The whole message with every field named by `name_of`.
  std::string message_with(const FieldNamer& name_of) const;
  /// What the message's "where" is in a front-end's words (the location, or the field's name).
  std::string where_with(const FieldNamer& name_of) const;
  /// What the message's key is in a front-end's words.
  std::string key_with(const FieldNamer& name_of) const;
  /// The reason with every field named by `name_of`.
  std::string reason_with(const FieldNamer& name_of) const;

 private:
  OptionError(std::string field, std::string reason, std::string key, std::string key_field,
              std::string location, std::string where_fields);
  std::string field_;
  std::string reason_template_;  // the reason, other fields written "{field}"
  std::string key_;              // a key or text the option gave; empty: see key_field_
  std::string key_field_;        // the field the message's key names; empty: field_
  std::string location_;         // a file and line the option named; empty: the field
  std::string where_fields_;     // the "where" written with fields; empty: location_ or the field
};

/// The reason of an InputError: its message after the "where: key '…': " that InputError puts
/// before every message (from where() and key(), not from reading the text).
std::string input_error_reason(const InputError& error);

/// "where: key 'key': reason", the form of every InputError's message.
std::string input_error_message(const std::string& where, const std::string& key,
                                const std::string& reason);

}  // namespace emnet
