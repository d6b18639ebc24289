#pragma once
// wavebenchd's command line: --config BENCH.yaml|sim [--runs DIR] [--listen HOST:PORT]
// [--token-file F] [--log-dir D].

#include <filesystem>
#include <string>

namespace wavebench::daemon {

struct ListenAddress {
  std::string host = "127.0.0.1";
  unsigned short port = 8470;
};

// "HOST:PORT", "[V6]:PORT" or ":PORT" (host stays 127.0.0.1). Throws std::invalid_argument
// naming --listen, the value and what was expected.
ListenAddress parse_listen_address(const std::string& text);

struct DaemonOptions {
  std::string config;  // a bench config file, or "sim"
  std::filesystem::path runs_dir = "runs";
  ListenAddress listen;
  std::filesystem::path token_file;  // empty: default_token_file()
  std::filesystem::path log_dir;     // empty: <runs_dir>/logs
  bool verbose = false;
};

}  // namespace wavebench::daemon
