#pragma once
// Shared by the hostile config suites: a sandbox folder, the `wavebench` binary run with a time
// limit, and the check that a refusal named its key and wrote nothing.
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

namespace wavebench::hostile {

namespace fs = std::filesystem;

struct CliResult {
  int exit_code = -1;
  std::string output;
};

inline std::string quoted(const fs::path& p) {
  return "'" + p.string() + "'";
}

inline void write_file(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
}

inline std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Every path under `dir` with its size: "nothing written" means this does not change.
inline std::set<std::string> listing(const fs::path& dir) {
  std::set<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    std::string line = fs::relative(e.path(), dir).string();
    if (e.is_regular_file()) line += " " + std::to_string(e.file_size());
    out.insert(line);
  }
  return out;
}

// A hang is a finding too: every run gets 120 s.
inline CliResult run_wavebench(const std::string& args, const fs::path& log) {
  const std::string cmd = "timeout 120 '" + std::string(WAVEBENCH_CLI) + "' " + args + " > " +
                          quoted(log) + " 2>&1 < /dev/null";
  const int status = std::system(cmd.c_str());
  CliResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.output = read_file(log);
  return r;
}

class Sandbox {
 public:
  explicit Sandbox(const std::string& name)
      : root_(fs::temp_directory_path() /
              ("wavebench-hostile-" + name + "-" + std::to_string(::getpid()))) {
    fs::remove_all(root_);
    fs::create_directories(root_ / "in");
    fs::create_directories(root_ / "logs");
  }
  ~Sandbox() {
    std::error_code ec;
    fs::remove_all(root_, ec);
  }
  const fs::path& root() const { return root_; }
  fs::path in(const std::string& name) const { return root_ / "in" / name; }
  fs::path log(const std::string& name) const { return root_ / "logs" / (name + ".log"); }

 private:
  fs::path root_;
};

}  // namespace wavebench::hostile
