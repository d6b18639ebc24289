// The commissioning check on the in-process simulated bench: all green as shipped; a wrong node
// id, an object the EDS lacks, a wrong identity and an unreachable brake each give a red row
// naming it. Nothing moves: the drive stays in its power-off state.
#include "wavebench/bench/bench_check.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "bench_test_support.hpp"
#include "wavebench/bench/bench_devices.hpp"
#include "wavebench/bench/canopen_bench.hpp"
#include "wavebench/canopen/cia402.hpp"
#include "wavebench/simdevices/brake_server.hpp"

namespace wavebench::bench::testing {
namespace {

struct Checked {
  CheckReport report;
  std::string table;
  canopen::Cia402State drive_state = canopen::Cia402State::unknown;
};

Checked check(const BenchConfig& config, const std::function<void(Bench&)>& before = {}) {
  auto bench = make_bench(config);
  if (before) before(*bench);
  auto* canopen = canopen_bench_of(*bench);
  EXPECT_NE(canopen, nullptr);
  Checked out;
  out.report = check_bench(*canopen);
  out.table = format_check_table(out.report);
  if (canopen->state() != BenchLifecycle::kUnconfigured) {
    std::error_code ec;
    out.drive_state = canopen::Cia402Drive(canopen->master().sdo(config.can.drive_node)).state(ec);
  }
  bench->disconnect();
  return out;
}

const CheckRow* red_row(const CheckReport& r, const std::string& device, const std::string& item) {
  for (const auto& row : r.rows)
    if (!row.ok && row.device.find(device) != std::string::npos &&
        row.item.find(item) != std::string::npos)
      return &row;
  return nullptr;
}

TEST(BenchCheck, AllGreenOnTheSimulatedBenchAndNothingMoves) {
  const auto c = check(sim_config());
  EXPECT_TRUE(c.report.all_green()) << c.table;
  std::printf("%s", c.table.c_str());
  // Every used object of the three devices has its row, plus the per-device and bus rows.
  std::size_t used = 0;
  for (const auto& d : canopen_devices(sim_config())) used += d.used.size();
  EXPECT_EQ(c.report.rows.size(), used + 3 * 6 + 3 + 1) << c.table;
  EXPECT_TRUE(c.drive_state == canopen::Cia402State::switch_on_disabled) << c.table;
  const auto json = check_report_json(c.report);
  EXPECT_TRUE(json["all_green"].get<bool>());
  EXPECT_EQ(json["rows"].size(), c.report.rows.size());
}

TEST(BenchCheck, WrongNodeIdIsRed) {
  // The master expects the drive at node 5; the simulated drive sits at node 1.
  auto config = sim_config([](BenchConfig& b) {
    b.can.drive_node = 5;
    b.simulated->drive_node = 1;
  });
  const auto c = check(config);
  EXPECT_FALSE(c.report.all_green());
  const auto* row = red_row(c.report, "servo drive (node 5)", "node answers");
  ASSERT_NE(row, nullptr) << c.table;
  EXPECT_NE(row->detail.find("can.nodes.drive"), std::string::npos) << row->detail;
  // The other nodes still answer.
  EXPECT_EQ(red_row(c.report, "output encoder", "node answers"), nullptr) << c.table;
}

TEST(BenchCheck, ObjectMissingFromTheEdsIsRed) {
  // servo_drive.eds without 0x6081 (profile velocity), which the bench writes for every move.
  std::ifstream in(std::filesystem::path(WAVEBENCH_SOURCE_DIR) / "configs/eds/servo_drive.eds");
  std::stringstream text;
  text << in.rdbuf();
  std::string eds = text.str();
  const auto at = eds.find("[6081]");
  ASSERT_NE(at, std::string::npos);
  eds.erase(at, eds.find("\n\n", at) + 2 - at);
  const auto pos = eds.find("=0x6081\n");
  ASSERT_NE(pos, std::string::npos);
  eds.replace(pos, 8, "=0x6080\n");  // the object list no longer names it
  auto config = sim_config([&](BenchConfig& b) {
    b.drive.expect.eds =
        std::make_shared<const canopen::Eds>(canopen::Eds::parse(eds, "no6081.eds"));
    b.drive.expect.eds_path = "no6081.eds";
  });
  const auto c = check(config);
  EXPECT_FALSE(c.report.all_green());
  const auto* row = red_row(c.report, "servo drive", "EDS");
  ASSERT_NE(row, nullptr) << c.table;
  EXPECT_NE(row->detail.find("0x6081:0 profile velocity: not in the EDS"), std::string::npos)
      << row->detail;
  // Connecting is refused before anything is configured: the EDS disagrees.
  const auto* pdo = red_row(c.report, "servo drive", "PDO mapping");
  ASSERT_NE(pdo, nullptr) << c.table;
  EXPECT_NE(pdo->detail.find("the EDS disagrees"), std::string::npos) << pdo->detail;
}

TEST(BenchCheck, EdsWarningsAreAGreenRowAndAnUnreadableUsedObjectSaysWhy) {
  // servo_drive.eds with 0x6081's AccessType misspelt (the object is left out of the EDS) and a
  // sub-index section without its object (a warning only).
  std::ifstream in(std::filesystem::path(WAVEBENCH_SOURCE_DIR) / "configs/eds/servo_drive.eds");
  std::stringstream text;
  text << in.rdbuf();
  std::string eds = text.str();
  const auto at = eds.find("AccessType=rw", eds.find("[6081]"));
  ASSERT_NE(at, std::string::npos);
  eds.replace(at, 13, "AccessType=readwrite");
  eds += "\n[2999sub1]\nParameterName=x\nDataType=0x0005\nAccessType=ro\n";
  auto config = sim_config([&](BenchConfig& b) {
    b.drive.expect.eds = std::make_shared<const canopen::Eds>(canopen::Eds::parse(eds, "w.eds"));
    b.drive.expect.eds_path = "w.eds";
  });
  const auto c = check(config);
  const auto* row = red_row(c.report, "servo drive", "EDS");
  ASSERT_NE(row, nullptr) << c.table;
  EXPECT_NE(row->detail.find("0x6081:0 profile velocity: in the EDS but unreadable: EDS w.eds: "
                             "[6081] AccessType = 'readwrite'"),
            std::string::npos)
      << row->detail;
  const CheckRow* warnings = nullptr;
  for (const auto& r : c.report.rows)
    if (r.item == "EDS warnings") warnings = &r;
  ASSERT_NE(warnings, nullptr) << c.table;
  EXPECT_TRUE(warnings->ok) << c.table;
  EXPECT_NE(warnings->device.find("servo drive"), std::string::npos) << c.table;
  EXPECT_NE(warnings->detail.find("w.eds: 2 warnings: "), std::string::npos) << warnings->detail;
  EXPECT_NE(warnings->detail.find("[2999sub1]: a sub-index of 0x2999"), std::string::npos)
      << warnings->detail;
}

TEST(BenchCheck, WrongIdentityIsRed) {
  auto config = sim_config([](BenchConfig& b) { b.drive.expect.identity.vendor_id = 0x999; });
  const auto c = check(config);
  EXPECT_FALSE(c.report.all_green());
  const auto* row = red_row(c.report, "servo drive", "identity");
  ASSERT_NE(row, nullptr) << c.table;
  EXPECT_NE(
      row->detail.find("vendor-ID 0x00000A57, expected 0x00000999 (drive.identity.vendor_id)"),
      std::string::npos)
      << row->detail;
  EXPECT_EQ(red_row(c.report, "output encoder", "identity"), nullptr) << c.table;
}

TEST(BenchCheck, UnreachableBrakeIsRed) {
  // No simulated brake controller; the config's endpoint has nobody listening.
  auto config = sim_config([](BenchConfig& b) {
    b.simulated->brake_server = false;
    b.brake.link.endpoint.transport = modbus::Transport::tcp;
    b.brake.link.endpoint.host = "127.0.0.1";
    b.brake.link.endpoint.port = 1;
  });
  const auto c = check(config);
  EXPECT_FALSE(c.report.all_green());
  const auto* row = red_row(c.report, "brake controller (tcp:127.0.0.1:1)", "registers readable");
  ASSERT_NE(row, nullptr) << c.table;
  // The CANopen side is still checked node by node.
  EXPECT_EQ(red_row(c.report, "servo drive", "node answers"), nullptr) << c.table;
  EXPECT_EQ(red_row(c.report, "servo drive", "0x6041"), nullptr) << c.table;
}

}  // namespace
}  // namespace wavebench::bench::testing
