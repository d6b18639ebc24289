// `wavebench sim CASE --out DIR` (issue #8): DIR is written only when it is new, empty or an
// earlier sim's output; the user's files stay byte-identical; a signal leaves no temp folder.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <functional>
#include <iostream>
#include <map>
#include <thread>
#include <vector>

#include "hostile_cli.hpp"

namespace wavebench::hostile {
namespace {

const fs::path kSource = WAVEBENCH_SOURCE_DIR;

// A case that runs in well under a second.
const char* kQuickCase = R"(name: quick
gear: {z_flex: 200, z_circ: 202, inertia_input: "3e-4 kg*m^2", inertia_output: "0.05 kg*m^2"}
te:
  terms:
    - {source: a, family: custom, order_input: 0, order_output: 1, amplitude: "1 arcmin"}
stiffness: {form: linear_periodic, k0: "3e4 N*m/rad"}
input: {type: kinematic, speed: "100 rpm"}
solver: {t_end: 0.2, sample_rate: "1 kHz"}
)";

// Hidden siblings of `out` the sim may leave: ".out.tmp-PID", ".out.old-PID".
std::vector<std::string> leftovers(const fs::path& out) {
  std::vector<std::string> found;
  for (const auto& e : fs::directory_iterator(out.parent_path())) {
    const std::string name = e.path().filename().string();
    if (name.rfind("." + out.filename().string() + ".", 0) == 0) found.push_back(name);
  }
  return found;
}

class SimOut : public ::testing::Test {
 protected:
  SimOut() : box_("simout") {
    write_file(box_.in("quick.yaml"), kQuickCase);
    fs::create_directories(box_.root() / "work");
  }
  CliResult sim(const fs::path& out) {
    return run_wavebench(
        "sim " + quoted(box_.in("quick.yaml")) + " --out " + quoted(out) + " --quiet",
        box_.log("sim"));
  }
  fs::path work(const std::string& name) const { return box_.root() / "work" / name; }
  Sandbox box_;
};

TEST_F(SimOut, RefusesOccupiedTargetsAndLeavesThemByteIdentical) {
  struct Target {
    std::string label;
    std::function<void(const fs::path&)> make;
  };
  const std::vector<Target> targets = {
      {"a plain file", [](const fs::path& p) { write_file(p, "precious\n"); }},
      {"a folder with a user file",
       [](const fs::path& p) {
         fs::create_directories(p);
         write_file(p / "thesis.tex", "chapter 1\n");
       }},
      {"a folder with a user folder",
       [](const fs::path& p) {
         fs::create_directories(p / "photos");
         write_file(p / "photos" / "a.jpg", "jpeg");
       }},
      {"a folder holding only a file named like an output",
       [](const fs::path& p) {
         fs::create_directories(p);
         write_file(p / "summary.json", "{\"mine\": true}\n");
       }},
      {"an earlier output plus a user file",
       [](const fs::path& p) {
         fs::create_directories(p);
         write_file(p / ".wavebench-sim", "{\"written_by\": \"wavebench sim\", \"format\": 1}\n");
         write_file(p / "summary.json", "{}\n");
         write_file(p / "notes.txt", "mine\n");
       }},
      {"a forged marker and a user folder",
       [](const fs::path& p) {
         fs::create_directories(p / "data");
         write_file(p / ".wavebench-sim", "{\"written_by\": \"wavebench sim\"}\n");
       }},
      {"a symbolic link to a folder",
       [this](const fs::path& p) {
         fs::create_directories(work("elsewhere"));
         write_file(work("elsewhere") / "keep.txt", "keep\n");
         fs::create_directory_symlink(work("elsewhere"), p);
       }},
  };
  int tried = 0, refused = 0;
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const fs::path out = work("target" + std::to_string(i));
    targets[i].make(out);
    const auto before = listing(box_.root() / "work");
    std::map<std::string, std::string> contents;
    for (const auto& e : fs::recursive_directory_iterator(box_.root() / "work")) {
      if (e.is_regular_file()) contents[e.path().string()] = read_file(e.path());
    }
    ++tried;
    const CliResult r = sim(out);
    SCOPED_TRACE(targets[i].label + ": " + r.output);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.output.find("--out"), std::string::npos);
    EXPECT_EQ(listing(box_.root() / "work"), before);
    for (const auto& [path, text] : contents) EXPECT_EQ(read_file(path), text) << path;
    EXPECT_TRUE(leftovers(out).empty());
    if (r.exit_code == 2 && listing(box_.root() / "work") == before) ++refused;
  }
  std::cout << "[hostile] occupied --out targets: tried " << tried << ", refused " << refused
            << "\n";
  EXPECT_EQ(refused, tried);
}

TEST_F(SimOut, WritesIntoNewOrEmptyFoldersAndReplacesOnlyItsOwnOutput) {
  const fs::path fresh = work("fresh");
  ASSERT_EQ(sim(fresh).exit_code, 0);
  EXPECT_TRUE(fs::exists(fresh / "summary.json"));
  EXPECT_TRUE(fs::exists(fresh / ".wavebench-sim"));

  const fs::path empty = work("empty");
  fs::create_directories(empty);
  ASSERT_EQ(sim(empty).exit_code, 0);
  EXPECT_TRUE(fs::exists(empty / "timeseries.csv"));

  // Its own earlier output is replaced ...
  write_file(fresh / "summary.json", "stale");
  ASSERT_EQ(sim(fresh).exit_code, 0);
  EXPECT_NE(read_file(fresh / "summary.json"), "stale");
  EXPECT_TRUE(leftovers(fresh).empty());
  // ... but not once the user put something of theirs into it.
  write_file(fresh / "my-notes.txt", "keep me\n");
  EXPECT_EQ(sim(fresh).exit_code, 2);
  EXPECT_EQ(read_file(fresh / "my-notes.txt"), "keep me\n");
}

// Starts the sim, waits until `ready` says the moment has come, sends SIGTERM, and returns the
// wait status.
int sim_killed_when(const fs::path& config, const fs::path& out,
                    const std::function<bool()>& ready) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    if (!std::freopen("/dev/null", "w", stdout) || !std::freopen("/dev/null", "w", stderr)) {
      ::_exit(126);
    }
    ::execl(WAVEBENCH_CLI, WAVEBENCH_CLI, "sim", config.c_str(), "--out", out.c_str(), "--quiet",
            static_cast<char*>(nullptr));
    ::_exit(127);
  }
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  int status = 0;
  while (std::chrono::steady_clock::now() < give_up) {
    if (::waitpid(pid, &status, WNOHANG) == pid) return status;  // finished before the moment
    if (ready()) break;
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  ::kill(pid, SIGTERM);
  ::waitpid(pid, &status, 0);
  return status;
}

TEST_F(SimOut, SigtermWhileWritingLeavesNoTempFolder) {
  // The XB-80 reference case for 1 s at 60 kHz: enough output that the write takes a while.
  const fs::path config = kSource / "configs/twin/xb-80-134h.yaml";
  const fs::path config_copy = box_.in("xb.yaml");
  write_file(config_copy, read_file(config));
  int killed_mid_write = 0;
  for (int attempt = 0; attempt < 3; ++attempt) {
    const fs::path out = work("killed" + std::to_string(attempt));
    bool saw_temp = false;
    const int status = sim_killed_when(config_copy, out, [&] {
      saw_temp = !leftovers(out).empty();
      return saw_temp;
    });
    SCOPED_TRACE("attempt " + std::to_string(attempt));
    if (saw_temp) {
      ++killed_mid_write;
      EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM) << status;
      EXPECT_FALSE(fs::exists(out));
    }
    EXPECT_TRUE(leftovers(out).empty()) << "temp folder left: " << leftovers(out).front();
  }
  std::cout << "[hostile] SIGTERM mid-write: " << killed_mid_write << " of 3 attempts caught "
            << "the sim with its temp folder open\n";
  EXPECT_GE(killed_mid_write, 1);
}

TEST_F(SimOut, SigtermWhileSimulatingLeavesNothing) {
  const fs::path config = box_.in("xb.yaml");
  write_file(config, read_file(kSource / "configs/twin/xb-80-134h.yaml"));
  const fs::path out = work("killed-early");
  const auto start = std::chrono::steady_clock::now();
  const int status = sim_killed_when(config, out, [&] {
    return std::chrono::steady_clock::now() - start > std::chrono::milliseconds(300);
  });
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM) << status;
  EXPECT_FALSE(fs::exists(out));
  EXPECT_TRUE(leftovers(out).empty());
}

}  // namespace
}  // namespace wavebench::hostile
