// OptionError: the message of a bad option, its fields named by the front-end that reports it
// (emnet/core/option_error.hpp).
#include "emnet/core/option_error.hpp"

#include <cctype>

namespace emnet {

namespace {

std::string own_name(const std::string& field) {
  return field;
}

bool field_character(char c) {
  return std::islower(static_cast<unsigned char>(c)) ||
         std::isdigit(static_cast<unsigned char>(c)) || c == '_' || c == '.';
}

// `text` with every "{field}" (lower-case letters, digits, '_' and '.') replaced by name_of(field).
std::string render_fields(const std::string& text, const FieldNamer& name_of) {
  std::string out;
  size_t start = 0;
  while (start < text.size()) {
    const size_t open = text.find('{', start);
    if (open == std::string::npos) break;
    size_t close = open + 1;
    while (close < text.size() && field_character(text[close])) ++close;
    out.append(text, start, open - start);
    if (close < text.size() && text[close] == '}' && close > open + 1) {
      out += name_of(text.substr(open + 1, close - open - 1));
      start = close + 1;
    } else {
      out += '{';
      start = open + 1;
    }
  }
  out.append(text, start, std::string::npos);
  return out;
}

std::string message_prefix(const std::string& where, const std::string& key) {
  std::string text = where.empty() ? std::string() : where + ": ";
  if (!key.empty()) text += "key '" + key + "': ";
  return text;
}

}  // namespace

std::string input_error_message(const std::string& where, const std::string& key,
                                const std::string& reason) {
  return message_prefix(where, key) + reason;
}

std::string input_error_reason(const InputError& error) {
  if (const auto* option_error = dynamic_cast<const OptionError*>(&error))
    return option_error->reason();
  const std::string text = error.what();
  const std::string prefix = message_prefix(error.where(), error.key());
  return text.compare(0, prefix.size(), prefix) == 0 ? text.substr(prefix.size()) : text;
}

OptionError::OptionError(std::string field, std::string reason, std::string key)
    : OptionError(std::move(field), std::move(reason), std::move(key), {}, {}, {}) {}

OptionError::OptionError(std::string field, std::string reason, std::string key,
                         std::string key_field, std::string location, std::string where_fields)
    : InputError(!location.empty()       ? location
                 : !where_fields.empty() ? render_fields(where_fields, own_name)
                                         : field,
                 !key.empty()         ? key
                 : !key_field.empty() ? key_field
                                      : field,
                 render_fields(reason, own_name)),
      field_(std::move(field)),
      reason_template_(std::move(reason)),
      key_(std::move(key)),
      key_field_(std::move(key_field)),
      location_(std::move(location)),
      where_fields_(std::move(where_fields)) {}

OptionError OptionError::between(std::string field, std::string key_field, std::string reason,
                                 std::string where) {
  return OptionError(std::move(field), std::move(reason), {}, std::move(key_field), {},
                     std::move(where));
}

OptionError OptionError::in_file(std::string field, std::string location, std::string key,
                                 std::string reason) {
  return OptionError(std::move(field), std::move(reason), std::move(key), {}, std::move(location),
                     {});
}

std::string OptionError::reason() const {
  return render_fields(reason_template_, own_name);
}

std::string OptionError::where_with(const FieldNamer& name_of) const {
  if (!location_.empty()) return location_;
  return where_fields_.empty() ? name_of(field_) : render_fields(where_fields_, name_of);
}

std::string OptionError::key_with(const FieldNamer& name_of) const {
  if (!key_.empty()) return key_;
  return name_of(key_field_.empty() ? field_ : key_field_);
}

std::string OptionError::reason_with(const FieldNamer& name_of) const {
  return render_fields(reason_template_, name_of);
}

std::string OptionError::message_with(const FieldNamer& name_of) const {
  return input_error_message(where_with(name_of), key_with(name_of), reason_with(name_of));
}

}  // namespace emnet
