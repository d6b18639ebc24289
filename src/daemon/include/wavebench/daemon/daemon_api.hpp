#pragma once
// The daemon's HTTP + JSON API as a function from request to response, independent of the
// transport (http_server.hpp carries it over Boost.Beast).
//
//   GET  /api/status                         state, bench, current run, fault, acquisition
//   POST /api/runs      {procedure, options}  start a run                       (token)
//   POST /api/abort                           trip the bench: "operator abort" (token)
//   POST /api/stop                            safe state: "operator stop"      (token)
//   POST /api/reset                           clear a fault / reconnect        (token)
//   GET  /api/runs?procedure=&status=&unit=&limit=
//   GET  /api/runs/{id}                       record + results.json
//   GET  /api/runs/{id}/samples?from=&limit=  from samples.wbs
//   GET  /api/live?since=&limit=              latest samples
//
// Errors are {"error": short text, "detail": what exactly}; bad input is 400 naming the key.

#include <nlohmann/json.hpp>
#include <string>

#include "wavebench/daemon/bench_thread.hpp"
#include "wavebench/daemon/http_target.hpp"
#include "wavebench/daemon/live_sample_buffer.hpp"
#include "wavebench/storage/run_store.hpp"

namespace wavebench::daemon {

struct ApiRequest {
  std::string method;  // "GET", "POST", ...
  std::string target;  // path and query as sent
  std::string authorization;
  std::string body;
};

struct ApiResponse {
  int status = 200;
  nlohmann::json body;
};

class DaemonApi {
 public:
  DaemonApi(BenchThread& bench, storage::RunStore& store, LiveSampleBuffer& live,
            std::string token);
  // Thread-safe; may block while a run is being started.
  ApiResponse handle(const ApiRequest& request) const;

 private:
  ApiResponse status() const;
  ApiResponse start_run(const ApiRequest& request) const;
  ApiResponse abort_run() const;
  ApiResponse stop() const;
  ApiResponse reset() const;
  ApiResponse list_runs(const HttpTarget& target) const;
  ApiResponse run_detail(const std::string& id) const;
  ApiResponse run_samples(const std::string& id, const HttpTarget& target) const;
  ApiResponse live(const HttpTarget& target) const;

  BenchThread& bench_;
  storage::RunStore& store_;
  LiveSampleBuffer& live_;
  std::string token_;
};

ApiResponse api_error(int status, const std::string& error, const std::string& detail);

}  // namespace wavebench::daemon
