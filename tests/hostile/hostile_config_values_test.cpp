// Extreme values (issue #8): each must be refused by the twin loader (or `--t-end`) with exit
// 2, a message naming the key and the bound, and nothing written; never std::bad_alloc, never
// a run that eats memory or does not end.
#include <gtest/gtest.h>
#include <unistd.h>

#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include "hostile_cli.hpp"
#include "hostile_config_cases.hpp"

namespace wavebench::hostile {
namespace {

struct Extreme {
  std::string label;
  std::string text;
  std::string key;
  std::string extra_args;  // after --out
};

Extreme in_gear(std::string label, std::string v, std::string key) {
  return {label, twin_case(v, "", "", "", "", ""), key, ""};
}
Extreme in_te(std::string label, std::string v, std::string key) {
  return {label, twin_case("", v, "", "", "", ""), key, ""};
}
Extreme in_input(std::string label, std::string v, std::string key) {
  return {label, twin_case("", "", v, "", "", ""), key, ""};
}
Extreme in_stiffness(std::string label, std::string v, std::string key) {
  return {label, twin_case("", "", "", v, "", ""), key, ""};
}
Extreme in_solver(std::string label, std::string v, std::string key) {
  return {label, twin_case("", "", "", "", v, ""), key, ""};
}
Extreme in_analysis(std::string label, std::string v, std::string key) {
  return {label, twin_case("", "", "", "", "", v), key, ""};
}

std::vector<Extreme> extremes() {
  std::string many_terms = "name: many\n";
  many_terms += "gear: {ratio: 100, inertia_input: 3e-4, inertia_output: 0.05}\nte:\n  terms:\n";
  for (int i = 0; i < 10001; ++i) {
    many_terms += "    - {source: s, family: custom, order_input: 1, amplitude: 1e-6}\n";
  }
  many_terms +=
      "stiffness: {form: cubic, k1: 3e4}\ninput: {type: kinematic, speed: 10}\n"
      "solver: {t_end: 0.1}\n";
  return {
      in_solver("t_end 1e300 s", ", t_end: 1e300", "solver.t_end"),
      in_solver("t_end 300 s at 100 kHz", ", t_end: \"300 s\", sample_rate: \"100 kHz\"",
                "solver.t_end"),
      in_solver("t_end NaN", ", t_end: .nan", "solver.t_end"),
      in_solver("t_end inf", ", t_end: .inf", "solver.t_end"),
      in_solver("sample_rate 1e12 Hz", ", sample_rate: 1e12", "solver.sample_rate"),
      in_solver("sample_rate 1 GHz as text", ", sample_rate: \"1000 MHz\"", "solver.sample_rate"),
      in_solver("fixed_step 1e-9 s", ", method: rk4, fixed_step: 1e-9", "solver.fixed_step"),
      in_solver("rk4 needing 1e9 steps", ", method: rk4, fixed_step: 1e-7, t_end: 100",
                "solver.fixed_step"),
      in_solver("max_step 1e-12 s", ", max_step: 1e-12", "solver.max_step"),
      in_solver("max_step needing 1e9 steps", ", max_step: 1e-7, t_end: 100", "solver.max_step"),
      in_solver("rtol 1e-300", ", rtol: 1e-300", "solver.rtol"),
      in_solver("atol 1e-300", ", atol: 1e-300", "solver.atol"),
      in_analysis("max_peaks 2e9", ", spectrum: {max_peaks: 2000000000}", "analysis.spectrum"),
      in_analysis("max_clusters 2e9", ", poincare: {max_clusters: 2000000000}",
                  "analysis.poincare.max_clusters"),
      in_analysis("sweep steps 1e8",
                  ", sweep: {from: 10, to: 20, steps: 100000000, settle_time: 0.1, "
                  "record_time: 0.1}",
                  "analysis.sweep.steps"),
      in_analysis("sweep simulating 4 h",
                  ", sweep: {from: 10, to: 20, steps: 100, settle_time: 36, record_time: 36}",
                  "analysis.sweep.steps"),
      in_analysis("monte_carlo_runs 2e9", ", sensitivity: {monte_carlo_runs: 2000000000}",
                  "analysis.sensitivity.monte_carlo_runs"),
      in_analysis("int overflow", ", spectrum: {max_peaks: 99999999999999999999}",
                  "analysis.spectrum.max_peaks"),
      in_te("TE order 1e300", ", order_input: 1e300", "te.terms[0].order_input"),
      in_te("TE amplitude 1e300", ", amplitude: 1e300", "te.terms[0]"),
      in_stiffness("harmonic order 1e9",
                   ", harmonics: [{amplitude: 1e3, order_input: 1e9, order_output: 0}]",
                   "stiffness.harmonics[0].order_input"),
      in_gear("tooth counts 2e9", ", z_flex: 2000000000, z_circ: 2000000002", "gear.z_flex"),
      in_gear("wave number 1e6", ", wave_number: 1000000", "gear.wave_number"),
      in_gear("inertia 1e-300", ", inertia_input: 1e-300", "gear.inertia"),
      in_input("speed 1e300 rpm", ", speed: \"1e300 rpm\"", "input.speed"),
      {"10001 TE terms", many_terms, "te.terms", ""},
      {"--t-end 1e300", twin_case("", "", "", "", "", ""), "--t-end", "--t-end 1e300"},
      {"--t-end nan", twin_case("", "", "", "", "", ""), "--t-end", "--t-end nan"},
      {"--t-end 300 on XB-80 (60 kHz)", read_file(kSource / "configs/twin/xb-80-134h.yaml"),
       "--t-end", "--t-end 300"},
  };
}

TEST(HostileConfigValues, TwinExtremeValuesAreRefusedNamingTheKey) {
  Sandbox box("extremes");
  const fs::path out = box.root() / "out";
  int tried = 0, refused = 0;
  for (const auto& e : extremes()) {
    ++tried;
    const CliResult r = run_twin_case(box, e.text, e.extra_args, out, "last");
    SCOPED_TRACE(e.label + ": " + r.output);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.output.find(e.key), std::string::npos) << "names " << e.key;
    EXPECT_NE(r.output.find("expected"), std::string::npos);
    EXPECT_EQ(r.output.find("bad_alloc"), std::string::npos);
    EXPECT_FALSE(fs::exists(out));
    if (r.exit_code == 2 && r.output.find(e.key) != std::string::npos && !fs::exists(out)) {
      ++refused;
    }
  }
  std::cout << "[hostile] twin extreme values: tried " << tried << ", refused " << refused << "\n";
  EXPECT_EQ(refused, tried);
}

TEST(HostileConfigValues, TheOutputBudgetMessageGivesTheNumbers) {
  Sandbox box("budget");
  const fs::path file = box.in("case.yaml");
  write_file(file, twin_case("", "", "", "", ", t_end: \"300 s\", sample_rate: \"100 kHz\"", ""));
  const CliResult r =
      run_wavebench("sim " + quoted(file) + " --out " + quoted(box.root() / "out"), box.log("b"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("solver.t_end: got '300 s', expected a run whose output fits in 2 GiB"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("at 100 kHz output"), std::string::npos) << r.output;
}

TEST(HostileConfigValues, BenchConfigRefusesDisarmedLimitsAndBadText) {
  Sandbox box("bench");
  const fs::path out = box.root() / "runs";
  struct Case {
    std::string label, text, key;
  };
  std::vector<Case> cases;
  for (const std::string key :
       {"max_input_speed", "max_brake_current", "max_brake_torque", "max_measured_torque",
        "max_following_error", "max_coil_temperature", "max_te_excursion", "heartbeat_timeout",
        "modbus_link_timeout"}) {
    const std::string base = bench_config();
    cases.push_back({key + " negative", with_line(base, "  " + key + ":", "  " + key + ": \"-3\""),
                     "safety." + key});
    cases.push_back(
        {key + " zero", with_line(base, "  " + key + ":", "  " + key + ": 0"), "safety." + key});
  }
  cases.push_back({"non-UTF-8 unit_serial",
                   with_line(bench_config(), "name:", "name: sim\nunit_serial: \"SN-\xC3\x28-1\""),
                   "unit_serial"});
  cases.push_back({"a 1000-character unit_serial",
                   with_line(bench_config(),
                             "name:", "name: sim\nunit_serial: \"" + std::string(1000, 'x') + "\""),
                   "unit_serial"});
  cases.push_back({"duplicate safety key",
                   with_line(bench_config(), "  max_input_speed:",
                             "  max_input_speed: \"3000 rpm\"\n  max_input_speed: \"9000 rpm\""),
                   "safety.max_input_speed"});
  // The drive's units (issue #9): a misspelt unit, a negative factor, a zero torque scale.
  for (const auto& [key, value] :
       std::vector<std::pair<std::string, std::string>>{{"velocity_unit", "rmp"},
                                                        {"position_unit", "\"-1 deg\""},
                                                        {"acceleration_unit", "rpm"},
                                                        {"torque_actual_scale", "\"0 N*m\""}}) {
    cases.push_back({"drive." + key + " " + value,
                     with_line(bench_config(), "  counts_per_revolution:",
                               "  counts_per_revolution: 131072\n  " + key + ": " + value),
                     "drive." + key});
  }
  int tried = 0, refused = 0;
  for (const auto& c : cases) {
    ASSERT_NE(c.text, bench_config()) << c.label << ": the edit must change the config";
    const fs::path file = box.in("bench.yaml");
    write_file(file, c.text);
    ++tried;
    const CliResult r = run_wavebench(
        "run static --bench " + quoted(file) + " --out " + quoted(out) + " --quiet", box.log("b"));
    SCOPED_TRACE(c.label + ": " + r.output);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.output.find(c.key), std::string::npos);
    EXPECT_NE(r.output.find(file.string()), std::string::npos);
    EXPECT_FALSE(fs::exists(out)) << "no run folder, no index";
    if (r.exit_code == 2 && r.output.find(c.key) != std::string::npos && !fs::exists(out)) {
      ++refused;
    }
  }
  std::cout << "[hostile] bench config values: tried " << tried << ", refused " << refused << "\n";
  EXPECT_EQ(refused, tried);
}

}  // namespace
}  // namespace wavebench::hostile

namespace wavebench::hostile {
namespace {

// The refusals above mean something only if the case they edit is valid as it stands.
TEST(HostileConfigValues, TheUneditedCaseRuns) {
  Sandbox box("base");
  write_file(box.in("case.yaml"), twin_case("", "", "", "", "", ""));
  const CliResult r = run_wavebench(
      "sim " + quoted(box.in("case.yaml")) + " --out " + quoted(box.root() / "out") + " --quiet",
      box.log("base"));
  EXPECT_EQ(r.exit_code, 0) << r.output;
}

}  // namespace
}  // namespace wavebench::hostile
