#pragma once
// wavebenchd's command line: --config BENCH.yaml|sim [--runs DIR] [--listen HOST:PORT]
// [--token-file F] [--log-dir D] [--specs-dir D] [--results FILE] [--accounts FILE]
// [--session-idle-timeout S] [--session-max-age S].

#include <filesystem>
#include <string>
#include <vector>

namespace wavebench::daemon {

struct ListenAddress {
  std::string host = "127.0.0.1";
  unsigned short port = 8470;
};

// "HOST:PORT", "[V6]:PORT" or ":PORT" (host stays 127.0.0.1); HOST is an IP address.
// Throws std::invalid_argument naming --listen, the value and what was expected.
ListenAddress parse_listen_address(const std::string& text);
// Whether the address only this machine can reach (127.0.0.0/8, ::1).
bool is_loopback(const ListenAddress& address);

struct DaemonOptions {
  std::string config;  // a bench config file, or "simulated" ("sim": its old name)
  std::filesystem::path runs_dir = "runs";
  ListenAddress listen;
  std::filesystem::path token_file;  // empty: default_token_file()
  std::filesystem::path log_dir;     // empty: <runs_dir>/logs
  std::filesystem::path specs_dir;   // empty: procedures::default_specs_dir()
  bool verbose = false;
  // Listening beyond loopback exposes the bench to the network: only when asked for.
  bool allow_remote = false;
  std::vector<std::string> allowed_hosts;      // Host names accepted beside IP literals, localhost
  std::filesystem::path web_root;              // empty: default_console_root()
  std::filesystem::path results_config;        // --results; empty: the runs folder only
  std::filesystem::path accounts_file;         // --accounts; empty: only the token logs in
  long long session_idle_timeout_s = 30 * 60;  // --session-idle-timeout
  long long session_max_age_s = 12 * 3600;     // --session-max-age
};

}  // namespace wavebench::daemon
