/// @file live_page.cpp
/// A live run's page (see live_page.hpp).

#include "sonarmap/live/live_page.hpp"

#include <charconv>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {

LivePage::LivePage(LiveSession& session, WebServerOptions options, LiveObserver* next, LiveViewOptions view)
    : session_(session), next_(next), view_(session.start(), view) {
  view_.setMapSource([&session](const Eigen::AlignedBox3d& box_m, const ShownMapVisitor& visit) {
    session.mapping().visitShown(box_m, visit);
  });
  WebHandlers handlers;
  handlers.save = [&session] {
    std::vector<std::pair<std::string, std::string>> written;
    for (const auto& [what, path] : session.saveNow()) written.emplace_back(what, path);
    return written;
  };
  handlers.reset = [&session] { session.resetNow(); };
  server_ = std::make_unique<WebServer>(view_, std::move(options), std::move(handlers));
  session_.setObserver(this);
}

LivePage::~LivePage() {
  session_.setObserver(next_);
  server_->stop();
  view_.setMapSource({});
}

void LivePage::headSettings(const std::string& device, const AppliedSettings& settings) {
  AppliedSettings shown = settings;
  if (!device.empty()) shown.head = device;
  view_.setSettings(shown);
  if (next_) next_->headSettings(device, settings);
}

void LivePage::beam(std::size_t sequence, const Beam& beam, double arrival_s, const Eigen::Isometry3d& sonar_to_map) {
  view_.addBeam(beam, arrival_s, placementOf(sonar_to_map));
  if (next_) next_->beam(sequence, beam, arrival_s, sonar_to_map);
}

void LivePage::mapped(std::size_t beams_shown, std::size_t sweeps) {
  view_.mapShows(beams_shown);
  view_.setSweeps(sweeps);
  if (next_) next_->mapped(beams_shown, sweeps);
}

void LivePage::fix(const NavSample& fix) {
  view_.addNavFix(fix);
  if (next_) next_->fix(fix);
}

void LivePage::status(const LiveProgress& status) {
  if (next_) next_->status(status);
}

void LivePage::note(const std::string& line) {
  view_.addWarning(line);
  if (next_) next_->note(line);
}

void LivePage::reset() {
  if (next_) next_->reset();
}

WebServerOptions webServerOptions(const std::string& spec) {
  WebServerOptions options;
  std::string port = spec;
  if (const std::size_t colon = spec.rfind(':'); colon != std::string::npos) {
    std::string host = spec.substr(0, colon);
    if (host.size() >= 2 && host.front() == '[' && host.back() == ']') host = host.substr(1, host.size() - 2);
    if (!host.empty()) options.address = host;
    port = spec.substr(colon + 1);
  }
  int number = -1;
  const auto [end, error] = std::from_chars(port.data(), port.data() + port.size(), number);
  if (port.empty() || error != std::errc{} || end != port.data() + port.size() || number < 0 || number > 65535) {
    throw ValueError("--serve takes [HOST:]PORT with a port in 0 .. 65535, got '" + spec + "'");
  }
  options.port = number;
  return options;
}

}  // namespace sonarmap
