#include "wavebench/daemon/client_commands.hpp"

#include <cmath>
#include <cstdint>
#include <fstream>
#include <iomanip>
#include <optional>
#include <span>
#include <sstream>
#include <thread>

#include "wavebench/daemon/api_token.hpp"
#include "wavebench/daemon/daemon_client.hpp"
#include "wavebench/daemon/http_target.hpp"
#include "wavebench/daemon/sample_json.hpp"
#include "wavebench/exports/export_folder.hpp"
#include "wavebench/exports/run_export.hpp"
#include "wavebench/exports/sample_export.hpp"
#include "wavebench/storage/atomic_file.hpp"
#include "wavebench/storage/channel_info.hpp"

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
    client.retry_busy(ctx.busy_wait, [err = ctx.err](const std::string& what) {
      *err << "wavebench: " << what << "\n";
    });
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
    // Recorded: its results are made in the background; the run has ended when they are.
    bool processing = false;
    for (const auto& p : s.value("post_runs", nlohmann::json::array())) {
      processing = processing || (!id.empty() && text_or(p, "run_id", "") == id);
    }
    if (processing) {
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
    *ctx.out << "bench in its safe state (operator stop); it is ready again by itself\n";
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

namespace {

// The format's name checked before anything is asked or written; nullopt after the message.
std::optional<exports::ExportFormat> export_format(const ClientContext& ctx,
                                                   const std::string& format) {
  const auto f = exports::export_format_from_name(format);
  if (!f) {
    *ctx.err << "wavebench: --format: got '" << format << "', expected "
             << exports::export_format_list() << "\n";
  }
  return f;
}

// The export folder refused before anything is fetched: exit 2, nothing touched.
bool export_folder_refused(const ClientContext& ctx, const std::filesystem::path& dir,
                           const std::string& run_id) {
  if (const auto refusal = exports::export_folder_refusal(dir, run_id)) {
    *ctx.err << "wavebench: --out: " << dir.string() << ": " << *refusal << "\n";
    return true;
  }
  return false;
}

// A running run refused before its samples are fetched: exit 2, nothing written.
bool running_run_refused(const ClientContext& ctx, const std::string& run_id,
                         const nlohmann::json& run, bool partial) {
  if (const auto refusal = exports::running_run_refusal(run, partial, "--partial")) {
    *ctx.err << "wavebench: export " << run_id << ": " << *refusal << "\n";
    return true;
  }
  return false;
}

// samples.*, run.json and results.json into `dir`: all of them or none.
int write_export(const ClientContext& ctx, exports::ExportInput input, exports::ExportFormat format,
                 const std::filesystem::path& dir, bool partial) {
  input.sample_json = [](const storage::SyncSample& s,
                         std::span<const storage::ChannelInfo> extra) {
    return sample_to_json(s, extra);
  };
  const std::string run_id = input.run_id;
  const auto summary = exports::export_run(std::move(input), format, dir, partial);
  *ctx.out << "exported " << summary.samples << " samples of run " << run_id << " to "
           << summary.file.string()
           << (summary.partial ? " (partial: the run is still running)" : "") << "\n";
  if (summary.torn_tail) *ctx.err << "note: the sample log ends in a torn record (ignored)\n";
  if (summary.corrupt_record) {
    *ctx.err << "warning: the sample log has a corrupt record; read up to it\n";
  }
  return 0;
}

// A page of the samples API as the log's page: the same records, the same extra channels.
storage::SampleLogPage page_from_api(const DaemonClient& client, const std::string& run_id,
                                     std::uint64_t from, std::size_t count) {
  const auto reply =
      client.get("/api/runs/" + url_encode(run_id) + "/samples?from=" + std::to_string(from) +
                 "&limit=" + std::to_string(count));
  if (!reply.ok())
    throw std::runtime_error("samples from " + std::to_string(from) + ": " + reply.error_text());
  storage::SampleLogPage page;
  page.from = reply.body.value("from", std::uint64_t{0});
  if (reply.body.contains("channels") && reply.body["channels"].is_array()) {
    for (const auto& c : reply.body["channels"])
      if (c.is_object() && c.value("extra", false) &&
          page.header.extra_channels.size() < storage::kMaxExtraChannels)
        page.header.extra_channels.push_back(
            {c.value("name", std::string()), c.value("unit", std::string())});
    // Names become CSV columns, JSON keys and variable names: a daemon's reply is checked like
    // any input.
    storage::check_extra_channels(page.header.extra_channels);
  }
  const auto& list = reply.body["samples"];
  if (!list.is_array()) throw std::runtime_error("samples: the reply has no sample list");
  for (const auto& s : list)
    page.samples.push_back(sample_from_json(s, page.header.extra_channels));
  page.total_records = reply.body.value("total", std::uint64_t{0});
  page.torn_tail_bytes = reply.body.value("torn_tail_bytes", std::size_t{0});
  page.corrupt_record = reply.body.value("corrupt", false);
  return page;
}

nlohmann::json json_file_or_null(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) return nullptr;
  auto j = nlohmann::json::parse(in, nullptr, false);
  return j.is_discarded() ? nlohmann::json(nullptr) : j;
}

}  // namespace

int client_export(const ClientContext& ctx, const std::string& run_id,
                  const std::filesystem::path& out_dir, const std::string& format, bool partial) {
  const auto f = export_format(ctx, format);
  if (!f) return 2;
  const auto dir = out_dir.empty() ? std::filesystem::path(run_id) : out_dir;
  if (export_folder_refused(ctx, dir, run_id)) return 2;
  return with_client(ctx, false, [&](const DaemonClient& client) {
    const auto detail = client.get("/api/runs/" + url_encode(run_id));
    if (!detail.ok()) return refused(ctx, "export " + run_id, detail);
    if (running_run_refused(ctx, run_id, detail.body["run"], partial)) return 2;
    exports::ExportInput input;
    input.run_id = run_id;
    input.run = detail.body["run"];
    if (detail.body.contains("results")) input.results = detail.body["results"];
    input.page_records = kExportPage;
    input.pages = [&client, &run_id](std::uint64_t from, std::size_t count) {
      return page_from_api(client, run_id, from, count);
    };
    return write_export(ctx, std::move(input), *f, dir, partial);
  });
}

int local_export(const ClientContext& ctx, const std::filesystem::path& runs_dir,
                 const std::string& run_id, const std::filesystem::path& out_dir,
                 const std::string& format, bool partial) {
  const auto f = export_format(ctx, format);
  if (!f) return 2;
  // A run id names a folder directly under the store: nothing that leaves it.
  const bool plain = !run_id.empty() && run_id != "." && run_id != ".." &&
                     run_id.find('/') == std::string::npos &&
                     run_id.find('\0') == std::string::npos;
  const auto run_dir = runs_dir / run_id;
  std::error_code ec;
  if (!plain || !std::filesystem::is_regular_file(run_dir / "samples.wbs", ec)) {
    *ctx.err << "wavebench: run_id: got '" << run_id << "', expected a run of " << runs_dir.string()
             << " (a folder holding samples.wbs; see 'wavebench runs')\n";
    return 2;
  }
  const auto dir = out_dir.empty() ? std::filesystem::path(run_id) : out_dir;
  if (export_folder_refused(ctx, dir, run_id)) return 2;
  try {
    exports::ExportInput input;
    input.run_id = run_id;
    input.run = json_file_or_null(run_dir / "status.json");
    if (running_run_refused(ctx, run_id, input.run, partial)) return 2;
    input.results = json_file_or_null(run_dir / "results.json");
    input.page_records = kExportPage;
    input.pages = exports::sample_log_pages(run_dir / "samples.wbs");
    return write_export(ctx, std::move(input), *f, dir, partial);
  } catch (const std::exception& e) {
    *ctx.err << "wavebench: export " << run_id << ": " << e.what() << "\n";
    return 1;
  }
}

}  // namespace wavebench::daemon
