#include "browser_check.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "cli_runner.hpp"

namespace sonarmap::test {
namespace {

namespace fs = std::filesystem;

/// Chromium's options for a page: headless, software WebGL (SwiftShader through ANGLE), its own
/// profile, a fixed window, and time for the page's script to run before the DOM or pixels are read.
/// `fragment` is appended to the page's URL ("#selfcheck" runs the page's own drawing check).
std::vector<std::string> chromiumArgs(const fs::path& page, const fs::path& work_dir, const std::string& fragment = "") {
  return {"--headless=new",
          "--no-sandbox",
          "--use-angle=swiftshader",
          "--enable-unsafe-swiftshader",
          "--ignore-gpu-blocklist",
          "--no-first-run",
          "--hide-scrollbars",
          "--user-data-dir=" + (work_dir / "chromium-profile").string(),
          "--window-size=1280,800",
          "--virtual-time-budget=20000",
          "file://" + fs::absolute(page).string() + fragment};
}

/// The text of `<pre id="check">` in the dumped DOM, or "".
std::string checkLine(const std::string& dom) {
  const std::string open = "<pre id=\"check\">";
  const std::size_t start = dom.find(open);
  if (start == std::string::npos) return "";
  const std::size_t end = dom.find("</pre>", start);
  return end == std::string::npos ? "" : dom.substr(start + open.size(), end - start - open.size());
}

}  // namespace

BrowserCheck checkInChromium(const fs::path& page, const fs::path& screenshot, const fs::path& work_dir) {
  BrowserCheck check;
  const char* from_environment = std::getenv("SONARMAP_CHROMIUM");
  const std::string chromium = from_environment != nullptr ? from_environment : SONARMAP_CHROMIUM;
  if (chromium.empty() || !fs::exists(chromium)) {
    check.skipped = true;
    check.message = "Chromium not found (SONARMAP_CHROMIUM is '" + chromium +
                    "'): install Debian's chromium and configure again to run the browser tests";
    return check;
  }
  std::vector<std::string> args = chromiumArgs(page, work_dir, "#selfcheck");
  args.insert(args.end() - 1, "--dump-dom");
  const ProgramRun dom = runProgram(chromium, args, work_dir);
  check.message = checkLine(dom.out);
  if (check.message.empty()) {
    check.message = "no check line in the page Chromium dumped (exit " + std::to_string(dom.exit_code) +
                    "): " + dom.err.substr(0, 400);
    return check;
  }
  char status[16] = {};
  char webgl[8] = {};
  std::size_t leaves = 0;
  int level = 0;
  const int read = std::sscanf(
      check.message.c_str(), "boxes=%zu stated=%zu leaves=%zu level=%d bands=%zu unseen=%zu missing_px=%zu box_px=%zu painted=%zu "
      "webgl=%7s %15s",
      &check.boxes, &check.stated, &leaves, &level, &check.bands, &check.unseen_bands, &check.missing_px,
      &check.box_px, &check.page_painted_px, webgl, status);
  check.ok = read == 11 && std::string(webgl) == "yes" && std::string(status) == "ok";

  args = chromiumArgs(page, work_dir);
  args.insert(args.end() - 1, "--screenshot=" + fs::absolute(screenshot).string());
  const ProgramRun shot = runProgram(chromium, args, work_dir);
  const cv::Mat image = cv::imread(screenshot.string(), cv::IMREAD_COLOR);
  if (image.empty()) {
    check.message += " | no screenshot (exit " + std::to_string(shot.exit_code) + "): " + shot.err.substr(0, 400);
    return check;
  }
  std::set<std::uint32_t> colours;
  for (int row = 0; row < image.rows; ++row) {
    for (int col = 0; col < image.cols; ++col) {
      const cv::Vec3b bgr = image.at<cv::Vec3b>(row, col);
      colours.insert(static_cast<std::uint32_t>(bgr[0]) | (static_cast<std::uint32_t>(bgr[1]) << 8) |
                     (static_cast<std::uint32_t>(bgr[2]) << 16));
      if (col < 400 || col >= 880 || row < 250 || row >= 750) continue;
      // The page's background is #1b1f24.
      if (std::abs(bgr[2] - 0x1b) + std::abs(bgr[1] - 0x1f) + std::abs(bgr[0] - 0x24) <= 12) continue;
      ++check.centre_painted_px;
      const int spread = std::max({bgr[0], bgr[1], bgr[2]}) - std::min({bgr[0], bgr[1], bgr[2]});
      if (spread > 60) ++check.centre_saturated_px;
    }
  }
  check.screenshot_colours = colours.size();
  check.message += " | screenshot " + std::to_string(image.cols) + "x" + std::to_string(image.rows) + ", " +
                   std::to_string(colours.size()) + " colours, centre " + std::to_string(check.centre_painted_px) +
                   " px painted, " + std::to_string(check.centre_saturated_px) + " saturated";
  return check;
}

}  // namespace sonarmap::test
