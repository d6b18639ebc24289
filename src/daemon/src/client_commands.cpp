#include "wavebench/daemon/client_commands.hpp"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <thread>

#include "wavebench/daemon/api_token.hpp"
#include "wavebench/daemon/daemon_client.hpp"
#include "wavebench/daemon/http_target.hpp"
#include "wavebench/daemon/sample_json.hpp"
#include "wavebench/storage/atomic_file.hpp"
#include "wavebench/storage/channel_info.hpp"
#include "wavebench/storage/sample_csv.hpp"

namespace wavebench::daemon {

namespace {

constexpr std::size_t kExportPage = 20000;

std::string token_or_empty(const ClientContext& ctx) {
  const auto path = ctx.token_file.empty() ? default_token_file() : ctx.token_file;
  try {
    return read_token(path);
  } catch (const std::exception&) {
    return {};
  }
}

// Commands that move hardware need the token; say where it was looked for.
std::string required_token(const ClientContext& ctx) {
  const auto path = ctx.token_file.empty() ? default_token_file() : ctx.token_file;
  return read_token(path);
}

std::string text_or(const nlohmann::json& j, const char* key, const std::string& fallback) {
  const auto it = j.find(key);
  if (it == j.end() || it->is_null()) return fallback;
  return it->is_string() ? it->get<std::string>() : it->dump();
}

int refused(const ClientContext& ctx, const std::string& what, const DaemonReply& reply) {
  *ctx.err << "wavebench: " << what << ": " << reply.error_text() << "\n";
  return reply.status == 400 ? 2 : 1;
}

// Runs `body` with the client; turns a missing daemon or token into exit 1 with the message.
template <typename Body>
int with_client(const ClientContext& ctx, bool needs_token, Body body) {
  try {
    DaemonClient client(ctx.daemon_url, needs_token ? required_token(ctx) : token_or_empty(ctx),
                        ctx.timeout, ctx.connect_timeout);
    return body(client);
  } catch (const std::invalid_argument& e) {
    *ctx.err << "wavebench: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    *ctx.err << "wavebench: " << e.what() << "\n";
    return 1;
  }
}

void print_status(std::ostream& out, const nlohmann::json& s) {
  out << "state        " << text_or(s, "state", "?") << "\n";
  if (s.contains("bench") && s["bench"].is_object()) {
    const auto& b = s["bench"];
    out << "bench        " << text_or(b, "name", "?") << " (unit " << text_or(b, "unit_serial", "?")
        << ", " << (b.value("simulated_clock", false) ? "simulated" : "real") << " clock, SYNC "
        << b.value("sync_period_s", 0.0) * 1e3 << " ms)\n";
  }
  if (s.contains("run") && s["run"].is_object()) {
    const auto& r = s["run"];
    out << "run          " << text_or(r, "id", "(starting)") << "  " << text_or(r, "procedure", "")
        << "  " << std::lround(100 * r.value("progress", 0.0)) << " %  " << text_or(r, "phase", "")
        << "\n";
  } else {
    out << "run          -\n";
  }
  out << "fault        " << text_or(s, "fault_reason", "-") << "\n";
  if (!text_or(s, "connect_error", "").empty()) {
    out << "connect      " << text_or(s, "connect_error", "") << "\n";
  }
  if (s.contains("acquisition") && s["acquisition"].is_object()) {
    const auto& a = s["acquisition"];
    out << "acquisition  " << a.value("samples", 0ull) << " samples, "
        << a.value("incomplete_samples", 0ull) << " incomplete, " << a.value("sync_late", 0ull)
        << " SYNC late, bus load " << std::lround(100 * a.value("bus_load", 0.0)) << " %\n";
  }
  if (s.contains("last_run") && s["last_run"].is_object()) {
    const auto& l = s["last_run"];
    out << "last run     " << text_or(l, "id", "?") << " " << text_or(l, "status", "?");
    if (!text_or(l, "reason", "").empty()) out << ": " << text_or(l, "reason", "");
    out << "\n";
  }
}

nlohmann::json option_value(const std::string& text) {
  if (nlohmann::json::accept(text)) return nlohmann::json::parse(text);
  return text;
}

// Polls until the run `id` (or, while it has no id yet, the run just queued) has ended.
int wait_for_run(const ClientContext& ctx, const DaemonClient& client, std::string id) {
  std::string last_phase;
  for (;;) {
    const auto reply = client.get("/api/status");
    if (!reply.ok()) return refused(ctx, "status", reply);
    const auto& s = reply.body;
    const bool active = s.contains("run") && s["run"].is_object();
    const std::string active_id = active ? text_or(s["run"], "id", "") : "";
    if (id.empty() && !active_id.empty()) id = active_id;
    if (active && (active_id.empty() || active_id == id)) {
      const auto phase = text_or(s["run"], "phase", "");
      if (phase != last_phase) {
        *ctx.err << "  [" << std::setw(3) << std::lround(100 * s["run"].value("progress", 0.0))
                 << " %] " << phase << "\n";
        last_phase = phase;
      }
      std::this_thread::sleep_for(ctx.poll_interval);
      continue;
    }
    if (id.empty()) {
      *ctx.err << "wavebench: the run ended before it was named: "
               << text_or(s.value("last_run", nlohmann::json::object()), "reason", "?") << "\n";
      return 1;
    }
    const auto detail = client.get("/api/runs/" + url_encode(id));
    if (!detail.ok()) return refused(ctx, "run " + id, detail);
    const auto& run = detail.body["run"];
    const auto status = text_or(run, "status", "?");
    *ctx.out << "run " << id << " " << status;
    if (!text_or(run, "reason", "").empty()) *ctx.out << ": " << text_or(run, "reason", "");
    *ctx.out << "\n";
    if (!text_or(detail.body, "dir", "").empty()) {
      *ctx.out << "folder       " << text_or(detail.body, "dir", "") << "\n";
    }
    if (!text_or(detail.body, "report", "").empty()) {
      *ctx.out << "report       " << text_or(detail.body, "report", "") << "\n";
    }
    return status == "complete" ? 0 : 1;
  }
}

}  // namespace

int client_status(const ClientContext& ctx) {
  return with_client(ctx, false, [&](const DaemonClient& client) {
    const auto reply = client.get("/api/status");
    if (!reply.ok()) return refused(ctx, "status", reply);
    print_status(*ctx.out, reply.body);
    return 0;
  });
}

int client_start(const ClientContext& ctx, const std::string& procedure,
                 const std::vector<std::string>& options, bool wait, const std::string& spec) {
  nlohmann::json body = {{"procedure", procedure}, {"options", nlohmann::json::object()}};
  if (!spec.empty()) body["spec"] = spec;
  for (const auto& option : options) {
    const auto eq = option.find('=');
    if (eq == std::string::npos || eq == 0) {
      *ctx.err << "wavebench: --option: got '" << option << "', expected KEY=VALUE\n";
      return 2;
    }
    body["options"][option.substr(0, eq)] = option_value(option.substr(eq + 1));
  }
  return with_client(ctx, true, [&](const DaemonClient& client) {
    const auto reply = client.post("/api/runs", body);
    if (!reply.ok()) return refused(ctx, "start " + procedure, reply);
    const auto id = text_or(reply.body, "run_id", "");
    *ctx.out << "run " << (id.empty() ? std::string("(queued)") : id) << " started (" << procedure
             << ")\n";
    return wait ? wait_for_run(ctx, client, id) : 0;
  });
}

int client_abort(const ClientContext& ctx) {
  return with_client(ctx, true, [&](const DaemonClient& client) {
    const auto reply = client.post("/api/abort");
    if (!reply.ok()) return refused(ctx, "abort", reply);
    *ctx.out << "aborting run " << text_or(reply.body, "run_id", "?") << "\n";
    return 0;
  });
}

int client_stop(const ClientContext& ctx) {
  return with_client(ctx, true, [&](const DaemonClient& client) {
    const auto reply = client.post("/api/stop");
    if (!reply.ok()) return refused(ctx, "stop", reply);
    *ctx.out << "bench in its safe state (operator stop); 'wavebench reset' clears it\n";
    return 0;
  });
}

int client_reset(const ClientContext& ctx) {
  return with_client(ctx, true, [&](const DaemonClient& client) {
    const auto reply = client.post("/api/reset");
    if (!reply.ok()) return refused(ctx, "reset", reply);
    print_status(*ctx.out, reply.body);
    return 0;
  });
}

int client_runs(const ClientContext& ctx, const RunsFilter& filter) {
  std::string query;
  const auto add = [&](const char* key, const std::string& value) {
    query += (query.empty() ? "?" : "&") + std::string(key) + "=" + url_encode(value);
  };
  if (filter.procedure) add("procedure", *filter.procedure);
  if (filter.status) add("status", *filter.status);
  if (filter.unit) add("unit", *filter.unit);
  if (filter.spec) add("spec", *filter.spec);
  if (filter.verdict) add("verdict", *filter.verdict);
  if (filter.limit > 0) add("limit", std::to_string(filter.limit));
  return with_client(ctx, false, [&](const DaemonClient& client) {
    const auto reply = client.get("/api/runs" + query);
    if (!reply.ok()) return refused(ctx, "runs", reply);
    auto& out = *ctx.out;
    out << std::left << std::setw(26) << "id" << std::setw(13) << "procedure" << std::setw(12)
        << "status" << std::setw(6) << "pass" << std::setw(16) << "unit"
        << "reason\n";
    for (const auto& run : reply.body.value("runs", nlohmann::json::array())) {
      const auto pass = run.contains("pass") && run["pass"].is_boolean()
                            ? std::string(run["pass"].get<bool>() ? "yes" : "no")
                            : std::string("-");
      out << std::setw(26) << text_or(run, "id", "?") << std::setw(13)
          << text_or(run, "procedure", "?") << std::setw(12) << text_or(run, "status", "?")
          << std::setw(6) << pass << std::setw(16) << text_or(run, "unit_serial", "?")
          << text_or(run, "reason", "") << "\n";
    }
    return 0;
  });
}

int client_export(const ClientContext& ctx, const std::string& run_id,
                  const std::filesystem::path& out_dir, const std::string& format) {
  if (format != "csv" && format != "json") {
    *ctx.err << "wavebench: --format: got '" << format << "', expected csv or json\n";
    return 2;
  }
  return with_client(ctx, false, [&](const DaemonClient& client) {
    const auto detail = client.get("/api/runs/" + url_encode(run_id));
    if (!detail.ok()) return refused(ctx, "export " + run_id, detail);
    // Every sample first, then the files: nothing half-written when the daemon goes away.
    std::vector<storage::SyncSample> samples;
    std::vector<storage::ChannelInfo> extra;
    bool torn = false, corrupt = false;
    for (;;) {
      const auto page = client.get("/api/runs/" + url_encode(run_id) +
                                   "/samples?from=" + std::to_string(samples.size()) +
                                   "&limit=" + std::to_string(kExportPage));
      if (!page.ok()) return refused(ctx, "export " + run_id, page);
      const auto& list = page.body["samples"];
      if (samples.empty() && page.body.contains("channels") && page.body["channels"].is_array()) {
        extra.clear();
        for (const auto& c : page.body["channels"])
          if (c.is_object() && c.value("extra", false) && extra.size() < storage::kMaxExtraChannels)
            extra.push_back({c.value("name", std::string()), c.value("unit", std::string())});
        // Names become CSV columns and JSON keys: a daemon's reply is checked like any input.
        storage::check_extra_channels(extra);
      }
      for (const auto& s : list) samples.push_back(sample_from_json(s, extra));
      torn = page.body.value("torn_tail_bytes", 0) > 0;
      corrupt = page.body.value("corrupt", false);
      if (list.empty() || samples.size() >= page.body.value("total", std::size_t{0})) break;
    }
    const auto dir = out_dir.empty() ? std::filesystem::path(run_id) : out_dir;
    std::filesystem::create_directories(dir);
    std::ostringstream text;
    std::filesystem::path samples_file;
    if (format == "csv") {
      storage::write_samples_csv(samples, text, extra);
      samples_file = dir / "samples.csv";
    } else {
      nlohmann::json array = nlohmann::json::array();
      for (const auto& s : samples) array.push_back(sample_to_json(s, extra));
      text << array.dump() << "\n";
      samples_file = dir / "samples.json";
    }
    storage::write_file_atomically(samples_file, text.str());
    storage::write_file_atomically(dir / "run.json", detail.body["run"].dump(2) + "\n");
    if (detail.body.contains("results") && !detail.body["results"].is_null()) {
      storage::write_file_atomically(dir / "results.json", detail.body["results"].dump(2) + "\n");
    }
    *ctx.out << "exported " << samples.size() << " samples of run " << run_id << " to "
             << samples_file.string() << "\n";
    if (torn) *ctx.err << "note: the sample log ends in a torn record (ignored)\n";
    if (corrupt) *ctx.err << "warning: the sample log has a corrupt record; read up to it\n";
    return 0;
  });
}

}  // namespace wavebench::daemon
