#pragma once
// libpq, owned: a connection and the results of its commands, freed by their destructors; every
// failure a std::runtime_error with libpq's message. Parameters are text (libpq's text format),
// a missing optional is SQL NULL.

#include <libpq-fe.h>

#include <optional>
#include <string>
#include <vector>

namespace wavebench::fleet {

using PgParams = std::vector<std::optional<std::string>>;

class PgResult {
 public:
  explicit PgResult(PGresult* result) : result_(result) {}
  ~PgResult() { PQclear(result_); }
  PgResult(PgResult&& other) noexcept : result_(other.result_) { other.result_ = nullptr; }
  PgResult(const PgResult&) = delete;
  PgResult& operator=(const PgResult&) = delete;
  PgResult& operator=(PgResult&&) = delete;

  // The command succeeded (with or without rows).
  bool ok() const;
  std::string error(PGconn* conn) const;
  int rows() const { return PQntuples(result_); }
  bool null(int row, int col) const { return PQgetisnull(result_, row, col) != 0; }
  std::string text(int row, int col) const { return PQgetvalue(result_, row, col); }
  std::optional<double> number(int row, int col) const;
  // Rows an INSERT/UPDATE/DELETE touched.
  long affected() const;

 private:
  PGresult* result_;
};

class PgConnection {
 public:
  // `conninfo` is a libpq URL or key=value string; `password` empty: libpq's own (environment,
  // ~/.pgpass). Throws std::runtime_error naming what failed.
  PgConnection(const std::string& conninfo, const std::string& password);
  ~PgConnection();
  PgConnection(const PgConnection&) = delete;
  PgConnection& operator=(const PgConnection&) = delete;

  PgResult exec(const std::string& sql, const PgParams& params = {});
  // Several statements, no parameters (a migration).
  void exec_script(const std::string& sql);
  // BEGIN; body; COMMIT (ROLLBACK and rethrow when the body throws).
  template <typename Body>
  void transaction(Body&& body) {
    exec("BEGIN");
    try {
      body();
    } catch (...) {
      if (ok()) {
        try {
          exec("ROLLBACK");
        } catch (...) {  // NOLINT(bugprone-empty-catch): the first failure is the one reported
        }
      }
      throw;
    }
    exec("COMMIT");
  }
  bool ok() const { return PQstatus(conn_) == CONNECTION_OK; }

 private:
  PGconn* conn_ = nullptr;
};

struct ConninfoProblem {
  std::string shown;     // the value as it may be shown (never a password)
  std::string expected;  // what was expected instead
};
// What is wrong with a connection string: libpq cannot parse it, or it carries a password.
std::optional<ConninfoProblem> conninfo_problem(const std::string& conninfo);
// Throws std::invalid_argument naming results.url when conninfo_problem() finds one.
void check_conninfo(const std::string& conninfo);

}  // namespace wavebench::fleet
