#include "wavebench/modbus/modbus_link.hpp"

#include <modbus/modbus.h>
#include <sys/socket.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <string>
#include <thread>

namespace wavebench::modbus {

namespace {

void set_timeout(modbus_t* ctx, std::chrono::milliseconds t, bool response) {
  const auto sec = static_cast<uint32_t>(t.count() / 1000);
  const auto usec = static_cast<uint32_t>((t.count() % 1000) * 1000);
  if (response) {
    modbus_set_response_timeout(ctx, sec, usec);
  } else {
    modbus_set_byte_timeout(ctx, sec, usec);
  }
}

std::string hex(const uint8_t* p, int n) {
  static const char* digits = "0123456789abcdef";
  std::string s;
  for (int i = 0; i < n && i < 32; ++i) {
    if (i) s += ' ';
    s += digits[p[i] >> 4];
    s += digits[p[i] & 15];
  }
  return s;
}

}  // namespace

ModbusLink::ModbusLink(BrakeLinkConfig config) : config_(std::move(config)) {}

ModbusLink::~ModbusLink() {
  close();
}

void ModbusLink::connect() {
  close();
  const auto& ep = config_.endpoint;
  modbus_t* ctx = nullptr;
  if (ep.transport == Transport::tcp) {
    ctx = modbus_new_tcp_pi(ep.host.c_str(), std::to_string(ep.port).c_str());
  } else {
    ctx = modbus_new_rtu(ep.device.c_str(), ep.baud, ep.parity, ep.data_bits, ep.stop_bits);
  }
  if (ctx == nullptr) {
    throw ModbusError(
        ModbusErrorKind::not_connected,
        "modbus " + to_string(ep) + ": cannot create context: " + modbus_strerror(errno));
  }
  modbus_set_slave(ctx, config_.unit_id);
  set_timeout(ctx, config_.response_timeout, true);
  set_timeout(ctx, config_.byte_timeout, false);
  if (modbus_connect(ctx) == -1) {
    const int err = errno;
    modbus_free(ctx);
    throw ModbusError(ModbusErrorKind::not_connected,
                      "modbus " + to_string(ep) + ": cannot connect: " + modbus_strerror(err));
  }
  ctx_ = ctx;
  open_.store(true, std::memory_order_release);
  connections_.fetch_add(1, std::memory_order_acq_rel);
  last_tid_ = 0;
  flush_before_next_ = ep.transport == Transport::rtu;
  if (config_.unlock_secret) unlock(*config_.unlock_secret);
}

// A controller that takes writes only after a shared secret (the simulated one, see
// brake_registers::unlock) is unlocked on every new connection: a reconnect is a new one.
void ModbusLink::unlock(std::uint64_t secret) {
  std::vector<uint16_t> words(4);
  for (int i = 3; i >= 0; --i, secret >>= 16)
    words[static_cast<size_t>(i)] = static_cast<uint16_t>(secret & 0xFFFF);
  try {
    write_registers(config_.unlock_address, words);
  } catch (const ModbusError& e) {
    close();
    throw ModbusError(ModbusErrorKind::not_connected,
                      "modbus " + to_string(config_.endpoint) +
                          ": the controller did not take the unlock secret: " + e.what());
  }
}

void ModbusLink::close() noexcept {
  if (ctx_ != nullptr) {
    modbus_close(ctx_);
    modbus_free(ctx_);
    ctx_ = nullptr;
    open_.store(false, std::memory_order_release);
  }
}

void ModbusLink::fail_transport(int err, const char* during) {
  const bool tcp = config_.endpoint.transport == Transport::tcp;
  ModbusErrorKind kind = ModbusErrorKind::connection;
  if (err == ETIMEDOUT) {
    kind = ModbusErrorKind::timeout;
  } else if (err == EMBBADCRC || err == EMBBADDATA || err == EMBMDATA || err == EMBBADEXC ||
             err == EMBUNKEXC) {
    kind = ModbusErrorKind::bad_reply;
  } else if (err == EMBBADSLAVE) {
    kind = ModbusErrorKind::wrong_unit;
  }
  std::string what = "modbus " + to_string(config_.endpoint) + " unit " +
                     std::to_string(config_.unit_id) + ": " + to_string(kind) + " during " +
                     during + " (" + modbus_strerror(err) + ")";
  if (kind == ModbusErrorKind::timeout) {
    what += ", response timeout " + std::to_string(config_.response_timeout.count()) +
            " ms, byte timeout " + std::to_string(config_.byte_timeout.count()) + " ms";
  }
  // A TCP stream after a timeout or a broken frame may still carry the late or partial
  // reply; starting over on a fresh connection is the only way to be back in step.
  if (tcp) {
    close();
  } else {
    flush_before_next_ = true;
    if (kind == ModbusErrorKind::timeout) {
      quiet_until_ = std::chrono::steady_clock::now() + config_.response_timeout;
    }
  }
  throw ModbusError(kind, what);
}

std::vector<uint8_t> ModbusLink::transact(const std::vector<uint8_t>& pdu) {
  if (ctx_ == nullptr) {
    throw ModbusError(ModbusErrorKind::not_connected,
                      "modbus " + to_string(config_.endpoint) + ": not connected");
  }
  if (flush_before_next_) {
    std::this_thread::sleep_until(quiet_until_);
    modbus_flush(ctx_);
    flush_before_next_ = false;
  }
  std::vector<uint8_t> raw;
  raw.reserve(pdu.size() + 1);
  raw.push_back(static_cast<uint8_t>(config_.unit_id));
  raw.insert(raw.end(), pdu.begin(), pdu.end());
  const uint8_t fc = pdu[0];
  ++transactions_;
  if (config_.endpoint.transport == Transport::tcp) {
    // libmodbus sends raw requests with transaction id 0; a fresh id per request lets a
    // stale or foreign reply be told from the answer, so the MBAP header is built here.
    last_tid_ = static_cast<uint16_t>(last_tid_ + 1);
    const auto length = static_cast<uint16_t>(raw.size());
    std::vector<uint8_t> adu{
        static_cast<uint8_t>(last_tid_ >> 8), static_cast<uint8_t>(last_tid_ & 0xFF), 0, 0,
        static_cast<uint8_t>(length >> 8),    static_cast<uint8_t>(length & 0xFF)};
    adu.insert(adu.end(), raw.begin(), raw.end());
    size_t sent = 0;
    while (sent < adu.size()) {
      const ssize_t w =
          ::send(modbus_get_socket(ctx_), adu.data() + sent, adu.size() - sent, MSG_NOSIGNAL);
      if (w < 0 && errno == EINTR) continue;
      if (w <= 0) fail_transport(errno, "send");
      sent += static_cast<size_t>(w);
    }
  } else if (modbus_send_raw_request(ctx_, raw.data(), static_cast<int>(raw.size())) == -1) {
    fail_transport(errno, "send");
  }
  uint8_t rsp[MODBUS_MAX_ADU_LENGTH];
  const int n = modbus_receive_confirmation(ctx_, rsp);
  if (n == -1) fail_transport(errno, "receive");
  const std::string who =
      "modbus " + to_string(config_.endpoint) + " unit " + std::to_string(config_.unit_id);
  if (n == 0) {
    // libmodbus drops an RTU frame addressed from another unit before looking further.
    flush_before_next_ = true;
    throw ModbusError(ModbusErrorKind::wrong_unit,
                      who + ": reply came from another unit id (expected " +
                          std::to_string(config_.unit_id) + ")");
  }
  const bool tcp = config_.endpoint.transport == Transport::tcp;
  const int header = modbus_get_header_length(ctx_);
  const int checksum = tcp ? 0 : 2;
  if (n < header + 2 + checksum) {
    if (tcp) close();
    throw ModbusError(ModbusErrorKind::bad_reply, who + ": reply too short: " + hex(rsp, n));
  }
  if (tcp) {
    const int tid = (rsp[0] << 8) | rsp[1];
    const int proto = (rsp[2] << 8) | rsp[3];
    if (tid != last_tid_ || proto != 0) {
      close();
      throw ModbusError(ModbusErrorKind::bad_reply,
                        who + ": reply with transaction id " + std::to_string(tid) + " protocol " +
                            std::to_string(proto) + " (expected " + std::to_string(last_tid_) +
                            ", 0): " + hex(rsp, n));
    }
  }
  const int unit = rsp[header - 1];
  if (unit != config_.unit_id) {
    throw ModbusError(ModbusErrorKind::wrong_unit, who + ": reply came from unit id " +
                                                       std::to_string(unit) + " (expected " +
                                                       std::to_string(config_.unit_id) + ")");
  }
  const uint8_t rfc = rsp[header];
  if (rfc == (fc | 0x80)) {
    const int code = rsp[header + 1];
    throw ModbusError(ModbusErrorKind::exception,
                      who + ": exception " + std::to_string(code) + " (" + exception_text(code) +
                          ") to function " + std::to_string(fc),
                      code);
  }
  if (rfc != fc) {
    if (tcp) close();
    throw ModbusError(ModbusErrorKind::bad_reply, who + ": reply has function " +
                                                      std::to_string(rfc) + ", expected " +
                                                      std::to_string(fc) + ": " + hex(rsp, n));
  }
  return {rsp + header, rsp + n - checksum};
}

std::vector<uint16_t> ModbusLink::read_registers(RegisterTable table, int address, int count) {
  if (count < 1 || count > MODBUS_MAX_READ_REGISTERS || address < 0 || address + count > 65536) {
    throw ModbusError(ModbusErrorKind::invalid_argument,
                      "read of " + std::to_string(count) + " registers at " +
                          std::to_string(address) + ": expected 1..125 registers below 65536");
  }
  const uint8_t fc = table == RegisterTable::holding ? MODBUS_FC_READ_HOLDING_REGISTERS
                                                     : MODBUS_FC_READ_INPUT_REGISTERS;
  const std::vector<uint8_t> pdu{
      fc, static_cast<uint8_t>(address >> 8), static_cast<uint8_t>(address & 0xFF),
      static_cast<uint8_t>(count >> 8), static_cast<uint8_t>(count & 0xFF)};
  const auto reply = transact(pdu);
  if (reply.size() != static_cast<size_t>(2 + 2 * count) || reply[1] != 2 * count) {
    if (config_.endpoint.transport == Transport::tcp) close();
    throw ModbusError(ModbusErrorKind::bad_reply,
                      "modbus " + to_string(config_.endpoint) + ": read of " +
                          std::to_string(count) + " registers answered with " +
                          std::to_string(reply.size() > 1 ? reply[1] : 0) + " bytes");
  }
  std::vector<uint16_t> values(static_cast<size_t>(count));
  for (int i = 0; i < count; ++i) {
    values[static_cast<size_t>(i)] = static_cast<uint16_t>(
        (reply[static_cast<size_t>(2 + 2 * i)] << 8) | reply[static_cast<size_t>(3 + 2 * i)]);
  }
  return values;
}

void ModbusLink::write_registers(int address, const std::vector<uint16_t>& values) {
  const int count = static_cast<int>(values.size());
  if (count < 1 || count > MODBUS_MAX_WRITE_REGISTERS || address < 0 || address + count > 65536) {
    throw ModbusError(ModbusErrorKind::invalid_argument,
                      "write of " + std::to_string(count) + " registers at " +
                          std::to_string(address) + ": expected 1..123 registers below 65536");
  }
  std::vector<uint8_t> pdu;
  if (count == 1) {
    pdu = {MODBUS_FC_WRITE_SINGLE_REGISTER, static_cast<uint8_t>(address >> 8),
           static_cast<uint8_t>(address & 0xFF), static_cast<uint8_t>(values[0] >> 8),
           static_cast<uint8_t>(values[0] & 0xFF)};
  } else {
    pdu = {MODBUS_FC_WRITE_MULTIPLE_REGISTERS,   static_cast<uint8_t>(address >> 8),
           static_cast<uint8_t>(address & 0xFF), static_cast<uint8_t>(count >> 8),
           static_cast<uint8_t>(count & 0xFF),   static_cast<uint8_t>(2 * count)};
    for (const uint16_t v : values) {
      pdu.push_back(static_cast<uint8_t>(v >> 8));
      pdu.push_back(static_cast<uint8_t>(v & 0xFF));
    }
  }
  const auto reply = transact(pdu);
  if (reply.size() != 5 || !std::equal(reply.begin(), reply.end(), pdu.begin())) {
    if (config_.endpoint.transport == Transport::tcp) close();
    throw ModbusError(ModbusErrorKind::bad_reply, "modbus " + to_string(config_.endpoint) +
                                                      ": write at " + std::to_string(address) +
                                                      " not echoed correctly");
  }
}

}  // namespace wavebench::modbus
