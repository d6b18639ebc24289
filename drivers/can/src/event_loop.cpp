#include "wavebench/can/event_loop.hpp"

namespace wavebench::can {

namespace {

// A loop stops when it runs out of work or when a handler threw; either way the next wait starts
// it afresh.
void ready_to_run(boost::asio::io_context& io) {
  if (io.stopped()) io.restart();
}

}  // namespace

bool run_until(boost::asio::io_context& io, const std::function<bool()>& ready) {
  while (!ready()) {
    ready_to_run(io);
    if (io.run_one() == 0) return ready();
  }
  return true;
}

std::size_t run_ready(boost::asio::io_context& io) {
  ready_to_run(io);
  return io.poll();
}

std::size_t run_next_within(boost::asio::io_context& io, std::chrono::milliseconds limit) {
  ready_to_run(io);
  return io.run_one_for(limit);
}

}  // namespace wavebench::can
