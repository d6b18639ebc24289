// The ResultsStore contract on the shared PostgreSQL store (label postgres): a server of its
// own per test.
#include "postgres_server.hpp"
#include "results_store_contract.hpp"
#include "wavebench/fleet/postgres_results_store.hpp"

namespace wavebench::fleet::testing {
namespace {

struct PostgresMaker {
  PostgresMaker() { server.create_database("wavebench"); }
  std::unique_ptr<ResultsStore> make() const {
    return std::make_unique<PostgresResultsStore>(server.config("wavebench", "bench-a"));
  }
  PostgresServer server;
};

using Postgres = ::testing::Types<PostgresMaker>;
INSTANTIATE_TYPED_TEST_SUITE_P(Postgres, ResultsStoreContract, Postgres);

}  // namespace
}  // namespace wavebench::fleet::testing
