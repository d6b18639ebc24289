// Hostile and careless config files (issue #8) through the five loaders, as a user meets them:
// the `wavebench` CLI. Every attempt must exit 2 with a message naming the file and the key,
// and write nothing.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <functional>
#include <iostream>
#include <vector>

#include "hostile_cli.hpp"

namespace wavebench::hostile {
namespace {

struct Loader {
  std::string name;
  // The command line with {f} for the config and {out} for a folder that must not appear.
  std::string command;
};

const std::vector<Loader>& loaders() {
  static const std::vector<Loader> all = {
      {"twin", "sim {f} --out {out} --quiet"},
      {"bench", "run static --bench {f} --out {out} --quiet"},
      {"procedure-options", "run static --bench sim --options {f} --out {out} --quiet"},
      {"brake", "brake status --config {f} --modbus tcp:127.0.0.1:9"},
      {"simbench", "simbench --config {f} --can wavebench-none0"},
  };
  return all;
}

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size())) {
    s.replace(at, from.size(), to);
  }
  return s;
}

// A text no loader accepts, and the key its refusal must name.
struct HostileText {
  std::string label;
  std::string text;
  std::string key;
};

std::vector<HostileText> hostile_texts() {
  std::string deep = "outer: ";
  for (int i = 0; i < 100; ++i) deep += "[";
  for (int i = 0; i < 100; ++i) deep += "]";
  std::string deeper = "outer: ";
  for (int i = 0; i < 5000; ++i) deeper += "[";
  for (int i = 0; i < 5000; ++i) deeper += "]";
  std::string bomb = "a0: &a0 [x, x, x, x, x, x, x, x, x, x]\n";
  for (int i = 1; i < 9; ++i) {
    const std::string p = "*a" + std::to_string(i - 1);
    bomb += "a" + std::to_string(i) + ": &a" + std::to_string(i) + " [" + p + ", " + p + ", " + p +
            ", " + p + ", " + p + ", " + p + ", " + p + ", " + p + ", " + p + ", " + p + "]\n";
  }
  std::string huge = "outer: 1\n";
  while (huge.size() <= (1u << 20)) huge += "# padding padding padding padding padding padding\n";
  return {
      {"empty", "", "(document)"},
      {"whitespace only", "  \n\t\n   \n", "(document)"},
      {"comments only", "# nothing here\n# nor here\n", "(document)"},
      {"a null document", "~\n", "(document)"},
      {"over 1 MiB", huge, "(file)"},
      {"non-UTF-8 value", "outer:\n  inner: \"ab\xff\xfe\"\n", "outer.inner"},
      {"overlong UTF-8", "outer: \"\xC0\xAF\"\n", "outer"},
      {"UTF-8 surrogate", "outer: \"\xED\xA0\x80\"\n", "outer"},
      {"NUL byte", std::string("outer: a\0b\n", 11), "outer"},
      {"UTF-16 text",
       std::string("\xFF\xFEo\0u\0t\0:\0 \0"
                   "1\0\n\0",
                   18),
       "(document)"},
      {"duplicate top-level key", "outer: 1\nouter: 2\n", "outer"},
      {"duplicate nested key", "outer:\n  inner: 1\n  inner: 2\n", "outer.inner"},
      {"duplicate key in a list item", "outer:\n  - {x: 1, x: 2}\n", "outer[0].x"},
      {"nested 100 deep", deep, "outer[0]"},
      {"nested 5000 deep", deeper, "(document)"},
      {"two documents", "outer: 1\n---\nouter: 2\n", "(document)"},
      {"alias bomb", bomb, "nodes"},
      {"a list as a key", "? [a, b]\n: 1\n", "(document)"},
      {"broken YAML", "outer: [1, 2\n", "(document)"},
      // yaml-cpp 0.7 loops forever on these (found by fuzz_procedure_options).
      {"a ',' starting the document", ",'", "(document)"},
      {"a ',' starting a later line", "outer:\n  a: 1\n ,  b: 2\n", "(document)"},
  };
}

void expect_refused(const Loader& loader, const std::string& label, const fs::path& file,
                    const std::string& key, const Sandbox& box, int& refused) {
  const fs::path out = box.root() / "out";
  const auto before = listing(box.root() / "in");
  std::string cmd = replace_all(loader.command, "{f}", quoted(file));
  cmd = replace_all(cmd, "{out}", quoted(out));
  const CliResult r = run_wavebench(cmd, box.log("last"));
  SCOPED_TRACE(loader.name + " / " + label + ": " + r.output);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find(file.string()), std::string::npos) << "message names the file";
  EXPECT_NE(r.output.find(key), std::string::npos) << "message names " << key;
  EXPECT_NE(r.output.find("expected"), std::string::npos);
  EXPECT_EQ(r.output.find("bad_alloc"), std::string::npos);
  EXPECT_FALSE(fs::exists(out)) << "nothing written";
  EXPECT_EQ(listing(box.root() / "in"), before) << "nothing changed beside the config";
  if (r.exit_code == 2 && r.output.find(key) != std::string::npos && !fs::exists(out)) ++refused;
}

TEST(HostileConfig, EveryLoaderRefusesHostileTextsWithExit2AndTheKey) {
  Sandbox box("texts");
  int tried = 0, refused = 0;
  for (const auto& loader : loaders()) {
    for (const auto& h : hostile_texts()) {
      const fs::path file = box.in(loader.name + ".yaml");
      write_file(file, h.text);
      ++tried;
      expect_refused(loader, h.label, file, h.key, box, refused);
      fs::remove(file);
    }
  }
  std::cout << "[hostile] config texts: tried " << tried << " (" << hostile_texts().size()
            << " texts x " << loaders().size() << " loaders), refused " << refused << "\n";
  EXPECT_EQ(refused, tried);
  EXPECT_EQ(tried, 105);
}

TEST(HostileConfig, EveryLoaderRefusesWhatIsNotARegularFile) {
  Sandbox box("files");
  fs::create_directories(box.in("a-folder.yaml"));
  ASSERT_EQ(::mkfifo(box.in("a-fifo.yaml").c_str(), 0600), 0);
  const std::vector<std::pair<std::string, fs::path>> files = {
      {"a folder", box.in("a-folder.yaml")},
      {"a FIFO", box.in("a-fifo.yaml")},
      {"a character device", "/dev/zero"},
      {"a missing file", box.in("missing.yaml")},
  };
  int tried = 0, refused = 0;
  for (const auto& loader : loaders()) {
    for (const auto& [label, file] : files) {
      ++tried;
      expect_refused(loader, label, file, "(file)", box, refused);
    }
  }
  std::cout << "[hostile] non-files: tried " << tried << ", refused " << refused << "\n";
  EXPECT_EQ(refused, tried);
}

}  // namespace
}  // namespace wavebench::hostile
