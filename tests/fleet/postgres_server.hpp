#pragma once
// A real PostgreSQL 15 server for one test process (Debian postgresql-15): initdb into a fresh
// folder under /tmp (short: the unix socket's path is limited to 107 bytes), reachable only by
// its unix socket there (listen_addresses = ''), SCRAM password auth, stopped and removed at the
// end. initdb refuses root: as root the server runs as `nobody` (runuser), the folder theirs.

#include <pwd.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

#include "wavebench/fleet/results_config.hpp"

namespace wavebench::fleet::testing {

inline constexpr const char* kPgBin = "/usr/lib/postgresql/15/bin";

class PostgresServer {
 public:
  PostgresServer() {
    if (!std::filesystem::exists(std::string(kPgBin) + "/initdb")) {
      throw std::runtime_error(std::string(kPgBin) +
                               "/initdb missing: install postgresql-15 (scripts/install-deps.sh)");
    }
    char pattern[] = "/tmp/wbpg-XXXXXX";
    if (!::mkdtemp(pattern)) throw std::runtime_error("mkdtemp failed");
    dir_ = pattern;
    as_root_ = ::geteuid() == 0;
    if (as_root_) {
      const passwd* nobody = ::getpwnam("nobody");
      if (!nobody) throw std::runtime_error("no user nobody to run PostgreSQL as");
      if (::chown(dir_.c_str(), nobody->pw_uid, nobody->pw_gid) != 0) {
        throw std::runtime_error("chown " + dir_.string() + " failed");
      }
    }
    write_secret(dir_ / "server.pw", as_root_);
    write_secret(dir_ / "client.pw", false);
    run(std::string(kPgBin) + "/initdb -D " + data().string() +
        " -U wavebench --auth-local=scram-sha-256 --auth-host=scram-sha-256 --pwfile=" +
        (dir_ / "server.pw").string() + " -E UTF8 --no-locale --no-sync > " +
        (dir_ / "initdb.log").string() + " 2>&1");
    std::ofstream conf(data() / "postgresql.conf", std::ios::app);
    conf << "listen_addresses = ''\nunix_socket_directories = '" << dir_.string()
         << "'\nport = 5432\nfsync = off\nsynchronous_commit = off\nfull_page_writes = off\n"
            "max_connections = 40\n";
    conf.close();
    start();
  }
  ~PostgresServer() {
    try {
      stop();
    } catch (...) {  // NOLINT(bugprone-empty-catch): best effort in a destructor
    }
    std::error_code ignored;
    std::filesystem::remove_all(dir_, ignored);
  }
  PostgresServer(const PostgresServer&) = delete;
  PostgresServer& operator=(const PostgresServer&) = delete;

  void start() {
    run(std::string(kPgBin) + "/pg_ctl -D " + data().string() + " -l " +
        (dir_ / "server.log").string() + " -w -t 60 start > /dev/null");
    running_ = true;
  }
  void stop() {
    if (!running_) return;
    run(std::string(kPgBin) + "/pg_ctl -D " + data().string() +
        " -m fast -w -t 60 stop > /dev/null");
    running_ = false;
  }

  // A results config for a database of this server (created by create_database()).
  ResultsConfig config(const std::string& database, const std::string& bench = {},
                       const std::string& station = {}) const {
    ResultsConfig c;
    c.store = StoreKind::kPostgresql;
    c.url = "host=" + dir_.string() + " port=5432 user=wavebench dbname=" + database;
    c.password_file = dir_ / "client.pw";
    c.bench = bench;
    c.station = station;
    c.retry_max_s = 0.2;
    return c;
  }
  // CREATE DATABASE through psql on the maintenance database.
  void create_database(const std::string& name) const {
    run("PGPASSWORD=" + std::string(kPassword) + " " + kPgBin + "/psql -X -q -h " + dir_.string() +
            " -p 5432 -U wavebench -d postgres -c 'CREATE DATABASE " + name + "'",
        false);
  }
  // One statement on `database` through psql (what an older build's schema looked like).
  void sql(const std::string& database, const std::string& statement) const {
    run("PGPASSWORD=" + std::string(kPassword) + " " + kPgBin +
            "/psql -X -q -v ON_ERROR_STOP=1 -h " + dir_.string() + " -p 5432 -U wavebench -d " +
            database + " -c \"" + statement + "\"",
        false);
  }
  const std::filesystem::path& dir() const { return dir_; }
  std::string log() const {
    std::ifstream in(dir_ / "server.log");
    return std::string(std::istreambuf_iterator<char>(in), {});
  }

 private:
  static constexpr const char* kPassword = "wavebench-test-secret";

  std::filesystem::path data() const { return dir_ / "data"; }

  void write_secret(const std::filesystem::path& file, bool for_server) const {
    {
      std::ofstream out(file);
      out << kPassword << "\n";
    }
    ::chmod(file.c_str(), 0600);
    if (for_server) {
      const passwd* nobody = ::getpwnam("nobody");
      if (::chown(file.c_str(), nobody->pw_uid, nobody->pw_gid) != 0) {
        throw std::runtime_error("chown " + file.string() + " failed");
      }
    }
  }

  // As the server's user, from its folder (nobody cannot enter the caller's).
  void run(const std::string& command, bool as_server = true) const {
    const std::string line = "cd " + dir_.string() + " && " +
                             (as_server && as_root_ ? "runuser -u nobody -- " : "") + command;
    if (std::system(line.c_str()) != 0) {
      throw std::runtime_error("failed: " + line + "\n" + log());
    }
  }

  std::filesystem::path dir_;
  bool as_root_ = false;
  bool running_ = false;
};

}  // namespace wavebench::fleet::testing
