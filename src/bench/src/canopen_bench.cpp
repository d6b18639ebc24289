#include "wavebench/bench/canopen_bench.hpp"

#include <spdlog/spdlog.h>

#include <boost/asio/post.hpp>
#include <cmath>

#include "wavebench/bench/bench_devices.hpp"
#include "wavebench/can/event_loop.hpp"
#include "wavebench/canopen/nmt.hpp"
#include "wavebench/canopen/pdo.hpp"
#include "wavebench/canopen/sdo_abort.hpp"

namespace wavebench::bench {
namespace {

using Clock = std::chrono::steady_clock;

std::chrono::milliseconds ms(double seconds) {
  return std::chrono::milliseconds(std::max<long>(1, std::lround(seconds * 1e3)));
}

std::string hex16(unsigned v) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "0x%04X", v & 0xFFFFU);
  return buf;
}

// Bits on the wire of a classic heartbeat frame, with a typical stuffing allowance.
constexpr double kHeartbeatFrameBits = (47.0 + 8.0) * 1.2;

}  // namespace

CanopenBench::CanopenBench(BenchConfig config, can::CanBus& bus)
    : config_(std::move(config)),
      bus_(bus),
      io_(bus.context()),
      limits_check_(config_.description.limits, config_.description.sense) {
  config_.description.sense.validate();
  auto devices = make_bench_devices(config_);
  drive_ = std::move(devices.drive);
  sensors_ = std::move(devices.sensors);
  drive_->bind({slot::kThetaIn, slot::kInputSpeed});
  sensors_[0]->bind({slot::kThetaOut});
  sensors_[1]->bind({slot::kTorque});
  for (std::size_t i = 2; i < sensors_.size(); ++i) sensors_[i]->bind({ChannelSlot::extra(i - 2)});
  brake_ = std::make_unique<PowderBrakeDevice>(config_.brake,
                                               static_cast<modbus::BrakeEventSink&>(*this));
  brake_->bind({slot::kBrakeCurrent, slot::kBrakeTorque});

  canopen::Master::Hooks hooks;
  hooks.on_emcy = [this](const canopen::Emergency& e) {
    for (auto* d : canopen_devices())
      if (d->node() == e.node) d->on_emcy(e);
    if (e.is_reset()) return;
    trip("EMCY from node " + std::to_string(e.node) + " (" + node_name(e.node) + "): error code " +
         hex16(e.error_code) + " (" + canopen::describe_emcy_code(e.error_code) + ")");
  };
  hooks.on_bus_event = [this](const can::BusEvent& e) {
    if (e.kind == can::BusEventKind::bus_off && acquiring_)
      trip(std::string("CAN controller bus-off on ") + std::string(bus_.name()));
  };
  master_ =
      std::make_unique<canopen::Master>(bus_, std::move(hooks), ms(config_.can.sdo_timeout_s));
  const double period = config_.description.sync_period_s;
  if (config_.description.simulated_clock) {
    // Late answers are waited for up to half the heartbeat timeout: the other nodes answer
    // SYNCs again before the heartbeat watch judges them.
    const double timeout = config_.description.limits.heartbeat_timeout_s;
    clock_ = std::make_unique<SimulatedSyncClock>(bus_, period, ms(config_.can.cycle_timeout_s),
                                                  ms(timeout > 0 ? timeout / 2 : 1.0));
  } else {
    auto real = std::make_unique<RealSyncClock>(
        *master_, std::chrono::microseconds(std::lround(period * 1e6)));
    real->on_tick([this](const canopen::SyncProducer::Tick& tick) {
      engine_->add_lateness(std::chrono::duration<double>(tick.sent - tick.deadline).count());
      if (tick_hook_) tick_hook_(tick);
    });
    clock_ = std::move(real);
  }
  engine_ = std::make_unique<CycleEngine>(*master_, *clock_);
}

CanopenBench::~CanopenBench() {
  disconnect();
  *alive_ = false;
  subscriptions_.clear();
}

std::vector<CanopenDevice*> CanopenBench::canopen_devices() const {
  std::vector<CanopenDevice*> out{drive_.get()};
  for (const auto& d : sensors_) out.push_back(d.get());
  return out;
}

std::vector<const BenchDevice*> CanopenBench::devices() const {
  std::vector<const BenchDevice*> out;
  for (auto* d : canopen_devices()) out.push_back(d);
  out.push_back(brake_.get());
  return out;
}

std::string CanopenBench::node_name(canopen::NodeId node) const {
  for (auto* d : canopen_devices())
    if (d->node() == node) return d->name();
  return "unknown node";
}

std::vector<canopen::NodeId> CanopenBench::all_nodes() const {
  std::vector<canopen::NodeId> nodes;
  for (auto* d : canopen_devices()) nodes.push_back(d->node());
  return nodes;
}

std::vector<storage::ChannelInfo> CanopenBench::extra_channels() const {
  std::vector<storage::ChannelInfo> channels;
  for (std::size_t i = 2; i < sensors_.size(); ++i)
    for (const auto& c : sensors_[i]->channels()) channels.push_back(c);
  return channels;
}

std::vector<BenchDeviceInfo> CanopenBench::device_info() const {
  std::vector<BenchDeviceInfo> out;
  auto describe = [](const BenchDevice& d, std::optional<std::uint8_t> node) {
    BenchDeviceInfo info{d.name(), node, d.channels(), {}};
    for (const auto& c : d.commands()) info.commands.push_back({c.name, c.unit});
    return info;
  };
  for (auto* d : canopen_devices()) out.push_back(describe(*d, d->node()));
  out.push_back(describe(*brake_, std::nullopt));
  return out;
}

std::string CanopenBench::fault_reason() const {
  std::lock_guard lock(reason_mutex_);
  return reason_;
}

void CanopenBench::set_state(BenchLifecycle state) noexcept {
  if (lifecycle_.exchange(state) == state) return;
  drive_->on_state_change(state);
  for (const auto& d : sensors_) d->on_state_change(state);
  brake_->on_state_change(state);
}

// --- connect / disconnect -------------------------------------------------------------------

void CanopenBench::connect() {
  if (operational(state())) return;
  if (state() == BenchLifecycle::kFault) {
    clear_fault();
    return;
  }
  {
    std::lock_guard lock(reason_mutex_);
    reason_.clear();
  }
  tripped_ = false;
  mode_.reset();
  powered_ = false;
  quick_stop_watch_.reset();
  clock_->reset();
  try {
    if (const auto problems = eds_problems(config_); !problems.empty()) {
      std::string text = "the EDS disagrees with the objects the bench uses";
      for (const auto& p : problems) text += "; " + p;
      throw std::runtime_error(text);
    }
    brake_->connect(clock_->simulated());
    configure_nodes();
    start_acquisition();
    set_mode(canopen::OperationMode::profile_position);
    // Inactive until a run needs the drive: a drive left enabled (a master that died mid-run)
    // or in fault is brought to its power-off state here.
    drive_command("disable voltage",
                  [&] { drive_->drive().go_to(canopen::Cia402State::switch_on_disabled); });
    const auto can_channels = storage::kThetaInValid | storage::kThetaOutValid |
                              storage::kInputSpeedValid | storage::kTorqueValid;
    if (!run_until([&] { return (latest_sample().flags & can_channels) == can_channels; }, 5.0)) {
      throw std::runtime_error("no complete sample within 5 s of bench time after SYNC started");
    }
    // The brake's first readback comes from the supervisor's thread (real time): wait for it
    // so that runs start on complete samples; a missing one is not fatal here.
    const auto brake_deadline = Clock::now() + 3 * config_.brake.heartbeat.period;
    while (!latest_sample().complete() && Clock::now() < brake_deadline) {
      run_once();
      throw_if_tripped();
    }
  } catch (const BenchAborted& e) {
    disconnect();
    throw;
  } catch (const std::exception& e) {
    disconnect();
    throw std::runtime_error("bench '" + config_.description.name + "': connect: " + e.what());
  }
  set_state(BenchLifecycle::kInactive);
  spdlog::info(
      "bench '{}' inactive (drive disabled, brake off): SYNC {} us on {}, {} clock, estimated bus "
      "load {:.0f} %",
      config_.description.name, std::lround(config_.description.sync_period_s * 1e6), bus_.name(),
      clock_->simulated() ? "simulated" : "real", bus_load_ * 100);
}

void CanopenBench::configure_nodes() {
  const auto& can = config_.can;
  master_->nmt().send(canopen::NmtCommand::enter_preoperational, 0);
  for (auto* device : canopen_devices()) {
    try {
      device->configure(master_->sdo(device->node()));
    } catch (const std::exception& e) {
      throw std::runtime_error(device->describe() + ": configure: " + e.what());
    }
    if (device != drive_.get())
      for (const auto& c : device->channels())
        spdlog::debug("bench '{}': {} records channel '{}' [{}]", config_.description.name,
                      device->describe(), c.name, c.unit);
  }
  log_drive_channels(config_.description.name, drive_->drive_channels());
  check_limits_have_channels(config_.description.limits, drive_->drive_channels());
  if (!drive_->abort_option_set())
    spdlog::warn(
        "bench '{}': {}: abort connection option 0x6007 not set: an NMT stop after an "
        "unconfirmed quick stop may leave its power stage on",
        config_.description.name, drive_->describe());

  const auto period_us =
      static_cast<std::uint32_t>(std::lround(config_.description.sync_period_s * 1e6));
  const auto producer_ms = static_cast<std::uint16_t>(std::lround(can.heartbeat_producer_s * 1e3));
  guards_.clear();
  const auto& guarded = can.node_guarding.nodes;
  for (auto* device : canopen_devices()) {
    auto& sdo = master_->sdo(device->node());
    // 0x1006 is optional on a consumer of SYNC; the simulated devices step by it.
    std::error_code ignored;
    sdo.write<std::uint32_t>(0x1006, 0, period_us, ignored);
    if (std::find(guarded.begin(), guarded.end(), device->node()) != guarded.end()) {
      // Its heartbeats would read as guard answers with a wrong toggle: off where it has them.
      sdo.write<std::uint16_t>(0x1017, 0, 0, ignored);
      guard_node(*device, sdo, "can.node_guarding.nodes");
      continue;
    }
    try {
      sdo.write<std::uint16_t>(0x1017, 0, producer_ms);
    } catch (const canopen::SdoError& e) {
      // No heartbeat producer (CiA 301 makes it optional only beside node guarding).
      using canopen::SdoAbort;
      if (e.code() == SdoAbort::no_object || e.code() == SdoAbort::read_only ||
          e.code() == SdoAbort::no_sub_index) {
        guard_node(*device, sdo, std::string("0x1017: ") + e.code().message());
        continue;
      }
      throw std::runtime_error(device->describe() +
                               ": heartbeat producer time 0x1017: " + e.what());
    } catch (const std::exception& e) {
      throw std::runtime_error(device->describe() +
                               ": heartbeat producer time 0x1017: " + e.what());
    }
  }
  engine_->attach(canopen_devices(), {brake_.get()});

  // Bus load: SYNC and every TPDO each period, one heartbeat per node per producer time.
  const double heartbeats = static_cast<double>(canopen_devices().size()) * kHeartbeatFrameBits /
                            can.heartbeat_producer_s;
  bus_load_ =
      (engine_->bits_per_cycle() / config_.description.sync_period_s + heartbeats) / can.bitrate;
  if (bus_load_ > can.bus_load_warning) {
    spdlog::warn(
        "bench '{}': estimated CAN bus load {:.0f} % of {:.0f} kbit/s at a {} us SYNC "
        "(warning above {:.0f} %)",
        config_.description.name, bus_load_ * 100, can.bitrate / 1e3, period_us,
        can.bus_load_warning * 100);
  }
}

void CanopenBench::start_acquisition() {
  master_->nmt().send(canopen::NmtCommand::start, 0);
  std::vector<canopen::NodeId> beating;
  for (const auto node : all_nodes())
    if (!guards_.guards(node)) beating.push_back(node);
  heartbeats_.arm(beating, now(), config_.description.limits.heartbeat_timeout_s,
                  clock_->simulated());
  guards_.start(Clock::now());
  subscriptions_.clear();
  subscriptions_.push_back(bus_.on_frame([this](const can::Frame& f) { on_heartbeat_frame(f); }));
  acquiring_ = true;
  engine_->start([this](const CycleRecord& record) { check_cycle(record); });
  watch_liveness();
}

void CanopenBench::stop_acquisition() noexcept {
  acquiring_ = false;
  liveness_timer_.cancel();
  engine_->stop();
  heartbeats_.disarm();
}

void CanopenBench::guard_node(CanopenDevice& device, canopen::SdoClient& sdo,
                              const std::string& why) {
  const auto& g = config_.can.node_guarding;
  const auto guard_time = ms(g.guard_time_s);
  auto life_time = guard_time * g.life_time_factor;
  // safety.heartbeat_timeout bounds a loss whichever way the node is supervised.
  const auto bound = config_.description.limits.heartbeat_timeout_s;
  if (bound > 0) life_time = std::max(guard_time, std::min(life_time, ms(bound)));
  // Where the node has them: it may then guard its master too (life guarding).
  std::error_code time_ec, factor_ec;
  sdo.write<std::uint16_t>(0x100C, 0, static_cast<std::uint16_t>(guard_time.count()), time_ec);
  sdo.write<std::uint8_t>(0x100D, 0, g.life_time_factor, factor_ec);
  guards_.add(device.node(), guard_time, life_time);
  spdlog::info(
      "bench '{}': {}: node guarding ({}): guard time {} ms, life time {} ms{}",
      config_.description.name, device.describe(), why, guard_time.count(), life_time.count(),
      time_ec || factor_ec ? " (0x100C/0x100D not written: the node does not guard its master)"
                           : "");
}

void CanopenBench::watch_liveness() noexcept {
  if (!acquiring_) return;
  guards_.poll(bus_, Clock::now());
  check_liveness();
  // Often enough to notice a loss within a few ms of its timeout, whatever the cycles do.
  liveness_timer_.expires_after(std::chrono::milliseconds(10));
  liveness_timer_.async_wait([this, alive = alive_](const boost::system::error_code& ec) {
    if (!ec && *alive) watch_liveness();
  });
}

void CanopenBench::check_liveness() noexcept {
  const auto wall = Clock::now();
  // Checked every 10 ms while the loop runs: a longer gap is a loop the bench thread held
  // (between calls, or busy elsewhere), during which nothing was read: not the nodes' silence.
  if (wall - last_liveness_check_ > std::chrono::milliseconds(100)) {
    heartbeats_.loop_resumed(wall);
    guards_.excuse(wall);
  }
  last_liveness_check_ = wall;
  if (tripped_ || !acquiring_ || state() == BenchLifecycle::kUnconfigured) return;
  if (const auto lost = heartbeats_.lost(now(), wall)) {
    trip("heartbeat of node " + std::to_string(lost->node) + " (" + node_name(lost->node) +
         ") lost: none for " + std::to_string(std::lround(lost->silent_s * 1e3)) +
         " ms (consumer time " + std::to_string(ms(heartbeats_.timeout()).count()) + " ms)");
    return;
  }
  if (const auto lost = guards_.lost(wall))
    trip(NodeGuardWatch::describe(*lost, node_name(lost->node)));
}

void CanopenBench::disconnect() noexcept {
  if (state() == BenchLifecycle::kUnconfigured && !acquiring_ && !brake_->connected()) return;
  // Brake output off, then its watchdog switched off and the link closed; then the drive.
  brake_->disconnect();
  if (acquiring_) {
    finish_safe_state();
    power_down_drive(canopen::Cia402State::switch_on_disabled);
  }
  // From here nodes leaving operational and silent heartbeats are what was asked for.
  set_state(BenchLifecycle::kUnconfigured);
  const bool was_acquiring = acquiring_;
  stop_acquisition();
  if (was_acquiring) nodes_to_preoperational();
}

void CanopenBench::nodes_to_preoperational() noexcept {
  std::error_code ec;
  master_->nmt().send(canopen::NmtCommand::enter_preoperational, 0, ec);
  if (ec) {
    spdlog::warn("bench '{}': NMT enter pre-operational not sent: {}", config_.description.name,
                 ec.message());
    return;
  }
  // A bus that delivers from the event loop (the in-process one) sends it on the next turn.
  try {
    can::run_ready(io_);
  } catch (const std::exception&) {
  }
}

// --- each cycle -----------------------------------------------------------------------------

void CanopenBench::check_cycle(const CycleRecord& record) noexcept {
  brake_->beat_if_due(now());
  if (quick_stop_watch_.pending()) watch_quick_stop(record.drive);
  if (tripped_) {
    // In fault the brake stays off whoever switches it on.
    if (const auto energised = brake_->energised_while_idle()) {
      spdlog::error("bench '{}': {}", config_.description.name, *energised);
      brake_->make_safe();
    }
    return;
  }
  check_liveness();
  if (tripped_) return;
  if (const auto energised = brake_->energised_while_idle()) {
    trip(*energised);
    return;
  }
  const auto& brake = brake_->cycle_readback();
  const auto temperature =
      brake ? std::optional<double>(brake->temperature_c) : std::optional<double>();
  if (auto crossed = limits_check_.check(record.sample, record.drive, temperature)) trip(*crossed);
}

void CanopenBench::on_heartbeat_frame(const can::Frame& frame) noexcept {
  const auto processed = Clock::now();
  heartbeats_.frame(frame, processed);
  auto hb = canopen::decode_heartbeat(frame);
  if (hb && guards_.guards(hb->node)) {
    // A guarded node's answers (and its boot-up) stand for its heartbeat below.
    const auto answer = guards_.on_frame(frame, processed);
    if (!answer && hb->state != canopen::NmtState::boot_up) return;
  } else {
    if (!hb || !heartbeats_.watches(hb->node)) return;
    heartbeats_.seen(hb->node, now(), processed, hb->state);
  }
  for (auto* d : canopen_devices()) {
    if (d->node() != hb->node) continue;
    if (hb->state == canopen::NmtState::boot_up)
      d->on_boot();
    else
      d->on_heartbeat(hb->state);
  }
  if (operational(state()) && hb->state != canopen::NmtState::operational) {
    trip("node " + std::to_string(hb->node) + " (" + node_name(hb->node) +
         ") left operational: " + std::string(canopen::to_string(hb->state)));
  }
}

// --- safety ---------------------------------------------------------------------------------

void CanopenBench::trip(const std::string& reason) noexcept {
  if (tripped_) return;
  if (!acquiring_ && state() == BenchLifecycle::kUnconfigured) {
    spdlog::warn("bench '{}': {} (not connected: nothing to stop)", config_.description.name,
                 reason);
    return;
  }
  tripped_ = true;
  {
    std::lock_guard lock(reason_mutex_);
    reason_ = reason;
  }
  set_state(BenchLifecycle::kFault);
  spdlog::error("bench '{}' tripped: {}", config_.description.name, reason);
  quick_stop_drive();  // a frame on the bus, first: the brake's write waits for its answer
  brake_->make_safe();
}

void CanopenBench::quick_stop_drive() noexcept {
  if (!acquiring_) return;
  // On the bus now, beside whatever SDO transfer is in flight (quick_stop_watch.hpp).
  std::error_code ec;
  bus_.send(quick_stop_frame(drive_->node()), ec);
  if (ec) {
    spdlog::error("bench '{}': quick-stop RPDO to the servo drive not sent: {}",
                  config_.description.name, ec.message());
  }
  quick_stop_watch_.start(now(), config_.can.quick_stop_timeout_s);
}

void CanopenBench::watch_quick_stop(const DriveCycleValues& drive) noexcept {
  const auto statusword = drive.status_valid ? std::optional(drive.statusword) : std::nullopt;
  switch (quick_stop_watch_.on_cycle(now(), statusword)) {
    case QuickStopWatch::Verdict::kConfirmed:
      spdlog::info("bench '{}': servo drive stopped: {}", config_.description.name,
                   canopen::describe_statusword(*statusword));
      break;
    case QuickStopWatch::Verdict::kTimedOut:
      stop_drive_by_nmt();
      break;
    default:
      break;
  }
}

void CanopenBench::stop_drive_by_nmt() noexcept {
  std::error_code ec;
  master_->nmt().send(canopen::NmtCommand::stop, drive_->node(), ec);
  const auto last = quick_stop_watch_.last_statusword();
  const std::string why =
      "the servo drive did not show the quick stop within " +
      std::to_string(ms(config_.can.quick_stop_timeout_s).count()) + " ms (" +
      (last ? canopen::describe_statusword(*last) : std::string("no statusword received")) +
      "): NMT stop sent to node " + std::to_string(drive_->node());
  spdlog::error("bench '{}': {}{}", config_.description.name, why,
                ec ? " but not delivered: " + ec.message() : std::string());
  std::lock_guard lock(reason_mutex_);
  reason_ += "; " + why + (ec ? " (send failed: " + ec.message() + ")" : "");
}

void CanopenBench::finish_safe_state() noexcept {
  // The watch counts bench time, which stands still when the loop's cycles stall: this
  // real-time bound sends the NMT stop itself then.
  const auto deadline = Clock::now() + ms(config_.can.quick_stop_timeout_s + 0.5);
  try {
    while (quick_stop_watch_.pending() && Clock::now() < deadline) run_once();
  } catch (const std::exception& e) {
    spdlog::error("bench '{}': waiting for the quick stop: {}", config_.description.name, e.what());
  }
  if (quick_stop_watch_.pending()) {
    stop_drive_by_nmt();
    quick_stop_watch_.reset();
  }
}

void CanopenBench::request_stop(const std::string& reason) noexcept {
  try {
    boost::asio::post(io_, [this, reason, alive = alive_] {
      if (*alive) trip("operator stop: " + reason);
    });
  } catch (...) {
  }
}

void CanopenBench::on_brake_event(const modbus::BrakeEvent& event) noexcept {
  try {
    boost::asio::post(io_, [this, event, alive = alive_] {
      if (!*alive) return;
      switch (event.kind) {
        case modbus::BrakeEvent::Kind::link_lost:
          trip("Modbus link to the brake controller lost: " + event.reason);
          break;
        case modbus::BrakeEvent::Kind::alarm_raised:
          if (operational(state())) trip("brake controller alarm: " + event.reason);
          break;
        case modbus::BrakeEvent::Kind::link_restored:
          spdlog::info("bench '{}': {}", config_.description.name, event.reason);
          brake_->retry_safe_state();
          break;
        case modbus::BrakeEvent::Kind::alarm_cleared:
          break;
      }
    });
  } catch (...) {
  }
}

void CanopenBench::clear_fault() {
  if (operational(state())) return;
  if (state() == BenchLifecycle::kUnconfigured || !acquiring_)
    throw std::logic_error("clear_fault: bench '" + config_.description.name +
                           "' is not connected");
  const auto& limits = config_.description.limits;
  // Let returning heartbeats and readbacks arrive before judging whether the cause persists.
  idle_for(std::max({limits.heartbeat_timeout_s, 2 * config_.can.heartbeat_producer_s, 0.05}));
  if (brake_->link_lost())
    throw std::runtime_error(
        "cannot clear the fault: the Modbus link to the brake controller is still lost (" +
        brake_->last_error() + ")");
  for (const auto node : all_nodes()) {
    if (heartbeats_.missing(node, now()))
      throw std::runtime_error("cannot clear the fault: the heartbeat of node " +
                               std::to_string(node) + " (" + node_name(node) +
                               ") is still missing");
    if (const auto* g = guards_.guard(node); g && g->silence(Clock::now()) > g->life_time())
      throw std::runtime_error("cannot clear the fault: node " + std::to_string(node) + " (" +
                               node_name(node) + ") does not answer node guarding");
  }
  guards_.start(Clock::now());
  try {
    brake_->reset_after_fault();
  } catch (const std::exception& e) {
    throw std::runtime_error("cannot clear the fault: brake controller: " + std::string(e.what()));
  }
  try {
    for (const auto node : all_nodes()) master_->nmt().send(canopen::NmtCommand::start, node);
    finish_safe_state();
    // The fault reset is on the way to Switch On Disabled; the drive stays off until a run
    // needs it.
    auto& drive = drive_->drive();
    drive.go_to(canopen::Cia402State::switch_on_disabled);
    powered_ = false;
    drive.set_mode(canopen::OperationMode::profile_position);
    drive.set_target_velocity(0);
    mode_ = canopen::OperationMode::profile_position;
  } catch (const std::exception& e) {
    throw std::runtime_error("cannot clear the fault: " + drive_->describe() + ": " + e.what());
  }
  limits_check_.reset_reference();
  {
    std::lock_guard lock(reason_mutex_);
    reason_.clear();
  }
  tripped_ = false;
  quick_stop_watch_.reset();
  set_state(BenchLifecycle::kInactive);
  spdlog::info("bench '{}': fault cleared", config_.description.name);
}

// --- power ----------------------------------------------------------------------------------

void CanopenBench::activate() {
  ensure_operational();
  if (powered_) return;
  // Enabled in profile position, which holds where the drive stands until a new set-point; a
  // stale profile-velocity target must not start the shaft on enable.
  auto& drive = drive_->drive();
  if (mode_ == canopen::OperationMode::profile_velocity)
    drive_command("target velocity 0", [&] { drive.set_target_velocity(0); });
  set_mode(canopen::OperationMode::profile_position);
  powered_ = true;  // from the first controlword on: deactivate() must power it down
  set_state(BenchLifecycle::kActive);
  drive_command("enable operation", [&] { drive.enable_operation(); });
  spdlog::info("bench '{}': active, servo drive enabled", config_.description.name);
}

void CanopenBench::deactivate() noexcept {
  if (!acquiring_) return;
  brake_->make_safe();
  finish_safe_state();
  power_down_drive(tripped_ ? canopen::Cia402State::switch_on_disabled
                            : canopen::Cia402State::ready_to_switch_on);
  if (state() == BenchLifecycle::kActive) set_state(BenchLifecycle::kInactive);
}

void CanopenBench::power_down_drive(canopen::Cia402State target) noexcept {
  if (!drive_->configured()) return;
  auto& drive = drive_->drive();
  std::error_code ec;
  try {
    const auto state = drive.state(ec);
    if (!ec) {
      if (state == canopen::Cia402State::fault || state == target ||
          state == canopen::Cia402State::switch_on_disabled) {
        powered_ = false;
        return;
      }
      if (mode_ == canopen::OperationMode::profile_velocity) drive.set_target_velocity(0, ec);
      drive.go_to(target, ec);
    }
  } catch (const std::exception& e) {
    // A handler's exception met while waiting: a fault path cannot pass it on, so it is told
    // as thrown.
    spdlog::error("bench '{}': {} not powered down to {}: {}", config_.description.name,
                  drive_->describe(), canopen::to_string(target), e.what());
    return;
  }
  if (ec) {
    spdlog::error(
        "bench '{}': {} not powered down to {}: {}", config_.description.name, drive_->describe(),
        canopen::to_string(target),
        drive.last_failure().message.empty() ? ec.message() : drive.last_failure().message);
    return;
  }
  powered_ = false;
  spdlog::info("bench '{}': servo drive disabled ({})", config_.description.name,
               canopen::to_string(target));
}

// --- blocking calls -------------------------------------------------------------------------

void CanopenBench::run_once() {
  can::run_next_within(io_, std::chrono::milliseconds(20));
}

void CanopenBench::throw_if_tripped() {
  if (!tripped_) return;
  finish_safe_state();
  throw BenchAborted(fault_reason());
}

void CanopenBench::ensure_operational() {
  throw_if_tripped();
  if (!operational(state()))
    throw std::logic_error("bench '" + config_.description.name + "' is not connected");
}

bool CanopenBench::run_until(const std::function<bool()>& done, double timeout_s,
                             bool tolerate_fault) {
  if (!acquiring_)
    throw std::logic_error("bench '" + config_.description.name + "' is not acquiring");
  const double deadline = now() + timeout_s;
  const auto& stats = engine_->statistics();
  std::uint64_t seen = stats.samples - 1;
  for (;;) {
    if (!tolerate_fault) throw_if_tripped();
    if (stats.samples != seen) {
      seen = stats.samples;
      if (done && done()) return true;
    }
    if (now() >= deadline) return false;
    run_once();
  }
}

template <typename F>
void CanopenBench::drive_command(const char* what, F&& f) {
  try {
    f();
  } catch (const std::exception& e) {
    throw_if_tripped();
    throw std::runtime_error(drive_->describe() + ": " + what + ": " + e.what());
  }
  throw_if_tripped();
}

template <typename F>
void CanopenBench::brake_command(const char* what, F&& f) {
  try {
    f();
  } catch (const std::invalid_argument&) {
    throw;
  } catch (const std::exception& e) {
    trip(brake_->describe() + ": " + what + " failed: " + e.what());
  }
  throw_if_tripped();
}

void CanopenBench::set_mode(canopen::OperationMode mode) {
  if (mode_ == mode) return;
  drive_command("set mode", [&] { drive_->drive().set_mode(mode); });
  mode_ = mode;
}

void CanopenBench::move_input_to(double theta_in_rad, double speed_rad_s) {
  ensure_operational();
  const auto& limits = config_.description.limits;
  if (!(speed_rad_s > 0) || !std::isfinite(speed_rad_s))
    throw std::invalid_argument("move_input_to: speed = " + std::to_string(speed_rad_s) +
                                " rad/s: expected > 0");
  if (limits.max_input_speed_rad_s > 0 && speed_rad_s > limits.max_input_speed_rad_s)
    throw std::invalid_argument("move_input_to: speed = " + std::to_string(speed_rad_s) +
                                " rad/s: above the limit safety.max_input_speed = " +
                                std::to_string(limits.max_input_speed_rad_s) + " rad/s");
  canopen::ProfileMove move;
  const auto& units = drive_->units();
  move.target = units.position_value(theta_in_rad, "move_input_to target");
  move.profile_velocity = static_cast<std::uint32_t>(
      std::max(1, units.velocity_value(speed_rad_s, "move_input_to speed")));
  if (config_.drive.profile_acceleration_rad_s2 > 0) {
    const auto a = units.acceleration_value(config_.drive.profile_acceleration_rad_s2,
                                            "drive.profile_acceleration");
    move.acceleration = a;
    move.deceleration = a;
  }
  activate();
  set_mode(canopen::OperationMode::profile_position);
  const double distance = std::abs(theta_in_rad - latest_sample().theta_in_rad);
  drive_command("profile position move", [&] { drive_->drive().move(move); });
  const auto start = engine_->statistics().samples;
  const double timeout = 3 * distance / speed_rad_s + 10;
  const bool reached = run_until(
      [&] {
        const auto& drive = latest_drive();
        return engine_->statistics().samples >= start + 2 && drive.status_valid &&
               (drive.statusword & canopen::statusword::target_reached) != 0;
      },
      timeout);
  if (!reached)
    throw std::runtime_error(drive_->describe() + ": target " + std::to_string(theta_in_rad) +
                             " rad not reached within " + std::to_string(timeout) +
                             " s of bench time (" +
                             canopen::describe_statusword(latest_drive().statusword) + ")");
  if (config_.drive.target_settle_s > 0) run_until(nullptr, config_.drive.target_settle_s);
}

void CanopenBench::run_input_velocity(double omega_in_rad_s) {
  ensure_operational();
  const auto& limits = config_.description.limits;
  if (!std::isfinite(omega_in_rad_s) ||
      (limits.max_input_speed_rad_s > 0 && std::abs(omega_in_rad_s) > limits.max_input_speed_rad_s))
    throw std::invalid_argument("run_input_velocity: omega = " + std::to_string(omega_in_rad_s) +
                                " rad/s: expected |omega| <= safety.max_input_speed = " +
                                std::to_string(limits.max_input_speed_rad_s) + " rad/s");
  const auto velocity = drive_->units().velocity_value(omega_in_rad_s, "run_input_velocity omega");
  activate();
  set_mode(canopen::OperationMode::profile_velocity);
  drive_command("target velocity", [&] { drive_->drive().set_target_velocity(velocity); });
}

void CanopenBench::stop_motion() {
  ensure_operational();
  if (powered_ && mode_ == canopen::OperationMode::profile_velocity)
    drive_command("target velocity 0", [&] { drive_->drive().set_target_velocity(0); });
  constexpr double kStill = 0.05;  // rad/s at the input (0.5 rpm)
  int still = 0;
  const bool stopped = run_until(
      [&] {
        still = std::abs(latest_sample().input_speed_rad_s) < kStill ? still + 1 : 0;
        return still >= 10;
      },
      30.0);
  if (!stopped)
    throw std::runtime_error(drive_->describe() + ": input still turning at " +
                             std::to_string(latest_sample().input_speed_rad_s) +
                             " rad/s 30 s of bench time after the stop");
}

void CanopenBench::set_brake_torque(double torque_nm, double ramp_nm_per_s) {
  ensure_operational();
  if (!(torque_nm >= 0) || !std::isfinite(torque_nm))
    throw std::invalid_argument("set_brake_torque: torque = " + std::to_string(torque_nm) +
                                " N*m: expected >= 0");
  const double limit = config_.description.limits.max_brake_torque_nm;
  if (limit > 0 && torque_nm > limit)
    throw std::invalid_argument("set_brake_torque: torque = " + std::to_string(torque_nm) +
                                " N*m: above safety.max_brake_torque = " + std::to_string(limit) +
                                " N*m");
  // The brake output is on only while the bench is active (a run or a jog).
  if (torque_nm > 0) activate();
  brake_command("set torque", [&] {
    brake_->set_torque(torque_nm, ramp_nm_per_s, state() == BenchLifecycle::kActive);
  });
}

void CanopenBench::wait_for(double seconds) {
  throw_if_tripped();
  run_until(nullptr, seconds);
}

bool CanopenBench::wait_until(const std::function<bool()>& done, double timeout_s) {
  throw_if_tripped();
  return run_until(done, timeout_s);
}

void CanopenBench::idle_for(double seconds) {
  if (!acquiring_) return;
  run_until(nullptr, seconds, true);
}

AcquisitionStats CanopenBench::acquisition_stats() const {
  AcquisitionStats s;
  const auto& e = engine_->statistics();
  s.syncs_sent = e.syncs_sent;
  s.samples = e.samples;
  s.incomplete_samples = e.incomplete_samples;
  s.late_frames = e.late_frames;
  const auto c = clock_->statistics();
  s.sync_late = c.late;
  s.sync_skipped = c.skipped;
  s.cycles_timed_out = c.cycles_timed_out;
  s.bus_load = bus_load_;
  const auto& drive = latest_drive();
  if (drive.status_valid) {
    s.drive_statusword = drive.statusword;
    s.drive_state = canopen::to_string(canopen::decode_state(drive.statusword));
  }
  if (const auto brake = brake_->fresh_readback()) {
    s.brake_output_on = brake->status.output_on;
    s.brake_coil_temperature_c = brake->temperature_c;
    s.brake_status_word = brake->status.raw;
    s.brake_alarm = brake->status.alarm ? brake->alarm_text : std::string();
  }
  for (const auto& n : heartbeats_.nodes()) {
    s.nodes.push_back({n.node, n.state ? std::string(canopen::to_string(*n.state)) : std::string(),
                       n.count > 0 ? n.age_s : -1.0, n.count});
  }
  for (const auto* g : guards_.all()) {
    s.nodes.push_back(
        {g->node(), g->state() ? std::string(canopen::to_string(*g->state())) : "",
         g->answers() > 0 ? std::chrono::duration<double>(g->silence(Clock::now())).count() : -1.0,
         g->answers(), "node guarding"});
  }
  s.cycles_waited_for_devices = c.cycles_waited_for_devices;
  s.longest_device_wait_s = c.longest_device_wait_s;
  s.late_devices = engine_->late_devices();
  s.drive_heartbeats = heartbeats_.count(drive_->node());
  s.drive_heartbeat_gap_max_s = heartbeats_.largest_gap(drive_->node());
  const auto& lateness = engine_->lateness();
  s.sync_lateness_p50_s = lateness.percentile(0.5);
  s.sync_lateness_p99_s = lateness.percentile(0.99);
  s.sync_lateness_max_s = lateness.max();
  s.bench_time_s = now();
  s.real_time_s = clock_->real_elapsed();
  return s;
}

}  // namespace wavebench::bench
