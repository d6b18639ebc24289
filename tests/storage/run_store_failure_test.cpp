// RunStore on a disk that fills up: a create_run that fails part-way leaves no folder, no temp
// file and no index row (issue #8: each start refused on a full disk left an orphan folder).
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "file_size_limit.hpp"
#include "test_dir.hpp"
#include "wavebench/storage/run_store.hpp"

namespace wavebench::storage {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> entries(const fs::path& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) out.push_back(e.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}

TEST(RunStoreOnAFullDisk, ACreateRunThatCannotWriteLeavesNoFolderAndNoRow) {
  const auto root = testing::fresh_test_dir();
  RunStore store(root, "test");
  const auto before = entries(root);
  const std::string config(256 * 1024, '#');  // larger than any file may grow below
  int refused = 0;
  {
    wavebench::testing::FileSizeLimit limit(128 * 1024);
    for (int i = 0; i < 5; ++i) {
      try {
        store.create_run("static", "SN-1", config);
        ADD_FAILURE() << "create_run " << i << " did not fail";
      } catch (const std::system_error& e) {
        EXPECT_EQ(e.code().value(), EFBIG) << e.what();
        ++refused;
      }
    }
  }
  EXPECT_EQ(refused, 5);
  EXPECT_EQ(entries(root), before);  // no run folder, no temp file
  EXPECT_TRUE(store.list_runs().empty());
  // The store still works once there is room.
  const auto id = store.create_run("static", "SN-1", "name: sim\n");
  EXPECT_TRUE(fs::exists(store.paths(id).config));
  EXPECT_EQ(store.list_runs().size(), 1u);
}

}  // namespace
}  // namespace wavebench::storage
