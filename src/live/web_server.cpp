#include "sonarmap/live/web_server.hpp"

#include <sys/socket.h>

#include <csignal>

#include <algorithm>
#include <atomic>
#include <charconv>
#include <chrono>
#include <mutex>
#include <sstream>
#include <stop_token>
#include <string_view>
#include <thread>

#include "live_json.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/io/web_text.hpp"

// Last: it brings glibc's <resolv.h>, whose `_res` macro breaks Eigen's headers included after it.
#include <httplib.h>

namespace sonarmap {
namespace embedded {
// src/live/page/*, embedded by CMake (cmake/EmbedText.cmake)
extern const std::string_view kLivePageHtml;
extern const std::string_view kLivePageCss;
extern const std::string_view kLivePageJs;
extern const std::string_view kLivePageMapViewJs;
}  // namespace embedded

namespace {

using namespace std::chrono_literals;

/// Longest wait of a long poll, and the least time between two events of one stream.
constexpr auto kLongestPoll = 25000ms;
constexpr auto kEventSpacing = 15ms;

/// Unsigned integers separated by spaces or commas.
std::vector<std::uint64_t> integers(std::string_view text) {
  std::vector<std::uint64_t> values;
  const char* at = text.data();
  const char* end = at + text.size();
  while (at < end) {
    if (*at == ' ' || *at == ',') {
      ++at;
      continue;
    }
    std::uint64_t value = 0;
    const auto [next, error] = std::from_chars(at, end, value);
    if (error != std::errc{}) break;
    values.push_back(value);
    at = next;
  }
  return values;
}

void allowAnyOrigin(httplib::Response& res) { res.set_header("Access-Control-Allow-Origin", "*"); }

void sendJson(httplib::Response& res, const std::string& json, int status = 200) {
  res.status = status;
  res.set_header("Cache-Control", "no-store");
  allowAnyOrigin(res);
  res.set_content(json, "application/json");
}

/// The page-only POSTs carry this header: a page of another site cannot send it without a CORS
/// preflight, which this server does not allow.
bool fromThePage(const httplib::Request& req, httplib::Response& res) {
  if (req.get_header_value("X-Sonarmap") == "1") return true;
  sendJson(res, "{\"ok\":false,\"error\":\"missing header X-Sonarmap: 1\"}", 403);
  return false;
}

}  // namespace

struct WebServer::Impl {
  Impl(LiveView& v, WebServerOptions o, WebHandlers h) : view(v), options(std::move(o)), handlers(std::move(h)) {}

  LiveView& view;
  WebServerOptions options;
  WebHandlers handlers;
  httplib::Server server;
  std::stop_source stopping;
  std::atomic<std::size_t> streams{0};  ///< event streams and waiting long polls
  std::mutex action_mutex;              ///< one save or reset at a time
  std::mutex stop_mutex;
  bool stopped = false;
  int port = 0;
  std::string page;
  std::thread listener;

  void routes();
  void serveEvents(httplib::Response& res);
  void serveUpdates(const httplib::Request& req, httplib::Response& res);
  void serveMap(httplib::Response& res);
  void runAction(const httplib::Request& req, httplib::Response& res, bool save);
};

void WebServer::Impl::routes() {
  const auto text = [](std::string_view body, const char* type) {
    return [body, type](const httplib::Request&, httplib::Response& res) {
      res.set_header("Cache-Control", "no-cache");
      allowAnyOrigin(res);
      res.set_content(body.data(), body.size(), type);
    };
  };
  const auto page_handler = [this](const httplib::Request&, httplib::Response& res) {
    res.set_header("Cache-Control", "no-cache");
    res.set_content(page, "text/html; charset=utf-8");
  };
  server.Get("/", page_handler);
  server.Get("/index.html", page_handler);
  server.Get("/live.css", text(embedded::kLivePageCss, "text/css; charset=utf-8"));
  server.Get("/live.js", text(embedded::kLivePageJs, "text/javascript; charset=utf-8"));
  server.Get("/map_view.js", text(embedded::kLivePageMapViewJs, "text/javascript; charset=utf-8"));
  server.Get("/events", [this](const httplib::Request&, httplib::Response& res) { serveEvents(res); });
  server.Get("/updates", [this](const httplib::Request& req, httplib::Response& res) { serveUpdates(req, res); });
  server.Get("/state", [this](const httplib::Request&, httplib::Response& res) {
    sendJson(res, live_json::update(view.updateSince({})));
  });
  server.Get("/map.png", [this](const httplib::Request&, httplib::Response& res) { serveMap(res); });
  server.Get("/latency", [this](const httplib::Request& req, httplib::Response& res) {
    sendJson(res, live_json::latencies(view.latencies(req.get_param_value("page"))));
  });
  server.Get("/register_service", [this](const httplib::Request&, httplib::Response& res) {
    sendJson(res, "{\"name\":" + jsonString(options.title) +
                      ",\"description\":\"The sonar's map growing during the dive: the current sweep, the map at the "
                      "vehicle's depth, the track\",\"icon\":\"mdi-radar\",\"company\":\"sonarmap\",\"version\":" +
                      jsonString(SONARMAP_VERSION) +
                      ",\"webpage\":\"\",\"api\":\"\",\"new_page\":false,\"works_in_relative_paths\":true}");
  });
  server.Post("/ack", [this](const httplib::Request& req, httplib::Response& res) {
    std::vector<std::uint64_t> beams, rasters;
    double held_ms = 0.0;
    std::string page;
    std::istringstream lines(req.body);
    for (std::string line; std::getline(lines, line);) {
      const std::string_view view_line(line);
      if (view_line.starts_with("beams ")) beams = integers(view_line.substr(6));
      if (view_line.starts_with("rasters ")) rasters = integers(view_line.substr(8));
      if (view_line.starts_with("held_ms ")) std::from_chars(line.data() + 8, line.data() + line.size(), held_ms);
      if (view_line.starts_with("page ")) page = line.substr(5, 64);
    }
    view.acknowledge(beams, rasters, std::clamp(held_ms, 0.0, 60000.0) / 1000.0, page);
    res.status = 204;
  });
  server.Post("/save", [this](const httplib::Request& req, httplib::Response& res) { runAction(req, res, true); });
  server.Post("/reset", [this](const httplib::Request& req, httplib::Response& res) { runAction(req, res, false); });
  server.Post("/latency/reset", [this](const httplib::Request& req, httplib::Response& res) {
    if (!fromThePage(req, res)) return;
    view.resetLatencies();
    sendJson(res, "{\"ok\":true}");
  });
  // CORS preflights: reading is open to any origin, acting is not (no X-Sonarmap header allowed).
  server.Options(".*", [](const httplib::Request&, httplib::Response& res) {
    allowAnyOrigin(res);
    res.set_header("Access-Control-Allow-Methods", "GET");
    res.status = 204;
  });
}

void WebServer::Impl::serveEvents(httplib::Response& res) {
  if (streams.fetch_add(1) >= options.max_streams) {
    streams.fetch_sub(1);
    res.status = 503;
    res.set_header("Retry-After", "2");
    allowAnyOrigin(res);
    res.set_content("too many event streams: poll /updates", "text/plain");
    return;
  }
  res.set_header("Cache-Control", "no-cache");
  res.set_header("X-Accel-Buffering", "no");  // nginx (BlueOS's proxy): pass each event on at once
  allowAnyOrigin(res);
  struct Stream {
    ViewCursor cursor;
    std::chrono::steady_clock::time_point last_event{};
  };
  auto stream = std::make_shared<Stream>();
  const auto heartbeat = std::chrono::milliseconds(static_cast<long>(options.heartbeat_s * 1000.0));
  res.set_chunked_content_provider(
      "text/event-stream",
      [this, stream, heartbeat](std::size_t, httplib::DataSink& sink) {
        const std::stop_token stop = stopping.get_token();
        std::string message;
        if (!stream->cursor.started) {
          message = "retry: 1000\n";
        } else {
          const auto since = std::chrono::steady_clock::now() - stream->last_event;
          if (since < kEventSpacing) std::this_thread::sleep_for(kEventSpacing - since);
          if (view.waitForChange(stream->cursor.changes, heartbeat, stop) <= stream->cursor.changes) {
            if (stop.stop_requested()) {
              sink.done();
              return true;
            }
            static constexpr std::string_view kHeartbeat = ": idle\n\n";
            return sink.write(kHeartbeat.data(), kHeartbeat.size());
          }
        }
        if (stop.stop_requested()) {
          sink.done();
          return true;
        }
        const ViewUpdate update = view.updateSince(stream->cursor);
        stream->cursor = update.cursor;
        stream->last_event = std::chrono::steady_clock::now();
        message += "event: update\ndata: " + live_json::update(update) + "\n\n";
        return sink.write(message.data(), message.size());
      },
      [this](bool) { streams.fetch_sub(1); });
}

void WebServer::Impl::serveUpdates(const httplib::Request& req, httplib::Response& res) {
  const std::optional<ViewCursor> cursor = live_json::parseCursor(req.get_param_value("cursor"));
  long wait_ms = 0;
  const std::string wait_text = req.get_param_value("wait_ms");
  std::from_chars(wait_text.data(), wait_text.data() + wait_text.size(), wait_ms);
  const auto wait = std::clamp(std::chrono::milliseconds(wait_ms), 0ms, kLongestPoll);
  // A poll waits only while a thread is free for it: at max_streams it answers at once.
  if (cursor && wait > 0ms && streams.fetch_add(1) < options.max_streams) {
    view.waitForChange(cursor->changes, wait, stopping.get_token());
    streams.fetch_sub(1);
  } else if (cursor && wait > 0ms) {
    streams.fetch_sub(1);
  }
  sendJson(res, live_json::update(view.updateSince(cursor.value_or(ViewCursor{}))));
}

void WebServer::Impl::serveMap(httplib::Response& res) {
  const auto [info, png] = view.rasterPng();
  allowAnyOrigin(res);
  res.set_header("Cache-Control", "no-store");
  if (!png) {
    res.status = 404;
    res.set_content("no map picture yet", "text/plain");
    return;
  }
  res.set_header("X-Raster-Version", std::to_string(info.version));
  res.set_header("X-Raster-North", jsonNumber(info.north_m));
  res.set_header("X-Raster-West", jsonNumber(info.west_m));
  res.set_header("X-Raster-Cell", jsonNumber(info.cell_m));
  res.set_header("X-Raster-Z", jsonNumber(info.z_m));
  res.set_header("X-Raster-Beams", std::to_string(info.beams));
  res.set_header("Access-Control-Expose-Headers",
                 "X-Raster-Version, X-Raster-North, X-Raster-West, X-Raster-Cell, X-Raster-Z, X-Raster-Beams");
  res.set_content(reinterpret_cast<const char*>(png->data()), png->size(), "image/png");
}

void WebServer::Impl::runAction(const httplib::Request& req, httplib::Response& res, bool save) {
  if (!fromThePage(req, res)) return;
  if (save ? !handlers.save : !handlers.reset) {
    sendJson(res, "{\"ok\":false,\"error\":\"not available in this session\"}", 501);
    return;
  }
  std::lock_guard lock(action_mutex);
  try {
    if (!save) {
      handlers.reset();
      view.mapReset();
      sendJson(res, "{\"ok\":true}");
      return;
    }
    std::string paths = "{";
    for (const auto& [name, path] : handlers.save()) {
      if (paths.size() > 1) paths += ',';
      paths += jsonString(name);
      paths += ':';
      paths += jsonString(path);
    }
    sendJson(res, "{\"ok\":true,\"paths\":" + paths + "}}");
  } catch (const std::exception& error) {
    sendJson(res, "{\"ok\":false,\"error\":" + jsonString(error.what()) + "}", 500);
  }
}

WebServer::WebServer(LiveView& view, WebServerOptions options, WebHandlers handlers)
    : impl_(std::make_unique<Impl>(view, std::move(options), std::move(handlers))) {
  Impl& impl = *impl_;
  const WebServerOptions& o = impl.options;
  if (o.threads < 2 || o.max_streams < 1 || o.max_streams >= o.threads) {
    throw ValueError("web server: needs threads >= 2 and 1 <= max_streams < threads");
  }
  if (!(o.heartbeat_s > 0.0)) throw ValueError("web server: heartbeat_s must be > 0");
  if (o.port < 0 || o.port > 65535) throw ValueError("web server: port must be 0 … 65535");
  // cpp-httplib writes with send() without MSG_NOSIGNAL: a page that left must not kill the session.
  struct sigaction pipe_action {};
  if (sigaction(SIGPIPE, nullptr, &pipe_action) == 0 && pipe_action.sa_handler == SIG_DFL) std::signal(SIGPIPE, SIG_IGN);

  impl.page = std::string(embedded::kLivePageHtml);
  for (std::size_t at; (at = impl.page.find("@TITLE@")) != std::string::npos;) impl.page.replace(at, 7, htmlText(o.title));
  const std::size_t threads = o.threads;
  impl.server.new_task_queue = [threads] { return new httplib::ThreadPool(threads); };
  impl.server.set_keep_alive_max_count(1);  // one response per connection: no idle connection holds a thread
  impl.server.set_read_timeout(2, 0);
  impl.server.set_write_timeout(2, 0);
  impl.server.set_tcp_nodelay(true);
  // cpp-httplib's default sets SO_REUSEPORT, with which a second server binds the same port and the
  // kernel splits the connections between them: a busy port must be refused instead.
  impl.server.set_socket_options([](socket_t sock) {
    const int yes = 1;
    ::setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  });
  impl.routes();
  impl.port = o.port == 0 ? impl.server.bind_to_any_port(o.address) : (impl.server.bind_to_port(o.address, o.port) ? o.port : -1);
  if (impl.port <= 0) {
    throw FileError("web server: cannot listen on " + o.address + ":" + std::to_string(o.port) +
                    " (the port is in use, or the address is not this machine's)");
  }
  impl.listener = std::thread([&impl] { impl.server.listen_after_bind(); });
  // stop() acts only on a running server: wait until it runs.
  for (int i = 0; i < 2000 && !impl.server.is_running(); ++i) std::this_thread::sleep_for(1ms);
}

WebServer::~WebServer() { stop(); }

int WebServer::port() const { return impl_->port; }

std::string WebServer::url() const {
  const std::string& address = impl_->options.address;
  const bool wildcard = address == "0.0.0.0" || address == "::" || address.empty();
  const std::string host = wildcard ? "127.0.0.1" : (address.find(':') != std::string::npos ? "[" + address + "]" : address);
  return "http://" + host + ":" + std::to_string(impl_->port) + "/";
}

std::size_t WebServer::streams() const { return impl_->streams.load(); }

void WebServer::stop() {
  std::lock_guard lock(impl_->stop_mutex);
  if (impl_->stopped) return;
  impl_->stopped = true;
  impl_->stopping.request_stop();
  impl_->server.stop();
  if (impl_->listener.joinable()) impl_->listener.join();
}

}  // namespace sonarmap
