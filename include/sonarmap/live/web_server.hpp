#pragma once
/// @file web_server.hpp
/// The HTTP server of `sonarmap live --serve`: the page (offline: its HTML, CSS and scripts are
/// compiled into the library, no CDN) and what it reads from a LiveView (live_view.hpp), on
/// cpp-httplib.
///
/// Endpoints (every URL the page uses is relative, so that it works under a proxy's prefix such as
/// BlueOS's /extensionv2/NAME/; GET answers carry `Access-Control-Allow-Origin: *` and nothing
/// forbids framing, so Cockpit's iframe widget can show the page):
///  - GET  /, /index.html, /live.css, /live.js, /map_view.js: the page.
///  - GET  /events: Server-Sent Events, one `update` event per change (live_json.hpp's update: the
///         first holds everything, then what changed), a comment every heartbeat_s when idle.
///  - GET  /updates?cursor=C&wait_ms=N: the same updates by long polling (the page's fallback when
///         event streams are refused or cut by a proxy): waits up to N ms (≤ 25000) for a change
///         after cursor C (empty: everything).
///  - GET  /map.png: the latest map picture's tiles put together (LiveView::rasterPng; the page
///         itself gets the tiles that changed inline in its updates), its place in headers
///         X-Raster-Version, -North, -West, -Cell, -Z, -Beams (metres, map frame); 404 before one.
///  - GET  /latency[?page=ID]: beam arrival → pixels, fan and map (LiveView::latencies) as JSON:
///         of all pages, or of the page that sent `page ID` in its acknowledgements.
///  - GET  /state: one full update as JSON.
///  - GET  /register_service: BlueOS's extension metadata.
///  - POST /ack: the page drew beams and pictures: lines `beams`, `rasters` (seqs and versions),
///         `held_ms` and `page` (its own id, at most 64 characters) (LiveView::acknowledge).
///  - POST /save, /reset, /latency/reset: the session's handlers (WebHandlers) and
///         LiveView::resetLatencies; JSON `{"ok":true,...}` or `{"ok":false,"error":...}`. They
///         need the header `X-Sonarmap: 1`, which a page of another site cannot send without a
///         CORS preflight this server refuses.
///
/// Threads: requests run on the server's own pool (WebServerOptions::threads); each event stream
/// holds one thread while open, and at most max_streams are open (more are refused with 503, and
/// the page polls instead). Every connection closes after one response (no keep-alive), so a
/// stopped server waits for no idle connection; stop() ends the event streams and long polls at
/// once and returns when every thread has ended (a request in progress finishes first).
/// Writing to a page that left: the server ignores SIGPIPE in the whole process when it was at
/// its default (cpp-httplib sends without MSG_NOSIGNAL); the write then fails and the stream ends.

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "sonarmap/live/live_view.hpp"

namespace sonarmap {

struct WebServerOptions {
  std::string address = "0.0.0.0";  ///< the address to listen on ("127.0.0.1": this machine only)
  int port = 0;                      ///< 0: any free port (port() tells which)
  std::string title = "sonarmap live";  ///< the page's title and BlueOS's extension name
  std::size_t threads = 16;     ///< request threads (≥ 2)
  std::size_t max_streams = 8;  ///< event streams open and long polls waiting at once (≥ 1, < threads)
  double heartbeat_s = 5.0;     ///< a comment on an idle event stream this often (> 0), so a gone page is noticed
};

/// What the page's buttons do; called on a server thread, one call at a time; may block. A
/// handler that throws answers `{"ok":false,"error":what()}` with status 500. Unset: 501.
struct WebHandlers {
  /// "Save map": write the map and flush the recorded log; returns what was written, (name, path)
  /// pairs such as ("map", "/data/run.bt").
  std::function<std::vector<std::pair<std::string, std::string>>()> save;
  /// "Reset map": clear the map. On success the server calls LiveView::mapReset().
  std::function<void()> reset;
};

class WebServer {
 public:
  /// Binds `options.address`:`options.port` and starts serving `view` (which must outlive the
  /// server) on its own threads.
  /// @throws FileError when the address cannot be bound (the system's reason); ValueError for
  ///         options out of range.
  WebServer(LiveView& view, WebServerOptions options = {}, WebHandlers handlers = {});
  /// stop().
  ~WebServer();
  WebServer(const WebServer&) = delete;
  WebServer& operator=(const WebServer&) = delete;

  /// The port listened on.
  int port() const;
  /// "http://ADDRESS:PORT/" (127.0.0.1 for a wildcard address).
  std::string url() const;
  /// Event streams open and long polls waiting now (together at most max_streams).
  std::size_t streams() const;
  /// Stops listening, ends the event streams and long polls, and joins every thread. Idempotent.
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sonarmap
