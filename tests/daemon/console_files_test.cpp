// The console's files as the daemon serves them: only files inside the web root, of the known
// content types, with names a console uses; everything else 404 without touching the disk
// outside the root.
#include "wavebench/daemon/console_files.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace wavebench::daemon {
namespace {

namespace fs = std::filesystem;

class ConsoleFilesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    base_ =
        fs::temp_directory_path() /
        ("wavebench-console-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
         "-" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(base_);
    fs::create_directories(base_ / "web" / "js");
    fs::create_directories(base_ / "web" / ".hidden");
    write(base_ / "web" / "index.html", "<!doctype html>index");
    write(base_ / "web" / "history.html", "<!doctype html>history");
    write(base_ / "web" / "js" / "api.js", "export {}");
    write(base_ / "web" / ".hidden" / "x.js", "secret");
    write(base_ / "web" / "notes.txt", "not a console type");
    write(base_ / "secret.html", "outside the root");
    fs::create_symlink(base_ / "secret.html", base_ / "web" / "escape.html");
  }
  void TearDown() override { fs::remove_all(base_); }
  static void write(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }
  static HttpTarget target(const std::string& t) { return parse_http_target(t); }

  fs::path base_;
};

TEST_F(ConsoleFilesTest, ServesPagesScriptsAndTheIndexWithTheirTypes) {
  const ConsoleFiles files(base_ / "web");
  auto r = files.answer(target("/"));
  ASSERT_EQ(r.status, 200);
  EXPECT_EQ(*r.raw_body, "<!doctype html>index");
  EXPECT_EQ(r.content_type, "text/html; charset=utf-8");
  r = files.answer(target("/history"));
  ASSERT_EQ(r.status, 200);
  EXPECT_EQ(*r.raw_body, "<!doctype html>history");
  r = files.answer(target("/js/api.js?v=2"));
  ASSERT_EQ(r.status, 200);
  EXPECT_EQ(r.content_type, "text/javascript; charset=utf-8");
  bool csp = false;
  for (const auto& [name, value] : r.headers) {
    csp = csp || (name == "Content-Security-Policy" &&
                  value.find("frame-ancestors 'none'") != std::string::npos);
  }
  EXPECT_TRUE(csp) << "pages must not be framed by another site";
}

TEST_F(ConsoleFilesTest, RefusesEverythingOutsideTheRootOrItsTypes) {
  const ConsoleFiles files(base_ / "web");
  for (const char* path : {"/../secret.html", "/%2e%2e/secret.html", "/js/../../secret.html",
                           "/escape.html", "/.hidden/x.js", "/notes.txt", "/missing.html", "/js",
                           "/index.html%00.js", "/a/b/c/d/e/f/g/h/i/j.html", "/ind ex.html"}) {
    const auto r = files.answer(target(path));
    EXPECT_EQ(r.status, 404) << path;
    EXPECT_FALSE(r.raw_body.has_value()) << path;
  }
}

TEST_F(ConsoleFilesTest, WithoutARootEveryPageSaysThereIsNoConsole) {
  const ConsoleFiles none;
  EXPECT_FALSE(none.enabled());
  const auto r = none.answer(target("/"));
  EXPECT_EQ(r.status, 404);
  EXPECT_NE(r.body["detail"].get<std::string>().find("no console"), std::string::npos);
  EXPECT_FALSE(ConsoleFiles(base_ / "does-not-exist").enabled());
}

TEST_F(ConsoleFilesTest, RefusesFilesOverTheSizeBound) {
  std::ofstream(base_ / "web" / "huge.js") << std::string(ConsoleFiles::kMaxFileBytes + 1, 'x');
  const ConsoleFiles files(base_ / "web");
  EXPECT_EQ(files.answer(target("/huge.js")).status, 404);
}

}  // namespace
}  // namespace wavebench::daemon
