#include "wavebench/fleet/results_config.hpp"

#include <sys/stat.h>

#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "pg_connection.hpp"
#include "wavebench/strict_yaml/strict_yaml.hpp"
#include "wavebench/strict_yaml/yaml_section.hpp"

namespace wavebench::fleet {

namespace {

bool is_name(const std::string& text) {
  return !text.empty() && text.size() <= 64 &&
         text.find_first_not_of(
             "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789._-") ==
             std::string::npos;
}

}  // namespace

ResultsConfig parse_results_config(const std::string& yaml_text, const std::string& source) {
  using strict_yaml::YamlSection;
  auto document = strict_yaml::document_section(strict_yaml::parse_strict_yaml(yaml_text, source),
                                                source, "a mapping with `results:`");
  ResultsConfig config;
  config.source = source;
  YamlSection results = document.section("results");
  config.store = results.choice("store", {"postgresql", "sqlite"}) == "postgresql"
                     ? StoreKind::kPostgresql
                     : StoreKind::kSqlite;
  if (config.shared()) {
    config.url = results.text("url");
    if (const auto problem = conninfo_problem(config.url)) {
      throw strict_yaml::RefusedConfig(results.key_path("url"), problem->shown, problem->expected,
                                       source);
    }
    if (const auto file = results.optional_text("password_file")) {
      config.password_file = *file;
      if (config.password_file.is_relative()) {
        // Relative to the config file, as every other config's paths are.
        config.password_file = std::filesystem::path(source).parent_path() / config.password_file;
      }
    }
  } else {
    // Kept for when the store is switched back: read, not used.
    (void)results.optional_text("url");
    (void)results.optional_text("password_file");
  }
  if (const auto bench = results.optional_text("bench")) {
    if (!is_name(*bench)) {
      results.fail("bench", *bench, "1..64 of [A-Za-z0-9._-]");
    }
    config.bench = *bench;
  }
  if (const auto station = results.optional_text("station")) {
    if (!is_name(*station)) {
      results.fail("station", *station, "1..64 of [A-Za-z0-9._-]");
    }
    config.station = *station;
  }
  if (const auto retry = results.optional_quantity_in("retry_max", strict_yaml::Dimension::kTime,
                                                      0.01, 3600, "a time in [10 ms, 1 h]")) {
    config.retry_max_s = *retry;
  }
  results.finish();
  document.finish();
  return config;
}

ResultsConfig load_results_config(const std::filesystem::path& file) {
  return parse_results_config(strict_yaml::read_config_file(file), file.string());
}

std::string read_password_file(const std::filesystem::path& file) {
  const std::string key = "results.password_file: " + file.string() + ": ";
  struct stat st {};
  if (::stat(file.c_str(), &st) != 0) {
    throw std::runtime_error(key +
                             "cannot be read (missing?), expected a file holding the "
                             "password");
  }
  if (!S_ISREG(st.st_mode)) throw std::runtime_error(key + "expected a regular file");
  if ((st.st_mode & 077) != 0) {
    char mode[8];
    std::snprintf(mode, sizeof mode, "%04o", static_cast<unsigned>(st.st_mode & 0777));
    throw std::runtime_error(key + "mode " + mode +
                             " lets others read or write it, expected 0600 or 0400");
  }
  std::ifstream in(file);
  std::string password;
  if (!in || !std::getline(in, password)) {
    throw std::runtime_error(key + "cannot be read, expected a file holding the password");
  }
  if (!password.empty() && password.back() == '\r') password.pop_back();
  if (password.empty()) throw std::runtime_error(key + "empty, expected the password");
  return password;
}

}  // namespace wavebench::fleet
