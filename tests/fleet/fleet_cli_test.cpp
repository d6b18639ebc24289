// `wavebench fleet runs|trend|spc` against a real PostgreSQL server: tables, JSON, and the exit
// statuses (2 for a bad argument or config, 1 when the store cannot be reached).
#include <gtest/gtest.h>

#include <fstream>

#include "cli_run.hpp"
#include "postgres_server.hpp"
#include "synthetic_runs.hpp"
#include "wavebench/fleet/postgres_results_store.hpp"

namespace wavebench::fleet {
namespace {

using wavebench::testing::run_cli;

class FleetCli : public ::testing::Test {
 protected:
  void SetUp() override {
    server_ = std::make_unique<testing::PostgresServer>();
    server_->create_database("wavebench");
    dir_ = testing::fresh_dir(::testing::UnitTest::GetInstance()->current_test_info()->name());
    const auto c = server_->config("wavebench");
    results_ = dir_ / "results.yaml";
    std::ofstream(results_) << "results:\n  store: postgresql\n  url: '" << c.url
                            << "'\n  password_file: " << c.password_file.string() << "\n";
    storage::RunStore local(dir_ / "runs", "test");
    PostgresResultsStore store(c);
    for (double p2p : {0.70, 0.74, 0.72}) {
      testing::SyntheticRun r;
      r.p2p_forward_arcmin = p2p;
      const auto id = testing::add_synthetic_run(local, r);
      store.publish(
          summarise_run(*local.find_run(id), testing::synthetic_results(id, r), {"bench-c", ""}));
    }
  }
  std::string fleet(const std::string& args) const {
    return "fleet " + args + " --results '" + results_.string() + "'";
  }
  std::unique_ptr<testing::PostgresServer> server_;
  std::filesystem::path dir_, results_;
};

TEST_F(FleetCli, SpcAsJsonAndTables) {
  const auto spc = run_cli(
      fleet("spc --figure static_te_p2p --model CSF-25-100-2A-GR --direction forward --load 0 "
            "--json"),
      dir_ / "spc.txt");
  ASSERT_EQ(spc.exit_code, 0) << spc.output;
  const auto j = nlohmann::json::parse(spc.output);
  EXPECT_EQ(j["spc"]["n"], 3);
  EXPECT_NEAR(j["spc"]["mean"].get<double>(), 0.72, 1e-12);
  EXPECT_NEAR(j["spc"]["mr_bar"].get<double>(), 0.03, 1e-12);
  EXPECT_DOUBLE_EQ(j["limits"]["upper"].get<double>(), 1.0);

  const auto png = dir_ / "spc.png";
  const auto table = run_cli(fleet("spc --figure static_te_p2p --model CSF-25-100-2A-GR --usl 0.9 "
                                   "--png '" +
                                   png.string() + "'"),
                             dir_ / "table.txt");
  ASSERT_EQ(table.exit_code, 0) << table.output;
  EXPECT_NE(table.output.find("limits from command line"), std::string::npos) << table.output;
  EXPECT_NE(table.output.find("Cpk"), std::string::npos) << table.output;
  std::ifstream chart(png, std::ios::binary);
  std::string magic(8, '\0');
  chart.read(magic.data(), 8);
  EXPECT_EQ(magic, std::string("\x89PNG\r\n\x1a\n", 8));

  const auto runs = run_cli(fleet("runs --bench bench-c"), dir_ / "runs.txt");
  ASSERT_EQ(runs.exit_code, 0) << runs.output;
  EXPECT_NE(runs.output.find("bench-c"), std::string::npos) << runs.output;
  EXPECT_NE(runs.output.find("static_te_p2p=0.79"), std::string::npos) << runs.output;

  const auto trend = run_cli(fleet("trend --figure static_te_p2p --model CSF-25-100-2A-GR --json"),
                             dir_ / "trend.txt");
  ASSERT_EQ(trend.exit_code, 0) << trend.output;
  EXPECT_EQ(nlohmann::json::parse(trend.output)["points"].size(), 3u);
}

TEST_F(FleetCli, BadArgumentsExitTwoNamingThem) {
  const auto figure =
      run_cli(fleet("trend --figure nonsense --model CSF-25-100-2A-GR"), dir_ / "figure.txt");
  EXPECT_EQ(figure.exit_code, 2) << figure.output;
  EXPECT_NE(figure.output.find("nonsense"), std::string::npos) << figure.output;

  const auto load = run_cli(
      fleet("trend --figure static_te_p2p --model CSF-25-100-2A-GR --load heavy"), dir_ / "l.txt");
  EXPECT_EQ(load.exit_code, 2) << load.output;
  EXPECT_NE(load.output.find("--load"), std::string::npos) << load.output;

  const auto with_password = dir_ / "with-password.yaml";
  std::ofstream(with_password)
      << "results: {store: postgresql, url: 'postgresql://w:topsecret@db/w'}\n";
  const auto refused =
      run_cli("fleet runs --results '" + with_password.string() + "'", dir_ / "pw.txt");
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("results.url"), std::string::npos) << refused.output;
  EXPECT_EQ(refused.output.find("topsecret"), std::string::npos) << refused.output;
}

TEST_F(FleetCli, ServerAwayExitsOne) {
  server_->stop();
  const auto away = run_cli(fleet("runs"), dir_ / "away.txt");
  EXPECT_EQ(away.exit_code, 1) << away.output;
  EXPECT_NE(away.output.find("cannot connect"), std::string::npos) << away.output;
}

}  // namespace
}  // namespace wavebench::fleet
