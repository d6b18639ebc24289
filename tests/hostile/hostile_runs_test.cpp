// Hostile and careless run requests (issue #8): over-limit loads and speeds, overlong lists,
// runs too long or too big for the disk are refused before anything is created or moves,
// with a message naming the key, the value and what was expected; in process (execute_run)
// and from the CLI (`wavebench run`, exit 2). The counts of what was tried are printed.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "cli_run.hpp"
#include "wavebench/bench/bench_config.hpp"
#include "wavebench/bench/bench_factory.hpp"
#include "wavebench/procedures/run_executor.hpp"
#include "wavebench/procedures/run_request_check.hpp"
#include "wavebench/storage/run_store.hpp"

namespace wavebench::procedures {
namespace {

namespace fs = std::filesystem;

struct HostileStart {
  std::string category;  // "load", "speed", "list length", "duration", "disk"
  std::string procedure;
  nlohmann::json options;
  std::vector<std::string> expected_in_message;  // the key, the value, the expectation
};

// Against the simulated bench (configs/benches/sim.yaml): brake limit 95 N·m (the brake's
// own 100), input speed limit 3000 rpm (314 rad/s), ratio 100, rated 100 N·m, SYNC 1 ms.
std::vector<HostileStart> hostile_starts() {
  std::vector<HostileStart> s;
  s.push_back({"load",
               "static",
               {{"positions", 2}, {"loads_nm", {0, 200}}},
               {"static.loads_nm[1]", "'200'", "at most 95 N*m", "brake limit"}});
  s.push_back({"load", "static", {{"loads_nm", {95.5}}}, {"static.loads_nm[0]", "'95.5'"}});
  s.push_back({"load", "dynamic", {{"load_nm", 120}}, {"dynamic.load_nm", "'120'", "95 N*m"}});
  s.push_back({"load",
               "lost-motion",
               {{"torques_nm", {10, 20, 30, 40, 1000}}},
               {"lost-motion.torques_nm[4]", "'1000'", "95 N*m"}});
  s.push_back({"speed",
               "static",
               {{"move_speed_rad_s", 400}},
               {"static.move_speed_rad_s", "'400'", "at most 314.159 rad/s", "input speed limit"}});
  s.push_back({"speed",
               "static",
               {{"approach_speed_rad_s", 1000}},
               {"static.approach_speed_rad_s", "'1000'"}});
  s.push_back(
      {"speed", "dynamic", {{"input_rpm", 4000}}, {"dynamic.input_rpm", "'4000'", "3000 rpm"}});
  s.push_back({"speed",
               "lost-motion",
               {{"input_speed_rad_s", 2000}},
               {"lost-motion.input_speed_rad_s", "'2000'", "rad/s"}});
  s.push_back({"list length",
               "static",
               {{"loads_nm", std::vector<double>(100000, 10.0)}},
               {"static.loads_nm", "100000 entries", "1 to 64 numbers"}});
  s.push_back({"list length",
               "static",
               {{"loads_nm", std::vector<double>(65, 10.0)}},
               {"static.loads_nm", "65 entries", "64"}});
  s.push_back({"list length",
               "lost-motion",
               {{"torque_fractions", std::vector<double>(1000, 0.1)}},
               {"lost-motion.torque_fractions", "1000 entries", "64"}});
  s.push_back({"list length",
               "lost-motion",
               {{"torques_nm", std::vector<double>(500, 10.0)}},
               {"lost-motion.torques_nm", "500 entries"}});
  s.push_back({"duration",
               "dynamic",
               {{"output_revolutions", 1000}},
               {"dynamic.output_revolutions", "1000", "expected at most 8 h", "duration bound"}});
  s.push_back({"duration",
               "dynamic",
               {{"input_rpm", 0.01}},
               {"dynamic.input_rpm", "0.01", "expected at most 8 h"}});
  s.push_back({"duration",
               "static",
               {{"positions", 3600}, {"window_s", 10}},
               {"static.positions 3600", "expected at most 8 h"}});
  s.push_back({"duration",
               "lost-motion",
               {{"input_speed_rad_s", 0.001}},
               {"lost-motion.input_speed_rad_s", "expected at most 8 h"}});
  return s;
}

// Only the store's own files (index, writer's lock): no run folder, no temp file.
void expect_nothing_created(const fs::path& root, storage::RunStore& store,
                            const std::string& what) {
  for (const auto& e : fs::directory_iterator(root)) {
    const auto name = e.path().filename().string();
    EXPECT_TRUE(name.rfind(storage::kRunIndexFile, 0) == 0 || name == storage::kWriterLockFile)
        << what << ": left " << e.path();
  }
  EXPECT_TRUE(store.list_runs().empty()) << what;
}

class HostileRuns : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("wavebench-hostile-runs-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(HostileRuns, EveryHostileStartIsRefusedInProcessBeforeAnythingIsCreatedOrMoves) {
  const auto config = bench::default_simulated_bench_config();
  // Not connected: a refused start must not need the bench for anything but its description,
  // and a bench that is not connected cannot have moved.
  const auto bench = bench::make_simulated_bench(config);
  const fs::path root = dir_ / "runs";
  storage::RunStore store(root, "test");
  std::map<std::string, int> tried, refused;
  for (const auto& h : hostile_starts()) {
    RunRequest request;
    request.procedure = h.procedure;
    request.options = h.options;
    request.config_text = config.text;
    const std::string what = h.procedure + " " + h.options.dump().substr(0, 80);
    ++tried[h.category];
    try {
      execute_run(*bench, store, request);
      ADD_FAILURE() << what << ": accepted";
    } catch (const std::invalid_argument& e) {
      ++refused[h.category];
      const std::string message = e.what();
      EXPECT_LT(message.size(), 600u) << what << ": " << message.substr(0, 600);
      for (const auto& part : h.expected_in_message) {
        EXPECT_NE(message.find(part), std::string::npos)
            << what << ": '" << part << "' not in: " << message;
      }
    }
    expect_nothing_created(root, store, what);
    EXPECT_EQ(bench->acquisition_stats().samples, 0u) << what;
  }
  for (const auto& [category, n] : tried) {
    std::printf("in process, %-12s %2d hostile starts, %2d refused\n", category.c_str(), n,
                refused[category]);
    EXPECT_EQ(refused[category], n) << category;
  }
}

TEST_F(HostileRuns, AStartTooBigForTheFreeDiskIsRefusedNamingTheEstimateAndTheFreeSpace) {
  const auto description = bench::default_simulated_bench_config().description;
  RunRequest request;
  request.procedure = "static";  // defaults: 24 positions, 0 and 60 N·m, a few minutes
  RunBudget budget;
  budget.runs_root = dir_;
  budget.free_disk_bytes = 8ull << 20;
  try {
    check_run_request(request, description, 0, budget);
    FAIL() << "accepted on 8 MiB free";
  } catch (const std::invalid_argument& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("static: got an estimated"), std::string::npos) << m;
    EXPECT_NE(m.find("expected at most 8 MiB"), std::string::npos) << m;
    EXPECT_NE(m.find(dir_.string()), std::string::npos) << m;
  }
  budget.free_disk_bytes = 10ull << 30;
  const auto e = check_run_request(request, description, 0, budget);
  std::printf("static defaults: estimated %.0f s of bench time, %llu samples, %.1f MiB\n",
              e.bench_time_s, static_cast<unsigned long long>(e.samples),
              static_cast<double>(e.disk_bytes()) / (1 << 20));
  EXPECT_GT(e.samples, 10000u);
  EXPECT_EQ(e.sample_log_bytes, 64 + 8 + 6 * 48 + 8 + e.samples * 96);  // version 2, 6 channels
  // The real free space of a real folder, and of one that does not exist yet.
  EXPECT_GT(run_budget(dir_).free_disk_bytes, 0u);
  // Same file system; other tests write beside this one, so the figure may move a little.
  EXPECT_NEAR(static_cast<double>(run_budget(dir_ / "not" / "yet").free_disk_bytes),
              static_cast<double>(run_budget(dir_).free_disk_bytes), 256.0 * (1 << 20));
}

// A real small file system, where the process may mount one (root, or a user namespace).
class SmallFileSystem {
 public:
  SmallFileSystem(const fs::path& dir, const char* size) : dir_(dir) {
    fs::create_directories(dir_);
    const std::string cmd = "mount -t tmpfs -o size=" + std::string(size) + " tmpfs '" +
                            dir_.string() + "' 2>/dev/null";
    mounted_ = std::system(cmd.c_str()) == 0;
  }
  ~SmallFileSystem() {
    if (mounted_) std::system(("umount '" + dir_.string() + "'").c_str());
  }
  bool mounted() const { return mounted_; }

 private:
  fs::path dir_;
  bool mounted_ = false;
};

TEST_F(HostileRuns, AStartOnAFullFileSystemIsRefusedBeforeAnyFolderExists) {
  SmallFileSystem small(dir_ / "small", "4m");
  if (!small.mounted()) GTEST_SKIP() << "cannot mount a tmpfs here (not root)";
  const auto config = bench::default_simulated_bench_config();
  const auto bench = bench::make_simulated_bench(config);
  const fs::path root = dir_ / "small" / "runs";
  storage::RunStore store(root, "test");
  int tried = 0, refused = 0;
  for (const char* procedure : {"static", "dynamic", "lost-motion"}) {
    RunRequest request;
    request.procedure = procedure;
    request.config_text = config.text;
    ++tried;
    try {
      execute_run(*bench, store, request);
      ADD_FAILURE() << procedure << ": accepted on a 4 MiB file system";
    } catch (const std::invalid_argument& e) {
      ++refused;
      EXPECT_NE(std::string(e.what()).find("free on the file system of the runs folder"),
                std::string::npos)
          << e.what();
    }
    expect_nothing_created(root, store, procedure);
  }
  std::printf("in process, disk         %2d hostile starts, %2d refused\n", tried, refused);
  EXPECT_EQ(refused, tried);
}

struct CliStart {
  std::string category;
  std::string args;
  std::string key;
};

TEST_F(HostileRuns, EveryHostileCliStartExitsTwoAndCreatesNothing) {
  std::string many_loads = "0";
  for (int i = 1; i < 65; ++i) many_loads += "," + std::to_string(i);
  std::string many_fractions = "[0.1";
  for (int i = 1; i < 70; ++i) many_fractions += ",0.1";
  many_fractions += "]";
  const std::vector<CliStart> starts = {
      {"load", "static --positions 2 --loads 0,200", "static.loads_nm[1]"},
      {"load", "dynamic --load 120", "dynamic.load_nm"},
      {"load", "lost-motion --torques 10,20,30,200", "lost-motion.torques_nm[3]"},
      {"speed", "static --option move_speed_rad_s=400", "static.move_speed_rad_s"},
      {"speed", "dynamic --rpm 4000", "dynamic.input_rpm"},
      {"speed", "lost-motion --option input_speed_rad_s=2000", "lost-motion.input_speed_rad_s"},
      {"list length", "static --loads " + many_loads, "static.loads_nm"},
      {"list length", "lost-motion --option 'torque_fractions=" + many_fractions + "'",
       "lost-motion.torque_fractions"},
      {"duration", "dynamic --revolutions 1000", "dynamic.output_revolutions"},
      {"duration", "static --positions 3600 --window 10", "static.positions"},
  };
  std::map<std::string, int> tried, refused;
  for (const auto& s : starts) {
    const fs::path out = dir_ / "runs";
    const auto r = wavebench::testing::run_cli(
        "run " + s.args + " --bench sim --out '" + out.string() + "' --quiet", dir_ / "cli.log");
    ++tried[s.category];
    EXPECT_EQ(r.exit_code, 2) << s.args << "\n" << r.output;
    EXPECT_NE(r.output.find(s.key), std::string::npos) << s.args << "\n" << r.output;
    EXPECT_NE(r.output.find("expected"), std::string::npos) << s.args << "\n" << r.output;
    EXPECT_FALSE(fs::exists(out)) << s.args << ": the runs folder was created";
    if (r.exit_code == 2 && !fs::exists(out)) ++refused[s.category];
  }
  for (const auto& [category, n] : tried) {
    std::printf("CLI,        %-12s %2d hostile starts, %2d refused with exit 2\n", category.c_str(),
                n, refused[category]);
    EXPECT_EQ(refused[category], n) << category;
  }
}

TEST_F(HostileRuns, ACliStartOnAFullFileSystemExitsTwoAndCreatesNothing) {
  // A private mount namespace (as root, or as a user where user namespaces are allowed): the
  // 2 MiB tmpfs exists only for this shell, which lists what the CLI left in it.
  const fs::path mnt = dir_ / "small";
  fs::create_directories(mnt);
  if (std::system("unshare -rm true 2>/dev/null") != 0) {
    GTEST_SKIP() << "no user or mount namespaces here";
  }
  const fs::path script = dir_ / "full-disk.sh";
  {
    std::ofstream out(script);
    out << "mount -t tmpfs -o size=2m tmpfs '" << mnt.string() << "' || exit 99\n"
        << "'" << WAVEBENCH_CLI << "' run static --bench sim --out '" << (mnt / "runs").string()
        << "' --quiet\n"
        << "echo \"exit=$?\"\n"
        << "echo \"left:$(ls -A '" << mnt.string() << "')\"\n";
  }
  const auto log = dir_ / "cli.log";
  std::system(("unshare -rm sh '" + script.string() + "' > '" + log.string() + "' 2>&1").c_str());
  std::ifstream in(log);
  const std::string output((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::printf("CLI,        disk          1 hostile start\n");
  EXPECT_NE(output.find("exit=2"), std::string::npos) << output;
  EXPECT_NE(output.find("left:\n"), std::string::npos) << output;  // nothing in the tmpfs
  EXPECT_NE(output.find("free on the file system of the runs folder"), std::string::npos) << output;
}

}  // namespace
}  // namespace wavebench::procedures
