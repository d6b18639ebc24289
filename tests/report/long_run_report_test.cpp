// The report of a long record read in pages (issue #12): a synthetic 300,000-sample dynamic run
// folder (benchmarks/long_runs/synthetic_run). What the report draws from samples.wbs and
// twin.csv, streamed, equals the reduction of the whole record in memory (dynamic_trace and
// analysis::min_max_columns); its facts equal the counts over the whole log; the averaged
// spectrum reads the record's lines; the page has its tables and plots.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../../benchmarks/long_runs/synthetic_run.hpp"
#include "wavebench/analysis/min_max_columns.hpp"
#include "wavebench/report/dynamic_plot_data.hpp"
#include "wavebench/report/run_folder.hpp"
#include "wavebench/report/run_plots.hpp"
#include "wavebench/report/run_report.hpp"
#include "wavebench/report/sample_log_scan.hpp"
#include "wavebench/report/twin_csv_envelope.hpp"
#include "wavebench/storage/sample_log.hpp"

namespace wavebench::report {
namespace {

namespace fs = std::filesystem;
constexpr std::size_t kColumns = 1000;

void expect_same_rows(const analysis::DecimatedTrace& got, const analysis::DecimatedTrace& want) {
  EXPECT_EQ(got.full_resolution, want.full_resolution);
  EXPECT_EQ(got.samples_in_range, want.samples_in_range);
  ASSERT_EQ(got.t, want.t);
  ASSERT_EQ(got.series.size(), want.series.size());
  for (std::size_t k = 0; k < got.series.size(); ++k) EXPECT_EQ(got.series[k], want.series[k]);
}

class LongRunReport : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    // One folder per process: ctest runs each test in its own, several at a time.
    base_ = fs::path(WAVEBENCH_BINARY_DIR) / "test-output" /
            ("long-run-report-" + std::to_string(::getpid()));
    fs::remove_all(base_);
    dir_ = base_ / "run";
    spec_.samples = 300'000;  // 5 output revolutions at 100 rpm, N = 100
    benchmarks::write_synthetic_run_files(dir_, spec_);
    whole_ = new std::vector<storage::SyncSample>(
        storage::read_sample_log(dir_ / "samples.wbs").samples);
  }
  static void TearDownTestSuite() {
    delete whole_;
    whole_ = nullptr;
    fs::remove_all(base_);
  }
  static metrology::GearSense sense() {
    metrology::GearSense s;
    s.ratio = spec_.ratio;
    return s;
  }
  static inline fs::path base_, dir_;
  static inline benchmarks::SyntheticRunSpec spec_;
  static inline std::vector<storage::SyncSample>* whole_ = nullptr;
};

TEST_F(LongRunReport, FactsAndGearSenseEqualThoseOfTheWholeLog) {
  const RunFolder run = read_run_folder(dir_);
  ASSERT_TRUE(run.sample_log);
  std::uint64_t missed = 0, incomplete = 0;
  for (const auto& s : *whole_) {
    missed += s.missed_before;
    incomplete += s.complete() ? 0 : 1;
  }
  EXPECT_EQ(run.sample_log->records, whole_->size());
  EXPECT_EQ(run.sample_log->records, 300'000u);
  EXPECT_EQ(run.sample_log->missed, missed);
  EXPECT_EQ(run.sample_log->missed, 2u);  // one SYNC missed every 100,000 samples
  EXPECT_EQ(run.sample_log->incomplete, incomplete);
  EXPECT_EQ(run.sample_log->angle_samples, whole_->size());

  GearSenseFit fit;
  scan_sample_log(run.samples_path(), 0, run.sample_log->records,
                  [&](const storage::SyncSample& s) { fit.add(s); });
  const auto streamed = fit.result();
  const auto in_memory = estimate_gear_sense(*whole_);
  ASSERT_TRUE(streamed && in_memory);
  EXPECT_EQ(streamed->ratio, in_memory->ratio);
  EXPECT_EQ(streamed->ratio, 100.0);
  EXPECT_EQ(streamed->direction_sign, in_memory->direction_sign);
}

TEST_F(LongRunReport, DynamicEnvelopesEqualTheWholeRecordReduction) {
  const RunFolder run = read_run_folder(dir_);
  analysis::SpectrumAnalyser analyser;
  const auto got =
      dynamic_plot_data(run.samples_path(), *run.sample_log, sense(), kColumns, analyser);
  const auto trace = dynamic_trace(*whole_, sense());
  ASSERT_TRUE(got && trace);
  EXPECT_EQ(got->samples, trace->te_arcsec.size());
  EXPECT_EQ(got->input_speed_hz, trace->input_speed_hz);
  EXPECT_NEAR(got->input_speed_hz, spec_.input_rpm / 60, 1e-3);
  // The steady part leaves out both 2 s ramps and little more.
  EXPECT_GT(got->samples, 295'000u);
  EXPECT_LT(got->samples, 296'100u);

  const std::vector<std::span<const double>> te{trace->te_arcsec};
  expect_same_rows(got->te_by_time,
                   analysis::min_max_columns(trace->time_s, te, 0, trace->time_s.back(), kColumns));
  ASSERT_TRUE(std::is_sorted(trace->output_angle_deg.begin(), trace->output_angle_deg.end()));
  expect_same_rows(
      got->te_by_angle,
      analysis::min_max_columns(trace->output_angle_deg, te, trace->output_angle_deg.front(),
                                trace->output_angle_deg.back(), kColumns));
  EXPECT_FALSE(got->te_by_time.full_resolution);
  EXPECT_EQ(got->te_by_time.t.size(), 2 * kColumns);

  // Without the folder pass's summary of the input speed (three passes instead): the same.
  ASSERT_TRUE(run.sample_log->input_speeds);
  EXPECT_TRUE(run.sample_log->input_speeds->fits(run.sample_log->angle_samples));
  SampleLogFacts bare = *run.sample_log;
  bare.input_speeds.reset();
  const auto slow = dynamic_plot_data(run.samples_path(), bare, sense(), kColumns, analyser);
  ASSERT_TRUE(slow);
  EXPECT_EQ(slow->samples, got->samples);
  expect_same_rows(slow->te_by_time, got->te_by_time);
  expect_same_rows(slow->te_by_angle, got->te_by_angle);
}

TEST_F(LongRunReport, SamplesWithoutAnglesAreLeftOutAsDynamicTraceLeavesThem) {
  // 40,000 samples, every 997th without its angles and every 1009th a repeated time; the
  // plots read both ways (the folder pass's summary, three passes) leave them out.
  const fs::path dir = dir_.parent_path() / "long-run-report-gaps";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::vector<storage::SyncSample> samples(whole_->begin(), whole_->begin() + 40'000);
  for (std::size_t i = 0; i < samples.size(); ++i) {
    if (i % 997 == 5) samples[i].flags &= ~storage::kThetaOutValid;
    if (i % 1009 == 7) samples[i].receive_time_ns = samples[i - 1].receive_time_ns;
  }
  {
    storage::SampleLogWriter log(dir / "samples.wbs");
    for (const auto& s : samples) log.append(s);
  }
  const RunFolder run = read_run_folder(dir);
  ASSERT_TRUE(run.sample_log);
  EXPECT_LT(run.sample_log->angle_samples, 40'000u - 40u);
  SampleLogFacts bare = *run.sample_log;
  bare.input_speeds.reset();
  analysis::SpectrumAnalyser analyser;
  const auto trace = dynamic_trace(samples, sense());
  ASSERT_TRUE(trace);
  EXPECT_LT(trace->te_arcsec.size(), 40'000u - 2'000u - 40u);  // the run-in and the gaps left out
  const std::vector<std::span<const double>> te{trace->te_arcsec};
  const std::vector<const SampleLogFacts*> both{&*run.sample_log, &bare};
  for (const SampleLogFacts* facts : both) {
    SCOPED_TRACE(facts->input_speeds ? "summary" : "three passes");
    const auto got = dynamic_plot_data(run.samples_path(), *facts, sense(), kColumns, analyser);
    ASSERT_TRUE(got);
    EXPECT_EQ(got->samples, trace->te_arcsec.size());
    expect_same_rows(got->te_by_time, analysis::min_max_columns(trace->time_s, te, 0,
                                                                trace->time_s.back(), kColumns));
    expect_same_rows(
        got->te_by_angle,
        analysis::min_max_columns(trace->output_angle_deg, te, trace->output_angle_deg.front(),
                                  trace->output_angle_deg.back(), kColumns));
  }
}

TEST_F(LongRunReport, AveragedSpectrumReadsTheRecordsLines) {
  const RunFolder run = read_run_folder(dir_);
  analysis::SpectrumAnalyser analyser;
  const auto got =
      dynamic_plot_data(run.samples_path(), *run.sample_log, sense(), kColumns, analyser);
  ASSERT_TRUE(got && got->spectrum);
  // 296 k samples is past the whole-record limit: segments of two output revolutions (60,000
  // samples each at 1 kHz and 1 rpm out), half overlapping.
  EXPECT_EQ(got->spectrum->samples, 120'000u);
  EXPECT_EQ(got->spectrum_segments, 3u);
  const double f_out = spec_.input_rpm / 60 / spec_.ratio;
  const auto amplitude_at = [&](double order) {
    const auto& s = *got->spectrum;
    return s.amplitude.at(static_cast<std::size_t>(std::lround(order * f_out / s.resolution_hz)));
  };
  // Whole revolutions per segment: each line on a bin, read at its amplitude.
  EXPECT_NEAR(amplitude_at(1), spec_.te_1_arcsec, 0.02 * spec_.te_1_arcsec);
  EXPECT_NEAR(amplitude_at(2), spec_.te_2_arcsec, 0.02 * spec_.te_2_arcsec);
  EXPECT_NEAR(amplitude_at(2 * spec_.ratio), spec_.te_mesh_arcsec, 0.02 * spec_.te_mesh_arcsec);
  EXPECT_LT(amplitude_at(77.5), 0.05);  // between the lines: the noise floor
}

// twin.csv in memory, as the old reader took it.
struct TwinColumns {
  std::vector<double> t, measured, predicted, residual;
};

TwinColumns read_whole_twin_csv(const fs::path& path) {
  TwinColumns c;
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    std::vector<double> v;
    std::istringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) v.push_back(std::stod(cell));
    c.t.push_back(v.at(0));
    c.measured.push_back(v.at(2));
    c.predicted.push_back(v.at(3));
    c.residual.push_back(v.at(4));
  }
  return c;
}

TEST_F(LongRunReport, TwinEnvelopeEqualsTheWholeFilesReduction) {
  const RunFolder run = read_run_folder(dir_);
  ASSERT_TRUE(run.twin);
  const auto whole = read_whole_twin_csv(dir_ / "twin.csv");
  ASSERT_EQ(whole.t.size(), 300'000u);
  EXPECT_EQ(run.twin->rows, whole.t.size());
  const std::vector<std::span<const double>> series{whole.measured, whole.predicted,
                                                    whole.residual};
  const auto want =
      analysis::min_max_columns(whole.t, series, whole.t.front(), whole.t.back(), kEnvelopeColumns);
  EXPECT_EQ(run.twin->t, want.t);
  EXPECT_EQ(run.twin->measured_te_arcsec, want.series[0]);
  EXPECT_EQ(run.twin->predicted_te_arcsec, want.series[1]);
  EXPECT_EQ(run.twin->residual_arcsec, want.series[2]);
  EXPECT_EQ(run.twin->t.size(), 2 * kEnvelopeColumns);
}

TEST_F(LongRunReport, TorqueTwistOfALongRecordIsBoundedAndKeepsItsExtent) {
  const RunFolder run = read_run_folder(dir_);
  const auto curve = torque_twist_from_log(run.samples_path(), run.sample_log->records, sense());
  const auto all = torque_twist_from_samples(*whole_, sense());
  ASSERT_TRUE(curve && all);
  EXPECT_LE(curve->torque_nm.size(), 2u * 640 * 360);  // a point per cell at most
  EXPECT_LT(curve->torque_nm.size(), all->torque_nm.size() / 5);
  // The first point of each occupied cell: the extremes within a cell of the true ones.
  const auto [lo, hi] = std::minmax_element(all->torque_nm.begin(), all->torque_nm.end());
  const auto [clo, chi] = std::minmax_element(curve->torque_nm.begin(), curve->torque_nm.end());
  const double cell = (*hi - *lo) / 360;
  EXPECT_NEAR(*clo, *lo, cell);
  EXPECT_NEAR(*chi, *hi, cell);
}

TEST_F(LongRunReport, ReportHasItsTablesAndPlots) {
  const fs::path out = dir_.parent_path() / "long-run-report-page";
  fs::remove_all(out);
  const auto report = write_run_report(dir_, out);
  std::ifstream in(report.html);
  const std::string html((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(html.find("300000 SYNC samples, 2 cycles missed, 0 incomplete"), std::string::npos);
  EXPECT_NE(html.find("Dynamic TE"), std::string::npos);
  EXPECT_NE(html.find("mesh 2N"), std::string::npos);  // the peaks table from results.json
  for (const char* png : {"dynamic_te.png", "spectrum.png", "twin.png"}) {
    EXPECT_TRUE(fs::is_regular_file(out / png)) << png;
    EXPECT_NE(html.find(std::string("<img src=\"") + png), std::string::npos) << png;
  }
}

TEST(TwinCsvEnvelope, RowsOutOfTimeOrderAndALastRowWithoutNewline) {
  const fs::path dir = fs::path(WAVEBENCH_BINARY_DIR) / "test-output" / "twin-csv-envelope";
  fs::create_directories(dir);
  {
    std::ofstream out(dir / "twin.csv");
    out << "t,index,measured_te_arcsec,predicted_te_arcsec\r\n";  // no residual column
    for (int i = 0; i < 10; ++i) {
      out << i << "," << i << "," << 2 * i << "," << i << "\r\n";
      if (i == 4) out << "-1,99,7,7\r\n0.5,bad,1\r\n";  // before the first row; malformed
    }
    out << "9.5,10,3,1";  // the last row, no newline: it ends the time range
  }
  std::vector<std::string> notes;
  const auto twin = read_twin_csv_envelope(dir / "twin.csv", 100, notes);
  ASSERT_TRUE(twin);
  EXPECT_EQ(twin->rows, 12u);
  EXPECT_EQ(twin->t, (std::vector<double>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 9.5}));
  EXPECT_EQ(twin->residual_arcsec, (std::vector<double>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 2}));
  ASSERT_EQ(notes.size(), 2u);
  EXPECT_EQ(notes[0], "twin.csv: 1 malformed rows skipped");
  EXPECT_EQ(notes[1], "twin.csv: 1 rows out of time order left out of the plot");
}

}  // namespace
}  // namespace wavebench::report
