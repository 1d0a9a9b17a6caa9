#pragma once
/// @file live_page.hpp
/// The page of a live run (`live --serve`): a LiveView (live_view.hpp) fed by the run as its
/// observer, served by a WebServer (web_server.hpp) whose buttons save and reset the run's map.
/// What it is told goes on to another observer too (the console's).

#include <memory>
#include <string>

#include "sonarmap/live/live_session.hpp"
#include "sonarmap/live/live_view.hpp"
#include "sonarmap/live/web_server.hpp"

namespace sonarmap {

class LivePage final : public LiveObserver {
 public:
  /// Serves the page of `session` (which must outlive the page) at `options`' address and port,
  /// and becomes its observer, passing everything on to `next` (may be null).
  /// @throws FileError when the address cannot be bound; ValueError for bad options.
  LivePage(LiveSession& session, WebServerOptions options, LiveObserver* next = nullptr, LiveViewOptions view = {});
  /// Stops the server, then lets go of the map.
  ~LivePage() override;

  /// "http://127.0.0.1:8080/".
  std::string url() const { return server_->url(); }
  LiveView& view() { return view_; }

  void headSettings(const std::string& device, const AppliedSettings& settings) override;
  void beam(std::size_t sequence, const Beam& beam, double arrival_s, const Eigen::Isometry3d& sonar_to_map) override;
  void mapped(std::size_t beams_shown, std::size_t sweeps) override;
  void fix(const NavSample& fix) override;
  void status(const LiveProgress& status) override;
  void note(const std::string& line) override;
  void reset() override;

 private:
  LiveSession& session_;
  LiveObserver* next_;
  LiveView view_;
  std::unique_ptr<WebServer> server_;
};

/// "8080" → {0.0.0.0, 8080}, "127.0.0.1:8080" → {127.0.0.1, 8080}, "[::1]:8080".
/// @throws ValueError for a malformed specification or a port outside 0…65535.
WebServerOptions webServerOptions(const std::string& spec);

}  // namespace sonarmap
