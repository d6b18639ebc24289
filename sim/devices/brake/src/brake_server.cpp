#include "wavebench/simdevices/brake_server.hpp"

#include <arpa/inet.h>
#include <modbus/modbus.h>
#include <netinet/in.h>
#include <sys/select.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <random>
#include <stdexcept>
#include <vector>

namespace wavebench::simdevices {

namespace {

uint16_t crc16_modbus(const uint8_t* data, size_t n) {
  uint16_t crc = 0xFFFF;
  for (size_t i = 0; i < n; ++i) {
    crc ^= data[i];
    for (int b = 0; b < 8; ++b) {
      crc = (crc & 1u) ? static_cast<uint16_t>((crc >> 1) ^ 0xA001u)
                       : static_cast<uint16_t>(crc >> 1);
    }
  }
  return crc;
}

void write_all(int fd, const uint8_t* data, size_t n) {
  while (n > 0) {
    const ssize_t w = ::write(fd, data, n);
    if (w <= 0) {
      if (w < 0 && errno == EINTR) continue;
      return;
    }
    data += w;
    n -= static_cast<size_t>(w);
  }
}

int read_u16(const uint8_t* p) {
  return (p[0] << 8) | p[1];
}

}  // namespace

void BrakeServer::MappingDeleter::operator()(_modbus_mapping_t* m) const noexcept {
  modbus_mapping_free(m);
}

BrakeServer::BrakeServer(BrakeServerOptions options)
    : options_(std::move(options)), controller_(options_.controller) {
  const auto& ep = options_.endpoint;
  const std::string where = "simulated brake on " + modbus::to_string(ep);
  mapping_.reset(
      modbus_mapping_new(0, 0, brake_registers::table_size, brake_registers::table_size));
  if (!mapping_) throw std::runtime_error(where + ": cannot allocate the register mapping");
  if (ep.transport == modbus::Transport::tcp) {
    ctx_ = modbus_new_tcp(ep.host.c_str(), ep.port);
    if (ctx_ == nullptr) {
      throw std::runtime_error(where + ": " + modbus_strerror(errno) +
                               " (expected a numeric IPv4 host)");
    }
    listen_fd_ = modbus_tcp_listen(ctx_, 8);
    if (listen_fd_ == -1) {
      const int err = errno;
      modbus_free(ctx_);
      throw std::runtime_error(where + ": cannot listen: " + modbus_strerror(err));
    }
    sockaddr_in addr{};
    socklen_t len = sizeof addr;
    getsockname(listen_fd_, reinterpret_cast<sockaddr*>(&addr), &len);
    port_ = ntohs(addr.sin_port);
  } else {
    ctx_ = modbus_new_rtu(options_.rtu_fd >= 0 ? "/dev/null" : ep.device.c_str(), ep.baud,
                          ep.parity, ep.data_bits, ep.stop_bits);
    if (ctx_ == nullptr) throw std::runtime_error(where + ": " + modbus_strerror(errno));
    if (options_.rtu_fd >= 0) {
      // A pty master needs no line settings; libmodbus reads and writes the fd as given.
      rtu_fd_ = options_.rtu_fd;
      modbus_set_socket(ctx_, rtu_fd_);
    } else {
      if (modbus_connect(ctx_) == -1) {
        const int err = errno;
        modbus_free(ctx_);
        throw std::runtime_error(where + ": cannot open: " + modbus_strerror(err));
      }
      rtu_fd_ = modbus_get_socket(ctx_);
    }
  }
  modbus_set_slave(ctx_, options_.unit_id);
  modbus_set_byte_timeout(ctx_, 0, 200000);
}

BrakeServer::~BrakeServer() {
  stop();
  if (listen_fd_ >= 0) ::close(listen_fd_);
  if (ctx_ != nullptr) {
    if (options_.endpoint.transport == modbus::Transport::rtu && options_.rtu_fd < 0) {
      modbus_close(ctx_);
    } else if (rtu_fd_ >= 0) {
      ::close(rtu_fd_);  // an adopted fd: libmodbus never saw its line settings, so no restore
    }
    modbus_free(ctx_);
  }
}

void BrakeServer::start() {
  if (server_thread_.joinable()) return;
  stopping_ = false;
  if (options_.endpoint.transport == modbus::Transport::tcp) {
    server_thread_ = std::thread([this] { serve_tcp(); });
  } else {
    server_thread_ = std::thread([this] { serve_rtu(); });
  }
  if (options_.real_time) clock_thread_ = std::thread([this] { run_clock(); });
}

void BrakeServer::stop() noexcept {
  {
    std::lock_guard lock(stop_mutex_);
    stopping_ = true;
  }
  stop_cv_.notify_all();
  if (server_thread_.joinable()) server_thread_.join();
  if (clock_thread_.joinable()) clock_thread_.join();
}

bool BrakeServer::sleep_unless_stopped(std::chrono::milliseconds d) {
  std::unique_lock lock(stop_mutex_);
  return !stop_cv_.wait_for(lock, d, [this] { return stopping_.load(); });
}

void BrakeServer::inject_fault(const BrakeFault& fault) {
  std::lock_guard lock(fault_mutex_);
  fault_ = fault;
}

void BrakeServer::clear_fault() {
  inject_fault(BrakeFault{});
}

bool BrakeServer::take_fault(BrakeFault& fault) {
  std::lock_guard lock(fault_mutex_);
  if (fault_.kind == BrakeFaultKind::none || fault_.requests == 0) return false;
  fault = fault_;
  if (fault_.requests > 0 && --fault_.requests == 0) fault_ = BrakeFault{};
  ++faults_committed_;
  return true;
}

void BrakeServer::step(double dt) {
  std::lock_guard lock(controller_mutex_);
  controller_.step(dt);
}

void BrakeServer::set_output_speed(double rad_per_s) {
  std::lock_guard lock(controller_mutex_);
  controller_.physics().set_output_speed(rad_per_s);
}

double BrakeServer::shaft_torque(double driving_torque_nm) const {
  std::lock_guard lock(controller_mutex_);
  return controller_.physics().shaft_torque(driving_torque_nm);
}

void BrakeServer::run_clock() noexcept {
  using Clock = std::chrono::steady_clock;
  auto last = Clock::now();
  std::unique_lock lock(stop_mutex_);
  while (!stop_cv_.wait_for(lock, options_.step_period, [this] { return stopping_.load(); })) {
    const auto now = Clock::now();
    const double dt = std::chrono::duration<double>(now - last).count();
    last = now;
    step(dt);
  }
}

void BrakeServer::reply_from_unit(int fd, const uint8_t* query, int unit) {
  const bool tcp = options_.endpoint.transport == modbus::Transport::tcp;
  const int header = modbus_get_header_length(ctx_);
  const uint8_t* pdu = query + header;
  const uint8_t fc = pdu[0];
  std::vector<uint8_t> reply_pdu;
  if (fc == MODBUS_FC_READ_HOLDING_REGISTERS || fc == MODBUS_FC_READ_INPUT_REGISTERS) {
    const int address = read_u16(pdu + 1);
    const int count = read_u16(pdu + 3);
    if (address + count <= brake_registers::table_size && count > 0 && count <= 125) {
      std::lock_guard lock(controller_mutex_);
      const auto& table =
          fc == MODBUS_FC_READ_HOLDING_REGISTERS ? controller_.holding() : controller_.input();
      reply_pdu = {fc, static_cast<uint8_t>(2 * count)};
      for (int i = 0; i < count; ++i) {
        reply_pdu.push_back(static_cast<uint8_t>(table[static_cast<size_t>(address + i)] >> 8));
        reply_pdu.push_back(static_cast<uint8_t>(table[static_cast<size_t>(address + i)]));
      }
    }
  } else if (fc == MODBUS_FC_WRITE_SINGLE_REGISTER) {
    reply_pdu.assign(pdu, pdu + 5);
  } else if (fc == MODBUS_FC_WRITE_MULTIPLE_REGISTERS) {
    reply_pdu.assign(pdu, pdu + 5);
  }
  if (reply_pdu.empty()) reply_pdu = {static_cast<uint8_t>(fc | 0x80), 2};
  std::vector<uint8_t> frame;
  if (tcp) {
    const size_t len = reply_pdu.size() + 1;
    frame = {query[0],
             query[1],
             0,
             0,
             static_cast<uint8_t>(len >> 8),
             static_cast<uint8_t>(len & 0xFF),
             static_cast<uint8_t>(unit)};
    frame.insert(frame.end(), reply_pdu.begin(), reply_pdu.end());
  } else {
    frame = {static_cast<uint8_t>(unit)};
    frame.insert(frame.end(), reply_pdu.begin(), reply_pdu.end());
    const uint16_t crc = crc16_modbus(frame.data(), frame.size());
    frame.push_back(static_cast<uint8_t>(crc & 0xFF));
    frame.push_back(static_cast<uint8_t>(crc >> 8));
  }
  write_all(fd, frame.data(), frame.size());
}

std::optional<BrakeServer::Outcome> BrakeServer::refuse_locked_write(int fd, const uint8_t* query,
                                                                     int length) {
  if (!options_.unlock_secret) return std::nullopt;
  const int header = modbus_get_header_length(ctx_);
  const uint8_t* pdu = query + header;
  const uint8_t fc = pdu[0];
  const bool write =
      fc == MODBUS_FC_WRITE_SINGLE_COIL || fc == MODBUS_FC_WRITE_SINGLE_REGISTER ||
      fc == MODBUS_FC_WRITE_MULTIPLE_COILS || fc == MODBUS_FC_WRITE_MULTIPLE_REGISTERS ||
      fc == MODBUS_FC_MASK_WRITE_REGISTER || fc == MODBUS_FC_WRITE_AND_READ_REGISTERS;
  if (!write) return std::nullopt;
  constexpr int kUnlockBytes = 2 * brake_registers::unlock_count;
  if (fc == MODBUS_FC_WRITE_MULTIPLE_REGISTERS && length >= header + 6 &&
      read_u16(pdu + 1) == brake_registers::unlock) {
    const bool whole = read_u16(pdu + 3) == brake_registers::unlock_count &&
                       pdu[5] == kUnlockBytes && length >= header + 6 + kUnlockBytes;
    std::uint64_t secret = 0;
    for (int i = 0; whole && i < brake_registers::unlock_count; ++i)
      secret = (secret << 16) | static_cast<std::uint64_t>(read_u16(pdu + 6 + 2 * i));
    if (whole && secret == *options_.unlock_secret) {
      unlocked_.insert(fd);
      reply_from_unit(fd, query, options_.unit_id);  // the echo of a write; nothing stored
      return Outcome::replied;
    }
    ++wrong_secrets_;
    modbus_reply_exception(ctx_, query, MODBUS_EXCEPTION_ILLEGAL_DATA_VALUE);
    unlocked_.erase(fd);
    return options_.endpoint.transport == modbus::Transport::tcp ? Outcome::drop_connection
                                                                 : Outcome::replied;
  }
  if (unlocked_.count(fd) != 0) return std::nullopt;
  ++writes_refused_;
  modbus_reply_exception(ctx_, query, MODBUS_EXCEPTION_ILLEGAL_FUNCTION);
  return Outcome::replied;
}

BrakeServer::Outcome BrakeServer::handle(int fd, const uint8_t* query, int length) {
  ++requests_;
  const bool tcp = options_.endpoint.transport == modbus::Transport::tcp;
  if (const auto refused = refuse_locked_write(fd, query, length)) return *refused;
  BrakeFault fault;
  if (take_fault(fault)) {
    switch (fault.kind) {
      case BrakeFaultKind::delayed_reply:
        if (!sleep_unless_stopped(fault.delay)) return Outcome::replied;
        break;  // then answer normally
      case BrakeFaultKind::exception_response:
        modbus_reply_exception(ctx_, query, static_cast<unsigned>(fault.exception_code));
        return Outcome::replied;
      case BrakeFaultKind::dropped_connection:
        return tcp ? Outcome::drop_connection : Outcome::replied;
      case BrakeFaultKind::wrong_unit_id:
        reply_from_unit(
            fd, query,
            fault.wrong_unit_id >= 0 ? fault.wrong_unit_id : (options_.unit_id + 1) % 256);
        return Outcome::replied;
      case BrakeFaultKind::garbage_bytes: {
        // Starts like a frame of ours so the client must look past the header to reject it.
        const uint8_t junk_tcp[] = {0xDE, 0xAD, 0xBE, 0xEF, 0x00, 0x03, 0xFF, 0xFF, 0x55};
        const uint8_t junk_rtu[] = {
            static_cast<uint8_t>(options_.unit_id), 0x03, 0x04, 0xDE, 0xAD, 0xBE, 0xEF, 0x00, 0x00};
        write_all(fd, tcp ? junk_tcp : junk_rtu, sizeof junk_tcp);
        return Outcome::replied;
      }
      case BrakeFaultKind::none:
        break;
    }
  }
  const int header = modbus_get_header_length(ctx_);
  const uint8_t fc = query[header];
  std::lock_guard lock(controller_mutex_);
  auto* m = mapping_.get();
  std::copy(controller_.holding().begin(), controller_.holding().end(), m->tab_registers);
  std::copy(controller_.input().begin(), controller_.input().end(), m->tab_input_registers);
  modbus_reply(ctx_, query, length, m);
  int address = -1;
  int count = 0;
  if (fc == MODBUS_FC_WRITE_SINGLE_REGISTER) {
    address = read_u16(query + header + 1);
    count = 1;
  } else if (fc == MODBUS_FC_WRITE_MULTIPLE_REGISTERS || fc == MODBUS_FC_WRITE_AND_READ_REGISTERS) {
    address = read_u16(query + header + (fc == MODBUS_FC_WRITE_MULTIPLE_REGISTERS ? 1 : 5));
    count = read_u16(query + header + (fc == MODBUS_FC_WRITE_MULTIPLE_REGISTERS ? 3 : 7));
  }
  if (address >= 0 && count > 0 && address + count <= brake_registers::table_size) {
    controller_.write_holding(address, count, m->tab_registers + address);
  }
  return Outcome::replied;
}

void BrakeServer::serve_tcp() noexcept {
  std::vector<int> clients;
  uint8_t query[MODBUS_TCP_MAX_ADU_LENGTH];
  while (!stopping_) {
    fd_set readable;
    FD_ZERO(&readable);
    FD_SET(listen_fd_, &readable);
    int max_fd = listen_fd_;
    for (const int c : clients) {
      FD_SET(c, &readable);
      max_fd = std::max(max_fd, c);
    }
    timeval tv{0, 50000};  // wake regularly to notice stop()
    const int n = select(max_fd + 1, &readable, nullptr, nullptr, &tv);
    if (n <= 0) continue;
    if (FD_ISSET(listen_fd_, &readable)) {
      const int c = accept(listen_fd_, nullptr, nullptr);
      if (c >= 0) {
        clients.push_back(c);
        ++connections_accepted_;
        most_clients_at_once_ = std::max<uint64_t>(most_clients_at_once_, clients.size());
      }
    }
    for (auto it = clients.begin(); it != clients.end();) {
      const int c = *it;
      if (!FD_ISSET(c, &readable)) {
        ++it;
        continue;
      }
      modbus_set_socket(ctx_, c);
      const int rc = modbus_receive(ctx_, query);
      bool drop = rc == -1;
      if (rc > 0) drop = handle(c, query, rc) == Outcome::drop_connection;
      if (drop) {
        unlocked_.erase(c);
        ::close(c);
        it = clients.erase(it);
      } else {
        ++it;
      }
    }
  }
  for (const int c : clients) ::close(c);
  unlocked_.clear();
  modbus_set_socket(ctx_, -1);
}

void BrakeServer::serve_rtu() noexcept {
  uint8_t query[MODBUS_RTU_MAX_ADU_LENGTH];
  while (!stopping_) {
    fd_set readable;
    FD_ZERO(&readable);
    FD_SET(rtu_fd_, &readable);
    timeval tv{0, 50000};
    const int n = select(rtu_fd_ + 1, &readable, nullptr, nullptr, &tv);
    if (n <= 0) continue;
    const int rc = modbus_receive(ctx_, query);
    if (rc > 0) {
      handle(rtu_fd_, query, rc);
    } else if (rc == -1) {
      if (errno == EIO || errno == EBADF) {
        // pty without a peer: nothing to read until a client opens the other side
        sleep_unless_stopped(std::chrono::milliseconds(20));
      }
      modbus_flush(ctx_);
    }
  }
}

std::uint64_t random_unlock_secret() {
  std::random_device source;
  std::uint64_t secret = 0;
  for (int i = 0; i < 2; ++i) secret = (secret << 32) | source();
  return secret;
}

std::string unlock_secret_text(std::uint64_t secret) {
  char text[19];
  std::snprintf(text, sizeof text, "0x%016llx", static_cast<unsigned long long>(secret));
  return text;
}

std::uint64_t parse_unlock_secret(const std::string& text) {
  std::size_t used = 0;
  unsigned long long v = 0;
  try {
    v = std::stoull(text, &used, 16);
  } catch (const std::exception&) {
    used = 0;
  }
  const bool digit_first = !text.empty() && std::isxdigit(static_cast<unsigned char>(text[0]));
  if (!digit_first || used == 0 || used != text.size() || text.size() > 18)
    throw std::invalid_argument("unlock secret '" + text.substr(0, 40) +
                                "': expected up to 16 hex digits, e.g. 0x1f2e3d4c5b6a7988");
  return v;
}

std::unique_ptr<BrakeServer> start_brake_server(BrakeServerOptions options) {
  auto server = std::make_unique<BrakeServer>(std::move(options));
  server->start();
  return server;
}

}  // namespace wavebench::simdevices
