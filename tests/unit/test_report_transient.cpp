// The JSON of a transient run (emnet/report/transient_json.hpp), and the transient and static
// analyses failing (Status) rather than returning a non-finite value.
//
// Reference of the JSON values: the step response of a parallel RC cell driven by a current
// step I from rest, v(t) = (I/G)·(1 − e^{−t·G/C}) (closed form of C·v' + G·v = I, v(0) = 0).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "emnet/analysis/analysis.hpp"
#include "emnet/analysis/transient.hpp"
#include "emnet/elements/capacitor.hpp"
#include "emnet/elements/conductance.hpp"
#include "emnet/elements/current_source.hpp"
#include "emnet/report/transient_json.hpp"

namespace emnet {
namespace {

// A capacitor C and a conductance G from node v to ground, fed by a constant current I that
// switches on at t = 0.
System rc_cell(double capacitance, double conductance, double current) {
  Network network;
  const NodeId v = network.add_node("v", Domain::electrical, "cell voltage");
  network.add<Capacitor>("C", v, ground, capacitance);
  network.add<Conductance>("G", v, ground, conductance);
  network.add<CurrentSource>("I", ground, v, Waveform::constant(current));
  return network.assemble();
}

// The cell's node is the first unknown (node across values come first in y).
Probe cell_voltage() {
  Probe probe;
  probe.name = "v";
  probe.quantity = ProbeQuantity::dea_voltage;  // a voltage across a capacitance
  probe.unit = "V";
  probe.description = "cell voltage";
  probe.terms = {{0, 1.0}};
  return probe;
}

TransientOptions uniform_outputs(double end_time, int count) {
  TransientOptions options;
  options.end_time = end_time;
  for (int k = 0; k <= count; ++k) options.output_times.push_back(end_time * k / count);
  return options;
}

// Exact method (matrix exponential of a 1×1 system): its only error is rounding, so 1e-12 of
// the final value I/G holds with a wide margin.
TEST(TransientJson, KeysInOrderAndValuesOfTheRcStepResponse) {
  const double capacitance = 2e-6, conductance = 1e-3, current = 5e-3;  // τ = C/G = 2 ms
  const System system = rc_cell(capacitance, conductance, current);
  const std::vector<Probe> probes{cell_voltage()};
  const TransientResult result = run_transient_exact(system, probes, uniform_outputs(10e-3, 50));
  ASSERT_TRUE(result.status.ok()) << result.status.message;

  TransientRunDescription run;
  run.scene = "rc";
  run.start_state = "at rest";
  run.switching_frequency_hz = 100.0;
  run.periods = 1.0;
  run.relative_tolerance = 1e-6;
  run.total_seconds = 0.25;
  const Json json = to_json(result, probes, run);

  const std::vector<std::string> keys{"scene",
                                      "automatic_choices",
                                      "method",
                                      "start_state",
                                      "switching_frequency_hz",
                                      "periods",
                                      "rtol",
                                      "times_s",
                                      "outputs",
                                      "statistics",
                                      "cost",
                                      "validity"};
  std::vector<std::string> written;
  for (const auto& item : json.items()) written.push_back(item.key());
  EXPECT_EQ(written, keys);
  EXPECT_EQ(json["method"], "exact");
  EXPECT_EQ(json["scene"], "rc");
  EXPECT_EQ(json["switching_frequency_hz"].get<double>(), 100.0);
  EXPECT_EQ(json["cost"]["total_seconds"].get<double>(), 0.25);
  EXPECT_EQ(json["statistics"]["restarts"].get<long>(), result.statistics.restarts);
  ASSERT_EQ(json["outputs"].size(), 1u);
  const Json& output = json["outputs"][0];
  EXPECT_EQ(output["name"], "v");
  EXPECT_EQ(output["unit"], "V");
  EXPECT_EQ(output["description"], "cell voltage");
  const auto times = json["times_s"].get<std::vector<double>>();
  const auto values = output["values"].get<std::vector<double>>();
  ASSERT_EQ(times.size(), 51u);
  ASSERT_EQ(values.size(), times.size());
  const double final_value = current / conductance;
  for (size_t i = 0; i < times.size(); ++i) {
    ASSERT_TRUE(std::isfinite(times[i]) && std::isfinite(values[i])) << i;
    const double reference = final_value * (1.0 - std::exp(-times[i] * conductance / capacitance));
    EXPECT_NEAR(values[i], reference, 1e-12 * final_value) << times[i];
  }
  EXPECT_EQ(times.back(), 10e-3);
}

// I = 1e300 A into C = 1e-7 F and G = 1e-9 S (τ = C/G = 100 s): I/C = 1e307 V/s is finite, but
// the final value I/G = 1e309 V is beyond double precision, and so is v(t) = (I/G)·(1 − e^{−t/τ})
// from t ≈ 20 s (v(25 s) ≈ 2.2e308 V). v(0) = 0 at rest. Each analysis must fail, naming what
// overflowed, instead of returning inf or NaN.
System overflowing_rc_cell() {
  return rc_cell(1e-7, 1e-9, 1e300);
}

TEST(TransientNonFinite, ExactMethodFailsNamingTheOutputAndTime) {
  const System system = overflowing_rc_cell();
  const std::vector<Probe> probes{cell_voltage()};
  const TransientResult result = run_transient_exact(system, probes, uniform_outputs(100.0, 4));
  ASSERT_FALSE(result.status.ok());
  EXPECT_NE(result.status.message.find("non-finite value of output 'v' at t = 25 s"),
            std::string::npos)
      << result.status.message;
}

TEST(TransientNonFinite, IdaFailsRatherThanReturningAnInfiniteValue) {
  const System system = overflowing_rc_cell();
  const std::vector<Probe> probes{cell_voltage()};
  const TransientResult result = run_transient_ida(system, probes, uniform_outputs(100.0, 4));
  ASSERT_FALSE(result.status.ok());
  EXPECT_FALSE(result.status.message.empty());
}

TEST(StaticNonFinite, SolveStaticFailsNamingTheUnknown) {
  const System system = overflowing_rc_cell();
  const StaticResult rest = solve_static(system);
  ASSERT_FALSE(rest.status.ok());
  EXPECT_NE(rest.status.message.find("non-finite"), std::string::npos) << rest.status.message;
  EXPECT_NE(rest.status.message.find("'v'"), std::string::npos) << rest.status.message;
}

}  // namespace
}  // namespace emnet
