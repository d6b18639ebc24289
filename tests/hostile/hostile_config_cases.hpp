#pragma once
// The valid configs the hostile config tests edit one line of: a small twin case and the
// shipped simulated bench with its files named by absolute path.
#include <string>

#include "hostile_cli.hpp"

namespace wavebench::hostile {

inline const fs::path kSource = WAVEBENCH_SOURCE_DIR;

// A small valid case; each extreme case replaces one of the {placeholders}.
inline std::string twin_case(const std::string& gear, const std::string& te,
                             const std::string& input, const std::string& stiffness,
                             const std::string& solver, const std::string& analysis) {
  return "name: hostile\n"
         "gear: {z_flex: 200, z_circ: 202, inertia_input: \"3e-4 kg*m^2\", "
         "inertia_output: \"0.05 kg*m^2\"" +
         gear + "}\n" +
         "te:\n  terms:\n    - {source: a, family: custom, order_input: 0, order_output: 1, "
         "amplitude: \"1 arcmin\"" +
         te + "}\n" + "stiffness: {form: linear_periodic, k0: \"3e4 N*m/rad\"" + stiffness + "}\n" +
         "input: {type: kinematic, speed: \"100 rpm\"" + input + "}\n" +
         // A case's own t_end or sample_rate replaces the short defaults (a second one
         // would be a duplicate key, refused for that reason instead).
         "solver: {locate_events: true" +
         (solver.find("t_end") == std::string::npos ? ", t_end: 0.2" : "") +
         (solver.find("sample_rate") == std::string::npos ? ", sample_rate: \"1 kHz\"" : "") +
         solver + "}\n" + "analysis: {order_spectrum: false" + analysis + "}\n";
}

// A bench config with the twin and true-gear cases and the EDS files named by absolute path, so
// that it can be written outside configs/.
inline std::string bench_config() {
  std::string text = read_file(kSource / "configs/benches/sim.yaml");
  const auto put = [&](const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    if (at != std::string::npos) text.replace(at, from.size(), to);
  };
  put("../twin/bench-unit-seed004.yaml",
      (kSource / "configs/twin/bench-unit-seed004.yaml").string());
  put("case: sim-true-gear.yaml",
      "case: " + (kSource / "configs/benches/sim-true-gear.yaml").string());
  for (const char* eds : {"servo_drive.eds", "output_encoder.eds", "torque_sensor.eds"})
    put(std::string("../eds/") + eds, (kSource / "configs/eds" / eds).string());
  return text;
}

inline std::string with_line(std::string text, const std::string& key_line,
                             const std::string& line) {
  const auto at = text.find(key_line);
  if (at == std::string::npos) return text;
  const auto end = text.find('\n', at);
  text.replace(at, end - at, line);
  return text;
}

// `wavebench sim` on a twin case written to `box`, with `extra_args`, its output aimed at `out`.
inline CliResult run_twin_case(Sandbox& box, const std::string& text, const std::string& extra_args,
                               const fs::path& out, const std::string& log_name) {
  const fs::path file = box.in("case.yaml");
  write_file(file, text);
  return run_wavebench("sim " + quoted(file) + " --out " + quoted(out) + " --quiet " + extra_args,
                       box.log(log_name));
}

}  // namespace wavebench::hostile
