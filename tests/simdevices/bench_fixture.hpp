#pragma once
// A simulated bench on an in-process VirtualCanBus with a "master" endpoint that records what
// the devices send. Frames are delivered while the io_context is polled.

#include <gtest/gtest.h>

#include <boost/asio/io_context.hpp>
#include <initializer_list>
#include <memory>
#include <vector>

#include "../support/simulated_devices_gear.hpp"
#include "wavebench/can/virtual_can_bus.hpp"
#include "wavebench/simdevices/simulated_bench.hpp"

namespace wavebench::simdevices::testing {

class BenchFixture : public ::testing::Test {
 protected:
  explicit BenchFixture(BenchClock clock = BenchClock::kManual) { config.clock = clock; }

  void SetUp() override {
    bus = std::make_unique<can::VirtualCanBus>(io);
    master = bus->endpoint("master");
    device_side = bus->endpoint("simbench");
    subscription = master->on_frame([this](const can::Frame& f) { received.push_back(f); });
    bench = std::make_unique<SimulatedBench>(config, *device_side);
    bench->start();
    io.poll();
    io.restart();
  }

  void TearDown() override {
    bench.reset();
    subscription.reset();
  }

  void send(std::uint32_t id, std::initializer_list<std::uint8_t> bytes) {
    master->send(can::Frame::make(id, bytes));
    io.poll();
    io.restart();
  }

  // Sends a request and returns the frames that came back.
  std::vector<can::Frame> exchange(std::uint32_t id, std::initializer_list<std::uint8_t> bytes) {
    received.clear();
    send(id, bytes);
    return received;
  }

  void advance(double dt) {
    bench->advance(dt);
    io.poll();
    io.restart();
  }

  std::vector<can::Frame> frames_with_id(std::uint32_t id) const {
    std::vector<can::Frame> out;
    for (const auto& f : received) {
      if (f.id == id) out.push_back(f);
    }
    return out;
  }

  SimulatedBenchConfig config = wavebench::testing::simulated_devices_config();
  boost::asio::io_context io;
  std::unique_ptr<can::VirtualCanBus> bus;
  std::unique_ptr<can::VirtualCanEndpoint> master;
  std::unique_ptr<can::VirtualCanEndpoint> device_side;
  can::CanBus::Subscription subscription;
  std::unique_ptr<SimulatedBench> bench;
  std::vector<can::Frame> received;
};

inline can::Frame frame(std::uint32_t id, std::initializer_list<std::uint8_t> bytes) {
  return can::Frame::make(id, bytes);
}

}  // namespace wavebench::simdevices::testing
