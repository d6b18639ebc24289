#pragma once
// A fresh directory under the build tree per test.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

namespace wavebench::daemon::testing {

inline std::filesystem::path fresh_test_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  auto dir = std::filesystem::path(WAVEBENCH_BINARY_DIR) / "test-tmp" / "daemon" /
             (std::string(info->test_suite_name()) + "." + info->name() + "." +
              std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace wavebench::daemon::testing
