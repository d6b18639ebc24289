#pragma once
// Where a bench's runs go besides its own run folders: the `results:` section of the file given
// with `wavebenchd --results FILE` (and `wavebench fleet --results FILE`):
//
//   results:
//     store: postgresql                   # postgresql | sqlite (sqlite: this bench only)
//     url: postgresql://wavebench@db.lab/wavebench   # libpq URL or key=value string, no password
//     password_file: /etc/wavebench/results.password # optional; else libpq's PGPASSWORD, ~/.pgpass
//     bench: bench-7                      # the bench's name in the fleet (default: its config's)
//     station: line-2                     # optional
//     retry_max: "60 s"                   # the outbox's longest wait between attempts
//
// The credential is never on the command line nor in the URL (refused there): a file only its
// owner can read, or libpq's own environment.

#include <filesystem>
#include <optional>
#include <string>

namespace wavebench::fleet {

enum class StoreKind { kSqlite, kPostgresql };

struct ResultsConfig {
  StoreKind store = StoreKind::kSqlite;
  std::string url;  // libpq connection string or URL, without a password
  std::filesystem::path password_file;
  std::string bench;  // empty: the bench config's name
  std::string station;
  double retry_max_s = 60;
  std::string source;  // the file, for messages

  bool shared() const { return store == StoreKind::kPostgresql; }
};

// Throws strict_yaml::RefusedConfig naming the key, the value and what was expected.
ResultsConfig parse_results_config(const std::string& yaml_text, const std::string& source);
ResultsConfig load_results_config(const std::filesystem::path& file);

// The password of `password_file`, first line. Throws std::runtime_error naming
// results.password_file when it is missing, unreadable, or readable by others than its owner.
std::string read_password_file(const std::filesystem::path& file);

}  // namespace wavebench::fleet
