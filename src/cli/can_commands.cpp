// `wavebench can ...`: commissioning tools that work against any standard CANopen device.
#include <fmt/format.h>

#include <boost/asio/io_context.hpp>
#include <boost/asio/signal_set.hpp>
#include <boost/asio/steady_timer.hpp>
#include <chrono>
#include <ctime>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "commands.hpp"
#include "wavebench/can/socket_can_bus.hpp"
#include "wavebench/canopen/frame_description.hpp"
#include "wavebench/canopen/nmt.hpp"
#include "wavebench/canopen/node_scanner.hpp"
#include "wavebench/canopen/sdo_client.hpp"
#include "wavebench/canopen/value_text.hpp"

namespace wavebench::cli {

namespace {

namespace co = wavebench::canopen;

struct CanOptions {
  std::string iface;
  std::string node;
  std::string index;
  std::string sub;
  std::string type;
  std::string value;
  std::string command;
  int timeout_ms = 1000;
  long count = 0;
  double seconds = 0;
};

// Runs a command body; maps failures to the exit codes of commands.hpp.
template <typename Body>
void run(ExitStatus& status, Body&& body) {
  try {
    body();
    status.code = 0;
  } catch (const co::SdoError& e) {
    std::cerr << "wavebench can: SDO node " << int(e.node())
              << fmt::format(" object {:04X}:{:02X}: abort {}\n", e.index(), e.sub_index(),
                             co::abort_text(co::abort_code_of(e.code())));
    status.code = 1;
  } catch (const std::invalid_argument& e) {
    std::cerr << "wavebench can: " << e.what() << "\n";
    status.code = 2;
  } catch (const std::exception& e) {
    std::cerr << "wavebench can: " << e.what() << "\n";
    status.code = 1;
  }
}

co::NodeId parse_node(const std::string& text) {
  const auto n = co::parse_number("node id", text, 127);
  if (n == 0) throw std::invalid_argument("node id '" + text + "': expected 1..127");
  return static_cast<co::NodeId>(n);
}

std::string timestamp_text(std::chrono::system_clock::time_point t) {
  const auto us =
      std::chrono::duration_cast<std::chrono::microseconds>(t.time_since_epoch()).count();
  return fmt::format("({}.{:06})", us / 1000000, us % 1000000);
}

void scan(const CanOptions& o) {
  boost::asio::io_context io;
  can::SocketCanBus bus(io, o.iface);
  co::ScanOptions options;
  options.sdo_timeout = std::chrono::milliseconds(o.timeout_ms);
  const auto nodes = co::scan_nodes(bus, options);
  if (nodes.empty()) {
    std::cout << "no CANopen node answered on " << o.iface << "\n";
    return;
  }
  auto opt = [](const std::optional<std::uint32_t>& v) {
    return v ? fmt::format("0x{:08X}", *v) : std::string("-");
  };
  std::cout << fmt::format("{:>4}  {:<10}  {:<10}  {:<10}  {:<10}  {:<10}  {}\n", "node", "0x1000",
                           "vendor", "product", "revision", "serial", "heartbeat");
  for (const auto& n : nodes) {
    std::cout << fmt::format("{:>4}  {:<10}  {:<10}  {:<10}  {:<10}  {:<10}  {}\n", int(n.node),
                             opt(n.device_type), opt(n.identity[0]), opt(n.identity[1]),
                             opt(n.identity[2]), opt(n.identity[3]),
                             n.heartbeat_state ? co::to_string(*n.heartbeat_state) : "-");
  }
}

void nmt(const CanOptions& o) {
  const auto command = co::parse_nmt_command(o.command);
  if (!command) {
    throw std::invalid_argument("NMT command '" + o.command +
                                "': expected start, stop, preop, reset or reset-comm");
  }
  const auto node = co::parse_number("node id", o.node, 127);  // 0 = all nodes
  boost::asio::io_context io;
  can::SocketCanBus bus(io, o.iface);
  co::NmtMaster(bus).send(*command, static_cast<co::NodeId>(node));
  std::cout << fmt::format("NMT {} sent to {}\n", co::to_string(*command),
                           node == 0 ? std::string("all nodes") : fmt::format("node {}", node));
}

void sdo_read(const CanOptions& o) {
  const auto node = parse_node(o.node);
  const auto index = static_cast<std::uint16_t>(co::parse_number("index", o.index, 0xFFFF));
  const auto sub = static_cast<std::uint8_t>(co::parse_number("sub-index", o.sub, 0xFF));
  if (!o.type.empty() && !co::is_value_type(o.type)) {
    throw std::invalid_argument("--type '" + o.type +
                                "': expected one of u8 u16 u32 u64 i8 i16 i32 i64 f32 f64 str hex");
  }
  boost::asio::io_context io;
  can::SocketCanBus bus(io, o.iface);
  co::SdoClient sdo(bus, node, std::chrono::milliseconds(o.timeout_ms));
  const auto bytes = sdo.upload(index, sub);
  std::cout << co::format_value(o.type, bytes) << "\n";
}

void sdo_write(const CanOptions& o) {
  const auto node = parse_node(o.node);
  const auto index = static_cast<std::uint16_t>(co::parse_number("index", o.index, 0xFFFF));
  const auto sub = static_cast<std::uint8_t>(co::parse_number("sub-index", o.sub, 0xFF));
  const auto bytes = co::encode_value(o.type, o.value);
  boost::asio::io_context io;
  can::SocketCanBus bus(io, o.iface);
  co::SdoClient sdo(bus, node, std::chrono::milliseconds(o.timeout_ms));
  sdo.download(index, sub, bytes);
  std::cout << fmt::format("node {} {:04X}:{:02X} <- [{}]\n", int(node), index, sub,
                           co::hex_bytes(bytes));
}

void dump(const CanOptions& o) {
  boost::asio::io_context io;
  can::SocketCanBus bus(io, o.iface);
  long seen = 0;
  auto frames = bus.on_frame([&](const can::Frame& f) {
    std::cout << timestamp_text(f.timestamp) << " " << o.iface << "  " << co::describe_frame(f)
              << "\n";
    std::cout.flush();  // a dump is watched live or piped into grep: no block buffering
    if (o.count > 0 && ++seen >= o.count) io.stop();
  });
  auto events = bus.on_event([&](const can::BusEvent& e) {
    std::cout << timestamp_text(e.frame.timestamp) << " " << o.iface << "  bus event "
              << can::to_string(e.kind) << " (" << can::to_string(e.frame) << ")\n";
  });
  boost::asio::signal_set signals(io, SIGINT, SIGTERM);
  signals.async_wait([&](const boost::system::error_code&, int) { io.stop(); });
  boost::asio::steady_timer limit(io);
  if (o.seconds > 0) {
    limit.expires_after(std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(o.seconds)));
    limit.async_wait([&](const boost::system::error_code& ec) {
      if (!ec) io.stop();
    });
  }
  io.run();
  std::cout.flush();
}

}  // namespace

void register_can_commands(CLI::App& app, ExitStatus& status) {
  auto* can_cmd =
      app.add_subcommand("can", "CANopen commissioning: scan, nmt, sdo-read, sdo-write, dump");
  can_cmd->require_subcommand(1);
  auto o = std::make_shared<CanOptions>();

  auto* scan_cmd =
      can_cmd->add_subcommand("scan", "list the nodes on the bus with 0x1000 and 0x1018");
  scan_cmd->add_option("IFACE", o->iface, "SocketCAN interface, e.g. can0 or vcan0")->required();
  scan_cmd->add_option("--timeout", o->timeout_ms, "SDO timeout per node [ms]")
      ->default_val(200)
      ->check(CLI::Range(1, 60000));
  scan_cmd->callback([o, &status] { run(status, [&] { scan(*o); }); });

  auto* nmt_cmd = can_cmd->add_subcommand("nmt", "send an NMT command");
  nmt_cmd->add_option("IFACE", o->iface, "SocketCAN interface")->required();
  nmt_cmd->add_option("COMMAND", o->command, "start|stop|preop|reset|reset-comm")->required();
  nmt_cmd->add_option("NODE", o->node, "node id 1..127, 0 = all")->required();
  nmt_cmd->callback([o, &status] { run(status, [&] { nmt(*o); }); });

  auto* read_cmd = can_cmd->add_subcommand("sdo-read", "upload an object and print its value");
  read_cmd->add_option("IFACE", o->iface, "SocketCAN interface")->required();
  read_cmd->add_option("NODE", o->node, "node id 1..127")->required();
  read_cmd->add_option("INDEX", o->index, "object index, e.g. 0x1018")->required();
  read_cmd->add_option("SUB", o->sub, "sub-index, e.g. 1")->required();
  read_cmd->add_option("--type", o->type, "u8 u16 u32 u64 i8 i16 i32 i64 f32 f64 str hex");
  read_cmd->add_option("--timeout", o->timeout_ms, "SDO timeout [ms]")->default_val(1000);
  read_cmd->callback([o, &status] { run(status, [&] { sdo_read(*o); }); });

  auto* write_cmd = can_cmd->add_subcommand("sdo-write", "download a value to an object");
  write_cmd->add_option("IFACE", o->iface, "SocketCAN interface")->required();
  write_cmd->add_option("NODE", o->node, "node id 1..127")->required();
  write_cmd->add_option("INDEX", o->index, "object index, e.g. 0x1017")->required();
  write_cmd->add_option("SUB", o->sub, "sub-index")->required();
  write_cmd->add_option("TYPE", o->type, "u8 u16 u32 u64 i8 i16 i32 i64 f32 f64 str hex")
      ->required();
  write_cmd->add_option("VALUE", o->value, "the value (0x prefix for hex integers)")->required();
  write_cmd->add_option("--timeout", o->timeout_ms, "SDO timeout [ms]")->default_val(1000);
  write_cmd->callback([o, &status] { run(status, [&] { sdo_write(*o); }); });

  auto* dump_cmd = can_cmd->add_subcommand("dump", "print the bus traffic decoded as CANopen");
  dump_cmd->add_option("IFACE", o->iface, "SocketCAN interface")->required();
  dump_cmd->add_option("-n,--count", o->count, "stop after this many frames");
  dump_cmd->add_option("-t,--seconds", o->seconds, "stop after this many seconds");
  dump_cmd->callback([o, &status] { run(status, [&] { dump(*o); }); });
}

}  // namespace wavebench::cli
