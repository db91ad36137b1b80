// Cross-check against ngspice: include/emnet/verification/crosscheck.hpp explains what is compared and why
// each tolerance.
#include "emnet/verification/crosscheck.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <complex>
#include <cstdio>
#include <map>
#include <sstream>

#include "emnet/analysis/analysis.hpp"
#include "emnet/analysis/operating_point.hpp"
#include "emnet/core/output_file.hpp"
#include "emnet/spice/spice_netlist.hpp"
#include "emnet/analysis/transient.hpp"

namespace emnet {

namespace {
std::string lower(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}
}  // namespace

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string number(const char* pattern, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, pattern, value);
  return buffer;
}

// Raised inside the cross-check for ngspice's or emnet's failure; becomes the report's status.
struct CrosscheckFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

std::string group_name(const Unknown& unknown, bool displacements) {
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

double real_at(const NgspiceVector& vector, std::size_t index) {
  return vector.is_complex ? vector.complex_values.at(index).real() : vector.real_values.at(index);
}

std::complex<double> complex_at(const NgspiceVector& vector, std::size_t index) {
  return vector.is_complex ? vector.complex_values.at(index)
                           : std::complex<double>(vector.real_values.at(index), 0.0);
}

// One group of compared values (emnet against ngspice) with names, for a row.
struct Group {
  std::vector<std::string> names;
  std::vector<std::complex<double>> emnet, spice;
};

class Crosscheck {
 public:
  Crosscheck(const Model& model, const CrosscheckOptions& options)
      : model_(model), options_(options) {}

  CrosscheckReport run() {
    check_options();
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

 private:
  void check_options() const {
    const auto& o = options_;
    if (!(o.same_network_tolerance > 0.0))
      throw InputError("crosscheck", "same_network_tolerance", "must be > 0");
    if (o.modal_count < 1 || o.modal_count > 20)
      throw InputError("crosscheck", "modal_count", "must be between 1 and 20");
    if (!(o.modal_half_width > 0.0 && o.modal_half_width < 0.5))
      throw InputError("crosscheck", "modal_half_width", "must be between 0 and 0.5");
    if (o.modal_points < 10 || o.modal_points > 100000)
      throw InputError("crosscheck", "modal_points", "must be between 10 and 100000");
    if (!(o.tran_periods > 0.0 && o.tran_periods <= 1000.0))
      throw InputError("--periods", "--periods", "must be > 0 and at most 1000");
    if (o.tran_points_per_period < 2 || o.tran_points_per_period > 100000)
      throw InputError("--points-per-period", "--points-per-period",
                       "must be between 2 and 100000");
    if (!(o.tran_reltol > 0.0 && o.tran_reltol < 1.0))
      throw InputError("--reltol", "--reltol", "must be between 0 and 1");
    if (!(o.tran_tolerance_per_reltol > 0.0))
      throw InputError("crosscheck", "tran_tolerance_per_reltol", "must be > 0");
  }

  // Runs one deck; a failure of ngspice ends the cross-check with a clear status.
  NgspiceResult run_deck(CrosscheckAnalysis analysis, const SpiceDeck& deck,
                         const std::string& label, bool failure_allowed = false) {
    if (!options_.keep_decks_directory.empty()) {
      const std::string path = options_.keep_decks_directory + "/" +
                               spice_identifier(model_.scene.name) + "-crosscheck-" + label +
                               ".cir";
      if (const Status written = write_output_file(path, deck.text); !written.ok)
        throw InputError("--keep-decks", path, written.message);
    }
    NgspiceResult result = run_ngspice(deck.text, options_.ngspice);
    if (!result.status.ok && !failure_allowed) {
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
  // absolute, in SI units, when the group is zero in emnet).
  void add_group_row(CrosscheckAnalysis analysis, const std::string& quantity, const Group& group,
                     const std::string& where_suffix = "") {
    if (group.names.empty()) return;
    double scale = 0.0;
    for (const auto& e : group.emnet) scale = std::max(scale, std::abs(e));
    CrosscheckRow row;
    row.analysis = analysis;
    row.quantity = quantity;
    row.tolerance = options_.same_network_tolerance;
    row.basis = scale > 0.0 ? "relative to the group's largest |value| " + number("%.4g", scale)
                            : "absolute in SI units (zero in emnet)";
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
      if (!point.status.ok) throw CrosscheckFailure("emnet " + point.status.message);
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

  // ---- op -----------------------------------------------------------------------------------
  void op() {
    const SpiceDeck deck = write_spice_deck(model_, deck_options(SpiceAnalysis::op));
    const NgspiceResult ng = run_deck(CrosscheckAnalysis::op, deck, "op");
    const System& sys = system();
    const auto start = std::chrono::steady_clock::now();
    const StaticResult result = solve_static(sys);
    const double emnet_seconds = seconds_since(start);
    if (!result.status.ok) throw CrosscheckFailure("emnet static: " + result.status.message);
    std::map<std::string, Group> groups;
    std::vector<std::string> order;
    for (std::size_t k = 0; k < deck.unknowns.size(); ++k) {
      const auto& map = deck.unknowns[k];
      if (map.vector.empty()) continue;
      const std::string name = group_name(sys.unknowns[k], true);
      if (!groups.count(name)) order.push_back(name);
      auto& group = groups[name];
      group.names.push_back(sys.unknowns[k].name);
      group.emnet.emplace_back(result.state[static_cast<Eigen::Index>(k)]);
      group.spice.emplace_back(map.sign * real_at(vector(ng, map.vector, "op"), 0));
    }
    const auto probes = spice_output_probes(model_);
    std::map<std::string, Group> outputs;
    for (std::size_t p = 0; p < deck.outputs.size() && p < probes.size(); ++p) {
      const std::string name = "outputs [" + deck.outputs[p].unit + "]";
      if (!outputs.count(name)) order.push_back(name);
      auto& group = outputs[name];
      group.names.push_back(deck.outputs[p].probe);
      group.emnet.emplace_back(static_probe_value(sys, result, probes[p]));
      group.spice.emplace_back(real_at(vector(ng, deck.outputs[p].vector, "op"), 0));
    }
    for (const auto& name : order)
      add_group_row(CrosscheckAnalysis::op, name,
                    groups.count(name) ? groups.at(name) : outputs.at(name));
    report_.timings.push_back({CrosscheckAnalysis::op, ng.ngspice_seconds, ng.seconds,
                               emnet_seconds, "solve_static (Newton, sparse LU)"});
  }

  // ---- ac -----------------------------------------------------------------------------------
  void ac() {
    const SpiceDeck deck = write_spice_deck(model_, deck_options(SpiceAnalysis::ac));
    const NgspiceResult ng = run_deck(CrosscheckAnalysis::ac, deck, "ac");
    const NgspiceVector* scale = ng.scale();
    if (!scale || scale->size() == 0) throw CrosscheckFailure("ngspice's ac run has no scale");
    std::vector<double> frequencies;
    for (std::size_t i = 0; i < scale->size(); ++i) frequencies.push_back(real_at(*scale, i));
    const System& sys = system();
    const StaticResult& operating = rest(sys);
    std::vector<Probe> probes = spice_output_probes(model_);
    const std::size_t output_count = probes.size();
    std::vector<std::size_t> unknown_of_probe;
    for (std::size_t k = 0; k < deck.unknowns.size(); ++k) {
      if (deck.unknowns[k].vector.empty()) continue;
      Probe probe;
      probe.name = sys.unknowns[k].name;
      probe.terms = {{static_cast<int>(k), 1.0}};
      probes.push_back(probe);
      unknown_of_probe.push_back(k);
    }
    const auto start = std::chrono::steady_clock::now();
    const AcResult result = run_ac(sys, operating.operating_point, frequencies, probes);
    const double emnet_seconds = seconds_since(start);
    if (!result.status.ok) throw CrosscheckFailure("emnet ac: " + result.status.message);

    // Outputs: magnitude and weighted phase, each relative to the output's own peak.
    CrosscheckRow magnitude, phase;
    magnitude.analysis = phase.analysis = CrosscheckAnalysis::ac;
    magnitude.quantity = "outputs |Y|";
    phase.quantity = "outputs arg Y (x |Y|/peak) [rad]";
    magnitude.tolerance = phase.tolerance = options_.same_network_tolerance;
    magnitude.basis = "relative to each output's peak |Y| over the sweep";
    phase.basis = "phase difference weighted by |Y|/peak";
    bool skipped_zero_frequency = false;
    for (std::size_t p = 0; p < output_count; ++p) {
      const auto& spice = vector(ng, deck.outputs[p].vector, "ac");
      if (spice.size() != frequencies.size())
        throw CrosscheckFailure("ngspice's ac vector " + deck.outputs[p].vector +
                                " has a different length than its frequency vector");
      const bool integral = probes[p].integrations > 0;
      double peak = 0.0;
      for (std::size_t f = 0; f < frequencies.size(); ++f)
        if (!(integral && frequencies[f] == 0.0))
          peak = std::max(peak, std::abs(result.values[p][f]));
      const bool zero = !(peak > 0.0);
      if (zero) peak = 1.0;  // zero in emnet (the clamp probe): absolute, SI units
      for (std::size_t f = 0; f < frequencies.size(); ++f) {
        if (integral && frequencies[f] == 0.0) {
          skipped_zero_frequency = true;
          continue;
        }
        const std::complex<double> e = result.values[p][f], s = complex_at(spice, f);
        const double dm = std::abs(std::abs(s) - std::abs(e)) / peak;
        const double dp = (std::abs(e) > 0.0 && std::abs(s) > 0.0)
                              ? std::abs(std::arg(s / e)) * std::abs(e) / peak
                              : std::abs(s - e) / peak;
        if (!std::isfinite(dm) || !std::isfinite(dp))
          throw CrosscheckFailure("non-finite ac difference at " + probes[p].name);
        const std::string where = probes[p].name + " at " + number("%.6g Hz", frequencies[f]) +
                                  (zero ? " (zero in emnet: absolute)" : "");
        if (dm >= magnitude.largest_difference) {
          magnitude.largest_difference = dm;
          magnitude.where = where;
        }
        if (dp >= phase.largest_difference) {
          phase.largest_difference = dp;
          phase.where = where;
        }
      }
    }
    magnitude.pass = magnitude.largest_difference <= magnitude.tolerance;
    phase.pass = phase.largest_difference <= phase.tolerance;
    report_.rows.push_back(magnitude);
    report_.rows.push_back(phase);
    if (skipped_zero_frequency)
      report_.notes.push_back(
          "ac: integrator outputs (deflections) are not compared at f = 0, where the deck's "
          "integrator gives 0 and emnet the static limit");

    // Every unknown with a vector, complex difference relative to its group's largest value.
    std::map<std::string, Group> groups;
    std::vector<std::string> order;
    for (std::size_t q = 0; q < unknown_of_probe.size(); ++q) {
      const std::size_t k = unknown_of_probe[q];
      const auto& map = deck.unknowns[k];
      const auto& spice = vector(ng, map.vector, "ac");
      const std::string name = group_name(sys.unknowns[k], false);
      if (!groups.count(name)) order.push_back(name);
      auto& group = groups[name];
      for (std::size_t f = 0; f < frequencies.size(); ++f) {
        group.names.push_back(sys.unknowns[k].name + " at " + number("%.6g Hz", frequencies[f]));
        group.emnet.push_back(result.values[output_count + q][f]);
        group.spice.push_back(map.sign * complex_at(spice, f));
      }
    }
    for (const auto& name : order)
      add_group_row(CrosscheckAnalysis::ac, name + " (complex)", groups.at(name));
    report_.timings.push_back(
        {CrosscheckAnalysis::ac, ng.ngspice_seconds, ng.seconds, emnet_seconds,
         "run_ac at " + std::to_string(frequencies.size()) + " frequencies, every unknown"});
  }

  // ---- modal --------------------------------------------------------------------------------
  void modal() {
    const System& sys = system();
    const StaticResult& operating = rest(sys);
    const auto start = std::chrono::steady_clock::now();
    const ModalResult modes = run_modes(sys, operating.operating_point);
    const double emnet_seconds = seconds_since(start);
    if (!modes.status.ok) throw CrosscheckFailure("emnet modes: " + modes.status.message);
    // The output whose peaks are read: "tip", else the last deflection probe.
    const Probe* output = nullptr;
    for (const auto& probe : model_.probes)
      if (probe.name == "tip" && probe.integrations == 1) output = &probe;
    if (!output)
      for (const auto& probe : model_.probes)
        if (probe.integrations == 1) output = &probe;
    if (!output) {
      report_.notes.push_back("modal: the scene has no deflection probe; not compared");
      return;
    }
    double ngspice_seconds = 0.0, ngspice_total = 0.0;
    const int count = std::min<int>(options_.modal_count, static_cast<int>(modes.modes.size()));
    for (int m = 0; m < count; ++m) {
      const Mode& mode = modes.modes[static_cast<std::size_t>(m)];
      const std::string label = "f" + std::to_string(m + 1);
      if (!(mode.damping_ratio < 0.5)) {
        report_.notes.push_back("modal: " + label + " has damping ratio " +
                                number("%.3g", mode.damping_ratio) +
                                ": no sharp amplitude peak; not compared");
        continue;
      }
      const double zeta = mode.damping_ratio;
      const double predicted = mode.natural_frequency_hz * std::sqrt(1.0 - 2.0 * zeta * zeta);
      SpiceDeckOptions d = deck_options(SpiceAnalysis::ac);
      d.outputs = {*output};
      AcSpec spec;
      // The peak lies within about ±ζ of f_p; a wider mode gets a wider grid (±2ζ).
      const double half_width = std::min(0.5, std::max(options_.modal_half_width, 2.0 * zeta));
      spec.from = predicted * (1.0 - half_width);
      spec.to = predicted * (1.0 + half_width);
      spec.points = options_.modal_points;
      spec.log = false;
      d.ac = spec;
      const SpiceDeck deck = write_spice_deck(model_, d);
      const NgspiceResult ng = run_deck(CrosscheckAnalysis::modal, deck, "modal-" + label);
      ngspice_seconds += ng.ngspice_seconds;
      ngspice_total += ng.seconds;
      const NgspiceVector* scale = ng.scale();
      if (!scale || scale->size() == 0)
        throw CrosscheckFailure("ngspice's modal ac run has no scale");
      std::vector<double> frequencies, spice_magnitude, emnet_magnitude;
      for (std::size_t i = 0; i < scale->size(); ++i) frequencies.push_back(real_at(*scale, i));
      const auto& spice = vector(ng, deck.outputs.at(0).vector, "modal");
      for (std::size_t i = 0; i < frequencies.size(); ++i)
        spice_magnitude.push_back(std::abs(complex_at(spice, i)));
      const AcResult own = run_ac(sys, operating.operating_point, frequencies, {*output});
      if (!own.status.ok) throw CrosscheckFailure("emnet ac (modal): " + own.status.message);
      for (const auto& v : own.values[0]) emnet_magnitude.push_back(std::abs(v));
      double spice_peak = 0.0, emnet_peak = 0.0;
      const bool spice_visible = parabolic_peak_frequency(frequencies, spice_magnitude, spice_peak);
      const bool emnet_visible = parabolic_peak_frequency(frequencies, emnet_magnitude, emnet_peak);
      if (!emnet_visible) {
        report_.notes.push_back("modal: " + label + " (" + number("%.6g Hz", predicted) +
                                ") is not visible in the response of " + output->name +
                                " (no peak inside the grid); not compared");
        continue;
      }
      CrosscheckRow row;
      row.analysis = CrosscheckAnalysis::modal;
      row.quantity = label + " peak of " + output->name + " [Hz]";
      row.basis =
          "relative to emnet's mode f_n*sqrt(1-2*zeta^2) = " + number("%.9g Hz", predicted) +
          "; tolerance: emnet's own AC peak offset " +
          number("%.2e", std::abs(emnet_peak - predicted) / predicted) + " + " +
          number("%.0e", options_.same_network_tolerance);
      row.tolerance =
          std::abs(emnet_peak - predicted) / predicted + options_.same_network_tolerance;
      if (!spice_visible) {
        row.largest_difference = INFINITY;
        row.where = "no peak in ngspice's response";
        row.pass = false;
      } else {
        row.largest_difference = std::abs(spice_peak - predicted) / predicted;
        row.where = "ngspice " + number("%.9g Hz", spice_peak) + ", emnet mode " +
                    number("%.9g Hz", predicted);
        row.pass = row.largest_difference <= row.tolerance;
      }
      report_.rows.push_back(row);
    }
    if (count < options_.modal_count)
      report_.notes.push_back("modal: emnet found " + std::to_string(modes.modes.size()) +
                              " oscillatory mode(s)");
    report_.timings.push_back(
        {CrosscheckAnalysis::modal, ngspice_seconds, ngspice_total, emnet_seconds,
         "run_modes (" + modes.method + ", " + std::to_string(modes.unknowns) + " unknowns)"});
  }

  // ---- tran ---------------------------------------------------------------------------------
  void tran() {
    Scene scene = model_.scene;
    bool ideal_drive = false;
    if (scene.drive.electrical_dynamics && !scene.deas.empty() &&
        scene.drive.kind != DriveKind::none) {
      set_electrical_dynamics(scene, false);
      ideal_drive = true;
    }
    const Model tran_model = ideal_drive ? build_model(scene) : Model{};
    const Model& m = ideal_drive ? tran_model : model_;
    const System sys = m.network.assemble();
    if (ideal_drive)
      report_.notes.push_back(
          "tran: compared with the ideal drive (drive.electrical_dynamics = false: force "
          "k_F*V(t)^2 from the source), the linear network emnet's exact method solves");
    double period = 0.0;
    std::string period_from;
    if (scene.drive.frequency > 0.0 && scene.drive.kind != DriveKind::none) {
      period = 1.0 / scene.drive.frequency;
      period_from = "the drive's period";
    } else {
      const OperatingPoint operating = operating_point(sys);
      if (!operating.status.ok) throw CrosscheckFailure("emnet " + operating.status.message);
      const ModalResult modes = run_modes(sys, operating.rest.operating_point);
      if (!modes.status.ok || modes.modes.empty()) {
        report_.notes.push_back("tran: no drive frequency and no oscillatory mode; not compared");
        return;
      }
      period = 1.0 / modes.modes.front().frequency_hz;
      period_from = "the first mode's period";
    }
    SpiceDeckOptions d = deck_options(SpiceAnalysis::tran);
    d.end_time = options_.tran_periods * period;
    d.output_step = period / options_.tran_points_per_period;
    d.max_step = 0.0;  // the output step
    d.relative_tolerance = options_.tran_reltol;
    d.edge_fraction = options_.tran_edge_fraction;
    d.start = StartState::rest;
    SpiceDeck deck = write_spice_deck(m, d);
    NgspiceResult ng = run_deck(CrosscheckAnalysis::tran, deck, "tran", true);
    auto stopped_at = [&](const NgspiceResult& r) {
      const NgspiceVector* sc = r.scale();
      return sc && sc->size() > 0 ? real_at(*sc, sc->size() - 1) : 0.0;
    };
    // A step load from rest near a massless node can make ngspice give up ("timestep too
    // small") when its max step is tight (the cantilever below about T/1000); one retry with a
    // max step of T/200, said in the notes — the tolerance stays the same.
    const bool gave_up = !ng.status.ok || !(stopped_at(ng) >= d.end_time * (1.0 - 1e-9));
    if (gave_up && options_.tran_points_per_period > 200 &&
        lower(ng.messages_text()).find("timestep too small") != std::string::npos) {
      report_.notes.push_back(
          "tran: ngspice gave up (" + last_error_line(ng) + ") with max step T/" +
          std::to_string(options_.tran_points_per_period) + "; retried with T/200");
      d.output_step = period / 200;
      deck = write_spice_deck(m, d);
      ng = run_deck(CrosscheckAnalysis::tran, deck, "tran");
    } else if (!ng.status.ok) {
      ng = run_deck(CrosscheckAnalysis::tran, deck, "tran");  // reports the failure
    }
    report_.notes.push_back("tran: " + number("%.4g", options_.tran_periods) + " x " + period_from +
                            " (" + number("%.6g s", d.end_time) + ") from rest, ngspice reltol " +
                            number("%.0e", d.relative_tolerance) + ", max step " +
                            number("%.4g s", d.output_step));
    const NgspiceVector* scale = ng.scale();
    if (!scale || scale->size() == 0) throw CrosscheckFailure("ngspice's tran run has no scale");
    const double last_time = real_at(*scale, scale->size() - 1);
    if (!(last_time >= d.end_time * (1.0 - 1e-9)))
      throw CrosscheckFailure(
          "ngspice stopped its transient at t = " + number("%.6g s", last_time) + " of " +
          number("%.6g s", d.end_time) + " (" + last_error_line(ng) + ")");
    // ngspice's time points within [0, end]; at most tran_compared_points of them, evenly
    // strided (each costs emnet one matrix exponential).
    const std::size_t stride =
        (scale->size() + options_.tran_compared_points - 1) / options_.tran_compared_points;
    std::vector<std::size_t> indices;
    for (std::size_t i = 0; i < scale->size(); i += std::max<std::size_t>(stride, 1))
      indices.push_back(i);
    if (indices.back() != scale->size() - 1) indices.push_back(scale->size() - 1);
    std::vector<double> times;
    for (std::size_t i : indices) times.push_back(std::clamp(real_at(*scale, i), 0.0, d.end_time));
    if (stride > 1)
      report_.notes.push_back("tran: ngspice took " + std::to_string(scale->size()) +
                              " time points; one in " + std::to_string(stride) + " is compared (" +
                              std::to_string(indices.size()) + ")");
    std::vector<double> unique_times = times;
    std::sort(unique_times.begin(), unique_times.end());
    unique_times.erase(std::unique(unique_times.begin(), unique_times.end()), unique_times.end());

    const auto probes = spice_output_probes(m);
    TransientOptions t;
    t.end_time = d.end_time;
    t.output_times = unique_times;
    t.start = StartState::rest;
    const bool linear = !sys.is_nonlinear();
    const auto start = std::chrono::steady_clock::now();
    TransientResult reference;
    if (linear) {
      reference = run_transient_exact(sys, probes, t);
    } else {
      t.relative_tolerance = 1e-10;
      reference = run_transient_ida(sys, probes, t);
      report_.notes.push_back(
          "tran: the network is nonlinear; the reference is IDA at rtol 1e-10, not the exact "
          "method");
    }
    const double emnet_seconds = seconds_since(start);
    if (!reference.status.ok)
      throw CrosscheckFailure("emnet tran (" + std::string(linear ? "exact" : "ida") +
                              "): " + reference.status.message);
    if (reference.times.size() != unique_times.size())
      throw CrosscheckFailure("emnet tran: reached " + std::to_string(reference.times.size()) +
                              " of " + std::to_string(unique_times.size()) + " output times");

    // Switching edges: emnet's instants; ε = edge fraction × the shorter level time.
    const std::vector<double> edges = sys.breakpoints(0.0, d.end_time);
    double shortest = d.end_time, previous = 0.0;
    for (double e : edges) {
      if (e - previous > 0.0) shortest = std::min(shortest, e - previous);
      previous = e;
    }
    const double epsilon = options_.tran_edge_fraction * shortest;
    const double window = options_.tran_edge_exclusion * epsilon;
    std::vector<bool> compared(times.size(), true);
    std::size_t excluded = 0;
    for (std::size_t i = 0; i < times.size(); ++i)
      for (double e : edges)
        if (std::abs(times[i] - e) <= window) {
          compared[i] = false;
          ++excluded;
          break;
        }
    if (!edges.empty())
      report_.notes.push_back("tran: " + std::to_string(edges.size()) +
                              " switching edge(s) of width " + number("%.3g s", epsilon) +
                              " in the deck; " + std::to_string(excluded) + " of " +
                              std::to_string(times.size()) + " ngspice time points within +/-" +
                              number("%.3g s", window) + " of an edge are not compared");

    std::map<std::string, CrosscheckRow> rows;
    std::vector<std::string> order;
    for (std::size_t p = 0; p < probes.size(); ++p) {
      const auto& spice = vector(ng, deck.outputs[p].vector, "tran");
      if (spice.size() != scale->size())
        throw CrosscheckFailure("ngspice's tran vector " + deck.outputs[p].vector +
                                " has a different length than its time vector");
      std::vector<double> emnet_values(times.size());
      double peak = 0.0;
      for (std::size_t i = 0; i < times.size(); ++i) {
        const std::size_t u = static_cast<std::size_t>(
            std::lower_bound(unique_times.begin(), unique_times.end(), times[i]) -
            unique_times.begin());
        emnet_values[i] = reference.values[p][u];
        if (compared[i]) peak = std::max(peak, std::abs(emnet_values[i]));
      }
      const bool zero = !(peak > 0.0);
      const std::string name = "outputs [" + probes[p].unit + "]";
      if (!rows.count(name)) {
        order.push_back(name);
        CrosscheckRow row;
        row.analysis = CrosscheckAnalysis::tran;
        row.quantity = name;
        row.tolerance = options_.tran_tolerance_per_reltol * options_.tran_reltol;
        row.basis = "relative to each output's peak |value| over the run; tolerance " +
                    number("%.4g", options_.tran_tolerance_per_reltol) + " x reltol";
        rows[name] = row;
      }
      auto& row = rows[name];
      for (std::size_t i = 0; i < times.size(); ++i) {
        if (!compared[i]) continue;
        const double difference =
            std::abs(real_at(spice, indices[i]) - emnet_values[i]) / (zero ? 1.0 : peak);
        if (!std::isfinite(difference))
          throw CrosscheckFailure("non-finite tran difference at " + probes[p].name);
        if (difference >= row.largest_difference) {
          row.largest_difference = difference;
          row.where = probes[p].name + " at t = " + number("%.6g s", times[i]) +
                      (zero ? " (zero in emnet: absolute)" : "");
        }
      }
    }
    for (const auto& name : order) {
      auto& row = rows.at(name);
      row.pass = row.largest_difference <= row.tolerance;
      report_.rows.push_back(row);
    }
    report_.timings.push_back(
        {CrosscheckAnalysis::tran, ng.ngspice_seconds, ng.seconds, emnet_seconds,
         std::string(linear ? "run_transient_exact" : "run_transient_ida (rtol 1e-10)") + " at " +
             std::to_string(unique_times.size()) + " of ngspice's time points"});
  }

  const Model& model_;
  const CrosscheckOptions& options_;
  CrosscheckReport report_;
  System system_;
  bool system_ready_ = false;
  StaticResult rest_;
  bool rest_ready_ = false;
};

}  // namespace

const char* crosscheck_analysis_name(CrosscheckAnalysis analysis) {
  switch (analysis) {
    case CrosscheckAnalysis::op:
      return "op";
    case CrosscheckAnalysis::ac:
      return "ac";
    case CrosscheckAnalysis::modal:
      return "modal";
    case CrosscheckAnalysis::tran:
      return "tran";
  }
  return "?";
}

std::vector<CrosscheckAnalysis> parse_crosscheck_analyses(const std::string& text,
                                                          const std::string& option) {
  if (text == "all")
    return {CrosscheckAnalysis::op, CrosscheckAnalysis::ac, CrosscheckAnalysis::modal,
            CrosscheckAnalysis::tran};
  std::vector<CrosscheckAnalysis> analyses;
  std::istringstream in(text);
  for (std::string name; std::getline(in, name, ',');) {
    CrosscheckAnalysis analysis;
    if (name == "op")
      analysis = CrosscheckAnalysis::op;
    else if (name == "ac")
      analysis = CrosscheckAnalysis::ac;
    else if (name == "modal")
      analysis = CrosscheckAnalysis::modal;
    else if (name == "tran")
      analysis = CrosscheckAnalysis::tran;
    else
      throw InputError(option, option,
                       "unknown analysis '" + name + "' (op, ac, modal, tran, or all)");
    if (std::find(analyses.begin(), analyses.end(), analysis) == analyses.end())
      analyses.push_back(analysis);
  }
  if (analyses.empty()) throw InputError(option, option, "names no analysis");
  return analyses;
}

bool CrosscheckReport::all_pass() const {
  if (!status.ok) return false;
  for (const auto& row : rows)
    if (!row.pass) return false;
  return true;
}

CrosscheckReport run_crosscheck(const Model& model, const CrosscheckOptions& options) {
  return Crosscheck(model, options).run();
}

LargestDifference largest_relative_difference(const std::vector<double>& a,
                                              const std::vector<double>& b, double scale) {
  if (a.size() != b.size()) throw std::invalid_argument("largest_relative_difference: sizes");
  if (!(scale > 0.0)) scale = 1.0;
  LargestDifference largest;
  for (std::size_t k = 0; k < a.size(); ++k) {
    const double d = std::abs(a[k] - b[k]) / scale;
    if (d > largest.value || k == 0) largest = {d, k};
  }
  return largest;
}

bool parabolic_peak_frequency(const std::vector<double>& frequencies,
                              const std::vector<double>& magnitudes, double& peak_hz) {
  if (frequencies.size() != magnitudes.size() || frequencies.size() < 3) return false;
  const std::size_t top = static_cast<std::size_t>(
      std::max_element(magnitudes.begin(), magnitudes.end()) - magnitudes.begin());
  if (top == 0 || top + 1 >= magnitudes.size() || !(magnitudes[top] > 0.0)) return false;
  // y = 1/|H|² against u = f²: y = a·u² + b·u + c through the three points.
  double u[3], y[3];
  for (int k = 0; k < 3; ++k) {
    const std::size_t i = top - 1 + static_cast<std::size_t>(k);
    if (!(magnitudes[i] > 0.0)) return false;
    u[k] = frequencies[i] * frequencies[i];
    y[k] = 1.0 / (magnitudes[i] * magnitudes[i]);
  }
  // Divided differences (well conditioned for a narrow bracket).
  const double d01 = (y[1] - y[0]) / (u[1] - u[0]);
  const double d12 = (y[2] - y[1]) / (u[2] - u[1]);
  const double a = (d12 - d01) / (u[2] - u[0]);
  if (!(a > 0.0)) return false;
  // y' = d01 + a·(2u − u0 − u1) = 0
  const double u_min = 0.5 * (u[0] + u[1] - d01 / a);
  if (!(u_min > u[0] && u_min < u[2])) return false;
  peak_hz = std::sqrt(u_min);
  return std::isfinite(peak_hz);
}

}  // namespace emnet
