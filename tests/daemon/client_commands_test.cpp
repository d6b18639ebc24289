// The `wavebench` client commands against an in-process daemon (fake bench, fake executor).
#include "wavebench/daemon/client_commands.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <future>
#include <sstream>

#include "daemon_fixture.hpp"
#include "wavebench/daemon/http_target.hpp"
#include "wavebench/daemon/run_export_download.hpp"
#include "wavebench/storage/sample_csv.hpp"

namespace wavebench::daemon::testing {
namespace {

class ClientCommandsTest : public DaemonFixture {
 protected:
  void SetUp() override {
    DaemonFixture::SetUp();
    token_file_ = dir_ / "token";
    std::ofstream(token_file_) << kToken << "\n";
  }
  ClientContext context() {
    out_.str("");
    err_.str("");
    ClientContext ctx;
    ctx.daemon_url = url();
    ctx.token_file = token_file_;
    ctx.out = &out_;
    ctx.err = &err_;
    ctx.poll_interval = std::chrono::milliseconds(5);
    return ctx;
  }
  static std::string read_file(const std::filesystem::path& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }

  std::filesystem::path token_file_;
  std::ostringstream out_, err_;
};

TEST_F(ClientCommandsTest, StatusPrintsTheState) {
  EXPECT_EQ(client_status(context()), 0);
  EXPECT_NE(out_.str().find("state        ready"), std::string::npos) << out_.str();
  EXPECT_NE(out_.str().find("unit SN-FAKE-1"), std::string::npos) << out_.str();
}

TEST_F(ClientCommandsTest, StartWaitFollowsTheRunToCompletion) {
  EXPECT_EQ(client_start(context(), "static", {"seconds=0.2", "label=left side"}, true), 0)
      << err_.str();
  EXPECT_NE(out_.str().find(" complete"), std::string::npos) << out_.str();
  const auto runs = client().get("/api/runs").body["runs"];
  ASSERT_EQ(runs.size(), 1u);
  const auto detail = client().get("/api/runs/" + runs[0]["id"].get<std::string>());
  EXPECT_EQ(detail.body["results"]["options"]["seconds"], 0.2);        // sent as a number
  EXPECT_EQ(detail.body["results"]["options"]["label"], "left side");  // and as a string
}

TEST_F(ClientCommandsTest, StartWaitEndsWithExit1WhenTheRunIsAborted) {
  auto waiting = std::async(std::launch::async, [this] {
    std::ostringstream out, err;
    auto ctx = context();
    ctx.out = &out;
    ctx.err = &err;
    const int rc = client_start(ctx, "dynamic", {"seconds=1e6"}, true);
    return std::make_pair(rc, out.str());
  });
  ASSERT_TRUE(eventually([&] {
    const auto s = client().get("/api/status").body;
    return s["run"].is_object() && !s["run"]["id"].is_null();
  }));
  EXPECT_EQ(client_abort(context()), 0) << err_.str();
  const auto [rc, out] = waiting.get();
  EXPECT_EQ(rc, 1);
  EXPECT_NE(out.find("aborted: operator abort"), std::string::npos) << out;
}

TEST_F(ClientCommandsTest, BadInputIsExit2AndStartsNothing) {
  EXPECT_EQ(client_start(context(), "static", {"seconds"}, false), 2);
  EXPECT_NE(err_.str().find("--option"), std::string::npos);
  EXPECT_EQ(client_start(context(), "static", {"seconds=-1"}, false), 2);
  EXPECT_NE(err_.str().find("seconds"), std::string::npos) << err_.str();
  RunsFilter finished;
  finished.status = "finished";
  EXPECT_EQ(client_runs(context(), finished), 2);
  EXPECT_NE(err_.str().find("status"), std::string::npos);
  EXPECT_EQ(client_export(context(), "x", "", "xml"), 2);
  EXPECT_TRUE(client().get("/api/runs").body["runs"].empty());
}

TEST_F(ClientCommandsTest, WithoutTheTokenNothingMoves) {
  auto ctx = context();
  ctx.token_file = dir_ / "no-such-token";
  EXPECT_EQ(client_start(ctx, "static", {}, false), 1);
  EXPECT_NE(err_.str().find("no-such-token"), std::string::npos) << err_.str();
  std::ofstream(dir_ / "wrong-token") << "nope\n";
  ctx.token_file = dir_ / "wrong-token";
  EXPECT_EQ(client_abort(ctx), 1);
  EXPECT_NE(err_.str().find("unauthorized"), std::string::npos) << err_.str();
  EXPECT_TRUE(client().get("/api/runs").body["runs"].empty());
}

TEST_F(ClientCommandsTest, NoDaemonIsExit1WithAClearMessage) {
  auto ctx = context();
  ctx.daemon_url = "http://127.0.0.1:1";
  EXPECT_EQ(client_status(ctx), 1);
  EXPECT_NE(err_.str().find("no daemon answering at http://127.0.0.1:1"), std::string::npos)
      << err_.str();
}

TEST_F(ClientCommandsTest, RunsListsWithFilters) {
  ASSERT_EQ(client_start(context(), "static", {"seconds=0.05"}, true), 0);
  ASSERT_EQ(client_start(context(), "lost-motion", {"seconds=0.05"}, true), 0);
  ASSERT_EQ(client_runs(context(), {}), 0);
  EXPECT_NE(out_.str().find("lost-motion"), std::string::npos);
  EXPECT_NE(out_.str().find("static"), std::string::npos);
  RunsFilter statics;
  statics.procedure = "static";
  ASSERT_EQ(client_runs(context(), statics), 0);
  EXPECT_EQ(out_.str().find("lost-motion"), std::string::npos) << out_.str();
  EXPECT_NE(out_.str().find("complete"), std::string::npos);
  // The spec and verdict filters reach the API (no run here was accepted against a spec).
  RunsFilter by_spec;
  by_spec.spec = "no-such-spec";
  out_.str("");
  ASSERT_EQ(client_runs(context(), by_spec), 0);
  EXPECT_EQ(out_.str().find("static"), std::string::npos) << out_.str();
  RunsFilter by_verdict;
  by_verdict.verdict = "maybe";
  EXPECT_EQ(client_runs(context(), by_verdict), 2);
  EXPECT_NE(err_.str().find("verdict"), std::string::npos) << err_.str();
}

TEST_F(ClientCommandsTest, ExportWritesTheSamplesAsTheStoreWouldAndTheResults) {
  ASSERT_EQ(client_start(context(), "dynamic", {"seconds=0.25"}, true), 0);
  const auto id = client().get("/api/runs").body["runs"][0]["id"].get<std::string>();
  const auto out_dir = dir_ / "export";
  ASSERT_EQ(client_export(context(), id, out_dir, "csv"), 0) << err_.str();
  EXPECT_NE(out_.str().find("exported 250 samples"), std::string::npos) << out_.str();
  // The CSV from the API is byte for byte the CSV of the log on disk.
  const auto reference = dir_ / "reference.csv";
  EXPECT_EQ(storage::export_sample_log_csv(daemon_->store().paths(id).samples, reference), 250u);
  EXPECT_EQ(read_file(out_dir / "samples.csv"), read_file(reference));
  const auto results = nlohmann::json::parse(read_file(out_dir / "results.json"));
  EXPECT_EQ(results["samples"], 250);
  EXPECT_EQ(nlohmann::json::parse(read_file(out_dir / "run.json"))["id"], id);

  ASSERT_EQ(client_export(context(), id, dir_ / "export-json", "json"), 0);
  const auto samples = nlohmann::json::parse(read_file(dir_ / "export-json" / "samples.json"));
  ASSERT_EQ(samples.size(), 250u);
  EXPECT_EQ(samples[249]["index"], 249);
  EXPECT_EQ(client_export(context(), "20990101T000000.000000Z", dir_ / "none", "csv"), 1);
  EXPECT_FALSE(std::filesystem::exists(dir_ / "none"));
}

TEST_F(ClientCommandsTest, ExportWritesMatAndHdf5FromTheApiPagesIntoItsOwnFolderOnly) {
  ASSERT_EQ(client_start(context(), "dynamic", {"seconds=0.25"}, true), 0);
  const auto id = client().get("/api/runs").body["runs"][0]["id"].get<std::string>();
  const auto out_dir = dir_ / "export";
  ASSERT_EQ(client_export(context(), id, out_dir, "mat"), 0) << err_.str();
  EXPECT_NE(out_.str().find("exported 250 samples"), std::string::npos) << out_.str();
  // An export's own folder takes the next format beside the first.
  ASSERT_EQ(client_export(context(), id, out_dir, "hdf5"), 0) << err_.str();
  EXPECT_NE(out_.str().find("samples.h5"), std::string::npos) << out_.str();
  EXPECT_EQ(read_file(out_dir / "samples.mat").substr(0, 19), "MATLAB 5.0 MAT-file");
  EXPECT_EQ(read_file(out_dir / "samples.h5").substr(0, 8), std::string("\x89HDF\r\n\x1a\n"));
  for (const auto& entry : std::filesystem::directory_iterator(out_dir)) {
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
  }
  // A folder the export did not write is refused before anything is fetched: exit 2.
  const auto foreign = dir_ / "foreign";
  std::filesystem::create_directories(foreign);
  std::ofstream(foreign / "notes.txt") << "mine\n";
  EXPECT_EQ(client_export(context(), id, foreign, "hdf5"), 2);
  EXPECT_NE(err_.str().find("--out"), std::string::npos) << err_.str();
  EXPECT_FALSE(std::filesystem::exists(foreign / "samples.h5"));
  EXPECT_EQ(client_export(context(), id, dir_ / "x", "xlsx"), 2);
  EXPECT_NE(err_.str().find("xlsx"), std::string::npos) << err_.str();
}

TEST_F(ClientCommandsTest, ExportDownloadFromTheApiIsTheFileTheCommandWrites) {
  ASSERT_EQ(client_start(context(), "dynamic", {"seconds=0.25"}, true), 0);
  const auto id = client().get("/api/runs").body["runs"][0]["id"].get<std::string>();
  ASSERT_EQ(client_export(context(), id, dir_ / "export", "csv"), 0) << err_.str();
  const auto csv = run_export_download(daemon_->store(), id,
                                       parse_http_target("/api/runs/" + id + "/export?format=csv"));
  ASSERT_EQ(csv.status, 200);
  // Sent in chunks (issue #22): the chunks together are the file the command writes.
  const auto whole = [](const ApiResponse& answer) {
    std::string body;
    if (!answer.chunks) return body;
    while (auto chunk = answer.chunks->next()) body += *chunk;
    return body;
  };
  ASSERT_TRUE(csv.chunks);
  EXPECT_EQ(whole(csv), read_file(dir_ / "export" / "samples.csv"));
  EXPECT_EQ(csv.content_type, "text/csv; charset=utf-8");
  const auto mat = run_export_download(daemon_->store(), id,
                                       parse_http_target("/api/runs/" + id + "/export?format=mat"));
  ASSERT_TRUE(mat.chunks);
  EXPECT_EQ(whole(mat).substr(0, 19), "MATLAB 5.0 MAT-file");
  // Through the routes: a bad format is 400 naming the key and the value.
  const auto bad = client().get("/api/runs/" + id + "/export?format=xlsx");
  EXPECT_EQ(bad.status, 400);
  EXPECT_NE(bad.error_text().find("format: got 'xlsx'"), std::string::npos) << bad.error_text();
  EXPECT_EQ(client().get("/api/runs/20990101T000000.000000Z/export?format=csv").status, 404);
}

TEST_F(ClientCommandsTest, StopAndReset) {
  EXPECT_EQ(client_stop(context()), 0);
  // The operator's stop is not a fault (issue #21): the bench is ready again by itself.
  EXPECT_TRUE(eventually([&] { return client().get("/api/status").body["state"] == "ready"; }));
  bench_->request_stop("over-torque");  // a real trip is one
  EXPECT_EQ(client().get("/api/status").body["state"], "fault");
  EXPECT_EQ(client_start(context(), "static", {}, false), 1);
  EXPECT_NE(err_.str().find("fault"), std::string::npos);
  EXPECT_EQ(client_reset(context()), 0);
  EXPECT_NE(out_.str().find("state        ready"), std::string::npos) << out_.str();
}

}  // namespace
}  // namespace wavebench::daemon::testing
