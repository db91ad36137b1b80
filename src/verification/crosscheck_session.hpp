// The cross-check's working state, shared by its four comparisons (op, ac, modal, tran; one file
// each): the model, the options, the report being filled, the assembled system and its operating
// point, and the helpers that run a deck and add a row. Private to src/verification.
#pragma once

#include <algorithm>
#include <cctype>
#include <cmath>
#include <complex>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "emnet/analysis/analysis.hpp"
#include "emnet/analysis/operating_point.hpp"
#include "emnet/core/option_error.hpp"
#include "emnet/core/output_file.hpp"
#include "emnet/model/outputs.hpp"
#include "emnet/spice/spice_netlist.hpp"
#include "emnet/verification/crosscheck.hpp"

namespace emnet::crosscheck_detail {

inline std::string lower(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

inline std::string number(const char* pattern, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, pattern, value);
  return buffer;
}

// Raised inside the cross-check for ngspice's or emnet's failure; becomes the report's status.
struct CrosscheckFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

inline std::string group_name(const Unknown& unknown, bool displacements) {
  if (unknown.kind == Unknown::Kind::node_across) {
    switch (unknown.domain) {
      case Domain::translational:
        return displacements ? "displacements [m]" : "velocities [m/s]";
      case Domain::rotational:
        return displacements ? "rotations [rad]" : "angular velocities [rad/s]";
      case Domain::electrical:
        return "node voltages [V]";
    }
  }
  if (unknown.geometric && unknown.domain == Domain::translational) return "chord changes [m]";
  if (unknown.geometric && unknown.domain == Domain::rotational) return "chord angles [rad]";
  switch (unknown.domain) {
    case Domain::translational:
      return "branch forces [N]";
    case Domain::rotational:
      return "branch torques [N*m]";
    case Domain::electrical:
      return "branch currents [A]";
  }
  return "unknowns";
}

inline double real_at(const NgspiceVector& vector, std::size_t index) {
  return vector.is_complex ? vector.complex_values.at(index).real() : vector.real_values.at(index);
}

inline std::complex<double> complex_at(const NgspiceVector& vector, std::size_t index) {
  return vector.is_complex ? vector.complex_values.at(index)
                           : std::complex<double>(vector.real_values.at(index), 0.0);
}

// One group of compared values (emnet against ngspice) with names, for a row.
struct Group {
  std::vector<std::string> names;
  std::vector<std::complex<double>> emnet, spice;
};

class CrosscheckSession {
 public:
  CrosscheckSession(const Model& model, const CrosscheckOptions& options)
      : model_(model), options_(options) {}

  CrosscheckReport run() {
    options_.validate();
    for (std::string& note : deck_left_out_notes(model_)) report_.notes.push_back(std::move(note));
    try {
      for (const auto analysis : options_.analyses) {
        switch (analysis) {
          case CrosscheckAnalysis::op:
            op();
            break;
          case CrosscheckAnalysis::ac:
            ac();
            break;
          case CrosscheckAnalysis::modal:
            modal();
            break;
          case CrosscheckAnalysis::tran:
            tran();
            break;
        }
      }
    } catch (const CrosscheckFailure& failure) {
      report_.status = Status::failure(failure.what());
    }
    return report_;
  }

  // Runs one deck; a failure of ngspice ends the cross-check with a clear status.
  NgspiceResult run_deck(CrosscheckAnalysis analysis, const SpiceDeck& deck,
                         const std::string& label, bool failure_allowed = false) {
    if (!options_.keep_decks_directory.empty()) {
      // The directory is made when missing (and its parents), as `mkdir -p` would.
      std::error_code made;
      std::filesystem::create_directories(options_.keep_decks_directory, made);
      if (made)
        throw OptionError("keep_decks_directory", "cannot make the directory: " + made.message(),
                          options_.keep_decks_directory);
      const std::string path = options_.keep_decks_directory + "/" +
                               spice_identifier(model_.scene.name) + "-crosscheck-" + label +
                               ".cir";
      if (const Status written = write_output_file(path, deck.text); !written.ok())
        throw OptionError("keep_decks_directory", written.message, path);
    }
    NgspiceResult result = run_ngspice(deck.text, options_.ngspice);
    if (!result.status.ok() && !failure_allowed) {
      std::string text = "ngspice on the " + label + " deck: " + result.status.message;
      const std::string messages = result.messages_text();
      if (!messages.empty()) {
        // The last lines say what went wrong; the whole log can be long.
        std::string tail = messages;
        std::size_t lines = 0, at = tail.size();
        while (at > 0 && lines < 8) {
          at = tail.rfind('\n', at - 1);
          if (at == std::string::npos) {
            at = 0;
            break;
          }
          ++lines;
        }
        text += "\nngspice said:\n" + tail.substr(at == 0 ? 0 : at + 1);
      }
      throw CrosscheckFailure(text);
    }
    if (report_.backend.empty()) report_.backend = result.backend_description;
    if (options_.inspect_ngspice_result) options_.inspect_ngspice_result(analysis, result);
    return result;
  }

  // The last line of ngspice's messages that names a problem, for a failure message.
  static std::string last_error_line(const NgspiceResult& result) {
    for (const char* word : {"too small", "error", "abort"})
      for (auto it = result.messages.rbegin(); it != result.messages.rend(); ++it) {
        std::string lower = it->text;
        for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        if (lower.find(word) != std::string::npos) return "ngspice: " + it->text;
      }
    return "ngspice gave no reason";
  }

  const NgspiceVector& vector(const NgspiceResult& result, const std::string& name,
                              const std::string& label) const {
    const NgspiceVector* found = result.find(name);
    if (!found || found->size() == 0)
      throw CrosscheckFailure("ngspice's " + label + " run has no vector '" + name + "'");
    return *found;
  }

  SpiceDeckOptions deck_options(SpiceAnalysis analysis) const {
    SpiceDeckOptions d;
    d.analysis = analysis;
    d.overrides = options_.overrides;
    return d;
  }

  // A row from a group: differences relative to the group's largest emnet magnitude (or
  // absolute, in SI units, when the group is zero in emnet). `floor` [SI]: a magnitude below
  // which the group's values are rounding, not results (static currents through capacitors
  // and open loops); the differences are then relative to the floor.
  void add_group_row(CrosscheckAnalysis analysis, const std::string& quantity, const Group& group,
                     const std::string& where_suffix = "", double floor = 0.0) {
    if (group.names.empty()) return;
    double scale = 0.0;
    for (const auto& e : group.emnet) scale = std::max(scale, std::abs(e));
    CrosscheckRow row;
    row.analysis = analysis;
    row.quantity = quantity;
    row.tolerance = options_.same_network_tolerance;
    if (scale > 0.0 && scale < floor) {
      row.basis = "relative to the rounding floor " + number("%.4g", floor) +
                  " (the group's largest |value| " + number("%.4g", scale) + " is below it)";
      scale = floor;
    } else {
      row.basis = scale > 0.0 ? "relative to the group's largest |value| " + number("%.4g", scale)
                              : "absolute in SI units (zero in emnet)";
    }
    if (!(scale > 0.0)) scale = 1.0;
    std::size_t worst = 0;
    for (std::size_t k = 0; k < group.names.size(); ++k) {
      const double d = std::abs(group.spice[k] - group.emnet[k]) / scale;
      if (!std::isfinite(d)) throw CrosscheckFailure("non-finite difference at " + group.names[k]);
      if (d > row.largest_difference || k == 0) {
        row.largest_difference = d;
        worst = k;
      }
    }
    row.where = group.names[worst] + where_suffix;
    row.pass = row.largest_difference <= row.tolerance;
    report_.rows.push_back(row);
  }

  // The static state (op) or the operating point about which ac and modal linearise.
  const StaticResult& rest(const System& system) {
    if (!rest_ready_) {
      OperatingPoint point = operating_point(system);
      rest_ready_ = true;
      if (!point.status.ok()) throw CrosscheckFailure("emnet " + point.status.message);
      if (point.about_zero) report_.notes.push_back(point.note);
      rest_ = std::move(point.rest);
    }
    return rest_;
  }

  const System& system() {
    if (!system_ready_) {
      system_ = model_.network.assemble();
      system_ready_ = true;
    }
    return system_;
  }

  // The four comparisons, one file each (crosscheck_<analysis>.cpp).
  void op();
  void ac();
  void modal();
  void tran();

  const Model& model_;
  const CrosscheckOptions& options_;
  CrosscheckReport report_;
  System system_;
  bool system_ready_ = false;
  StaticResult rest_;
  bool rest_ready_ = false;
};

}  // namespace emnet::crosscheck_detail
