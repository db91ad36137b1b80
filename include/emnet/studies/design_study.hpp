// Design studies: one scene, many variants of its numeric keys, a few analyses per variant, a
// table of results (one row per variant, failed variants included with their reason).
//
// Variants come from
//   - a Cartesian grid: every combination of the values of each varied key;
//   - Monte Carlo: `samples` draws of every randomly varied key (for each grid point, when a
//     grid is varied as well), from one seeded generator in the order variant by variant,
//     key by key, so that a seed gives the same variants whatever the thread count;
//   - a list: a CSV file whose header names the keys and whose rows are the variants.
// A variation is written KEY=SPEC (KEY as `--set` takes it: "beam.bending_stiffness",
// "dea.A.lever_arm"):
//   v1,v2,...            the values (a grid axis)
//   linspace(a,b,n)      n values from a to b, equally spaced (a grid axis)
//   logspace(a,b,n)      n values from a to b, geometrically spaced (a, b > 0; a grid axis)
//   uniform(a,b)         uniform on [a, b]                               (Monte Carlo)
//   normal(mean,sd)      normal                                          (Monte Carlo)
//   lognormal(median,s)  ln X normal with mean ln(median) and standard deviation s (Monte Carlo)
// Every value is a number in the key's SI unit, a quantity with a unit ("60 mm"), or a
// percentage of the scene's own value ("95%"; for normal's sd, 5% is 0.05 times the value); s is
// a plain number (or a percentage: 5% is 0.05).
// KEY1+KEY2+...=SPEC varies several keys together, by the same relative change: the values are
// KEY1's, and each other key takes its own value times KEY1's value over KEY1's scene value (one
// film's dielectric and force thickness: "dea.A.dielectric_thickness+dea.A.force_thickness=
// uniform(95%,105%)"). Each key is a column of the variants.
//
// Each variant changes only the varied fields of the nominal scene (set_parameter: no TOML is
// read again), and is then resolved and built as any scene (prepare_model). beam.segments = "auto"
// is resolved once, on the nominal scene, so that every variant has the same mesh (a note says
// so), and so is beam.kinematics = "auto"; the other "auto" keys are resolved per variant. With
// beam.kinematics = "large" the modes are about the deflected static state and the sweep is shot
// (as `emnet modes` and `emnet sweep-switching`): seconds per variant instead of milliseconds.
// Analyses, each a group of columns:
//   modes            f<k>_hz, zeta<k>, f<k>_error_hz for the k = 1..mode_count lowest oscillatory
//                    modes about the operating point (run_modes; the error is the pole's rounding
//                    bound over 2π: a mode whose error cannot be bounded fails the variant);
//   static           static.<probe>_<unit> for each of the scene's probes (the static state under
//                    the drive at t = 0, as `emnet static`);
//   sweep-switching  the periodic steady state of the switched drive over sweep.frequencies (the
//                    exact method, as `emnet sweep-switching`): sweep.peak_hz (the largest
//                    peak-to-peak of the last output) and, for each output and each frequency of
//                    `report_frequencies`, sweep.<output>.min_at_<f>Hz_<unit> and .max_at_….
// Units: SI throughout; frequencies in Hz, times in seconds.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "emnet/core/errors.hpp"
#include "emnet/core/progress.hpp"
#include "emnet/model/validity.hpp"
#include "emnet/scene/scene.hpp"

namespace emnet {

enum class VariationKind { values, uniform, normal, log_normal };

// One varied key, its values in SI.
struct Variation {
  std::string key;  // canonical ("dea[A].lever_arm")
  // Keys varied with it by the same relative change, and their scene values over key's.
  std::vector<std::string> linked;
  std::vector<double> linked_ratios;
  VariationKind kind = VariationKind::values;
  std::vector<double> values;  // values: the grid axis
  double first = 0.0;          // uniform: lower; normal: mean; log_normal: median
  double second = 0.0;         // uniform: upper; normal: standard deviation; log_normal: s
  bool random() const { return kind != VariationKind::values; }
};

// "KEY=SPEC" (see above) against `scene` (which gives the nominal value for percentages and
// checks the key). Throws OptionError naming the field "variations" and the key.
Variation parse_variation(const Scene& scene, const std::string& text);

// The variants: keys (canonical) and one row of SI values per variant.
struct VariantTable {
  std::vector<std::string> keys;
  std::vector<std::vector<double>> rows;
};

// At most this many variants in one study: each variant's values and results are held in
// memory (a few hundred bytes each), so a study stays within a few hundred MB. A larger study
// is several studies (or a Dask cluster's chunks).
inline constexpr std::size_t kMaxVariants = 1000000;

// The grid × Monte Carlo variants of `variations` (see above). `samples`: draws per grid point
// when a variation is random (0 there: InputError asking for it; given without a random
// variation: InputError). Throws OptionError (field "variations" or "samples") for a bad
// combination or more than kMaxVariants variants.
VariantTable make_variants(const std::vector<Variation>& variations, std::size_t samples,
                           std::uint64_t seed);

// The variants of a CSV file: a header of keys (any form --set takes), then one variant per line
// of values (numbers in SI, quantities with units, percentages of the scene's value); ',' or ';'
// between fields; blank lines and lines starting with '#' skipped. Errors name the file, line and
// key (an OptionError of the field "variants" for the file's form).
VariantTable read_variants_csv(const Scene& scene, const std::string& path);

enum class StudyAnalysis { modes, static_state, switching_sweep };
// "modes", "static", "sweep-switching" (and "sweep_switching"), comma-separated; OptionError
// naming the field "analyses" of DesignStudyOptions.
std::vector<StudyAnalysis> parse_study_analyses(const std::string& text);

struct DesignStudyOptions {
  std::vector<StudyAnalysis> analyses{StudyAnalysis::modes};
  int mode_count = 1;  // modes: the lowest oscillatory modes reported (1..100)
  // sweep-switching: the switching frequencies [Hz] (default 1 to 7 Hz in steps of 0.1, as
  // `emnet sweep-switching`), and those whose extremes are columns (each added to the sweep when
  // it is not one of them).
  std::vector<double> sweep_frequencies;
  std::vector<double> report_frequencies;
  int sweep_samples = 0;  // per period; 0: the exact method's default
  int threads = 0;        // 0: every core (std::thread::hardware_concurrency)
  // Reported from the calling thread (variants done of all, "variants"), about ten times a
  // second; cancelled: the variants not started are rows "cancelled".
  Progress* progress = nullptr;

  /// The checks of the options alone, as run_design_study makes them first.
  /// @throws OptionError naming "analyses" (none), "mode_count" (outside 1..100), "threads"
  /// (outside 0..1024) or "report_frequencies" (more than 1000, or one not > 0)
  void validate() const;
};

// What a variant cost, per stage [s].
struct VariantCost {
  double build = 0.0;            // set the keys, resolve, build and assemble the network
  double operating_point = 0.0;  // the static state (or zero, for a linear free body)
  double modes = 0.0;
  double static_state = 0.0;  // the probes' static values
  double sweep = 0.0;
  double total() const { return build + operating_point + modes + static_state + sweep; }
};

struct VariantResult {
  Status status;               // failed: why ("set_parameter: key 'beam.length': must be > 0 …")
  std::vector<double> values;  // one per DesignStudyResult::columns; empty when failed
  // The model's validity (emnet/model/validity.hpp) over what the variant computed: the static
  // deflection probes, the sweep's deflection extremes, the drive's peak DEA voltages. Its
  // summary and violations; checked for every variant that computed.
  Validity validity;
  VariantCost cost;
};

struct DesignStudyResult {
  Status status;  // failed only when nothing could run (the nominal scene itself fails to build)
  std::vector<std::string> keys;  // the varied keys (VariantTable::keys)
  std::vector<std::string> key_units;
  std::vector<std::vector<double>> variants;  // the table's rows
  std::vector<std::string> columns;           // result columns (see above), with their units:
  std::vector<std::string> units;
  std::vector<VariantResult> rows;   // one per variant, in order
  std::size_t failed = 0;            // rows whose status failed
  std::size_t outside_validity = 0;  // rows computed but outside the model's validity
  int threads = 1;
  int unknowns = 0;      // of the nominal network
  int segments = 0;      // of every variant's beam
  VariantCost cost;      // summed over the variants
  double seconds = 0.0;  // wall time of the whole study
  std::vector<std::string> notes;
};

// Runs every variant of `table` on `scene` (a read scene). Bad options are OptionError (naming
// the field; "variants" for a table of more than kMaxVariants rows, "variations" for a key no
// variant can set); a nominal scene that cannot be built is InputError too; a variant's failure
// (input or numerical) is its row's Status, never an exception. The rows and their values depend
// only on the scene, the table and the options, not on `threads`.
DesignStudyResult run_design_study(const Scene& scene, const VariantTable& table,
                                   const DesignStudyOptions& options);

}  // namespace emnet
