// GET /api/live/stream: frames decimated by min/max per column with TE in arcsec (against the
// closed form), the status every fifth frame, bounded parameters and clients; and the stream
// over real HTTP from the in-process daemon.
#include "wavebench/daemon/live_stream.hpp"

#include <gtest/gtest.h>

#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/read.hpp>
#include <boost/asio/write.hpp>
#include <cmath>
#include <numbers>

#include "daemon_fixture.hpp"

namespace wavebench::daemon::testing {
namespace {

constexpr double kArcsecPerRad = 180.0 * 3600.0 / std::numbers::pi;

storage::SyncSample sample(double t, double te_rad, double torque) {
  storage::SyncSample s;
  s.flags = storage::kAllChannelsValid;
  s.receive_time_ns = static_cast<std::int64_t>(std::llround(t * 1e9));
  s.theta_out_rad = 0.25;                   // with direction sign -1: theta2 = -0.25
  s.theta_in_rad = (-0.25 - te_rad) * 100;  // TE = theta2 - theta_in / N = te_rad
  s.input_speed_rad_s = 10;
  s.torque_nm = torque;
  s.brake_current_a = 0.5;
  return s;
}

nlohmann::json bench_status() {
  return {{"state", "ready"}, {"bench", {{"ratio", 100.0}, {"direction_sign", -1}}}};
}

LiveStreamParams params(double window_s, std::size_t columns) {
  LiveStreamParams p;
  p.window_s = window_s;
  p.columns = columns;
  return p;
}

TEST(LiveStreamFrames, CompleteColumnsCarryMinAndMaxWithTheSpikeAndTeInArcsec) {
  LiveSampleBuffer live(4096);
  for (int i = 0; i < 250; ++i) {
    live.on_sample(sample(i * 1e-3, i == 37 ? 1e-4 : 0.0, i == 150 ? -7.0 : 1.0));
  }
  LiveStreamFrames frames(live, bench_status, params(1, 10), nullptr);  // 0.1 s columns
  const auto first = frames.frame();
  ASSERT_TRUE(first.contains("status"));
  EXPECT_EQ(first["seq"], 250);
  EXPECT_DOUBLE_EQ(first["column_s"].get<double>(), 0.1);
  const auto& rows = first["rows"];
  // Columns [0, 0.1) and [0.1, 0.2) are complete; the one holding t = 0.249 is not yet.
  ASSERT_EQ(rows["t"].size(), 4u);
  EXPECT_FALSE(first["full_resolution"].get<bool>());
  double te_max = -1e9, torque_min = 1e9;
  for (std::size_t i = 0; i < 4; ++i) {
    te_max = std::max(te_max, rows["te_arcsec"][i].get<double>());
    torque_min = std::min(torque_min, rows["torque_nm"][i].get<double>());
    EXPECT_LT(rows["t"][i].get<double>(), 0.2);
  }
  EXPECT_NEAR(te_max, 1e-4 * kArcsecPerRad, 1e-6);  // the one-sample spike survives
  EXPECT_DOUBLE_EQ(torque_min, -7.0);
  EXPECT_NEAR(rows["te_arcsec"][3].get<double>(), 0.0, 1e-6);

  EXPECT_TRUE(frames.frame().is_null());  // nothing new, no status due
  for (int i = 250; i < 420; ++i) live.on_sample(sample(i * 1e-3, 0.0, 1.0));
  const auto second = frames.frame();
  ASSERT_TRUE(second.contains("rows"));
  ASSERT_EQ(second["rows"]["t"].size(), 4u);  // columns 2 and 3, each sample counted once
  EXPECT_GE(second["rows"]["t"][0].get<double>(), 0.2);
  EXPECT_FALSE(second["reset"].get<bool>());
}

TEST(LiveStreamFrames, FewSamplesComeAtFullResolutionAndInvalidValuesAreNull) {
  LiveSampleBuffer live(64);
  for (int i = 0; i < 10; ++i) {
    auto s = sample(i * 1e-3, 0, 2.0);
    if (i < 5) s.flags &= ~storage::kTorqueValid;
    live.on_sample(s);
  }
  live.on_sample(sample(1.0, 0, 2.0));  // completes every column before t = 1 s
  LiveStreamFrames frames(live, bench_status, params(1, 100), nullptr);
  const auto f = frames.frame();
  ASSERT_TRUE(f["full_resolution"].get<bool>());
  ASSERT_EQ(f["rows"]["t"].size(), 10u);
  EXPECT_TRUE(f["rows"]["torque_nm"][0].is_null());
  EXPECT_DOUBLE_EQ(f["rows"]["torque_nm"][9].get<double>(), 2.0);
}

TEST(LiveStreamFrames, WithoutABenchDescriptionTeIsNull) {
  LiveSampleBuffer live(64);
  for (int i = 0; i < 10; ++i) live.on_sample(sample(i * 1e-3, 0, 2.0));
  live.on_sample(sample(1.0, 0, 2.0));
  LiveStreamFrames frames(
      live,
      [] {
        return nlohmann::json{{"bench", nullptr}};
      },
      params(1, 100), nullptr);
  const auto f = frames.frame();
  EXPECT_TRUE(f["rows"]["te_arcsec"][0].is_null());
  EXPECT_DOUBLE_EQ(f["rows"]["input_speed_rad_s"][0].get<double>(), 10.0);
}

TEST(LiveStreamParams, BoundedAndNamed) {
  const auto parse = [](const std::string& query) {
    return live_stream_params(parse_http_target("/api/live/stream?" + query));
  };
  EXPECT_DOUBLE_EQ(parse("window_s=600&columns=4000").window_s, 600);
  for (const auto& [query, named] : std::vector<std::pair<std::string, std::string>>{
           {"window_s=601", "window_s: got '601'"},
           {"window_s=0.5", "window_s: got '0.5'"},
           {"window_s=nan", "window_s: got 'nan'"},
           {"columns=4001", "columns: got '4001'"},
           {"columns=-1", "columns: got '-1'"},
           {"columns=1e3", "columns: got '1e3'"},
           {"colums=10", "colums: unknown parameter"}}) {
    try {
      parse(query);
      ADD_FAILURE() << query;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(named), std::string::npos) << e.what();
    }
  }
}

TEST(LiveStreamClients, AtMostTheBoundAndSlotsComeBack) {
  LiveStreamClients clients(2);
  auto a = clients.admit();
  auto b = clients.admit();
  EXPECT_TRUE(a && b);
  EXPECT_FALSE(clients.admit());
  a.reset();
  EXPECT_TRUE(clients.admit());
}

using LiveStreamHttpTest = DaemonFixture;

// Reads from the socket until `needle` has appeared `count` times (or 5 MB went by).
std::string read_until(boost::asio::ip::tcp::socket& socket, const std::string& needle, int count) {
  std::string text;
  char buffer[4096];
  for (;;) {
    int found = 0;
    for (auto p = text.find(needle); p != std::string::npos; p = text.find(needle, p + 1)) ++found;
    if (found >= count || text.size() > 5'000'000) return text;
    boost::system::error_code ec;
    const auto n = socket.read_some(boost::asio::buffer(buffer), ec);
    if (ec) return text;
    text.append(buffer, n);
  }
}

TEST_F(LiveStreamHttpTest, TheStreamSendsFramesWithStatusAndRowsAndIsBounded) {
  boost::asio::io_context io;
  const auto open = [&](const std::string& query) {
    auto socket = std::make_unique<boost::asio::ip::tcp::socket>(io);
    socket->connect({boost::asio::ip::make_address("127.0.0.1"), daemon_->port()});
    const std::string request = "GET /api/live/stream" + query +
                                " HTTP/1.1\r\nHost: 127.0.0.1\r\nAccept: text/event-stream\r\n\r\n";
    boost::asio::write(*socket, boost::asio::buffer(request));
    return socket;
  };
  auto first = open("?window_s=10&columns=100");
  const auto text = read_until(*first, "\n\ndata: ", 6);
  ASSERT_NE(text.find("HTTP/1.1 200"), std::string::npos) << text.substr(0, 300);
  EXPECT_NE(text.find("Content-Type: text/event-stream"), std::string::npos);
  EXPECT_EQ(text.find("Access-Control-"), std::string::npos);
  bool status = false, rows = false;
  for (auto p = text.find("data: "); p != std::string::npos; p = text.find("data: ", p + 1)) {
    const auto end = text.find("\n\n", p);
    if (end == std::string::npos) break;
    const auto frame = nlohmann::json::parse(text.substr(p + 6, end - p - 6));
    status = status || frame.contains("status");
    rows = rows || (frame.contains("rows") && !frame["rows"]["t"].empty());
  }
  EXPECT_TRUE(status);
  EXPECT_TRUE(rows);

  std::vector<std::unique_ptr<boost::asio::ip::tcp::socket>> more;
  for (std::size_t i = 1; i < DaemonApi::kMaxLiveStreams; ++i) {
    more.push_back(open(""));
    EXPECT_NE(read_until(*more.back(), "data: ", 1).find("200"), std::string::npos);
  }
  auto refused = open("");
  EXPECT_NE(read_until(*refused, "}", 1).find("HTTP/1.1 503"), std::string::npos);
  auto bad = open("?window_s=9999");
  const auto bad_text = read_until(*bad, "}", 1);
  // Parameters are checked before the client bound: the message names the key and the range.
  EXPECT_NE(bad_text.find("HTTP/1.1 400"), std::string::npos);
  EXPECT_NE(bad_text.find("window_s: got '9999', expected a number of seconds from"),
            std::string::npos);
}

}  // namespace
}  // namespace wavebench::daemon::testing
