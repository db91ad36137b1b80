// The keys of a [[circuit]] entry: a resistor, capacitor, inductor or source between two nodes of
// the circuit around the DEAs, and a source's waveform (dc, sine, square, pulse, pwl).
#include "scene/scene_text.hpp"
#include "scene_key_tables.hpp"

namespace emnet {
namespace scene_keys {

namespace {

const char* const kCircuitUsers = "circuit elements";
const char* const kLevelUnit = "V (voltage_source), A (current_source)";

// A field of a [[circuit]] entry's waveform (circuit[].low, .frequency, ...).
void waveform_field(ParameterInfo& info, double WaveformSpec::*member) {
  info.get = [member](const Scene& scene, std::size_t entry) -> std::optional<double> {
    return scene.circuit[entry].waveform.*member;
  };
  info.set = [member](Scene& scene, std::size_t entry, double value) {
    scene.circuit[entry].waveform.*member = value;
  };
}

// The element: its name, kind, ends and value.
void add_element_keys(SceneTableKeys& keys) {
  keys.add(key("circuit", "name", ParameterKind::name, kCircuitUsers,
               "the element's name (it names the element in SPICE decks and messages)"))
      .required = true;
  keys.back().constraint = kEntryNameConstraint;
  keys.back().text = [](const Scene& scene, std::size_t entry) {
    return scene.circuit[entry].name;
  };
  keys.add(choice("circuit", "kind",
                  {"resistor", "capacitor", "inductor", "voltage_source", "current_source"}, true,
                  kCircuitUsers, "what the element is"))
      .text = [](const Scene& scene, std::size_t entry) {
    return std::string(circuit_kind_name(scene.circuit[entry].kind));
  };
  for (const char* end : {"from", "to"}) {
    keys
        .add(key(
            "circuit", end, ParameterKind::text, kCircuitUsers,
            std::string(end) == "from"
                ? "the node of the element's first end: a name of the circuit's own, \"ground\" "
                  "(or \"0\"), or \"dea.X\" (DEA X's terminal, in front of its electrode "
                  "resistance); a voltage source's + terminal, where a current source's current "
                  "leaves"
                : "the node of the element's second end (as circuit[].from); a voltage source's "
                  "- terminal, where a current source's current enters"))
        .required = true;
    keys.back().constraint =
        "a node touched by two element ends at least, with a DC path to ground";
    const bool first = std::string(end) == "from";
    keys.back().text = [first](const Scene& scene, std::size_t entry) {
      return first ? scene.circuit[entry].from : scene.circuit[entry].to;
    };
  }
  entry_field(
      keys.add(quantity("circuit", "value", dim::resistance, unbounded(), true, kCircuitUsers,
                        "the resistance, capacitance or inductance; a source's constant value "
                        "(waveform dc)")),
      &Scene::circuit, &CircuitSpec::value);
  keys.back().sensitivity = true;
  keys.back().unit_note = "Ohm (resistor), F (capacitor), H (inductor), V or A (sources)";
  keys.back().constraint = "> 0 for a resistor, capacitor or inductor";
  keys.back().default_note = "required (sources: with waveform dc)";
}

// A source's waveform: its kind, levels, timing and the sine's phase.
void add_waveform_keys(SceneTableKeys& keys) {
  keys.add(choice("circuit", "waveform", {"dc", "sine", "square", "pulse", "pwl"}, false,
                  "circuit sources", "the source's time function"))
      .text = [](const Scene& scene, std::size_t entry) {
    return std::string(waveform_kind_name(scene.circuit[entry].waveform.kind));
  };
  auto level = [&](const char* name, const char* users, bool required, const char* meaning,
                   double WaveformSpec::*member) {
    waveform_field(
        keys.add(quantity("circuit", name, dim::voltage, unbounded(), required, users, meaning)),
        member);
    keys.back().unit_note = kLevelUnit;
  };
  level("low", "source waveforms square, pulse", true, "the level before and between the pulses",
        &WaveformSpec::low);
  level("high", "source waveforms square, pulse", true, "the pulses' level", &WaveformSpec::high);
  waveform_field(keys.add(quantity("circuit", "frequency", dim::frequency, positive(), true,
                                   "source waveforms square, sine",
                                   "the square wave's or sine's "
                                   "frequency")),
                 &WaveformSpec::frequency);
  waveform_field(keys.add(quantity("circuit", "duty", dim::none,
                                   interval(Limit::exclusive, 0.0, Limit::exclusive, 1.0,
                                            "must be between 0 and 1 (exclusive), got {}"),
                                   false, "source waveform square",
                                   "the fraction of each period at the high level (its rise "
                                   "included)")),
                 &WaveformSpec::duty);
  waveform_field(keys.add(quantity("circuit", "rise", dim::time, non_negative(), false,
                                   "source waveforms square, pulse", "the rising edge's time")),
                 &WaveformSpec::rise);
  {
    ParameterInfo& fall =
        keys.add(quantity("circuit", "fall", dim::time, non_negative(), false,
                          "source waveforms square, pulse", "the falling edge's time"));
    fall.get = [](const Scene& scene, std::size_t entry) -> std::optional<double> {
      return scene.circuit[entry].waveform.fall_time();
    };
    fall.set = [](Scene& scene, std::size_t entry, double value) {
      scene.circuit[entry].waveform.fall = value;
    };
    fall.default_note = "the rise time (square), 0 s (pulse)";
  }
  waveform_field(
      keys.add(quantity("circuit", "delay", dim::time, non_negative(), false,
                        "source waveforms square, pulse, sine",
                        "the time before the waveform starts (the first pulse's rise, the "
                        "sine's t = 0)")),
      &WaveformSpec::delay);
  waveform_field(keys.add(quantity("circuit", "width", dim::time, non_negative(), true,
                                   "source waveform pulse", "the time at the high level")),
                 &WaveformSpec::width);
  waveform_field(keys.add(quantity("circuit", "period", dim::time, non_negative(), false,
                                   "source waveform pulse", "the pulse's period (0: one pulse)")),
                 &WaveformSpec::period);
  keys.back().constraint = "0 or at least rise + width + fall";
  level("offset", "source waveform sine", false, "the sine's constant part", &WaveformSpec::offset);
  level("amplitude", "source waveform sine", true,
        "the sine's amplitude: offset + amplitude*sin(2*pi*f*(t - delay) + phase)",
        &WaveformSpec::amplitude);
  waveform_field(
      keys.add(quantity("circuit", "phase", dim::none, unbounded(), false, "source waveform sine",
                        "the sine's phase at t = delay, in degrees (a plain number)")),
      &WaveformSpec::phase_degrees);
  keys.back().unit_note = "deg";
}

// A piecewise-linear source's points, inline or from a file.
void add_piecewise_linear_keys(SceneTableKeys& keys) {
  keys.add(
      key("circuit", "points", ParameterKind::text, "source waveform pwl",
          "the piecewise-linear waveform inline: [[\"0 s\", \"0 V\"], [\"1 ms\", \"3 kV\"], ...], "
          "times increasing"));
  keys.back().constraint = "either points or file";
  keys.back().default_note = "required with waveform pwl (or file)";
  keys.back().text = [](const Scene& scene, std::size_t entry) {
    const WaveformSpec& waveform = scene.circuit[entry].waveform;
    if (!waveform.file.empty()) return std::string();
    std::string list;
    for (const auto& [time, value] : waveform.points)
      list += (list.empty() ? "[" : ", [") + scene_text::format_number(time) + ", " +
              scene_text::format_number(value) + "]";
    return "[" + list + "]";
  };
  keys.add(
      key("circuit", "file", ParameterKind::text, "source waveform pwl",
          "the piecewise-linear waveform from a CSV file (relative to the scene file's folder): "
          "time [s], value [SI] per line, one header line allowed"));
  keys.back().constraint = "either points or file";
  keys.back().default_note = "none";
  keys.back().text = [](const Scene& scene, std::size_t entry) {
    return scene.circuit[entry].waveform.file;
  };
}

}  // namespace

// [[circuit]]
SceneTableKeys circuit_table_keys() {
  SceneTableKeys keys =
      entries_table("circuit", scene_limits::circuit_elements,
                    "electrical circuit elements around the DEAs, one [[circuit]] entry each");
  add_element_keys(keys);
  add_waveform_keys(keys);
  add_piecewise_linear_keys(keys);
  entry_field(keys.add(quantity("circuit", "ac", dim::voltage, unbounded(), false,
                                "circuit sources", "the source's magnitude in the AC analysis")),
              &Scene::circuit, &CircuitSpec::ac);
  keys.back().unit_note = kLevelUnit;
  return keys;
}

}  // namespace scene_keys
}  // namespace emnet
