// The command line's names for the library's Options fields (tools/cli/option_names.hpp).
#include "cli/option_names.hpp"

#include <algorithm>
#include <map>
#include <mutex>
#include <vector>

#include "emnet/core/option_error.hpp"

namespace emnet_cli {

namespace {

// Per option, the fields it sets. Filled while the commands are registered (before parsing),
// read when an error is printed.
using OptionFields = std::map<const CLI::Option*, std::vector<std::string>>;

OptionFields& option_fields() {
  static OptionFields fields;
  return fields;
}

std::mutex& field_flags_mutex() {
  static std::mutex mutex;
  return mutex;
}

// What the library calls the origin of a value an override wrote (emnet/scene/scene_reader.hpp).
constexpr const char* kLibraryOverrideWhere = "override";

}  // namespace

CLI::Option* sets_fields(CLI::Option* option, std::initializer_list<const char*> fields) {
  const std::lock_guard<std::mutex> lock(field_flags_mutex());
  std::vector<std::string>& set = option_fields()[option];
  set.insert(set.end(), fields.begin(), fields.end());
  return option;
}

std::string flag_of_field(const CLI::App* command, const std::string& field) {
  const std::lock_guard<std::mutex> lock(field_flags_mutex());
  for (const CLI::Option* option : command->get_options()) {
    const auto found = option_fields().find(option);
    if (found != option_fields().end() &&
        std::find(found->second.begin(), found->second.end(), field) != found->second.end())
      return option->get_name();
  }
  return field;
}

std::string input_error_text(const CLI::App* command, const emnet::InputError& error) {
  if (const auto* option_error = dynamic_cast<const emnet::OptionError*>(&error))
    return option_error->message_with(
        [command](const std::string& field) { return flag_of_field(command, field); });
  if (error.where() == kLibraryOverrideWhere)
    return emnet::input_error_message(flag_of_field(command, "overrides"), error.key(),
                                      emnet::input_error_reason(error));
  return error.what();
}

}  // namespace emnet_cli
