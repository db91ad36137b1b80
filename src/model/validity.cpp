// The validity checks of computed results (emnet/model/validity.hpp explains the limits).
#include "emnet/model/validity.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "emnet/core/units.hpp"
#include "emnet/model/circuit.hpp"
#include "emnet/model/model.hpp"

namespace emnet {

namespace {

template <typename Of>
std::vector<DeaVoltage> driven_voltages(const Scene& scene, Of of) {
  std::vector<DeaVoltage> voltages;
  for (const DeaSpec& dea : scene.deas)
    if (std::find(scene.drive.deas.begin(), scene.drive.deas.end(), dea.name) !=
        scene.drive.deas.end())
      voltages.push_back({dea.name, of(dea_drive(scene.drive, dea.name).voltage), ""});
  return voltages;
}

// The circuit-driven DEAs with the bound of their voltage (`at_start`: at t = 0, else over the
// whole waveform); none when the circuit has no proven bound.
std::vector<DeaVoltage> circuit_bounded_voltages(const Scene& scene, bool at_start) {
  std::vector<DeaVoltage> voltages;
  const std::vector<std::string> driven = circuit_driven_deas(scene);
  if (driven.empty()) return voltages;
  for (const std::string& dea : driven) {
    const CircuitVoltageBound bound = circuit_voltage_bound(scene, dea);
    if (!bound.bounded) continue;
    voltages.push_back({dea, at_start ? bound.at_start : bound.peak,
                        std::string("bound: the circuit's largest source level") +
                            (at_start ? " at t = 0" : "") +
                            ", which an RC network of grounded voltage sources never exceeds"});
  }
  return voltages;
}

std::vector<DeaVoltage> joined(std::vector<DeaVoltage> first,
                               const std::vector<DeaVoltage>& second) {
  first.insert(first.end(), second.begin(), second.end());
  return first;
}

// "field not checked: ..." for a scene whose circuit drives DEAs without a known bound, else "".
std::string unchecked_field_text(const Scene& scene, const std::vector<DeaVoltage>& voltages) {
  const std::vector<std::string> driven = circuit_driven_deas(scene);
  std::string text;
  for (const std::string& dea : driven) {
    const bool judged = std::any_of(voltages.begin(), voltages.end(),
                                    [&](const DeaVoltage& v) { return v.dea == dea; });
    if (judged) continue;
    const CircuitVoltageBound bound = circuit_voltage_bound(scene, dea);
    text += std::string(text.empty() ? "" : "; ") + "field not checked for circuit-driven DEA " +
            dea + ": " +
            (bound.bounded ? std::string("its voltage was not computed") : bound.reason) +
            ", so no bound on its voltage is known";
  }
  return text;
}

std::string length_text(double metres) {
  const double size = std::abs(metres);
  if (size >= 1e3) return format_number("%.4g km", metres * 1e-3);
  if (size >= 1.0) return format_number("%.4g m", metres);
  if (size >= 1e-3) return format_number("%.4g mm", metres * 1e3);
  return format_number("%.4g um", metres * 1e6);
}

// "10.7 % of L", "1943 times L": `fraction` of `whole`.
std::string share(double fraction, const std::string& whole) {
  return fraction >= 10.0 ? format_number("%.4g times ", fraction) + whole
                          : format_number("%.3g %% of ", 100.0 * fraction) + whole;
}

std::string percent(double fraction) {
  return format_number("%.3g %%", 100.0 * fraction);
}

// How the geometric error was estimated: "estimate (w/L)^2", or with the largest rotation
// "estimate max((w/L)^2, psi^2), psi = 0.494 rad at x = 35 mm".
std::string geometric_estimate_text(double fraction, const std::optional<RotationPeak>& rotation) {
  if (!rotation) return "estimate (w/L)^2";
  return "estimate max((w/L)^2, psi^2) = max(" + percent(fraction * fraction) + ", " +
         percent(rotation->peak * rotation->peak) +
         "), psi = " + format_number("%.3g rad", rotation->peak) + " at " + rotation->where;
}

}  // namespace

double geometric_error_estimate(double peak, double length) {
  const double fraction = peak / length;
  return fraction * fraction;
}

RotationPeak rotation_peak_at(double position, double peak) {
  return {format_number("x = %.4g mm", 1e3 * position), std::abs(peak)};
}

std::optional<RotationPeak> larger_rotation(const std::optional<RotationPeak>& a,
                                            const std::optional<RotationPeak>& b) {
  if (!a) return b;
  return b && b->peak > a->peak ? b : a;
}

double geometric_error_estimate(double peak, double length, double rotation) {
  return std::max(geometric_error_estimate(peak, length), rotation * rotation);
}

const char* validity_check_name(ValidityCheck check) {
  switch (check) {
    case ValidityCheck::deflection:
      return "deflection";
    case ValidityCheck::electric_field:
      return "electric_field";
  }
  return "?";
}

std::vector<DeaVoltage> drive_peak_voltages(const Scene& scene) {
  return joined(
      driven_voltages(scene, [](const Waveform& w) { return waveform_largest_magnitude(w); }),
      circuit_bounded_voltages(scene, false));
}

std::vector<DeaVoltage> drive_voltages_at_start(const Scene& scene) {
  return joined(driven_voltages(scene, [](const Waveform& w) { return std::abs(w.value(0.0)); }),
                circuit_bounded_voltages(scene, true));
}

Validity check_validity(const Scene& scene, const std::vector<DeflectionPeak>& deflections,
                        const std::vector<DeaVoltage>& voltages,
                        const std::optional<RotationPeak>& rotation) {
  Validity validity;
  const double length = scene.beam.length;
  const double psi = rotation ? rotation->peak : 0.0;
  const double limit = scene.model.deflection_limit * length;
  const DeflectionPeak* largest = nullptr;
  // Large kinematics has no small-deflection assumption: the deflections are not limited.
  const bool large = scene.beam.kinematics == BeamKinematics::large;
  const std::vector<DeflectionPeak> none;
  const std::vector<DeflectionPeak>& checked = large ? none : deflections;
  for (const DeflectionPeak& deflection : checked) {
    if (!largest || deflection.peak > largest->peak) largest = &deflection;
    if (!(deflection.peak > limit)) continue;
    ValidityViolation violation;
    violation.check = ValidityCheck::deflection;
    violation.subject = deflection.output;
    violation.key = "model.deflection_limit";
    violation.value = deflection.peak;
    violation.limit = limit;
    violation.message = "|deflection| of " + deflection.output + " is " +
                        length_text(deflection.peak) + ", " +
                        share(deflection.peak / length, "beam.length " + length_text(length)) +
                        "; a small-deflection linear beam is trusted with at most " +
                        percent(scene.model.deflection_limit) + " (" + length_text(limit) +
                        ", model.deflection_limit); its geometric error is estimated at " +
                        percent(geometric_error_estimate(deflection.peak, length, psi)) +
                        ", which beam.kinematics = \"large\" does not have";
    validity.violations.push_back(violation);
  }
  std::string deflection_text =
      large ? "deflection not limited (beam.kinematics = \"large\")" : "no deflection computed";
  if (largest) {
    validity.deflection_fraction = largest->peak / limit;
    validity.geometric_error = geometric_error_estimate(largest->peak, length, psi);
    validity.largest_rotation = psi;
    deflection_text = "largest |deflection| " + length_text(largest->peak) + " (" +
                      largest->output + ") = " + share(largest->peak / length, "L") + ", limit " +
                      percent(scene.model.deflection_limit) + ", geometric error ~" +
                      percent(validity.geometric_error) + " (" +
                      geometric_estimate_text(largest->peak / length, rotation) + ")";
  }

  std::string field_text = "no DEA driven";
  double worst_fraction = -1.0;
  for (const DeaVoltage& voltage : voltages) {
    const auto dea = std::find_if(scene.deas.begin(), scene.deas.end(),
                                  [&](const DeaSpec& spec) { return spec.name == voltage.dea; });
    if (dea == scene.deas.end())
      throw std::invalid_argument("check_validity: no DEA named '" + voltage.dea + "'");
    const double field = std::abs(voltage.voltage) / dea->dielectric_thickness;
    const double fraction = field / dea->breakdown_field;
    const std::string numbers =
        format_number("%.4g V", voltage.voltage) +
        (voltage.bound.empty() ? std::string() : " (" + voltage.bound + ")") + " / " +
        length_text(dea->dielectric_thickness) + " = " + format_number("%.4g V/um", field * 1e-6);
    if (fraction > worst_fraction) {
      worst_fraction = fraction;
      validity.field_fraction = fraction;
      field_text = "largest field " + numbers + " (DEA " + dea->name +
                   ") = " + share(fraction, "its breakdown field ") +
                   format_number("%.4g V/um", dea->breakdown_field * 1e-6);
    }
    if (!(field > dea->breakdown_field)) continue;
    ValidityViolation violation;
    violation.check = ValidityCheck::electric_field;
    violation.subject = dea->name;
    violation.key = "dea[" + dea->name + "].breakdown_field";
    violation.value = field;
    violation.limit = dea->breakdown_field;
    violation.message =
        "electric field in DEA " + dea->name + " is " + numbers + ", above its breakdown field " +
        format_number("%.4g V/um", dea->breakdown_field * 1e-6) + " (dea[" + dea->name +
        "].breakdown_field): the film would break down, the DEA is no longer "
        "a capacitor";
    validity.violations.push_back(violation);
  }
  const std::string unchecked = unchecked_field_text(scene, voltages);
  if (!unchecked.empty()) field_text = voltages.empty() ? unchecked : field_text + "; " + unchecked;
  validity.summary = deflection_text + "; " + field_text;
  return validity;
}

}  // namespace emnet
