#include "wavebench/bench/canopen_bench.hpp"

#include <spdlog/spdlog.h>

#include <boost/asio/post.hpp>
#include <cmath>
#include <sstream>

#include "wavebench/bench/bench_devices.hpp"
#include "wavebench/canopen/cob_id.hpp"
#include "wavebench/canopen/nmt.hpp"
#include "wavebench/canopen/pdo.hpp"
#include "wavebench/canopen/sdo_abort.hpp"
#include "wavebench/modbus/modbus_endpoint.hpp"

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

// Bits on the wire of a classic frame with `len` data bytes, with a typical stuffing allowance.
double frame_bits(unsigned len) {
  return (47.0 + 8.0 * len) * 1.2;
}

}  // namespace

CanopenBench::CanopenBench(BenchConfig config, can::CanBus& bus)
    : config_(std::move(config)),
      bus_(bus),
      io_(bus.context()),
      limits_check_(config_.description.limits, config_.description.sense),
      cycle_timer_(bus.context()) {
  config_.description.sense.validate();
  for (const auto& d : config_.devices) {
    const auto* kind = find_channel_device_kind(d.kind);
    if (!kind)
      throw std::invalid_argument("bench device '" + d.channel + "': unknown kind " + d.kind);
    channel_devices_.push_back(kind->make(d));
  }
  canopen::Master::Hooks hooks;
  hooks.on_heartbeat_lost = [this](canopen::NodeId n) {
    if (lifecycle_ != BenchLifecycle::kUnconfigured)
      trip("heartbeat of node " + std::to_string(n) + " (" + node_name(n) + ") lost: none for " +
           std::to_string(ms(config_.description.limits.heartbeat_timeout_s).count()) + " ms");
  };
  hooks.on_emcy = [this](const canopen::Emergency& e) {
    for (auto& d : channel_devices_)
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
}

CanopenBench::~CanopenBench() {
  disconnect();
  *alive_ = false;
  subscriptions_.clear();
}

std::string CanopenBench::node_name(canopen::NodeId node) const {
  if (node == config_.can.drive_node) return "servo drive";
  if (node == config_.can.encoder_node) return "output encoder";
  if (node == config_.can.torque_node) return "torque sensor";
  for (const auto& d : channel_devices_)
    if (d->node() == node) return d->describe();
  return "unknown node";
}

std::vector<canopen::NodeId> CanopenBench::all_nodes() const {
  std::vector<canopen::NodeId> nodes{config_.can.drive_node, config_.can.encoder_node,
                                     config_.can.torque_node};
  for (const auto& d : channel_devices_) nodes.push_back(d->node());
  return nodes;
}

std::vector<storage::ChannelInfo> CanopenBench::extra_channels() const {
  std::vector<storage::ChannelInfo> channels;
  for (const auto& d : channel_devices_) channels.push_back(d->channel());
  return channels;
}

std::string CanopenBench::fault_reason() const {
  std::lock_guard lock(reason_mutex_);
  return reason_;
}

double CanopenBench::now() const {
  if (config_.description.simulated_clock) {
    return static_cast<double>(sync_index_) * config_.description.sync_period_s;
  }
  if (t0_ == Clock::time_point{}) return 0;
  return std::chrono::duration<double>(Clock::now() - t0_).count();
}

// --- connect / disconnect -------------------------------------------------------------------

void CanopenBench::connect() {
  if (state() == BenchLifecycle::kReady) return;
  if (state() == BenchLifecycle::kFault) {
    clear_fault();
    return;
  }
  {
    std::lock_guard lock(reason_mutex_);
    reason_.clear();
  }
  tripped_ = false;
  sync_index_ = 0;
  samples_ = 0;
  stats_ = {};
  lateness_ = {};
  mode_.reset();
  powered_ = false;
  last_drive_heartbeat_ = {};
  t0_ = Clock::now();
  try {
    if (const auto problems = eds_problems(config_); !problems.empty()) {
      std::string text = "the EDS disagrees with the objects the bench uses";
      for (const auto& p : problems) text += "; " + p;
      throw std::runtime_error(text);
    }
    connect_brake();
    configure_nodes();
    start_acquisition();
    set_mode(canopen::OperationMode::profile_position);
    // Inactive until a run needs the drive: a drive left enabled (a master that died mid-run)
    // or in fault is brought to its power-off state here.
    drive_command("disable voltage",
                  [&] { drive_->go_to(canopen::Cia402State::switch_on_disabled); });
    const auto can_channels = storage::kThetaInValid | storage::kThetaOutValid |
                              storage::kInputSpeedValid | storage::kTorqueValid;
    if (!run_until([&] { return (latest_.flags & can_channels) == can_channels; }, 5.0)) {
      throw std::runtime_error("no complete sample within 5 s of bench time after SYNC started");
    }
    // The brake's first readback comes from the supervisor's thread (real time): wait for it
    // so that runs start on complete samples; a missing one is not fatal here.
    const auto brake_deadline = Clock::now() + 3 * config_.brake.heartbeat.period;
    while (!latest_.complete() && Clock::now() < brake_deadline) {
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
  lifecycle_ = BenchLifecycle::kReady;
  spdlog::info(
      "bench '{}' ready (inactive, drive disabled): SYNC {} us on {}, {} clock, estimated bus "
      "load {:.0f} %",
      config_.description.name, std::lround(config_.description.sync_period_s * 1e6), bus_.name(),
      config_.description.simulated_clock ? "simulated" : "real", stats_.bus_load * 100);
}

void CanopenBench::connect_brake() {
  brake_ = std::make_unique<modbus::BrakeClient>(config_.brake);
  const auto where = modbus::to_string(config_.brake.link.endpoint);
  try {
    brake_->connect();
    brake_->reset_alarm();
    brake_->make_safe();
    brake_->set_mode(modbus::BrakeMode::torque);
    if (config_.description.simulated_clock) brake_->heartbeat();
  } catch (const std::exception& e) {
    throw std::runtime_error("brake controller at " + where + ": " + e.what());
  }
  next_brake_heartbeat_ = 0;
  // One master on the line: the supervisor's heartbeats and polls share brake_'s link.
  brake_supervisor_ = std::make_unique<modbus::BrakeSupervisor>(
      *brake_, static_cast<modbus::BrakeEventSink&>(*this));
  brake_supervisor_->start();
}

void CanopenBench::configure_nodes() {
  const auto& can = config_.can;
  const auto nodes = all_nodes();
  auto step = [&](canopen::NodeId node, const std::string& what, const std::function<void()>& f) {
    try {
      f();
    } catch (const std::exception& e) {
      throw std::runtime_error(node_name(node) + " (node " + std::to_string(node) + "): " + what +
                               ": " + e.what());
    }
  };
  master_->nmt().send(canopen::NmtCommand::enter_preoperational, 0);

  canopen::Cia406Config encoder_config{config_.encoder.counts_per_turn, config_.encoder.turns};
  encoder_ =
      std::make_unique<canopen::Cia406Encoder>(master_->sdo(can.encoder_node), encoder_config);
  step(can.encoder_node, "read configuration", [&] { encoder_->read_configuration(); });
  torque_ = std::make_unique<canopen::TorqueSensor>(master_->sdo(can.torque_node),
                                                    config_.torque_sensor.sensor);
  drive_ = std::make_unique<canopen::Cia402Drive>(master_->sdo(can.drive_node));
  step(can.drive_node, "units and optional objects",
       [&] { drive_channels_ = read_drive_channels(master_->sdo(can.drive_node), config_.drive); });

  using canopen::PdoDirection;
  step(can.drive_node, "TPDO1 (statusword, position)", [&] {
    canopen::configure_pdo(master_->sdo(can.drive_node), PdoDirection::transmit, 1,
                           SampleAssembler::drive_position_pdo(can.drive_node));
  });
  step(can.drive_node, "TPDO2 (velocity, following error)", [&] {
    map_drive_velocity_pdo(master_->sdo(can.drive_node), drive_channels_);
    check_limits_have_channels(config_.description.limits, drive_channels_);
  });
  log_drive_channels(config_.description.name, drive_channels_);
  assembler_ = std::make_unique<SampleAssembler>(drive_channels_.units, *encoder_, *torque_,
                                                 drive_channels_.following_error);
  step(can.encoder_node, "TPDO1 (0x6004)", [&] {
    canopen::configure_pdo(master_->sdo(can.encoder_node), PdoDirection::transmit, 1,
                           SampleAssembler::encoder_pdo(can.encoder_node));
  });
  step(can.drive_node, "RPDO1 (controlword: the quick stop's path)", [&] {
    canopen::configure_pdo(master_->sdo(can.drive_node), PdoDirection::receive, kQuickStopRpdo,
                           quick_stop_rpdo(can.drive_node));
  });
  // 0x6007 is optional (CiA 402): where present, an NMT stop (the quick stop's fallback) disables
  // the drive's voltage.
  std::error_code abort_option_ec;
  master_->sdo(can.drive_node)
      .write<std::int16_t>(0x6007, 0, kAbortConnectionDisableVoltage, abort_option_ec);
  if (abort_option_ec) {
    spdlog::warn(
        "bench '{}': servo drive (node {}): abort connection option 0x6007 not set ({}): an NMT "
        "stop after an unconfirmed quick stop may leave its power stage on",
        config_.description.name, can.drive_node, abort_option_ec.message());
  }
  step(can.torque_node, "TPDO1 (torque)", [&] {
    canopen::configure_pdo(master_->sdo(can.torque_node), PdoDirection::transmit, 1,
                           assembler_->torque_pdo(can.torque_node));
  });
  configure_channel_devices();
  const auto period_us =
      static_cast<std::uint32_t>(std::lround(config_.description.sync_period_s * 1e6));
  const auto producer_ms = static_cast<std::uint16_t>(std::lround(can.heartbeat_producer_s * 1e3));
  for (const auto node : nodes) {
    // 0x1006 is optional on a consumer of SYNC; the simulated devices step by it.
    std::error_code ignored;
    master_->sdo(node).write<std::uint32_t>(0x1006, 0, period_us, ignored);
    step(node, "heartbeat producer time 0x1017",
         [&] { master_->sdo(node).write<std::uint16_t>(0x1017, 0, producer_ms); });
    if (!config_.description.simulated_clock &&
        config_.description.limits.heartbeat_timeout_s > 0) {
      master_->consume_heartbeat(node, ms(config_.description.limits.heartbeat_timeout_s));
    }
  }

  subscriptions_.clear();
  master_->on_pdo(canopen::tpdo_cob_id(1, can.drive_node),
                  [this](const can::Frame& f) { on_pdo(SampleAssembler::kDrivePosition, f); });
  master_->on_pdo(canopen::tpdo_cob_id(2, can.drive_node),
                  [this](const can::Frame& f) { on_pdo(SampleAssembler::kDriveVelocity, f); });
  master_->on_pdo(canopen::tpdo_cob_id(1, can.encoder_node),
                  [this](const can::Frame& f) { on_pdo(SampleAssembler::kEncoder, f); });
  master_->on_pdo(canopen::tpdo_cob_id(1, can.torque_node),
                  [this](const can::Frame& f) { on_pdo(SampleAssembler::kTorque, f); });
  for (std::size_t i = 0; i < channel_devices_.size(); ++i)
    master_->on_pdo(channel_devices_[i]->tpdo().cob_id,
                    [this, i](const can::Frame& f) { on_extra_pdo(i, f); });
  subscriptions_.push_back(bus_.on_frame([this](const can::Frame& f) { on_heartbeat_frame(f); }));

  // Bus load: SYNC + the cycle's PDOs every period, heartbeats of three nodes.
  const double per_cycle =
      frame_bits(0) + frame_bits(6) + frame_bits(drive_channels_.following_error ? 8 : 4) +
      frame_bits(4) +
      frame_bits(static_cast<unsigned>(canopen::size_of(config_.torque_sensor.sensor.type)));
  double extra_bits = 0;
  for (const auto& d : channel_devices_) {
    unsigned bytes = 0;
    for (const auto& e : d->tpdo().entries) bytes += e.bits / 8u;
    extra_bits += frame_bits(bytes);
  }
  const double per_cycle_all = per_cycle + extra_bits;
  const double heartbeats =
      static_cast<double>(nodes.size()) * frame_bits(1) / can.heartbeat_producer_s;
  stats_.bus_load = (per_cycle_all / config_.description.sync_period_s + heartbeats) / can.bitrate;
  if (stats_.bus_load > can.bus_load_warning) {
    spdlog::warn(
        "bench '{}': estimated CAN bus load {:.0f} % of {:.0f} kbit/s at a {} us SYNC "
        "(warning above {:.0f} %)",
        config_.description.name, stats_.bus_load * 100, can.bitrate / 1e3, period_us,
        can.bus_load_warning * 100);
  }
}

void CanopenBench::configure_channel_devices() {
  assembler_->expect_extra(channel_devices_.size());
  for (auto& d : channel_devices_) {
    auto& sdo = master_->sdo(d->node());
    try {
      d->configure(sdo);
      canopen::configure_pdo(sdo, canopen::PdoDirection::transmit, 1, d->tpdo());
    } catch (const std::exception& e) {
      throw std::runtime_error(d->describe() + ": configure: " + e.what());
    }
    spdlog::info("bench '{}': {} records channel '{}' [{}]", config_.description.name,
                 d->describe(), d->channel().name, d->channel().unit);
  }
}

void CanopenBench::start_acquisition() {
  master_->nmt().send(canopen::NmtCommand::start, 0);
  for (const auto node : all_nodes()) last_heartbeat_[node] = now();
  acquiring_ = true;
  if (config_.description.simulated_clock) {
    send_simulated_sync();
    return;
  }
  const auto period =
      std::chrono::microseconds(std::lround(config_.description.sync_period_s * 1e6));
  auto& producer = master_->start_sync(period);
  producer.on_tick([this](const canopen::SyncProducer::Tick& tick) {
    if (!acquiring_) return;
    ++stats_.syncs_sent;
    lateness_.add(std::chrono::duration<double>(tick.sent - tick.deadline).count());
    if (tick_hook_) tick_hook_(tick);
    finish_cycle();
    // The SYNC's send time on the clock of receive timestamps: a frame received before it
    // belongs to an earlier cycle, however late it is processed.
    sync_sent_wall_ =
        std::chrono::system_clock::now() -
        std::chrono::duration_cast<std::chrono::system_clock::duration>(Clock::now() - tick.sent);
    sync_index_ = tick.index;
    begin_cycle(tick.index,
                std::chrono::duration_cast<std::chrono::nanoseconds>(tick.sent - t0_).count());
  });
}

void CanopenBench::stop_acquisition() noexcept {
  acquiring_ = false;
  master_->stop_sync();
  ++cycle_generation_;
  cycle_timer_.cancel();
}

void CanopenBench::disconnect() noexcept {
  if (lifecycle_ == BenchLifecycle::kUnconfigured && !acquiring_ && !brake_) return;
  make_brake_safe();
  if (brake_supervisor_) brake_supervisor_->stop();
  brake_supervisor_.reset();
  release_brake_watchdog();
  if (drive_ && acquiring_) {
    finish_safe_state();
    power_down_drive(canopen::Cia402State::switch_on_disabled);
  }
  // From here nodes leaving operational and silent heartbeats are what was asked for.
  lifecycle_ = BenchLifecycle::kUnconfigured;
  const bool was_acquiring = acquiring_;
  stop_acquisition();
  if (was_acquiring) nodes_to_preoperational();
  if (brake_) brake_->disconnect();
  brake_.reset();
}

void CanopenBench::release_brake_watchdog() noexcept {
  if (!brake_) return;
  // A real controller latches a watchdog alarm when the heartbeats stop with its watchdog armed:
  // switched off, the next connect starts without an alarm to reset.
  try {
    brake_->set_watchdog(std::chrono::milliseconds(0));
  } catch (const std::exception& e) {
    spdlog::warn("bench '{}': brake controller watchdog not switched off: {}",
                 config_.description.name, e.what());
  }
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
    if (io_.stopped()) io_.restart();
    io_.poll();
  } catch (const std::exception&) {
  }
}

// --- acquisition ----------------------------------------------------------------------------

void CanopenBench::begin_cycle(std::uint64_t index, std::int64_t time_ns) {
  assembler_->begin(index, time_ns);
}

void CanopenBench::send_simulated_sync() noexcept {
  if (!acquiring_) return;
  ++sync_index_;
  begin_cycle(sync_index_, std::llround(static_cast<double>(sync_index_) *
                                        config_.description.sync_period_s * 1e9));
  std::error_code ec;
  bus_.send(canopen::sync_frame(), ec);
  ++stats_.syncs_sent;
  const auto generation = ++cycle_generation_;
  cycle_timer_.expires_after(ms(config_.can.cycle_timeout_s));
  cycle_timer_.async_wait([this, generation, alive = alive_](const boost::system::error_code& e) {
    if (e || !*alive || generation != cycle_generation_ || !acquiring_) return;
    ++stats_.cycles_timed_out;
    finish_cycle();
    send_simulated_sync();
  });
}

void CanopenBench::on_extra_pdo(std::size_t device, const can::Frame& frame) noexcept {
  if (!assembler_ || !assembler_->open() ||
      (!config_.description.simulated_clock && frame.timestamp.time_since_epoch().count() != 0 &&
       frame.timestamp < sync_sent_wall_) ||
      !assembler_->on_extra(device, channel_devices_[device]->on_pdo(frame))) {
    ++stats_.late_frames;
    return;
  }
  if (assembler_->all_frames()) {
    finish_cycle();
    if (config_.description.simulated_clock) send_simulated_sync();
  }
}

void CanopenBench::on_pdo(unsigned which, const can::Frame& frame) noexcept {
  if (!assembler_ || !assembler_->open() ||
      (!config_.description.simulated_clock && frame.timestamp.time_since_epoch().count() != 0 &&
       frame.timestamp < sync_sent_wall_)) {
    ++stats_.late_frames;
    return;
  }
  bool taken = false;
  switch (which) {
    case SampleAssembler::kDrivePosition:
      taken = assembler_->on_drive_position(frame);
      break;
    case SampleAssembler::kDriveVelocity:
      taken = assembler_->on_drive_velocity(frame);
      break;
    case SampleAssembler::kEncoder:
      taken = assembler_->on_encoder(frame);
      break;
    case SampleAssembler::kTorque:
      taken = assembler_->on_torque(frame);
      break;
    default:
      break;
  }
  if (!taken) ++stats_.late_frames;
  if (assembler_->all_frames()) {
    finish_cycle();
    if (config_.description.simulated_clock) send_simulated_sync();
  }
}

std::optional<modbus::BrakeReadback> CanopenBench::fresh_brake_readback() const {
  if (!brake_supervisor_ || brake_supervisor_->link_lost()) return std::nullopt;
  const auto age = Clock::now() - brake_supervisor_->latest_time();
  if (age > 3 * config_.brake.heartbeat.period + std::chrono::milliseconds(50)) return std::nullopt;
  return brake_supervisor_->latest();
}

void CanopenBench::finish_cycle() noexcept {
  if (!assembler_ || !assembler_->open()) return;
  ++cycle_generation_;  // the simulated clock's timeout of this cycle no longer applies
  const auto brake = fresh_brake_readback();
  if (brake) assembler_->set_brake(brake->coil_current_a, brake->torque_nm);
  const auto& sample = assembler_->finish();
  latest_ = sample;
  latest_drive_ = assembler_->drive();
  ++samples_;
  ++stats_.samples;
  if (!sample.complete()) ++stats_.incomplete_samples;
  for (auto* observer : observers_) observer->on_sample(latest_);

  if (config_.description.simulated_clock && brake_ && now() >= next_brake_heartbeat_) {
    next_brake_heartbeat_ =
        now() + std::chrono::duration<double>(config_.brake.heartbeat.period).count();
    try {
      brake_->heartbeat();
    } catch (const std::exception&) {
      // The supervisor decides when the link is lost; a missed beat is the watchdog's business.
    }
  }
  if (quick_stop_watch_.pending()) watch_quick_stop();
  if (tripped_) return;
  if (config_.description.simulated_clock) watch_heartbeats_in_bench_time();
  if (tripped_) return;
  const auto temperature =
      brake ? std::optional<double>(brake->temperature_c) : std::optional<double>();
  if (auto crossed = limits_check_.check(latest_, latest_drive_, temperature)) trip(*crossed);
}

void CanopenBench::watch_heartbeats_in_bench_time() noexcept {
  const double timeout = config_.description.limits.heartbeat_timeout_s;
  if (timeout <= 0 || lifecycle_ == BenchLifecycle::kUnconfigured) return;
  const double t = now();
  for (const auto& [node, last] : last_heartbeat_) {
    if (t - last > timeout) {
      trip("heartbeat of node " + std::to_string(node) + " (" + node_name(node) +
           ") lost: none for " + std::to_string(std::lround((t - last) * 1e3)) +
           " ms of bench time (consumer time " + std::to_string(std::lround(timeout * 1e3)) +
           " ms)");
      return;
    }
  }
}

void CanopenBench::on_heartbeat_frame(const can::Frame& frame) noexcept {
  const auto hb = canopen::decode_heartbeat(frame);
  if (!hb || !last_heartbeat_.contains(hb->node)) return;
  last_heartbeat_[hb->node] = now();
  for (auto& d : channel_devices_) {
    if (d->node() != hb->node) continue;
    if (hb->state == canopen::NmtState::boot_up)
      d->on_boot();
    else
      d->on_heartbeat(static_cast<std::uint8_t>(hb->state));
  }
  if (hb->node == config_.can.drive_node) {
    const auto processed = Clock::now();
    if (last_drive_heartbeat_ != Clock::time_point{}) {
      stats_.drive_heartbeat_gap_max_s =
          std::max(stats_.drive_heartbeat_gap_max_s,
                   std::chrono::duration<double>(processed - last_drive_heartbeat_).count());
    }
    last_drive_heartbeat_ = processed;
    ++stats_.drive_heartbeats;
  }
  if (lifecycle_ == BenchLifecycle::kReady && hb->state != canopen::NmtState::operational) {
    trip("node " + std::to_string(hb->node) + " (" + node_name(hb->node) +
         ") left operational: " + std::string(canopen::to_string(hb->state)));
  }
}

// --- safety ---------------------------------------------------------------------------------

void CanopenBench::trip(const std::string& reason) noexcept {
  if (tripped_) return;
  if (!acquiring_ && lifecycle_ == BenchLifecycle::kUnconfigured) {
    spdlog::warn("bench '{}': {} (not connected: nothing to stop)", config_.description.name,
                 reason);
    return;
  }
  tripped_ = true;
  {
    std::lock_guard lock(reason_mutex_);
    reason_ = reason;
  }
  lifecycle_ = BenchLifecycle::kFault;
  spdlog::error("bench '{}' tripped: {}", config_.description.name, reason);
  quick_stop_drive();  // a frame on the bus, first: the brake's write waits for its answer
  make_brake_safe();
}

void CanopenBench::make_brake_safe() noexcept {
  if (!brake_) return;
  try {
    brake_->make_safe();
    brake_safe_pending_ = false;
  } catch (const std::exception& e) {
    brake_safe_pending_ = true;
    spdlog::error(
        "bench '{}': brake safe state not confirmed ({}); retrying when the link "
        "returns, the controller's watchdog switches the output off meanwhile",
        config_.description.name, e.what());
  }
}

void CanopenBench::quick_stop_drive() noexcept {
  if (!drive_ || !acquiring_) return;
  // On the bus now, beside whatever SDO transfer is in flight (quick_stop_watch.hpp).
  std::error_code ec;
  bus_.send(quick_stop_frame(config_.can.drive_node), ec);
  if (ec) {
    spdlog::error("bench '{}': quick-stop RPDO to the servo drive not sent: {}",
                  config_.description.name, ec.message());
  }
  quick_stop_watch_.start(now(), config_.can.quick_stop_timeout_s);
}

void CanopenBench::watch_quick_stop() noexcept {
  const auto statusword =
      latest_drive_.status_valid ? std::optional(latest_drive_.statusword) : std::nullopt;
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
  master_->nmt().send(canopen::NmtCommand::stop, config_.can.drive_node, ec);
  const auto last = quick_stop_watch_.last_statusword();
  const std::string why =
      "the servo drive did not show the quick stop within " +
      std::to_string(ms(config_.can.quick_stop_timeout_s).count()) + " ms (" +
      (last ? canopen::describe_statusword(*last) : std::string("no statusword received")) +
      "): NMT stop sent to node " + std::to_string(config_.can.drive_node);
  spdlog::error("bench '{}': {}{}", config_.description.name, why,
                ec ? " but not delivered: " + ec.message() : std::string());
  std::lock_guard lock(reason_mutex_);
  reason_ += "; " + why + (ec ? " (send failed: " + ec.message() + ")" : "");
}

void CanopenBench::finish_safe_state() noexcept {
  // The watch counts bench time, which stands still when the loop's cycles stall: this
  // real-time bound sends the NMT stop itself then.
  const auto deadline = Clock::now() + ms(config_.can.quick_stop_timeout_s + 0.5);
  while (quick_stop_watch_.pending() && Clock::now() < deadline) run_once();
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
          if (lifecycle_ == BenchLifecycle::kReady) trip("brake controller alarm: " + event.reason);
          break;
        case modbus::BrakeEvent::Kind::link_restored:
          spdlog::info("bench '{}': {}", config_.description.name, event.reason);
          if (brake_safe_pending_) make_brake_safe();
          break;
        case modbus::BrakeEvent::Kind::alarm_cleared:
          break;
      }
    });
  } catch (...) {
  }
}

void CanopenBench::clear_fault() {
  if (state() == BenchLifecycle::kReady) return;
  if (state() == BenchLifecycle::kUnconfigured || !acquiring_)
    throw std::logic_error("clear_fault: bench '" + config_.description.name +
                           "' is not connected");
  const auto& limits = config_.description.limits;
  // Let returning heartbeats and readbacks arrive before judging whether the cause persists.
  idle_for(std::max({limits.heartbeat_timeout_s, 2 * config_.can.heartbeat_producer_s, 0.05}));
  if (brake_supervisor_ && brake_supervisor_->link_lost())
    throw std::runtime_error(
        "cannot clear the fault: the Modbus link to the brake controller is still lost (" +
        brake_supervisor_->last_error() + ")");
  for (const auto& [node, last] : last_heartbeat_) {
    bool missing = false;
    if (config_.description.simulated_clock) {
      missing = limits.heartbeat_timeout_s > 0 && now() - last > limits.heartbeat_timeout_s;
    } else if (const auto* consumer = master_->heartbeat(node)) {
      missing = consumer->timed_out();
    }
    if (missing)
      throw std::runtime_error("cannot clear the fault: the heartbeat of node " +
                               std::to_string(node) + " (" + node_name(node) +
                               ") is still missing");
  }
  try {
    brake_->reset_alarm();
    brake_->make_safe();
    brake_->set_mode(modbus::BrakeMode::torque);
    brake_safe_pending_ = false;
  } catch (const std::exception& e) {
    throw std::runtime_error("cannot clear the fault: brake controller: " + std::string(e.what()));
  }
  try {
    for (const auto node : all_nodes()) master_->nmt().send(canopen::NmtCommand::start, node);
    finish_safe_state();
    // The fault reset is on the way to Switch On Disabled; the drive stays off until a run
    // needs it.
    drive_->go_to(canopen::Cia402State::switch_on_disabled);
    powered_ = false;
    drive_->set_mode(canopen::OperationMode::profile_position);
    drive_->set_target_velocity(0);
    mode_ = canopen::OperationMode::profile_position;
  } catch (const std::exception& e) {
    throw std::runtime_error("cannot clear the fault: servo drive (node " +
                             std::to_string(config_.can.drive_node) + "): " + e.what());
  }
  limits_check_.reset_reference();
  {
    std::lock_guard lock(reason_mutex_);
    reason_.clear();
  }
  tripped_ = false;
  quick_stop_watch_.reset();
  lifecycle_ = BenchLifecycle::kReady;
  spdlog::info("bench '{}': fault cleared", config_.description.name);
}

// --- power ----------------------------------------------------------------------------------

void CanopenBench::activate() {
  ensure_ready();
  if (powered_) return;
  // Enabled in profile position, which holds where the drive stands until a new set-point; a
  // stale profile-velocity target must not start the shaft on enable.
  if (mode_ == canopen::OperationMode::profile_velocity)
    drive_command("target velocity 0", [&] { drive_->set_target_velocity(0); });
  set_mode(canopen::OperationMode::profile_position);
  powered_ = true;  // from the first controlword on: deactivate() must power it down
  drive_command("enable operation", [&] { drive_->enable_operation(); });
  spdlog::info("bench '{}': servo drive enabled", config_.description.name);
}

void CanopenBench::deactivate() noexcept {
  if (!acquiring_) return;
  make_brake_safe();
  finish_safe_state();
  power_down_drive(tripped_ ? canopen::Cia402State::switch_on_disabled
                            : canopen::Cia402State::ready_to_switch_on);
}

void CanopenBench::power_down_drive(canopen::Cia402State target) noexcept {
  if (!drive_) return;
  std::error_code ec;
  const auto state = drive_->state(ec);
  if (!ec) {
    if (state == canopen::Cia402State::fault || state == target ||
        state == canopen::Cia402State::switch_on_disabled) {
      powered_ = false;
      return;
    }
    if (mode_ == canopen::OperationMode::profile_velocity) drive_->set_target_velocity(0, ec);
    drive_->go_to(target, ec);
  }
  if (ec) {
    spdlog::error(
        "bench '{}': servo drive (node {}) not powered down to {}: {}", config_.description.name,
        config_.can.drive_node, canopen::to_string(target),
        drive_->last_failure().message.empty() ? ec.message() : drive_->last_failure().message);
    return;
  }
  powered_ = false;
  spdlog::info("bench '{}': servo drive disabled ({})", config_.description.name,
               canopen::to_string(target));
}

// --- blocking calls -------------------------------------------------------------------------

void CanopenBench::run_once() {
  if (io_.stopped()) io_.restart();
  io_.run_one_for(std::chrono::milliseconds(20));
}

void CanopenBench::throw_if_tripped() {
  if (!tripped_) return;
  finish_safe_state();
  throw BenchAborted(fault_reason());
}

void CanopenBench::ensure_ready() {
  throw_if_tripped();
  if (state() != BenchLifecycle::kReady)
    throw std::logic_error("bench '" + config_.description.name + "' is not connected");
}

bool CanopenBench::run_until(const std::function<bool()>& done, double timeout_s,
                             bool tolerate_fault) {
  if (!acquiring_)
    throw std::logic_error("bench '" + config_.description.name + "' is not acquiring");
  const double deadline = now() + timeout_s;
  std::uint64_t seen = samples_ - 1;
  for (;;) {
    if (!tolerate_fault) throw_if_tripped();
    if (samples_ != seen) {
      seen = samples_;
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
    throw std::runtime_error("servo drive (node " + std::to_string(config_.can.drive_node) +
                             "): " + what + ": " + e.what());
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
    trip("brake controller at " + modbus::to_string(config_.brake.link.endpoint) + ": " + what +
         " failed: " + e.what());
  }
  throw_if_tripped();
}

void CanopenBench::set_mode(canopen::OperationMode mode) {
  if (mode_ == mode) return;
  drive_command("set mode", [&] { drive_->set_mode(mode); });
  mode_ = mode;
}

void CanopenBench::move_input_to(double theta_in_rad, double speed_rad_s) {
  ensure_ready();
  const auto& limits = config_.description.limits;
  if (!(speed_rad_s > 0) || !std::isfinite(speed_rad_s))
    throw std::invalid_argument("move_input_to: speed = " + std::to_string(speed_rad_s) +
                                " rad/s: expected > 0");
  if (limits.max_input_speed_rad_s > 0 && speed_rad_s > limits.max_input_speed_rad_s)
    throw std::invalid_argument("move_input_to: speed = " + std::to_string(speed_rad_s) +
                                " rad/s: above the limit safety.max_input_speed = " +
                                std::to_string(limits.max_input_speed_rad_s) + " rad/s");
  canopen::ProfileMove move;
  const auto& units = drive_channels_.units;
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
  const double distance = std::abs(theta_in_rad - latest_.theta_in_rad);
  drive_command("profile position move", [&] { drive_->move(move); });
  const auto start = samples_;
  const double timeout = 3 * distance / speed_rad_s + 10;
  const bool reached = run_until(
      [&] {
        return samples_ >= start + 2 && latest_drive_.status_valid &&
               (latest_drive_.statusword & canopen::statusword::target_reached) != 0;
      },
      timeout);
  if (!reached)
    throw std::runtime_error(
        "servo drive (node " + std::to_string(config_.can.drive_node) + "): target " +
        std::to_string(theta_in_rad) + " rad not reached within " + std::to_string(timeout) +
        " s of bench time (" + canopen::describe_statusword(latest_drive_.statusword) + ")");
  if (config_.drive.target_settle_s > 0) run_until(nullptr, config_.drive.target_settle_s);
}

void CanopenBench::run_input_velocity(double omega_in_rad_s) {
  ensure_ready();
  const auto& limits = config_.description.limits;
  if (!std::isfinite(omega_in_rad_s) ||
      (limits.max_input_speed_rad_s > 0 && std::abs(omega_in_rad_s) > limits.max_input_speed_rad_s))
    throw std::invalid_argument("run_input_velocity: omega = " + std::to_string(omega_in_rad_s) +
                                " rad/s: expected |omega| <= safety.max_input_speed = " +
                                std::to_string(limits.max_input_speed_rad_s) + " rad/s");
  const auto velocity =
      drive_channels_.units.velocity_value(omega_in_rad_s, "run_input_velocity omega");
  activate();
  set_mode(canopen::OperationMode::profile_velocity);
  drive_command("target velocity", [&] { drive_->set_target_velocity(velocity); });
}

void CanopenBench::stop_motion() {
  ensure_ready();
  if (powered_ && mode_ == canopen::OperationMode::profile_velocity)
    drive_command("target velocity 0", [&] { drive_->set_target_velocity(0); });
  constexpr double kStill = 0.05;  // rad/s at the input (0.5 rpm)
  int still = 0;
  const bool stopped = run_until(
      [&] {
        still = std::abs(latest_.input_speed_rad_s) < kStill ? still + 1 : 0;
        return still >= 10;
      },
      30.0);
  if (!stopped)
    throw std::runtime_error("servo drive (node " + std::to_string(config_.can.drive_node) +
                             "): input still turning at " +
                             std::to_string(latest_.input_speed_rad_s) +
                             " rad/s 30 s of bench time after the stop");
}

void CanopenBench::set_brake_torque(double torque_nm, double ramp_nm_per_s) {
  ensure_ready();
  if (!(torque_nm >= 0) || !std::isfinite(torque_nm))
    throw std::invalid_argument("set_brake_torque: torque = " + std::to_string(torque_nm) +
                                " N*m: expected >= 0");
  const double limit = config_.description.limits.max_brake_torque_nm;
  if (limit > 0 && torque_nm > limit)
    throw std::invalid_argument("set_brake_torque: torque = " + std::to_string(torque_nm) +
                                " N*m: above safety.max_brake_torque = " + std::to_string(limit) +
                                " N*m");
  brake_command("set torque", [&] {
    brake_->set_setpoint(torque_nm, modbus::BrakeMode::torque, ramp_nm_per_s);
    brake_->enable();
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

void CanopenBench::add_observer(SampleObserver& observer) {
  if (std::find(observers_.begin(), observers_.end(), &observer) == observers_.end())
    observers_.push_back(&observer);
}

void CanopenBench::remove_observer(SampleObserver& observer) {
  std::erase(observers_, &observer);
}

AcquisitionStats CanopenBench::acquisition_stats() const {
  AcquisitionStats s = stats_;
  if (!config_.description.simulated_clock && master_) {
    if (const auto* producer = const_cast<canopen::Master&>(*master_).sync()) {
      s.sync_late = producer->statistics().late;
      s.sync_skipped = producer->statistics().skipped;
    }
  }
  if (latest_drive_.status_valid) {
    s.drive_statusword = latest_drive_.statusword;
    s.drive_state = canopen::to_string(canopen::decode_state(latest_drive_.statusword));
  }
  if (const auto brake = fresh_brake_readback()) s.brake_output_on = brake->status.output_on;
  s.sync_lateness_p50_s = lateness_.percentile(0.5);
  s.sync_lateness_p99_s = lateness_.percentile(0.99);
  s.sync_lateness_max_s = lateness_.max();
  s.bench_time_s = now();
  s.real_time_s =
      t0_ == Clock::time_point{} ? 0 : std::chrono::duration<double>(Clock::now() - t0_).count();
  return s;
}

}  // namespace wavebench::bench
