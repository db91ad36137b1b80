// emnet command-line program: one scene, one command (tools/cli/<command>.cpp each parse their
// options, call the library and report).
//
// Exit status: 0 success; 2 bad input (scene file, override, option), with one message naming
// the file, line and key, or an output file (--csv, --plot, -o) or standard output that could
// not be written (the result is printed first); 3 numerical failure, with the reason (for
// crosscheck also: ngspice missing, failing or timed out); 4 crosscheck: a difference exceeds its
// tolerance; 5 computed but outside the model's validity (a deflection above
// model.deflection_limit of the beam length, or a DEA's field V/d above its breakdown field;
// emnet/model/validity.hpp): the result is printed with a WARNING line on standard output and error
// and "validity" in --json; 130 interrupted (Ctrl-C), no output file written; 1 anything else.
//
// Output files are written only after the result is computed and printed, each one completely or
// not at all (emnet::OutputFile). Text from outside (names, titles, file names, tool messages)
// reaches the terminal through emnet::terminal_text, control characters escaped.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <new>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "cli/common.hpp"
#include "cli/option_names.hpp"
#include "emnet/core/terminal_text.hpp"
#include "emnet/core/version.hpp"

using namespace emnet_cli;

namespace {

// Words wrapped at 90 columns, continuation lines indented by two.
std::string wrapped_at_90_columns(const std::string& text) {
  std::string out, line;
  size_t start = 0;
  while (start < text.size()) {
    size_t end = text.find(' ', start);
    if (end == std::string::npos) end = text.size();
    const std::string word = text.substr(start, end - start);
    if (!line.empty() && line.size() + 1 + word.size() > 90) {
      out += line + "\n";
      line = "  " + word;
    } else {
      line += (line.empty() ? "" : " ") + word;
    }
    start = end + 1;
  }
  return out + line;
}

// Each command's help ends with one example and the scene keys it reads (their units,
// defaults and meanings: docs/scene-reference.md, `emnet schema`), before the exit statuses.
void add_examples_and_keys_read_to_the_help(const std::vector<Command>& commands) {
  const std::string model_tables =
      "the tables that build the model: [beam] (or [[section]]), [[mass]], [[spring]], "
      "[damping], [[dea]], [drive], [[load]], [[circuit]], [environment], [model]; and "
      "[[probe]] for the outputs (docs/scene-reference.md)";
  struct Usage {
    std::string command, example, reads;
  };
  const std::vector<Usage> usages = {
      {"static", "emnet static netlists/fishfin.toml", model_tables},
      {"modes", "emnet modes netlists/fishfin.toml --count 3", model_tables},
      {"ac", "emnet ac netlists/fishfin.toml --plot bode.png",
       model_tables + "; [ac] for the sweep (from, to, points, scale)"},
      {"tran", "emnet tran netlists/fishfin.toml --periods 5",
       model_tables + "; drive.frequency sets the period of --periods"},
      {"sweep-switching", "emnet sweep-switching netlists/fishfin.toml --from 1 --to 4 --step 0.1",
       model_tables + "; the drive's switching frequency is swept (drive.frequency is replaced)"},
      {"identify", "",  // its description has the example
       model_tables + "; the fitted key (beam.bending_stiffness unless --fit names another; "
                      "with --peak also damping.loss_factor) is replaced"},
      {"sensitivity", "emnet sensitivity netlists/fishfin.toml --modes 2", model_tables},
      {"mismatch", "emnet mismatch netlists/fishfin.toml", model_tables},
      {"netlist", "emnet netlist netlists/fishfin.toml --analysis ac -o fishfin-ac.cir",
       model_tables + "; [ac] for --analysis ac"},
      {"crosscheck", "emnet crosscheck netlists/fishfin.toml --analysis ac,modal",
       model_tables + "; [ac] for the AC comparison"},
      {"study", "",  // its description has the example
       model_tables + "; the keys named by --vary or --variants are replaced per variant"},
      {"schema", "emnet schema --markdown", "no scene: it lists every key the reader accepts"}};
  for (const Command& command : commands)
    for (const Usage& usage : usages)
      if (command.app->get_name() == usage.command)
        command.app->footer((usage.example.empty() ? "" : "Example:\n  " + usage.example + "\n") +
                            wrapped_at_90_columns("Reads: " + usage.reads + ".") + "\n\n" +
                            command.app->get_footer());
}

// The commands in the order of the help, each with the function that adds it.
struct CommandMaker {
  std::string_view name;
  Command (*add)(CLI::App&, CommonOptions&);
};
const CommandMaker kCommandMakers[] = {
    {"static", add_static_command},
    {"modes", add_modes_command},
    {"ac", add_ac_command},
    {"tran", add_tran_command},
    {"sweep-switching", add_sweep_switching_command},
    {"identify", add_identify_command},
    {"sensitivity", add_sensitivity_command},
    {"mismatch", add_mismatch_command},
    {"netlist", add_netlist_command},
    {"crosscheck", add_crosscheck_command},
    {"study", add_study_command},
    {"schema", [](CLI::App& app, CommonOptions&) { return add_schema_command(app); }}};

// Where argv[1] names a command, that command alone; else every command (for emnet --help, the
// version, an unknown command's list). Adding every command's options was a third of the
// instructions of `emnet --help`, paid by every run.
std::vector<Command> added_commands(CLI::App& app, CommonOptions& options, int argc, char** argv) {
  const auto named = [&](const CommandMaker& maker) { return argc >= 2 && maker.name == argv[1]; };
  const bool one = std::any_of(std::begin(kCommandMakers), std::end(kCommandMakers), named);
  std::vector<Command> commands;
  for (const CommandMaker& maker : kCommandMakers)
    if (!one || named(maker)) commands.push_back(maker.add(app, options));
  return commands;
}

// An unknown command would otherwise be taken for a scene file ("A subcommand is required").
bool refused_as_no_known_command(CLI::App& app, int argc, char** argv) {
  std::vector<std::string> command_names;
  std::string command_list;
  for (const CLI::App* command : app.get_subcommands([](CLI::App*) { return true; })) {
    command_names.push_back(command->get_name());
    command_list += (command_list.empty() ? "" : ", ") + command->get_name();
  }
  if (argc >= 2 && (argv[1][0] == '-' || std::find(command_names.begin(), command_names.end(),
                                                   argv[1]) != command_names.end()))
    return false;
  std::cerr << "emnet: error: "
            << (argc < 2 ? std::string("a command is required")
                         : "unknown command '" + shown(argv[1]) + "'")
            << "; the commands are " << command_list << " (see emnet --help)\n";
  return true;
}

// The help (or the version) is output too: a full disk or closed file behind standard output
// fails it (2).
int help_printed(CLI::App& app, const CLI::ParseError& e) {
  const int status = app.exit(e);
  std::cout.flush();
  if (!std::cout || std::fflush(stdout) != 0 || std::ferror(stdout)) {
    std::cerr << "emnet: error: cannot write the help to standard output (" << std::strerror(errno)
              << ")\n";
    return 2;
  }
  return status;
}

// The exit status when parsing ends the program (help, a bad option); nullopt to go on.
std::optional<int> status_if_parsing_ends_the_program(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return help_printed(app, e);
  } catch (const CLI::CallForAllHelp& e) {
    return help_printed(app, e);
  } catch (const CLI::CallForVersion& e) {
    return help_printed(app, e);
  } catch (const CLI::ParseError& e) {
    // CLI11's message quotes the argument as given: control characters escaped here.
    std::cerr << "emnet: error: " << emnet::terminal_text(e.what()) << " (see emnet --help)\n";
    return 2;
  }
  return std::nullopt;
}

// One message for a failure: after the progress line, control characters escaped; an
// interruption wins over the failure it caused.
int failed(TerminalProgress& reporter, int status, const std::string& kind,
           const std::string& what) {
  reporter.finish();
  if (InterruptHandler::interrupted()) {
    std::cerr << "emnet: interrupted (Ctrl-C): stopped, no output file written\n";
    return 130;
  }
  std::cerr << "emnet: " << kind << ": "
            << (status == 2 ? emnet::terminal_text(what) : emnet::terminal_lines(what)) << "\n";
  return status;
}

// The chosen command's status, each kind of exception its own.
int run_the_chosen_command(const CLI::App& app, const std::vector<Command>& commands,
                           TerminalProgress& reporter) {
  int status = 1;
  try {
    for (const Command& command : commands)
      if (*command.app) status = command.run();
  } catch (const InputError& e) {
    // Worded with the command's flags: a library OptionError names its Options fields.
    status = failed(reporter, 2, "error", input_error_text(app.get_subcommands().front(), e));
  } catch (const FileError& e) {
    status = failed(reporter, 2, "error", e.what());
  } catch (const Interrupted& e) {
    status = failed(reporter, 130, "interrupted", e.what());
  } catch (const NumericalFailure& e) {
    status = failed(reporter, 3, "numerical failure", e.what());
  } catch (const std::bad_alloc&) {
    status = failed(reporter, 3, "numerical failure",
                    "out of memory: the model does not fit in the memory this process may "
                    "use; fewer segments (--segments), or --reduce where the command has it");
  } catch (const std::exception& e) {
    status = failed(reporter, 1, "internal error", e.what());
  }
  return status;
}

// The result printed is output too: a full disk or a closed file behind standard output is
// an error, not a silent loss.
int status_once_the_output_is_written(int status) {
  std::cout.flush();
  const bool lost = !std::cout || std::fflush(stdout) != 0 || std::ferror(stdout);
  if (lost) {
    std::cerr << "emnet: error: cannot write the result to standard output ("
              << std::strerror(errno) << ")\n";
    return status == 0 ? 2 : status;
  }
  return status;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "emnet: lumped electromechanical network simulator.\n"
      "Bending beams (Euler-Bernoulli or Timoshenko) cut into N segments, with masses, springs\n"
      "and circuits, driven by dielectric elastomer actuators, as Firestone (mobility)\n"
      "networks: force = current, velocity = voltage."};
  app.set_version_flag("--version", std::string("emnet ") + emnet::version());
  app.require_subcommand(1);
  app.footer(
      "Exit status: 0 success; 2 bad input; 3 numerical failure; 4 crosscheck: a difference\n"
      "exceeds its tolerance; 5 computed but outside the model's validity (a deflection above\n"
      "model.deflection_limit of the beam length, default 10 %, or a DEA's field V/d above\n"
      "dea[].breakdown_field): printed with a WARNING and \"validity\" in --json.");
  CommonOptions options;
  const std::vector<Command> commands = added_commands(app, options, argc, argv);
  const CLI::App* crosscheck_command = nullptr;
  for (const Command& command : commands)
    if (command.app->get_name() == "crosscheck") crosscheck_command = command.app;
  add_examples_and_keys_read_to_the_help(commands);
  if (refused_as_no_known_command(app, argc, argv)) return 2;
  if (const std::optional<int> status = status_if_parsing_ends_the_program(app, argc, argv))
    return *status;

  // Before any thread starts (terminal_progress.hpp): Ctrl-C sets a flag that the analyses
  // poll; SIGTERM, SIGHUP and a second Ctrl-C remove the temporaries and end the program.
  // `crosscheck` polls none (ngspice runs on its own), so Ctrl-C ends it at once, its
  // temporaries removed (an output file is renamed into place only when complete).
  const InterruptHandler signal_handling(
      /*interrupt_cancels=*/!(crosscheck_command && *crosscheck_command));
  using Mode = TerminalProgress::Mode;
  TerminalProgress reporter("emnet " + app.get_subcommands().front()->get_name(),
                            options.quiet      ? Mode::quiet
                            : options.progress ? Mode::forced
                                               : Mode::automatic);
  options.reporter = &reporter;
  const int status = run_the_chosen_command(app, commands, reporter);
  reporter.finish();
  return status_once_the_output_is_written(status);
}
