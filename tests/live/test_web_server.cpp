// The server of `live --serve` (live/web_server.hpp) through cpp-httplib's client: the page and
// its offline files, BlueOS's metadata, CORS and framing, the event stream and the long poll (with
// their latency), the map picture, the buttons' handlers, acknowledgements, many clients, a client
// that leaves, and a prompt stop.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <map>
#include <mutex>
#include <thread>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/live/live_view.hpp"
#include "sonarmap/live/web_server.hpp"

// Last: it brings glibc's <resolv.h>, whose `_res` macro breaks Eigen's headers included after it.
#include <httplib.h>

namespace sonarmap {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;
using nlohmann::json;

Beam beamOf(double bearing_rad) {
  Beam beam;
  beam.bearing_rad = bearing_rad;
  beam.bin_length_m = 50.0 / 1200;
  beam.intensities.assign(1200, 40);
  return beam;
}

OcTree16 wallMap() {
  OcTree16 map(0.1);
  for (double y = -3.0; y < 3.0; y += 0.1) {
    for (int i = 0; i < 3; ++i) map.integrate(map.coder().keyOfChecked({5.05, y + 0.05, 0.05}), true);
  }
  map.updateInnerOccupancy();
  return map;
}

/// An event-stream client on its own thread: the `update` events it received, with their times.
class EventClient {
 public:
  EventClient(int port, bool* refused = nullptr) : client_("127.0.0.1", port) {
    client_.set_read_timeout(10, 0);
    thread_ = std::thread([this, refused] {
      std::string buffer;
      const httplib::Result result = client_.Get(
          "/events", httplib::Headers{},
          [refused](const httplib::Response& response) {
            if (refused != nullptr) *refused = response.status == 503;
            return response.status == 200;
          },
          [&](const char* data, std::size_t length) {
            buffer.append(data, length);
            for (std::size_t end; (end = buffer.find("\n\n")) != std::string::npos;) {
              const std::string event = buffer.substr(0, end);
              buffer.erase(0, end + 2);
              const std::size_t data_at = event.find("data: ");
              if (data_at == std::string::npos) continue;
              std::lock_guard lock(mutex_);
              events_.push_back({Clock::now(), json::parse(event.substr(data_at + 6))});
            }
            return !leave_;
          });
      ended_ = true;
    });
  }
  ~EventClient() {
    leave_ = true;
    client_.stop();
    thread_.join();
  }
  struct Event {
    Clock::time_point at;
    json update;
  };
  std::vector<Event> events() {
    std::lock_guard lock(mutex_);
    return events_;
  }
  /// The time the beam `seq` was received.
  std::optional<Clock::time_point> received(std::uint64_t seq) {
    std::lock_guard lock(mutex_);
    for (const Event& event : events_) {
      for (const json& beam : event.update["beams"]) {
        if (beam["s"] == seq) return event.at;
      }
    }
    return std::nullopt;
  }
  void leave() { leave_ = true; }
  bool ended() const { return ended_; }

 private:
  httplib::Client client_;
  std::thread thread_;
  std::mutex mutex_;
  std::vector<Event> events_;
  std::atomic<bool> leave_{false}, ended_{false};
};

template <class Done>
bool eventually(Done done, std::chrono::milliseconds limit = 5000ms) {
  const auto until = Clock::now() + limit;
  while (Clock::now() < until) {
    if (done()) return true;
    std::this_thread::sleep_for(2ms);
  }
  return done();
}

WebServerOptions localOptions() {
  WebServerOptions options;
  options.address = "127.0.0.1";
  options.heartbeat_s = 0.5;
  options.threads = 12;
  options.max_streams = 6;
  return options;
}

double percentileMs(std::vector<double> samples, double q) {
  std::sort(samples.begin(), samples.end());
  return 1000.0 * samples[std::min(samples.size() - 1, static_cast<std::size_t>(q * samples.size()))];
}

TEST(WebServer, ServesTheOfflinePageAndBlueOSMetadata) {
  LiveView view(Clock::now());
  WebServer server(view, localOptions());
  ASSERT_GT(server.port(), 0);
  EXPECT_EQ(server.url(), "http://127.0.0.1:" + std::to_string(server.port()) + "/");
  httplib::Client client("127.0.0.1", server.port());
  const httplib::Result page = client.Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_NE(page->body.find("<canvas id=\"map\""), std::string::npos);
  EXPECT_NE(page->body.find("<title>sonarmap live</title>"), std::string::npos);
  EXPECT_FALSE(page->has_header("X-Frame-Options"));  // Cockpit's iframe widget may show it
  EXPECT_EQ(page->get_header_value("Connection"), "close");
  std::string everything = page->body;
  for (const char* file : {"/live.css", "/live.js", "/map_view.js"}) {
    const httplib::Result got = client.Get(file);
    ASSERT_TRUE(got) << file;
    EXPECT_EQ(got->status, 200) << file;
    EXPECT_GT(got->body.size(), 500U) << file;
    everything += got->body;
  }
  // Offline and prefix-proof: no absolute URL, no root-relative fetch or source.
  EXPECT_EQ(everything.find("http://"), std::string::npos);
  EXPECT_EQ(everything.find("https://"), std::string::npos);
  for (const char* absolute : {"src=\"/", "href=\"/", "fetch('/", "EventSource('/", "fetch(`/"}) {
    EXPECT_EQ(everything.find(absolute), std::string::npos) << absolute;
  }

  const httplib::Result metadata = client.Get("/register_service");
  ASSERT_TRUE(metadata);
  const json service = json::parse(metadata->body);
  for (const char* key : {"name", "description", "icon", "company", "version", "webpage", "api"}) {
    EXPECT_TRUE(service.contains(key) && service[key].is_string()) << key;
  }
  EXPECT_EQ(service["icon"].get<std::string>().rfind("mdi-", 0), 0U);
  EXPECT_EQ(service["new_page"], false);
  EXPECT_EQ(service["works_in_relative_paths"], true);
  EXPECT_EQ(metadata->get_header_value("Access-Control-Allow-Origin"), "*");
  EXPECT_EQ(client.Get("/nothing-here")->status, 404);
}

TEST(WebServer, ReadingIsOpenToAnyOriginActingIsNot) {
  LiveView view(Clock::now());
  int saves = 0;
  WebHandlers handlers;
  handlers.save = [&] {
    ++saves;
    return std::vector<std::pair<std::string, std::string>>{{"map", "/tmp/a \"b\".bt"}, {"log", "/tmp/run.bin"}};
  };
  WebServer server(view, localOptions(), handlers);
  httplib::Client client("127.0.0.1", server.port());
  const httplib::Result state = client.Get("/state");
  ASSERT_TRUE(state);
  EXPECT_EQ(state->get_header_value("Access-Control-Allow-Origin"), "*");
  EXPECT_TRUE(json::parse(state->body)["full"]);
  const httplib::Result preflight =
      client.Options("/save", httplib::Headers{{"Origin", "http://elsewhere"}, {"Access-Control-Request-Method", "POST"},
                                               {"Access-Control-Request-Headers", "x-sonarmap"}});
  ASSERT_TRUE(preflight);
  EXPECT_EQ(preflight->get_header_value("Access-Control-Allow-Methods"), "GET");
  EXPECT_FALSE(preflight->has_header("Access-Control-Allow-Headers"));
  EXPECT_EQ(client.Post("/save")->status, 403);  // a form of another site cannot add the header
  EXPECT_EQ(saves, 0);
  const httplib::Result saved = client.Post("/save", httplib::Headers{{"X-Sonarmap", "1"}}, "", "text/plain");
  ASSERT_TRUE(saved);
  EXPECT_EQ(saved->status, 200);
  const json answer = json::parse(saved->body);
  EXPECT_EQ(answer["ok"], true);
  EXPECT_EQ(answer["paths"]["map"], "/tmp/a \"b\".bt");
  EXPECT_EQ(answer["paths"]["log"], "/tmp/run.bin");
  EXPECT_EQ(saves, 1);
  EXPECT_EQ(client.Post("/reset", httplib::Headers{{"X-Sonarmap", "1"}}, "", "text/plain")->status, 501);  // no handler
}

TEST(WebServer, ResetClearsThePictureAndReportsFailures) {
  LiveView view(Clock::now());
  bool fail = false;
  int resets = 0;
  WebHandlers handlers;
  handlers.reset = [&] {
    if (fail) throw FileError("the map is busy");
    ++resets;
  };
  handlers.save = [] () -> std::vector<std::pair<std::string, std::string>> { throw FileError("disk full"); };
  WebServer server(view, localOptions(), handlers);
  httplib::Client client("127.0.0.1", server.port());
  EXPECT_EQ(client.Get("/map.png")->status, 404);  // no picture yet
  view.addBeam(beamOf(0.0), view.now_s(), {});
  view.offerMap(wallMap(), 1);
  ASSERT_TRUE(eventually([&] { return view.rasterPng().first.version == 1; }));
  httplib::Result png = client.Get("/map.png");
  ASSERT_TRUE(png);
  EXPECT_EQ(png->get_header_value("Content-Type"), "image/png");
  EXPECT_EQ(png->get_header_value("X-Raster-Version"), "1");
  EXPECT_EQ(png->get_header_value("X-Raster-Beams"), "1");
  EXPECT_NE(png->get_header_value("Access-Control-Expose-Headers").find("X-Raster-North"), std::string::npos);
  const cv::Mat picture = cv::imdecode(std::vector<unsigned char>(png->body.begin(), png->body.end()), cv::IMREAD_GRAYSCALE);
  EXPECT_EQ(cv::countNonZero(picture == 0), 60);

  const httplib::Headers page{{"X-Sonarmap", "1"}};
  const httplib::Result reset = client.Post("/reset", page, "", "text/plain");
  ASSERT_TRUE(reset);
  EXPECT_EQ(json::parse(reset->body)["ok"], true);
  EXPECT_EQ(resets, 1);
  png = client.Get("/map.png");
  EXPECT_EQ(png->get_header_value("X-Raster-Version"), "2");
  EXPECT_EQ(view.rasterPng().first.occupied_px, 0U);
  fail = true;
  const httplib::Result failed = client.Post("/reset", page, "", "text/plain");
  EXPECT_EQ(failed->status, 500);
  EXPECT_EQ(json::parse(failed->body)["error"], "the map is busy");
  EXPECT_EQ(view.rasterPng().first.version, 2U);  // a failed reset leaves the picture
  const httplib::Result not_saved = client.Post("/save", page, "", "text/plain");
  EXPECT_EQ(not_saved->status, 500);
  EXPECT_EQ(json::parse(not_saved->body)["error"], "disk full");
}

TEST(WebServer, AcknowledgementsGiveTheLatencies) {
  LiveView view(Clock::now());
  WebServer server(view, localOptions());
  for (int i = 0; i < 3; ++i) view.addBeam(beamOf(0.0), view.now_s() - 0.1, {});
  httplib::Client client("127.0.0.1", server.port());
  EXPECT_EQ(client.Post("/ack", "beams 0 1 2\nrasters \nheld_ms 20\n", "text/plain")->status, 204);
  const json latency = json::parse(client.Get("/latency")->body);
  EXPECT_EQ(latency["fan"]["count"], 3);
  EXPECT_NEAR(latency["fan"]["median_s"].get<double>(), 0.08, 0.05);
  EXPECT_EQ(latency["map"]["count"], 0);
  EXPECT_EQ(client.Post("/latency/reset", httplib::Headers{{"X-Sonarmap", "1"}}, "", "text/plain")->status, 200);
  EXPECT_EQ(json::parse(client.Get("/latency")->body)["fan"]["count"], 0);
}

TEST(WebServer, EachPageHasItsOwnLatencies) {
  LiveView view(Clock::now());
  WebServer server(view, localOptions());
  for (int i = 0; i < 3; ++i) view.addBeam(beamOf(0.0), view.now_s() - 0.2, {});
  httplib::Client client("127.0.0.1", server.port());
  // Two pages draw the same beams: one as its acknowledgement leaves, one 150 ms before.
  EXPECT_EQ(client.Post("/ack", "beams 0 1 2\nrasters \nheld_ms 0\npage slow\n", "text/plain")->status, 204);
  EXPECT_EQ(client.Post("/ack", "beams 0 1 2\nrasters \nheld_ms 150\npage quick\n", "text/plain")->status, 204);
  const auto fan = [&](const std::string& query) { return json::parse(client.Get("/latency" + query)->body)["fan"]; };
  const json slow = fan("?page=slow"), quick = fan("?page=quick"), all = fan("");
  EXPECT_EQ(slow["count"], 3);
  EXPECT_EQ(quick["count"], 3);
  EXPECT_GT(slow["median_s"].get<double>(), quick["median_s"].get<double>() + 0.1);
  EXPECT_EQ(all["count"], 3);  // of all pages: each beam once, at the first page that drew it
  EXPECT_EQ(fan("?page=never")["count"], 0);
}

// Event stream vs long polling, from LiveView::addBeam to the client holding the beam, on this
// machine: both deliver within a few milliseconds; the stream needs no request per update.
TEST(WebServer, EventsAndLongPollsDeliverBeamsAtOnce) {
  LiveView view(Clock::now());
  WebServer server(view, localOptions());
  EventClient stream(server.port());
  ASSERT_TRUE(eventually([&] { return !stream.events().empty(); }));
  EXPECT_TRUE(stream.events().front().update["full"]);

  std::atomic<bool> polling{true};
  std::mutex poll_mutex;
  std::map<std::uint64_t, Clock::time_point> polled;
  std::size_t polls = 0;
  std::thread poller([&] {
    httplib::Client client("127.0.0.1", server.port());
    client.set_read_timeout(10, 0);
    std::string cursor;
    while (polling) {
      const httplib::Result got = client.Get("/updates?cursor=" + cursor + "&wait_ms=2000");
      if (!got || got->status != 200) continue;
      const json update = json::parse(got->body);
      cursor = update["cursor"];
      std::lock_guard lock(poll_mutex);
      ++polls;
      for (const json& beam : update["beams"]) polled.emplace(beam["s"].get<std::uint64_t>(), Clock::now());
    }
  });
  std::this_thread::sleep_for(100ms);
  std::map<std::uint64_t, Clock::time_point> added;
  const int beams = 60;
  for (int i = 0; i < beams; ++i) {  // 12 beams a second, a Ping360's pace, sped up 2×
    const auto at = Clock::now();
    added[view.addBeam(beamOf(0.0157 * i), view.now_s(), {})] = at;
    std::this_thread::sleep_for(40ms);
  }
  ASSERT_TRUE(eventually([&] { return stream.received(beams - 1).has_value(); }));
  ASSERT_TRUE(eventually([&] {
    std::lock_guard lock(poll_mutex);
    return polled.count(beams - 1) > 0;
  }));
  polling = false;
  poller.join();
  std::vector<double> by_stream, by_poll;
  for (const auto& [seq, at] : added) {
    by_stream.push_back(std::chrono::duration<double>(*stream.received(seq) - at).count());
    by_poll.push_back(std::chrono::duration<double>(polled.at(seq) - at).count());
  }
  std::printf("addBeam -> client, %d beams: event stream median %.2f ms, p95 %.2f ms; long polling median %.2f ms, "
              "p95 %.2f ms (%zu requests); one update with a beam of 400 bins: %zu bytes\n",
              beams, percentileMs(by_stream, 0.5), percentileMs(by_stream, 0.95), percentileMs(by_poll, 0.5),
              percentileMs(by_poll, 0.95), polls, stream.events().back().update.dump().size());
  EXPECT_LT(percentileMs(by_stream, 0.95), 100.0);
  EXPECT_LT(percentileMs(by_poll, 0.95), 100.0);
  EXPECT_EQ(stream.events().back().update["beams"][0]["i"].get<std::string>().size(), 400U / 3 * 4 + 4);
}

TEST(WebServer, ServesManyClientsAndOutlivesOnesThatLeave) {
  LiveView view(Clock::now());
  WebServer server(view, localOptions());  // 6 streams at most
  std::vector<std::unique_ptr<EventClient>> clients;
  for (int i = 0; i < 6; ++i) clients.push_back(std::make_unique<EventClient>(server.port()));
  ASSERT_TRUE(eventually([&] { return server.streams() == 6; }));
  bool refused = false;
  {
    EventClient extra(server.port(), &refused);
    ASSERT_TRUE(eventually([&] { return extra.ended(); }));
  }
  EXPECT_TRUE(refused);  // the seventh: 503, and its page polls instead
  httplib::Client poll("127.0.0.1", server.port());
  const auto poll_start = Clock::now();
  EXPECT_EQ(poll.Get("/updates?cursor=&wait_ms=3000")->status, 200);  // answered, not held, at capacity
  EXPECT_LT(Clock::now() - poll_start, 1000ms);

  const std::uint64_t seq = view.addBeam(beamOf(1.0), view.now_s(), {});
  for (auto& client : clients) ASSERT_TRUE(eventually([&] { return client->received(seq).has_value(); }));
  clients[0]->leave();  // closes its connection at the next event
  clients[1]->leave();
  view.addBeam(beamOf(1.1), view.now_s(), {});
  clients.erase(clients.begin(), clients.begin() + 2);
  ASSERT_TRUE(eventually([&] { return server.streams() == 4; }));
  const std::uint64_t after = view.addBeam(beamOf(1.2), view.now_s(), {});
  for (auto& client : clients) ASSERT_TRUE(eventually([&] { return client->received(after).has_value(); }));
}

TEST(WebServer, StopsPromptlyWithStreamsAndPollsOpen) {
  LiveView view(Clock::now());
  auto server = std::make_unique<WebServer>(view, localOptions());
  std::vector<std::unique_ptr<EventClient>> clients;
  for (int i = 0; i < 3; ++i) clients.push_back(std::make_unique<EventClient>(server->port()));
  ASSERT_TRUE(eventually([&] { return server->streams() == 3; }));
  std::thread poller([port = server->port()] {
    httplib::Client client("127.0.0.1", port);
    client.set_read_timeout(30, 0);
    client.Get("/updates?cursor=0.0.0.0.0.0.999999.0&wait_ms=25000");
  });
  std::this_thread::sleep_for(100ms);
  const auto start = Clock::now();
  server->stop();
  const double stop_ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
  std::printf("stop with 3 event streams and a long poll open: %.1f ms\n", stop_ms);
  EXPECT_LT(stop_ms, 500.0);
  for (auto& client : clients) EXPECT_TRUE(eventually([&] { return client->ended(); }, 2000ms));
  poller.join();
  server.reset();  // idempotent stop in the destructor
}

TEST(WebServer, RefusesABusyPortAndBadOptions) {
  LiveView view(Clock::now());
  WebServer first(view, localOptions());
  WebServerOptions same = localOptions();
  same.port = first.port();
  EXPECT_THROW(WebServer(view, same), FileError);
  WebServerOptions bad = localOptions();
  bad.max_streams = bad.threads;
  EXPECT_THROW(WebServer(view, bad), ValueError);
}

}  // namespace
}  // namespace sonarmap
