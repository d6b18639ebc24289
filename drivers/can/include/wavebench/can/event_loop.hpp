#pragma once
// The one place that turns a bus's io_context. The bench thread owns the io_context; a driver call
// that needs its answer before it returns waits here, running the loop's handlers one at a time
// on the owning thread until the answer is ready. No other file runs, polls or restarts the
// io_context (tests/check_one_event_loop.sh holds that).
//
// Exceptions keep their message: a handler that throws leaves these functions unchanged, so the
// waiting caller sees exactly what was thrown (never rewritten into a transport error).

#include <boost/asio/io_context.hpp>
#include <chrono>
#include <cstddef>
#include <functional>

namespace wavebench::can {

// Runs handlers until `ready()` holds; returns false when the loop ran out of work first (nothing
// left that could make it ready).
bool run_until(boost::asio::io_context& io, const std::function<bool()>& ready);

// Runs the handlers that are ready now without waiting for more; returns how many ran.
std::size_t run_ready(boost::asio::io_context& io);

// Runs at most one handler, waiting up to `limit` for one; returns how many ran (0 or 1).
std::size_t run_next_within(boost::asio::io_context& io, std::chrono::milliseconds limit);

}  // namespace wavebench::can
