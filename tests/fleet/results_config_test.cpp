// The `results:` config: what it accepts, and refusals that name the key, the value and what
// was expected (never the password).
#include "wavebench/fleet/results_config.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <fstream>

#include "synthetic_runs.hpp"
#include "wavebench/strict_yaml/strict_yaml.hpp"

namespace wavebench::fleet {
namespace {

std::string refusal(const std::string& yaml) {
  try {
    parse_results_config(yaml, "results.yaml");
  } catch (const strict_yaml::RefusedConfig& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(ResultsConfig, PostgresqlWithEverything) {
  const auto c = parse_results_config(
      "results:\n  store: postgresql\n  url: postgresql://wavebench@db.lab/wavebench\n"
      "  password_file: /etc/wavebench/results.password\n  bench: bench-7\n  station: line-2\n"
      "  retry_max: 30 s\n",
      "/etc/wavebench/results.yaml");
  EXPECT_TRUE(c.shared());
  EXPECT_EQ(c.url, "postgresql://wavebench@db.lab/wavebench");
  EXPECT_EQ(c.password_file, "/etc/wavebench/results.password");
  EXPECT_EQ(c.bench, "bench-7");
  EXPECT_EQ(c.station, "line-2");
  EXPECT_DOUBLE_EQ(c.retry_max_s, 30);
}

TEST(ResultsConfig, ShippedExampleLoads) {
  const auto c = load_results_config(std::string(WAVEBENCH_SOURCE_DIR) +
                                     "/configs/daemon/results-postgresql.yaml");
  EXPECT_TRUE(c.shared());
  EXPECT_EQ(c.bench, "bench-1");
  EXPECT_DOUBLE_EQ(c.retry_max_s, 60);
}

TEST(ResultsConfig, SqliteIsTheBenchAlone) {
  const auto c = parse_results_config("results: {store: sqlite}\n", "results.yaml");
  EXPECT_FALSE(c.shared());
}

TEST(ResultsConfig, RelativePasswordFileIsBesideTheConfig) {
  const auto c = parse_results_config(
      "results: {store: postgresql, url: 'host=db dbname=w', password_file: pw}\n",
      "/etc/wavebench/results.yaml");
  EXPECT_EQ(c.password_file, "/etc/wavebench/pw");
}

TEST(ResultsConfig, RefusalsNameKeyValueAndExpected) {
  const auto store = refusal("results: {store: mysql}\n");
  EXPECT_NE(store.find("results.store"), std::string::npos) << store;
  EXPECT_NE(store.find("mysql"), std::string::npos) << store;
  EXPECT_NE(store.find("postgresql"), std::string::npos) << store;

  const auto typo = refusal("results: {store: postgresql, url: 'host=db', pasword_file: x}\n");
  EXPECT_NE(typo.find("pasword_file"), std::string::npos) << typo;

  const auto no_url = refusal("results: {store: postgresql}\n");
  EXPECT_NE(no_url.find("results.url"), std::string::npos) << no_url;

  const auto bad_url = refusal("results: {store: postgresql, url: 'host=db nonsense'}\n");
  EXPECT_NE(bad_url.find("results.url"), std::string::npos) << bad_url;

  const auto bench = refusal("results: {store: postgresql, url: 'host=db', bench: 'a b'}\n");
  EXPECT_NE(bench.find("results.bench"), std::string::npos) << bench;
  EXPECT_NE(bench.find("'a b'"), std::string::npos) << bench;

  const auto retry = refusal("results: {store: sqlite, retry_max: 2 h}\n");
  EXPECT_NE(retry.find("results.retry_max"), std::string::npos) << retry;
}

TEST(ResultsConfig, PasswordInTheUrlIsRefusedWithoutShowingIt) {
  for (const auto* url : {"postgresql://wavebench:hunter2secret@db/wavebench",
                          "host=db password=hunter2secret dbname=w"}) {
    const auto message = refusal(std::string("results: {store: postgresql, url: '") + url + "'}\n");
    EXPECT_NE(message.find("results.url"), std::string::npos) << message;
    EXPECT_NE(message.find("password_file"), std::string::npos) << message;
    EXPECT_EQ(message.find("hunter2secret"), std::string::npos) << message;
  }
}

TEST(ResultsConfig, PasswordFileMustBeTheOwnersAlone) {
  const auto dir = testing::fresh_dir("PasswordFile");
  const auto file = dir / "pw";
  std::ofstream(file) << "s3cret\n";
  ::chmod(file.c_str(), 0600);
  EXPECT_EQ(read_password_file(file), "s3cret");
  ::chmod(file.c_str(), 0644);
  try {
    read_password_file(file);
    FAIL() << "a world-readable password file was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("results.password_file"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("0644"), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find("s3cret"), std::string::npos);
  }
  EXPECT_THROW(read_password_file(dir / "missing"), std::runtime_error);
}

}  // namespace
}  // namespace wavebench::fleet
