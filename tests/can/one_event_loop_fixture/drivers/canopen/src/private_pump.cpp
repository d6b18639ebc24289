// Fixture for check_one_event_loop.sh: a private pump the check must reject.
#include <boost/asio/io_context.hpp>

void wait_privately(boost::asio::io_context& io, const bool& done) {
  while (!done) io.run_one();
}
