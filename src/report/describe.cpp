// A scene's drive in words (emnet/report/describe.hpp).
#include "emnet/report/describe.hpp"

#include <cmath>
#include <complex>
#include <cstdio>
#include <sstream>
#include <vector>

#include "emnet/core/constants.hpp"
#include "emnet/core/terminal_text.hpp"
#include "emnet/core/units.hpp"
#include "emnet/model/drive.hpp"

namespace emnet {

namespace {

std::string format(const char* pattern, double value) {
  return format_number(pattern, value);
}

std::string si(double value, const std::string& unit) {
  return format_with_unit(value, unit);
}

std::string shown(const std::string& text) {
  return terminal_text(text);
}

}  // namespace

std::string drive_summary(const Scene& scene) {
  const auto& drive = scene.drive;
  std::ostringstream out;
  out << "drive " << drive_kind_name(drive.kind);
  switch (drive.kind) {
    case DriveKind::antagonistic:
      out << " 0/" << si(drive.voltage, "V") << " square wave at " << si(drive.frequency, "Hz");
      break;
    case DriveKind::switched:
      out << " 0/" << si(drive.voltage, "V") << " square wave at " << si(drive.frequency, "Hz")
          << " on DEA " << drive.deas[0];
      break;
    case DriveKind::bias_differential:
      out << " V0 = " << si(drive.bias, "V") << ", v = " << si(drive.amplitude, "V");
      break;
    case DriveKind::single:
      out << " V0 + v*sin(2*pi*f*t), V0 = " << si(drive.bias, "V")
          << ", v = " << si(drive.amplitude, "V") << ", f = " << si(drive.frequency, "Hz")
          << " on DEA " << drive.deas[0];
      break;
    case DriveKind::none:
      break;
  }
  // A circuit's sources drive the network too (with or without a drive kind of its own).
  std::string sources;
  for (const CircuitSpec& element : scene.circuit)
    if (is_source(element.kind)) sources += (sources.empty() ? "" : ", ") + shown(element.name);
  if (!sources.empty()) out << ", circuit source(s) " << sources;
  return out.str();
}

// The AC input in a few words (empty when there is none): the plot's title.
std::string ac_input_summary(const Scene& scene) {
  const auto& drive = scene.drive;
  std::vector<std::string> parts;
  switch (drive.kind) {
    case DriveKind::antagonistic:
      parts.push_back("the antagonistic drive's force level k_F*V^2/2 as a sinusoid (V = " +
                      si(drive.voltage, "V") + ", DEAs " + shown(drive.deas[0]) + " and " +
                      shown(drive.deas[1]) + " in antiphase)");
      break;
    case DriveKind::switched:
      parts.push_back("the switched drive's force level k_F*V^2/2 as a sinusoid (V = " +
                      si(drive.voltage, "V") + ", DEA " + shown(drive.deas[0]) + ")");
      break;
    case DriveKind::bias_differential:
      parts.push_back("v = " + si(drive.amplitude, "V") + " on DEA " + shown(drive.deas[0]) +
                      " and -v on DEA " + shown(drive.deas[1]) +
                      " (about V0 = " + si(drive.bias, "V") + ")");
      break;
    case DriveKind::single:
      parts.push_back("v = " + si(drive.amplitude, "V") + " on DEA " + shown(drive.deas[0]) +
                      " (about V0 = " + si(drive.bias, "V") + ")");
      break;
    case DriveKind::none:
      break;
  }
  if (!scene.loads.empty()) parts.push_back("the scene's loads at their values");
  for (const CircuitSpec& element : scene.circuit)
    if (is_source(element.kind) && element.ac != 0.0)
      parts.push_back("ac " +
                      si(element.ac, element.kind == CircuitKind::voltage_source ? "V" : "A") +
                      " of circuit source " + shown(element.name));
  std::string text;
  for (size_t k = 0; k < parts.size(); ++k)
    text += (k == 0 ? "" : k + 1 == parts.size() ? " and " : ", ") + parts[k];
  return text;
}

// What the AC input is, in words: printed with every AC result. `top_hz`: the sweep's highest
// frequency, where the square-wave drives' omitted RC factor is largest.
std::string ac_input_description(const Scene& scene, double top_hz) {
  std::ostringstream out;
  const auto& drive = scene.drive;
  // The square-wave drives' force goes in directly; through the RC loops its fundamental would
  // be 1/(1 + j*omega*tau) times it (src/model/model.cpp).
  auto rc_loops = [&] {
    const double tau = drive_time_constant(scene);
    const std::complex<double> lag = 1.0 / std::complex<double>(1.0, 2 * kPi * top_hz * tau);
    out << " The DEAs' RC loops are not in this input, whatever drive.electrical_dynamics: "
           "through them the force's fundamental would be 1/(1 + j*2*pi*f*tau) times it (exact "
           "at duty 0.5; tau = "
        << format_duration(tau) << ": at " << si(top_hz, "Hz") << " "
        << format("%.6g", std::abs(lag)) << ", " << format("%.3g", std::arg(lag) * 180.0 / kPi)
        << " deg).";
  };
  switch (drive.kind) {
    case DriveKind::antagonistic:
      out << "AC input: the alternating part of the antagonistic square-wave drive: each DEA's "
             "force k_F*V^2/2 (V = "
          << si(drive.voltage, "V") << ") as a sinusoid, DEA " << shown(drive.deas[0])
          << " and DEA " << shown(drive.deas[1])
          << " in antiphase (the square wave's +/- level; its fundamental is 4/pi times this); "
             "exact, no linearisation: a 0/V voltage squares to a 0/k_F*V^2 force.";
      rc_loops();
      break;
    case DriveKind::switched:
      out << "AC input: the alternating part of the switched square-wave drive on DEA "
          << shown(drive.deas[0])
          << ": its force, a 0/k_F*V^2 square wave (V = " << si(drive.voltage, "V")
          << "), is +/- k_F*V^2/2 about its mean k_F*V^2/2; the +/- level as a sinusoid (its "
             "fundamental is 4/pi times this); exact, no linearisation: a 0/V voltage squares to "
             "a 0/k_F*V^2 force. The mean is a static offset, not in this input. The network is "
             "linearised at the static state (DEA on), which only the back-coupling sees.";
      rc_loops();
      break;
    case DriveKind::bias_differential:
      out << "AC input: v = " << si(drive.amplitude, "V") << " on DEA " << shown(drive.deas[0])
          << " and -v on DEA " << shown(drive.deas[1])
          << " about the bias V0 = " << si(drive.bias, "V")
          << "; the network linearised at V0 (the moment is exactly linear in v).";
      break;
    case DriveKind::single:
      out << "AC input: v = " << si(drive.amplitude, "V") << " on DEA " << shown(drive.deas[0])
          << ", linearised about the bias V0 = " << si(drive.bias, "V")
          << " (the force's part 2*k_F*V0*v; its DC and 2f parts, k_F*v^2/2 each, are left out).";
      break;
    case DriveKind::none:
      out << "AC input: the scene's loads, each with its value as amplitude.";
      break;
  }
  if (drive.kind != DriveKind::none && !scene.loads.empty())
    out << " Plus the scene's loads, each with its value as amplitude.";
  std::string sources;
  for (const CircuitSpec& element : scene.circuit)
    if (is_source(element.kind) && element.ac != 0.0)
      sources += (sources.empty() ? "" : ", ") + element.name;
  if (!scene.circuit.empty())
    out << " Circuit sources: "
        << (sources.empty() ? std::string("none has an AC magnitude (circuit[].ac)")
                            : "each with its circuit[].ac as magnitude (" + sources + ")")
        << ", the network linearised at the static state (the sources at t = 0).";
  return out.str();
}

}  // namespace emnet
