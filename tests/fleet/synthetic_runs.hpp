#pragma once
// Finished runs in a RunStore as execute_run leaves them (index row, results.json), with the
// figures the shared store reads, without running a bench: the fleet tests publish hundreds.

#include <unistd.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "wavebench/storage/run_store.hpp"

namespace wavebench::fleet::testing {

struct SyntheticRun {
  std::string unit = "U-0001";
  std::string model = "CSF-25-100-2A-GR";
  double p2p_forward_arcmin = 0.8;
  double p2p_reverse_arcmin = 0.3;  // below every forward pass the tests write
  double lost_motion_arcmin = 0.4;
  double p2p_limit_arcmin = 1.0;
};

inline nlohmann::json synthetic_results(const std::string& run_id, const SyntheticRun& r) {
  const auto pass = [](const char* direction, double load, double p2p) {
    return nlohmann::json{
        {"direction", direction}, {"load_nm", load},
        {"mean_arcmin", 0.1},     {"p2p_arcmin", p2p},
        {"std_arcmin", p2p / 4},  {"points", nlohmann::json::array({{{"te_arcmin", 0.1}}})}};
  };
  return {{"schema", "wavebench.results/2"},
          {"run_id", run_id},
          {"procedure", "static"},
          {"unit_serial", r.unit},
          {"operator", "ana"},
          {"bench", "sim"},
          {"spec",
           {{"name", "csf-25-100"},
            {"model", r.model},
            {"limits", nlohmann::json::array({{{"key", "static_te_p2p"},
                                               {"limit", "static_p2p_arcmin"},
                                               {"value", r.p2p_limit_arcmin},
                                               {"unit", "arcmin"}}})}}},
          {"static", nlohmann::json::array({pass("forward", 0, r.p2p_forward_arcmin),
                                            pass("reverse", 0, r.p2p_reverse_arcmin),
                                            pass("forward", 60, r.p2p_forward_arcmin + 0.05)})},
          {"lost_motion",
           nlohmann::json::array({{{"load_nm", 0}, {"max_abs_arcmin", r.lost_motion_arcmin}}})},
          {"status", "complete"},
          {"verdict", "PASS"}};
}

// A complete run in `store`; returns its id.
inline std::string add_synthetic_run(storage::RunStore& store, const SyntheticRun& r) {
  const nlohmann::json limits = {{"static_p2p_arcmin", r.p2p_limit_arcmin}};
  const auto id = store.create_run("static", r.unit, "name: sim\n", limits.dump(), "csf-25-100");
  store.write_results(id, synthetic_results(id, r));
  store.finish_run(id, storage::RunStatus::kComplete, "", true, "PASS");
  return id;
}

inline std::filesystem::path fresh_dir(const std::string& name) {
  auto dir = std::filesystem::path(WAVEBENCH_BINARY_DIR) / "test-tmp" / "fleet" /
             (name + "." + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace wavebench::fleet::testing
