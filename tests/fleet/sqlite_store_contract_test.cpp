// The ResultsStore contract on a lone bench's SQLite store (label unit).
#include "results_store_contract.hpp"
#include "wavebench/fleet/sqlite_results_store.hpp"

namespace wavebench::fleet::testing {
namespace {

struct SqliteMaker {
  std::filesystem::path file = fresh_dir("SqliteContractStore") / "index.sqlite";
  std::unique_ptr<ResultsStore> make() const { return std::make_unique<SqliteResultsStore>(file); }
};

using Sqlite = ::testing::Types<SqliteMaker>;
INSTANTIATE_TYPED_TEST_SUITE_P(Sqlite, ResultsStoreContract, Sqlite);

}  // namespace
}  // namespace wavebench::fleet::testing
