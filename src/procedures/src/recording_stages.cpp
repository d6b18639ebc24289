#include "recording_stages.hpp"

#include <filesystem>

#include "wavebench/procedures/sample_log_observer.hpp"
#include "wavebench/procedures/software_version.hpp"
#include "wavebench/storage/sample_log.hpp"
#include "wavebench/twin/unit_twin_store.hpp"

namespace wavebench::procedures {

namespace {

nlohmann::json acquisition_json(const bench::AcquisitionStats& a,
                                const storage::SampleLogWriter& writer,
                                const SampleLogObserver& log) {
  const auto& g = writer.gap_totals();
  return {{"samples_logged", writer.records_flushed()},
          {"log_write_errors", log.samples_not_logged()},
          {"log_queue_dropped", log.samples_dropped()},
          {"log_first_error", log.failure()},
          {"missed_syncs", g.missed_cycles},
          {"incomplete_samples", g.incomplete_samples},
          {"gaps", g.gaps},
          {"counter_anomalies", g.anomalies},
          {"bench_syncs_sent", a.syncs_sent},
          {"bench_samples", a.samples},
          {"bench_incomplete_samples", a.incomplete_samples},
          {"bench_sync_late", a.sync_late},
          {"bench_sync_skipped", a.sync_skipped},
          {"bench_bus_load", a.bus_load}};
}

// The bench's measuring devices with the calibration its config states (null: not stated).
nlohmann::json sensors_json(const std::vector<bench::SensorCalibration>& sensors) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& s : sensors) {
    out.push_back({{"sensor", s.sensor},
                   {"calibration_id", s.id.empty() ? nlohmann::json() : nlohmann::json(s.id)},
                   {"calibration_due", s.due.empty() ? nlohmann::json() : nlohmann::json(s.due)}});
  }
  return out;
}

// results.json "spec": what the verdict was judged against.
nlohmann::json spec_json(const ProductSpec& spec) {
  const auto j = spec.to_json();
  return {{"name", j["name"]},
          {"model", j["model"]},
          {"description", j["description"]},
          {"lost_motion_at_percent", j["lost_motion_at_percent"]},
          {"undecided", j["undecided"]},
          {"limits", j["limits"]}};
}

nlohmann::json results_head(const RunContext& c, const bench::Bench& bench) {
  const auto& d = c.description;
  const auto& r = c.request;
  return {{"schema", kResultsSchema},
          {"run_id", c.outcome.run_id},
          {"procedure", r.procedure},
          {"unit_serial", c.unit_serial},
          {"operator",
           r.operator_name.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.operator_name)},
          {"bench", d.name},
          {"bench_sensors", sensors_json(d.sensors)},
          {"software_version", software_version()},
          {"software_commit", software_commit()},
          {"gear", {{"ratio", d.sense.ratio}, {"direction_sign", d.sense.direction_sign}}},
          {"sync_period_s", d.sync_period_s},
          {"simulated_clock", d.simulated_clock},
          {"absent_channels", bench.absent_channels()},
          {"options", c.parsed.procedure_options},
          {"limits", c.parsed.limits},
          {"spec", r.spec ? spec_json(*r.spec) : nlohmann::json()}};
}

// The twin beside the bench: the unit's own when it has one on disk now (calibrated over its
// earlier runs, unit_twin_store.hpp), else the bench's nominal twin case.
void choose_twin(RunContext& c) {
  c.twin_gear = c.description.twin_gear;
  c.twin_source = {{"kind", "nominal"}, {"case", c.description.twin_case_path}};
  if (!c.request.twin || c.unit_serial.empty()) return;
  try {
    auto unit = twin::load_unit_twin(c.store->root(), c.unit_serial, c.description.sense.ratio);
    if (!unit) return;
    c.twin_gear = std::move(unit->twin.gear);
    c.twin_solver = unit->solver;
    nlohmann::json from = nlohmann::json::array();
    for (const auto& r : unit->provenance.value("runs", nlohmann::json::array())) {
      from.push_back({{"run_id", r.value("run_id", "")}, {"procedure", r.value("procedure", "")}});
    }
    c.twin_source = {{"kind", "unit"},
                     {"case", std::filesystem::relative(unit->case_file, c.store->root()).string()},
                     {"calibrated_from", from}};
  } catch (const std::exception& e) {
    c.results["warnings"].push_back(std::string(e.what()) + "; the nominal twin case is used");
  }
}

void start_twin(RunContext& c) {
  if (!c.request.twin) return;
  try {
    twin::TwinBesideBenchOptions options;
    options.diagnosis.sensor_noise_rad = c.description.output_encoder_noise_rad;
    if (c.request.on_diagnosis) {
      // The context outlives the twin's thread (finish() joins it).
      options.on_flag = [&c](const twin::DiagnosticFlag& flag) {
        if (c.request.on_diagnosis) c.request.on_diagnosis(twin::to_json(flag));
      };
    }
    options.solver = c.twin_solver;
    options.overlay_csv = c.paths.dir / "twin.csv";
    if (c.description.simulated_clock) options.lockstep_backlog = 1024;
    c.twin_beside =
        std::make_unique<twin::TwinBesideBench>(c.twin_gear, c.description.sense, options);
  } catch (const std::exception& e) {
    c.twin_json = {{"error", std::string("twin not started: ") + e.what()}};
  }
}

}  // namespace

void ResultsHeadStage::start(RunContext& c, bench::Bench& bench) {
  c.results = results_head(c, bench);
  const auto extra_channels = bench.extra_channels();
  if (!extra_channels.empty()) {
    nlohmann::json channels = nlohmann::json::array();
    for (const auto& ch : extra_channels) {
      channels.push_back({{"name", ch.name}, {"unit", ch.unit}});
    }
    c.results["extra_channels"] = channels;
  }
}

// The writer and its observer together: the observer writes through the writer.
struct SampleLogStage::Log {
  Log(const std::filesystem::path& file, const storage::SampleLogWriterOptions& options,
      bench::Bench& bench)
      : writer(file, options), observer(writer, bench) {}
  storage::SampleLogWriter writer;
  SampleLogObserver observer;
};

SampleLogStage::SampleLogStage() = default;
SampleLogStage::~SampleLogStage() = default;

void SampleLogStage::start(RunContext& c, bench::Bench& bench) {
  try {
    storage::SampleLogWriterOptions options;
    options.extra_channels = bench.extra_channels();
    log_ = std::make_unique<Log>(c.paths.samples, options, bench);
  } catch (const std::exception& e) {
    c.abort_with(std::string("sample log not created, nothing moved: ") + e.what());
  }
}

bool SampleLogStage::observes() const {
  return log_ != nullptr;
}

void SampleLogStage::on_sample(const storage::SyncSample& sample) noexcept {
  log_->observer.on_sample(sample);
}

std::optional<std::string> SampleLogStage::trip_reason() const {
  if (log_ && log_->observer.failed()) return log_->observer.failure();
  return std::nullopt;
}

void SampleLogStage::finish(RunContext& c) {
  if (!log_) return;
  // Every queued sample to the file before the run is finalised. The log may fail after the
  // procedure's last blocking call, or while draining: the run is still missing samples.
  log_->observer.finish();
  if (log_->observer.failed()) c.abort_with(log_->observer.failure());
}

void SampleLogStage::close(RunContext& c, const bench::Bench& bench) {
  if (!log_) return;
  try {
    log_->writer.close();
  } catch (const std::exception& e) {
    c.abort_with(std::string("sample log: not closed cleanly: ") + e.what());
  }
  c.samples = log_->writer.records_flushed();
  c.results["acquisition"] =
      acquisition_json(bench.acquisition_stats(), log_->writer, log_->observer);
  if (log_->observer.samples_dropped() > 0) {
    c.results["warnings"].push_back(
        "sample log: " + std::to_string(log_->observer.samples_dropped()) +
        " samples dropped, its queue was full (the disk fell behind)");
  }
}

void TwinBesideBenchStage::start(RunContext& c, bench::Bench& /*bench*/) {
  choose_twin(c);
  start_twin(c);
  twin_ = c.twin_beside.get();
}

void TwinBesideBenchStage::on_sample(const storage::SyncSample& sample) noexcept {
  twin_->on_sample(sample);
}

std::vector<std::unique_ptr<RecordingStage>> recording_stages() {
  std::vector<std::unique_ptr<RecordingStage>> stages;
  stages.push_back(std::make_unique<ResultsHeadStage>());
  stages.push_back(std::make_unique<SampleLogStage>());
  stages.push_back(std::make_unique<TwinBesideBenchStage>());
  return stages;
}

}  // namespace wavebench::procedures
