// The command line's names for the fields of the library's Options: each command declares, where
// it registers a CLI11 option, which field that option sets (`--samples` sets "samples"), and an
// emnet::OptionError, which names fields, is printed with the command's flags instead. An
// override's InputError (where "override") is printed with "--set".
#pragma once

#include <CLI/CLI.hpp>
#include <initializer_list>
#include <string>

#include "emnet/core/option_error.hpp"

namespace emnet_cli {

// Records that `option` (of its command) sets each of `fields` of the library's Options and
// returns it, so that a registration reads
//   sets_fields(command->add_option("--samples", sweep.samples, "..."), {"samples"});
CLI::Option* sets_fields(CLI::Option* option, std::initializer_list<const char*> fields);

// The flag of `command` that sets `field` ("--samples"); a field no option of the command sets
// keeps its own name.
std::string flag_of_field(const CLI::App* command, const std::string& field);

// The message of an input error as `command` prints it: an OptionError with the command's flags
// for its fields, an override's InputError with "--set", any other as it is.
std::string input_error_text(const CLI::App* command, const emnet::InputError& error);

}  // namespace emnet_cli
