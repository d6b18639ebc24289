// libFuzzer target: bytes off the socket -> Beast's request parser (with the server's limits)
// -> the daemon's API handler -> the answer serialised, as the server does it. The API runs on
// a stand-in bench (tests/daemon/fake_bench.hpp) and a run store in a temp folder; starts are
// checked by the real run-request check against a simulated bench description and never
// launched. Anything escaping (an exception, a crash, a sanitizer report) is a finding.
#include <unistd.h>

#include <boost/asio/buffer.hpp>
#include <boost/beast/http/parser.hpp>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>

#include "fake_bench.hpp"
#include "wavebench/bench/bench_config.hpp"
#include "wavebench/daemon/api_request_from_http.hpp"
#include "wavebench/daemon/bench_thread.hpp"
#include "wavebench/daemon/daemon_api.hpp"
#include "wavebench/daemon/http_server.hpp"
#include "wavebench/procedures/run_request_check.hpp"

namespace {

using namespace wavebench;
namespace http = boost::beast::http;

constexpr const char* kToken = "fuzz-token-0123456789abcdef";

// Checks like the real launcher; launching is refused, so no input moves the stand-in bench.
class CheckOnlyLauncher : public daemon::RunLauncher {
 public:
  procedures::RunOutcome launch(bench::Bench&, storage::RunStore&, const procedures::RunRequest&,
                          const procedures::ProgressSink&) override {
    throw std::invalid_argument("fuzz: runs are checked, never launched");
  }
  void check(const procedures::RunRequest& request, const bench::BenchDescription& /*fake*/,
             std::size_t extra_channels, const std::filesystem::path& runs_root) const override {
    procedures::check_run_request(request, simulated_, extra_channels, runs_root);
  }

 private:
  bench::BenchDescription simulated_ = bench::default_simulated_bench_config().description;
};

struct Api {
  Api()
      : dir(std::filesystem::temp_directory_path() /
            ("wavebench-fuzz-http-" + std::to_string(::getpid()))),
        store(dir / "runs", "fuzz"),
        live(256),
        bench_thread([] { return std::make_unique<daemon::testing::FakeBench>(); }, store, launcher,
                     "name: fuzz\n", live),
        api(bench_thread, store, live, kToken) {
    bench_thread.start();
  }
  std::filesystem::path dir;
  storage::RunStore store;
  daemon::LiveSampleBuffer live;
  CheckOnlyLauncher launcher;
  daemon::BenchThread bench_thread;
  daemon::DaemonApi api;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static Api* world = new Api();  // lives for the process: the bench thread keeps running
  http::request_parser<http::string_body> parser;
  parser.header_limit(daemon::kRequestHeaderLimit);
  parser.body_limit(daemon::kRequestBodyLimit);
  parser.eager(true);
  boost::beast::error_code ec;
  parser.put(boost::asio::buffer(data, size), ec);
  if (!ec && !parser.is_done()) parser.put_eof(ec);
  daemon::ApiResponse response;
  if (ec || !parser.is_done()) {
    response = daemon::parse_error_answer(ec);
  } else {
    response = world->api.handle(daemon::api_request_from_http(parser.get()));
  }
  const auto text = daemon::response_text(response);
  if (text.empty() || response.status < 100 || response.status > 599) __builtin_trap();
  return 0;
}
