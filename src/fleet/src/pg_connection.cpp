#include "pg_connection.hpp"

#include <cstdlib>
#include <stdexcept>

namespace wavebench::fleet {

namespace {

std::string trimmed(std::string message) {
  while (!message.empty() && (message.back() == '\n' || message.back() == ' ')) {
    message.pop_back();
  }
  return message;
}

}  // namespace

bool PgResult::ok() const {
  const auto status = result_ ? PQresultStatus(result_) : PGRES_FATAL_ERROR;
  return status == PGRES_COMMAND_OK || status == PGRES_TUPLES_OK;
}

std::string PgResult::error(PGconn* conn) const {
  return trimmed(result_ ? PQresultErrorMessage(result_) : PQerrorMessage(conn));
}

std::optional<double> PgResult::number(int row, int col) const {
  if (null(row, col)) return std::nullopt;
  return std::strtod(PQgetvalue(result_, row, col), nullptr);
}

long PgResult::affected() const {
  const char* n = PQcmdTuples(result_);
  return n && *n ? std::strtol(n, nullptr, 10) : 0;
}

std::optional<ConninfoProblem> conninfo_problem(const std::string& conninfo) {
  char* error = nullptr;
  PQconninfoOption* options = PQconninfoParse(conninfo.c_str(), &error);
  if (!options) {
    std::string message = error ? error : "out of memory";
    PQfreemem(error);
    return ConninfoProblem{conninfo,
                           "a PostgreSQL URL (postgresql://user@host/db) or key=value connection "
                           "string (libpq: " +
                               trimmed(message) + ")"};
  }
  bool has_password = false;
  for (auto* o = options; o->keyword; ++o) {
    if (std::string(o->keyword) == "password" && o->val && *o->val) has_password = true;
  }
  PQconninfoFree(options);
  if (!has_password) return std::nullopt;
  // The value is not shown: it holds the secret.
  return ConninfoProblem{"(a connection string with a password)",
                         "none in it: the password goes in results.password_file or libpq's "
                         "environment (PGPASSWORD, ~/.pgpass)"};
}

void check_conninfo(const std::string& conninfo) {
  if (const auto problem = conninfo_problem(conninfo)) {
    throw std::invalid_argument("results.url: got '" + problem->shown + "', expected " +
                                problem->expected);
  }
}

PgConnection::PgConnection(const std::string& conninfo, const std::string& password) {
  // expand_dbname: `dbname` holds the whole URL; the password goes beside it, never in it.
  std::vector<const char*> keys = {"dbname", "connect_timeout", "application_name"};
  std::vector<const char*> values = {conninfo.c_str(), "5", "wavebench"};
  if (!password.empty()) {
    keys.push_back("password");
    values.push_back(password.c_str());
  }
  keys.push_back(nullptr);
  values.push_back(nullptr);
  conn_ = PQconnectdbParams(keys.data(), values.data(), 1);
  if (!conn_ || PQstatus(conn_) != CONNECTION_OK) {
    std::string message = conn_ ? PQerrorMessage(conn_) : "out of memory";
    PQfinish(conn_);
    conn_ = nullptr;
    throw std::runtime_error("results store: cannot connect: " + trimmed(message));
  }
  exec("SET client_min_messages = warning");
}

PgConnection::~PgConnection() {
  PQfinish(conn_);
}

void PgConnection::exec_script(const std::string& sql) {
  PgResult result(PQexec(conn_, sql.c_str()));
  if (!result.ok()) throw std::runtime_error("results store: " + result.error(conn_));
}

PgResult PgConnection::exec(const std::string& sql, const PgParams& params) {
  std::vector<const char*> values;
  values.reserve(params.size());
  for (const auto& p : params) values.push_back(p ? p->c_str() : nullptr);
  PgResult result(PQexecParams(conn_, sql.c_str(), static_cast<int>(values.size()), nullptr,
                               values.data(), nullptr, nullptr, 0));
  if (!result.ok()) throw std::runtime_error("results store: " + result.error(conn_));
  return result;
}

}  // namespace wavebench::fleet
