// Issue #22 item 12, the configs: every duration, rate and threshold is bounded above as well as
// below (a heartbeat_timeout of 1e9 s switched the check off in effect; a bus_load_warning of 5
// could never warn), values whose products overflow the twin (k0: 1e308 N*m/rad) and a --t-end
// of 1e-300 are refused naming the key, and names carrying markup or control characters (an
// HTML unit_serial) are refused. Each: exit 2, a message naming the key, the value as written
// and what was expected, nothing created.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include "hostile_cli.hpp"
#include "hostile_config_cases.hpp"
#include "wavebench/config/config_error.hpp"
#include "wavebench/config/twin_case.hpp"

namespace wavebench::hostile {
namespace {

struct Case {
  std::string label;
  std::string text;
  std::string key;
  std::string value;  // as the message quotes it ("" where it is shown cleaned)
  std::string extra_args = {};
};

Case bench_line(const std::string& key_line, const std::string& line, const std::string& key,
                const std::string& value) {
  return {key + " " + value, with_line(bench_config(), key_line, line), key, value};
}

Case safety(const std::string& key, const std::string& value) {
  return bench_line("  " + key + ":", "  " + key + ": \"" + value + "\"", "safety." + key, value);
}

// `value` as written in YAML; the message quotes it without the YAML quotes.
Case can(const std::string& key, const std::string& value) {
  std::string shown = value;
  if (shown.size() >= 2 && shown.front() == '"') shown = shown.substr(1, shown.size() - 2);
  return bench_line("  " + key + ":", "  " + key + ": " + value, "can." + key, shown);
}

std::vector<Case> bench_cases() {
  std::vector<Case> cases = {
      // Safety limits (key class: a limit nothing reaches is a limit switched off).
      safety("heartbeat_timeout", "1e9 s"),
      safety("heartbeat_timeout", "11 s"),
      safety("modbus_link_timeout", "3600 s"),
      safety("max_input_speed", "1e6 rpm"),
      safety("max_brake_current", "5000 A"),
      safety("max_brake_torque", "5e6 N*m"),
      safety("max_measured_torque", "5e6 N*m"),
      safety("max_following_error", "1000 rev"),
      safety("max_coil_temperature", "500 degC"),
      safety("max_te_excursion", "1 rev"),
      // CAN timing and rates (key class: durations and fractions of the bus).
      can("bus_load_warning", "5"),
      can("bus_load_warning", "\"150 %\""),
      can("bus_load_warning", "-0.1"),
      can("sdo_timeout", "\"1e6 s\""),
      can("cycle_timeout", "\"1 min\""),
      can("quick_stop_timeout", "\"60 s\""),
      can("heartbeat_producer", "\"100 s\""),
      can("bitrate", "1e12"),
      // The brake link (key class: the Modbus driver's safety timeout).
      bench_line(
          "  timeouts:", "  timeouts: {response_ms: 500, byte_ms: 100, link_loss_ms: 600000}",
          "brake.timeouts.link_loss_ms", "600000"),
      // A dimension's ceiling behind every key of it (the torque sensor's offset, in N*m).
      bench_line("  offset: 0", "  offset: \"1e300 N*m\"", "torque_sensor.offset", "1e300 N*m"),
  };
  // Names (key class: text that ends up in reports, the console and the runs index).
  const auto serial = [&](const std::string& yaml, const std::string& shown) {
    cases.push_back(bench_line("unit_serial:", "unit_serial: " + yaml, "unit_serial", shown));
  };
  serial("\"<script>alert(1)</script>\"", "<script>alert(1)</script>");
  serial("\"SN-1\\\" onmouseover=\\\"x\"", "SN-1\" onmouseover=\"x");
  serial("\"SN-\\u0001-2\"", "SN-?-2");
  serial("\"SN-\\t-3\"", "SN-?-3");
  serial("\"\"", "");
  cases.push_back(bench_line("name: sim", "name: \"<img src=x onerror=alert(1)>\"", "name",
                             "<img src=x onerror=alert(1)>"));
  cases.push_back(bench_line("  calibration: {id: \"SIM-ENC-2026-001\"",
                             "  calibration: {id: \"<b>ENC</b>\", due: \"2027-06-30\"}",
                             "encoder.calibration.id", "<b>ENC</b>"));
  return cases;
}

std::vector<Case> twin_cases() {
  const std::string ok = twin_case("", "", "", "", "", "");
  const auto edit = [&](const std::string& from, const std::string& to) {
    std::string text = ok;
    text.replace(text.find(from), from.size(), to);
    return text;
  };
  return {
      {"k0 1e308 N*m/rad", edit("k0: \"3e4 N*m/rad\"", "k0: \"1e308 N*m/rad\""), "stiffness.k0",
       "1e308 N*m/rad"},
      {"k0 1e11 plain", edit("k0: \"3e4 N*m/rad\"", "k0: 1e11"), "stiffness.k0", "1e11"},
      {"viscous_input 1e300", twin_case(", viscous_input: 1e300", "", "", "", "", ""),
       "gear.viscous_input", "1e300"},
      {"ramp_time 1e300 s", twin_case("", "", ", ramp_time: \"1e300 s\"", "", "", ""),
       "input.ramp_time", "1e300 s"},
      {"speed 1e6 rad/s", edit("speed: \"100 rpm\"", "speed: \"1e6 rad/s\""), "input.speed",
       "1e6 rad/s"},
      {"t_end 1e-300", twin_case("", "", "", "", ", t_end: 1e-300", ""), "solver.t_end", "1e-300"},
      {"--t-end 1e-300", ok, "--t-end", "1e-300", "--t-end 1e-300"},
      {"--t-end 1e-7", ok, "--t-end", "1e-07", "--t-end 1e-7"},
      {"--t-end 1e5", ok, "--t-end", "100000", "--t-end 1e5"},
      {"min_relative_amplitude 5",
       twin_case("", "", "", "", "", ", spectrum: {min_relative_amplitude: 5}"),
       "analysis.spectrum.min_relative_amplitude", "5"},
      {"max_frequency 1e8 Hz", twin_case("", "", "", "", "", ", spectrum: {max_frequency: 1e8}"),
       "analysis.spectrum.max_frequency", "1e8"},
      {"HTML case name", edit("name: hostile", "name: \"<svg onload=alert(1)>\""), "name",
       "<svg onload=alert(1)>"},
  };
}

TEST(HostileConfigBounds, BenchConfigValuesBeyondTheirBoundsAreRefused) {
  Sandbox box("bench-bounds");
  const fs::path out = box.root() / "runs";
  int tried = 0, refused = 0;
  for (const auto& c : bench_cases()) {
    ASSERT_NE(c.text, bench_config()) << c.label << ": the edit must change the config";
    const fs::path file = box.in("bench.yaml");
    write_file(file, c.text);
    ++tried;
    const CliResult r = run_wavebench(
        "run static --bench " + quoted(file) + " --out " + quoted(out) + " --quiet", box.log("b"));
    SCOPED_TRACE(c.label + ": " + r.output);
    const bool names_all = r.output.find(c.key + ": got '" + c.value + "'") != std::string::npos &&
                           r.output.find("expected") != std::string::npos;
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(names_all) << "names " << c.key << " and '" << c.value << "'";
    EXPECT_FALSE(fs::exists(out)) << "no run folder, no index";
    if (r.exit_code == 2 && names_all && !fs::exists(out)) ++refused;
  }
  std::cout << "[hostile] bench config bounds and names: tried " << tried << ", refused " << refused
            << "\n";
  EXPECT_EQ(refused, tried);
}

TEST(HostileConfigBounds, TwinValuesThatOverflowAndTinyRunsAreRefusedNamingTheKey) {
  Sandbox box("twin-bounds");
  const fs::path out = box.root() / "out";
  int tried = 0, refused = 0;
  for (const auto& c : twin_cases()) {
    ++tried;
    const CliResult r = run_twin_case(box, c.text, c.extra_args, out, "t");
    SCOPED_TRACE(c.label + ": " + r.output);
    const bool names_all = r.output.find(c.key + ": got '" + c.value + "'") != std::string::npos &&
                           r.output.find("expected") != std::string::npos;
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(names_all) << "names " << c.key << " and '" << c.value << "'";
    EXPECT_FALSE(fs::exists(out));
    if (r.exit_code == 2 && names_all && !fs::exists(out)) ++refused;
  }
  std::cout << "[hostile] twin bounds: tried " << tried << ", refused " << refused << "\n";
  EXPECT_EQ(refused, tried);
}

// Keys finite one by one can still overflow together: the response is checked before anything
// is written, and the refusal names the keys behind the first channel that overflowed.
TEST(HostileConfigBounds, ANonFiniteTwinResponseIsRefusedNamingTheKeys) {
  model::SampledResponse r;
  r.t = {0, 0.5, 1};
  r.twist = {0, 1e-3, std::numeric_limits<double>::infinity()};
  r.gear_torque = {0, std::nan(""), 0};
  try {
    config::check_finite_response(r);
    ADD_FAILURE() << "a non-finite response was accepted";
  } catch (const config::ConfigError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("stiffness"), std::string::npos) << m;
    EXPECT_NE(m.find("t = 0.5 s"), std::string::npos) << m;  // the gear torque went first
    EXPECT_NE(m.find("expected"), std::string::npos) << m;
  }
  r.gear_torque = {0, 1, 2};
  r.twist = {0, 1e-3, 2e-3};
  EXPECT_NO_THROW(config::check_finite_response(r));
}

}  // namespace
}  // namespace wavebench::hostile
