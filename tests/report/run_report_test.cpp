// Run reports from synthetic run folders written with the storage APIs: the page carries the
// tables' values and links its plots, the plots are PNG files, a missing or malformed section
// is left out without an error, text from the run is escaped, an aborted run shows its reason.
#include "wavebench/report/run_report.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include "wavebench/report/run_plots.hpp"
#include "wavebench/storage/run_store.hpp"
#include "wavebench/storage/sample_log.hpp"

namespace wavebench::report {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
constexpr double kPi = std::numbers::pi;
constexpr double kRadPerArcsec = kPi / (180.0 * 3600.0);

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::path(WAVEBENCH_BINARY_DIR) / "test-output" / "run-report" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

bool is_png(const fs::path& p) {
  std::error_code ec;
  if (!fs::is_regular_file(p, ec) || fs::file_size(p, ec) <= 8) return false;
  return slurp(p).substr(0, 8) == std::string("\x89PNG\r\n\x1a\n", 8);
}

std::size_t count(const std::string& haystack, const std::string& needle) {
  std::size_t n = 0;
  for (auto pos = haystack.find(needle); pos != std::string::npos;
       pos = haystack.find(needle, pos + 1)) {
    ++n;
  }
  return n;
}

// One run folder in a RunStore; samples, results and twin.csv as each test needs.
struct SyntheticRun {
  fs::path dir;
  std::string id;
};

SyntheticRun make_run(storage::RunStore& store, const std::string& procedure,
                      const std::string& serial, const json& results,
                      const std::vector<storage::SyncSample>& samples,
                      storage::RunStatus status = storage::RunStatus::kComplete,
                      const std::string& reason = {}) {
  SyntheticRun run;
  run.id = store.create_run(procedure, serial, "bench: sim\n");
  run.dir = store.paths(run.id).dir;
  if (!samples.empty()) {
    storage::SampleLogWriter log(store.paths(run.id).samples);
    for (auto s : samples) log.append(s);
    log.close();
  }
  if (!results.is_null()) store.write_results(run.id, results);
  store.finish_run(
      run.id, status, reason,
      status == storage::RunStatus::kComplete ? std::optional<bool>(true) : std::nullopt);
  return run;
}

storage::SyncSample sample(std::uint32_t i, double t, double th_in, double th_out, double torque) {
  storage::SyncSample s;
  s.sync_counter = 1 + i % 240;
  s.flags = storage::kAllChannelsValid;
  s.receive_time_ns = static_cast<std::int64_t>(std::llround(t * 1e9));
  s.theta_in_rad = th_in;
  s.theta_out_rad = th_out;
  s.input_speed_rad_s = 0;
  s.torque_nm = torque;
  return s;
}

json static_results() {
  json passes = json::array();
  const struct {
    const char* dir;
    double load, mean, p2p, std;
  } rows[] = {{"forward", 0, -1.6, 5.2, 1.8},
              {"reverse", 0, -1.9, 5.8, 2.0},
              {"forward", 60, 3.3, 6.5, 2.2},
              {"reverse", 60, 3.1, 6.1, 2.1}};
  for (const auto& r : rows) {
    json pts = json::array();
    for (int k = 0; k < 24; ++k) {
      const double a = 15.0 * k;
      pts.push_back({{"position", k},
                     {"output_angle_deg", a},
                     {"te_arcmin", r.mean + 0.5 * r.p2p * std::sin(a * kPi / 180)},
                     {"torque_nm", r.load}});
    }
    passes.push_back({{"direction", r.dir},
                      {"load_nm", r.load},
                      {"mean_arcmin", r.mean},
                      {"p2p_arcmin", r.p2p},
                      {"std_arcmin", r.std},
                      {"points", pts}});
  }
  return {{"procedure", "static"},
          {"acquisition", {{"missed_syncs", 3}, {"log_first_error", ""}}},
          {"settle_timeouts", 1},
          {"limit_checks",
           {{{"limit", "static_p2p_arcmin"},
             {"value", 6.0},
             {"measured", 6.5},
             {"what", "p2p, forward 60 N*m"},
             {"pass", false}}}},
          {"gear", {{"ratio", 80}, {"direction_sign", 1}}},
          {"static", passes},
          {"lost_motion",
           {{{"load_nm", 0}, {"mean_arcmin", 0.31}, {"max_arcmin", 0.47}},
            {{"load_nm", 60}, {"mean_arcmin", 0.22}, {"max_arcmin", 0.36}}}},
          {"load_shift",
           {{{"direction", "forward"},
             {"load_nm", 60},
             {"reference_load_nm", 0},
             {"shift_arcmin", 4.9},
             {"stiffness_nm_per_rad", 42093.0}}}},
          {"twin",
           {{"residual_before", {{"rms_arcsec", 41.5}}},
            {"residual_after", {{"rms_arcsec", 3.25}}},
            {"calibrated_config", "twin-calibrated.yaml"}}}};
}

void write_twin_csv(const fs::path& dir) {
  std::ofstream out(dir / "twin.csv");
  out << "t,index,measured_te_arcsec,predicted_te_arcsec,residual_arcsec\n";
  for (int i = 0; i < 500; ++i) {
    const double t = i * 1e-3;
    const double m = 30 * std::sin(2 * kPi * 3 * t), p = 28 * std::sin(2 * kPi * 3 * t + 0.05);
    out << t << "," << i << "," << m << "," << p << "," << m - p << "\n";
  }
}

class RunReportTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fresh_dir(::testing::UnitTest::GetInstance()->current_test_info()->name());
    store_ = std::make_unique<storage::RunStore>(root_ / "runs", "wavebench 9.9.9-test");
  }
  fs::path root_;
  std::unique_ptr<storage::RunStore> store_;
};

TEST_F(RunReportTest, StaticRunTablesPlotsAndTwin) {
  std::vector<storage::SyncSample> samples;
  for (std::uint32_t i = 0; i < 2000; ++i) {
    const double out = 2 * kPi * i / 2000.0;
    samples.push_back(sample(i, i * 1e-3, 80 * out, out + 1e-4 * std::sin(out), 0));
  }
  const auto run = make_run(*store_, "static", "HD-20-80 #0042", static_results(), samples);
  write_twin_csv(run.dir);

  const auto rep = write_run_report(run.dir);
  ASSERT_EQ(rep.html, run.dir / "report.html");
  const std::string html = slurp(rep.html);
  EXPECT_NE(html.find(run.id), std::string::npos);
  EXPECT_NE(html.find("HD-20-80 #0042"), std::string::npos);
  EXPECT_NE(html.find("wavebench 9.9.9-test"), std::string::npos);
  EXPECT_NE(html.find(">complete<"), std::string::npos);
  EXPECT_EQ(html.find("class=\"alert\">complete"), std::string::npos);
  // Per direction and load: mean, p2p, std in arcmin.
  for (const char* v : {">-1.60<", ">5.20<", ">1.80<", ">-1.90<", ">5.80<", ">2.00<", ">3.30<",
                        ">6.50<", ">2.20<", ">3.10<", ">6.10<", ">2.10<"}) {
    EXPECT_NE(html.find(v), std::string::npos) << v;
  }
  EXPECT_NE(html.find(">0.31<"), std::string::npos);  // lost motion at 0 N*m
  EXPECT_NE(html.find("<span class=\"alert\">FAIL</span>"), std::string::npos);
  EXPECT_NE(html.find(">4.90<"), std::string::npos);  // load shift
  EXPECT_NE(html.find("4.209e+04"), std::string::npos);
  EXPECT_NE(html.find("residual_after.rms_arcsec"), std::string::npos);
  EXPECT_NE(html.find(">3.25<"), std::string::npos);
  EXPECT_NE(html.find("<img src=\"static_te.png\""), std::string::npos);
  EXPECT_NE(html.find("<img src=\"twin.png\""), std::string::npos);
  EXPECT_EQ(html.find("spectrum.png"), std::string::npos);  // no dynamic section
  EXPECT_TRUE(is_png(run.dir / "static_te.png"));
  EXPECT_TRUE(is_png(run.dir / "twin.png"));
  EXPECT_EQ(rep.plots.size(), 2u);
  EXPECT_NE(html.find("<a href=\"samples.wbs\">samples.wbs</a>"), std::string::npos);
  EXPECT_NE(html.find("<td>missed_syncs</td><td>3</td>"), std::string::npos);
  EXPECT_NE(html.find("<td>settle_timeouts</td><td>1</td>"), std::string::npos);
  EXPECT_EQ(html.find("log_first_error"), std::string::npos);
  EXPECT_NE(html.find("<a href=\"results.json\">results.json</a>"), std::string::npos);
  EXPECT_FALSE(fs::exists(run.dir / ".static_te.png.tmp"));
}

TEST_F(RunReportTest, DynamicRunSpectrumPeaksAndAliased) {
  // N = 50, input 600 rpm (10 Hz): one output revolution in 5 s at 1 kHz, TE of 1/rev and of
  // the mesh (z_F = 100 per output revolution).
  const double n = 50, f_in = 10;
  std::vector<storage::SyncSample> samples;
  for (std::uint32_t i = 0; i < 6500; ++i) {
    const double t = i * 1e-3;
    // 0.5 s run-in from rest, then steady speed.
    const double th_in = t < 0.5 ? 2 * kPi * f_in * t * t : 2 * kPi * f_in * (t - 0.25);
    const double th2 = th_in / n;
    const double te = (20 * std::sin(th2) + 6 * std::sin(100 * th2)) * kRadPerArcsec;
    samples.push_back(sample(i, t, th_in, th2 + te, 0));
  }
  json dyn = {{"mean_arcsec", 0.04},
              {"p2p_arcsec", 51.7},
              {"rms_arcsec", 14.9},
              {"input_speed_hz", f_in},
              {"sample_rate_hz", 1000.0},
              {"nyquist_hz", 500.0},
              {"output_revolutions", 1.02},
              {"peaks",
               {{{"name", "output 1/rev"},
                 {"order_output", 1.0},
                 {"order_input", 0.02},
                 {"frequency_hz", 0.2},
                 {"amplitude_arcsec", 19.8}},
                {{"name", "mesh"},
                 {"order_output", 100.0},
                 {"order_input", 2.0},
                 {"frequency_hz", 20.0},
                 {"amplitude_arcsec", 5.97}}}},
              {"aliased",
               {{{"name", "tooth line 2*zC*fH"},
                 {"frequency_hz", 2040.0},
                 {"folded_hz", 40.0},
                 {"amplitude_arcsec", 0.4}}}}};
  const json results = {{"gear", {{"ratio", n}, {"direction_sign", 1}}}, {"dynamic", dyn}};
  const auto run = make_run(*store_, "dynamic", "SN-7", results, samples);

  const auto rep = write_run_report(run.dir);
  const std::string html = slurp(rep.html);
  for (const char* v :
       {">51.70<", ">14.90<", ">600.0<", "output 1/rev", "mesh", ">19.800<", ">5.970<", ">100.00<",
        "tooth line 2*zC*fH", ">2040.00<", ">40.00<", ">aliased<"}) {
    EXPECT_NE(html.find(v), std::string::npos) << v;
  }
  EXPECT_NE(html.find("<img src=\"dynamic_te.png\""), std::string::npos);
  EXPECT_NE(html.find("<img src=\"spectrum.png\""), std::string::npos);
  EXPECT_TRUE(is_png(run.dir / "dynamic_te.png"));
  EXPECT_TRUE(is_png(run.dir / "spectrum.png"));
}

TEST(DynamicTrace, LeavesTheRunInOutAndComputesTe) {
  const metrology::GearSense sense{50, 1};
  std::vector<storage::SyncSample> samples;
  for (std::uint32_t i = 0; i < 3000; ++i) {
    const double t = i * 1e-3;
    const double th_in = t < 0.5 ? 2 * kPi * 10 * t * t : 2 * kPi * 10 * (t - 0.25);
    samples.push_back(sample(i, t, th_in, th_in / 50 + 10 * kRadPerArcsec, 0));
  }
  const auto trace = dynamic_trace(samples, sense);
  ASSERT_TRUE(trace);
  // Steady from 0.5 s on; a 60-sample window's length is trimmed at each end at most.
  EXPECT_GT(trace->time_s.size(), 2380u);
  EXPECT_LE(trace->time_s.size(), 2500u);
  EXPECT_NEAR(trace->input_speed_hz, 10, 1e-9);
  EXPECT_NEAR(trace->te_arcsec.front(), 10, 1e-6);
  EXPECT_NEAR(trace->te_arcsec.back(), 10, 1e-6);
}

TEST_F(RunReportTest, LostMotionRunHysteresisWithFittedStiffness) {
  // Twist follows a three-segment compliance with ±0.5 arcmin branch offsets; torque follows
  // the direction of travel through a ladder.
  const double k1 = 3.0e4, k2 = 5.0e4, k3 = 7.0e4, t1 = 10, t2 = 30;
  const auto phi = [&](double t) {
    const double a = std::abs(t);
    const double p =
        std::min(a, t1) / k1 + std::clamp(a - t1, 0.0, t2 - t1) / k2 + std::max(a - t2, 0.0) / k3;
    return t >= 0 ? p : -p;
  };
  std::vector<storage::SyncSample> samples;
  std::uint32_t i = 0;
  for (const double travel : {1.0, -1.0}) {
    for (int rung = 0; rung <= 10; ++rung) {
      const double torque = travel * 6.0 * rung;
      for (int k = 0; k < 100; ++k, ++i) {
        const double twist = travel * 0.5 / 60 * kPi / 180 + phi(torque);
        samples.push_back(sample(i, i * 1e-3, 0.0, twist, torque));
      }
    }
  }
  const json results = {{"gear", {{"ratio", 100}, {"direction_sign", 1}}},
                        {"lost_motion_fit",
                         {{"lost_motion_arcmin", 1.23},
                          {"lost_motion_torque_nm", 1.8},
                          {"backlash_arcmin", 1.0},
                          {"hysteresis_loss_j", 0.0123},
                          {"stiffness",
                           {{"k1_nm_per_rad", k1},
                            {"k2_nm_per_rad", k2},
                            {"k3_nm_per_rad", k3},
                            {"t1_nm", t1},
                            {"t2_nm", t2},
                            {"rms_residual_arcsec", 0.8}}}}}};
  const auto run = make_run(*store_, "lost-motion", "SN-8", results, samples);
  const auto rep = write_run_report(run.dir);
  const std::string html = slurp(rep.html);
  for (const char* v : {">1.23<", ">1.80<", ">1.00<", ">0.0123<", ">3e+04<", ">5e+04<", ">7e+04<",
                        ">10.00<", ">30.00<", ">0.80<"}) {
    EXPECT_NE(html.find(v), std::string::npos) << v;
  }
  EXPECT_NE(html.find("<img src=\"hysteresis.png\""), std::string::npos);
  EXPECT_TRUE(is_png(run.dir / "hysteresis.png"));
  // "lost_motion" here is the fit, not a per-position static list: no static tables.
  EXPECT_EQ(html.find("Static TE"), std::string::npos);
}

TEST_F(RunReportTest, PlotsFromTheResultsAloneWithoutSamples) {
  // The dynamic results carry their analysed trace, the lost-motion fit its torque-twist
  // points: the plots need no samples.wbs.
  json t = json::array(), a = json::array(), te = json::array();
  for (int i = 0; i < 400; ++i) {
    t.push_back(i * 0.01);
    a.push_back(i * 0.9);
    te.push_back(12 * std::sin(i * 0.9 * kPi / 180) + 3 * std::sin(100 * i * 0.9 * kPi / 180));
  }
  json pts = json::array();
  for (const int travel : {1, -1}) {
    for (int rung = 1; rung <= 8; ++rung) {
      const double torque = travel * 5.0 * rung;
      pts.push_back(
          {{"torque_nm", torque}, {"twist_rad", torque / 4e4 + travel * 1e-4}, {"travel", travel}});
    }
  }
  const json results = {
      {"dynamic",
       {{"mean_arcsec", 0.5},
        {"p2p_arcsec", 30.0},
        {"rms_arcsec", 8.9},
        {"input_speed_hz", 1.6667},
        {"peaks", {{{"name", "mesh"}, {"frequency_hz", 0.33}, {"amplitude_arcsec", 3.0}}}},
        {"trace", {{"time_s", t}, {"output_angle_deg", a}, {"te_arcsec", te}}}}},
      {"lost_motion_fit",
       {{"lost_motion_arcmin", 0.69},
        {"lost_motion_torque_nm", 3.0},
        {"stiffness",
         {{"k1_nm_per_rad", 4e4},
          {"k2_nm_per_rad", 4e4},
          {"k3_nm_per_rad", 4e4},
          {"t1_nm", 10.0},
          {"t2_nm", 20.0}}},
        {"points", pts}}}};
  const auto run = make_run(*store_, "lost-motion", "SN-9", results, {});
  const auto rep = write_run_report(run.dir);
  const std::string html = slurp(rep.html);
  EXPECT_TRUE(is_png(run.dir / "dynamic_te.png"));
  EXPECT_TRUE(is_png(run.dir / "spectrum.png"));
  EXPECT_TRUE(is_png(run.dir / "hysteresis.png"));
  EXPECT_NE(html.find(">0.69<"), std::string::npos);
  EXPECT_NE(html.find(">8.90<"), std::string::npos);
  EXPECT_EQ(rep.plots.size(), 3u);
}

TEST_F(RunReportTest, MissingAndMalformedSectionsAreLeftOut) {
  // No results, no samples: the header and a note, nothing else.
  const auto bare = make_run(*store_, "static", "SN-1", json(), {});
  const auto rep = write_run_report(bare.dir);
  const std::string html = slurp(rep.html);
  EXPECT_NE(html.find(bare.id), std::string::npos);
  EXPECT_EQ(html.find("<img"), std::string::npos);
  EXPECT_NE(html.find("no results.json"), std::string::npos);
  EXPECT_TRUE(rep.plots.empty());

  // Sections of the wrong shape and values of the wrong type.
  const json odd = {{"static", "not a list"},
                    {"dynamic", {{"peaks", {1, "x", nullptr}}, {"rms_arcsec", "high"}}},
                    {"lost_motion", {{"stiffness", {{"k1_nm_per_rad", "stiff"}}}}},
                    {"twin", {{"residual", nullptr}}}};
  const auto weird = make_run(*store_, "dynamic", "SN-2", odd, {});
  EXPECT_NO_THROW(write_run_report(weird.dir));
  EXPECT_TRUE(fs::exists(weird.dir / "report.html"));

  // A results.json that is not JSON, a twin.csv with a bad row.
  const auto broken = make_run(*store_, "static", "SN-3", json::object(), {});
  {
    std::ofstream(broken.dir / "results.json") << "{ truncated";
    std::ofstream csv(broken.dir / "twin.csv");
    csv << "t,index,measured_te_arcsec,predicted_te_arcsec,residual_arcsec\n0,0,1,1,0\n"
        << "0.001,1,oops,1,0\n0.002,2,3,2,1\n";
  }
  const auto rep3 = write_run_report(broken.dir);
  const std::string html3 = slurp(rep3.html);
  EXPECT_NE(html3.find("results.json is not a JSON object"), std::string::npos);
  EXPECT_NE(html3.find("1 malformed rows skipped"), std::string::npos);
  EXPECT_TRUE(is_png(broken.dir / "twin.png"));
}

TEST_F(RunReportTest, TextFromTheRunIsEscaped) {
  json results = static_results();
  results["static"][0]["direction"] = "<b>fwd</b>";
  results["twin"]["calibrated_config"] = "a&b \"c\" 'd'.yaml";
  const auto run = make_run(*store_, "static", "<script>alert(1)</script>", results, {});
  const std::string html = slurp(write_run_report(run.dir).html);
  EXPECT_EQ(html.find("<script>"), std::string::npos);
  EXPECT_EQ(html.find("<b>fwd"), std::string::npos);
  EXPECT_NE(html.find("&lt;script&gt;alert(1)&lt;/script&gt;"), std::string::npos);
  EXPECT_NE(html.find("&lt;b&gt;fwd&lt;/b&gt;"), std::string::npos);
  EXPECT_NE(html.find("a&amp;b &quot;c&quot; &#39;d&#39;.yaml"), std::string::npos);
  EXPECT_EQ(html_escape("<&>\"'"), "&lt;&amp;&gt;&quot;&#39;");
}

TEST_F(RunReportTest, AbortedRunShowsItsReasonInRed) {
  std::vector<storage::SyncSample> samples;
  for (std::uint32_t i = 0; i < 100; ++i) samples.push_back(sample(i, i * 1e-3, 0, 0, 0));
  const auto run = make_run(*store_, "static", "SN-4", json::object(), samples,
                            storage::RunStatus::kAborted, "heartbeat lost: node 3 (encoder)");
  const std::string html = slurp(write_run_report(run.dir).html);
  EXPECT_NE(html.find("<span class=\"alert\">aborted: heartbeat lost: node 3 (encoder)</span>"),
            std::string::npos);
  EXPECT_NE(html.find("<p class=\"alert\">Run aborted: heartbeat lost: node 3 (encoder)</p>"),
            std::string::npos);
  EXPECT_NE(html.find("100 SYNC samples"), std::string::npos);
}

TEST_F(RunReportTest, SessionIndexLinksEachRunAndGathersTheTables) {
  const auto a = make_run(*store_, "static", "SN-5", static_results(), {});
  const auto b =
      make_run(*store_, "lost-motion", "SN-5",
               {{"lost_motion_fit",
                 {{"lost_motion_arcmin", 0.77}, {"stiffness", {{"k1_nm_per_rad", 1.5e4}}}}}},
               {}, storage::RunStatus::kAborted, "over-torque");
  write_run_report(a.dir);
  write_run_report(b.dir);
  const fs::path index = write_session_report(root_ / "runs", {a.dir, b.dir});
  ASSERT_EQ(index, root_ / "runs" / "index.html");
  const std::string html = slurp(index);
  EXPECT_NE(html.find("<a href=\"" + a.id + "/report.html\">" + a.id + "</a>"), std::string::npos);
  EXPECT_NE(html.find("<a href=\"" + b.id + "/report.html\">" + b.id + "</a>"), std::string::npos);
  EXPECT_NE(html.find(">-1.60<"), std::string::npos);
  EXPECT_NE(html.find(">0.77<"), std::string::npos);
  EXPECT_NE(html.find("aborted: over-torque"), std::string::npos);
  // The static run's four passes, each with the run id in the first column.
  EXPECT_GE(count(html, "<td>" + a.id + "</td>"), 4u);

  const std::string text = tables_as_text(session_tables({{a.dir, {}}, {b.dir, {}}}));
  EXPECT_NE(text.find("Static TE per direction and load"), std::string::npos);
  EXPECT_NE(text.find("-1.60"), std::string::npos);
  EXPECT_NE(text.find("aborted: over-torque"), std::string::npos);
}

TEST_F(RunReportTest, NotARunFolderIsAnError) {
  EXPECT_THROW(write_run_report(root_ / "does-not-exist"), std::invalid_argument);
  fs::create_directories(root_ / "empty");
  try {
    write_run_report(root_ / "empty");
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("holds none of status.json"), std::string::npos);
  }
  EXPECT_FALSE(fs::exists(root_ / "empty" / "report.html"));
}

TEST(GearSenseEstimate, RecoversRatioAndSign) {
  std::vector<storage::SyncSample> samples;
  for (std::uint32_t i = 0; i < 1000; ++i) {
    const double out = -0.5 * i / 1000.0;
    samples.push_back(sample(i, i * 1e-3, -80 * out + 1e-3 * std::sin(40 * out), out, 0));
  }
  const auto sense = estimate_gear_sense(samples);
  ASSERT_TRUE(sense);
  EXPECT_EQ(sense->ratio, 80);
  EXPECT_EQ(sense->direction_sign, -1);
  samples.resize(5);  // the output hardly moved
  EXPECT_FALSE(estimate_gear_sense(samples));
}

}  // namespace
}  // namespace wavebench::report

namespace wavebench::report {
namespace {

TEST(StaticTeFigure, MultiTurnAnglesFromPositionZeroWithinOneRevolution) {
  json passes = json::array();
  for (const char* dir : {"forward", "reverse"}) {
    json pts = json::array();
    for (int k = 0; k < 24; ++k) {
      // 2047 turns in, and position 0 of the reverse pass a hair below a whole turn.
      const double a = 2047 * 360.0 + 15.0 * k + (k == 0 && dir[0] == 'r' ? -1e-3 : 0.0);
      pts.push_back({{"position", k}, {"output_angle_deg", a}, {"te_arcmin", 0.1 * k}});
    }
    passes.push_back({{"direction", dir}, {"load_nm", 0}, {"points", pts}});
  }
  const auto fig = static_te_figure(passes);
  ASSERT_TRUE(fig);
  ASSERT_EQ(fig->rows(), 1);
  int checked = 0;
  for (const auto& s : fig->axes(0, 0).series) {
    ASSERT_EQ(s.x.size(), 24u);
    EXPECT_NEAR(s.x.front(), 0, 2e-3);
    EXPECT_NEAR(s.x.back(), 345, 1e-9);
    EXPECT_NEAR(s.y.front(), 0, 1e-12);  // position 0 first, whichever side it came from
    ++checked;
  }
  EXPECT_EQ(checked, 4);  // a line and its points per direction
}

}  // namespace
}  // namespace wavebench::report
