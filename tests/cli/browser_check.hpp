#pragma once
/// @file browser_check.hpp
/// Opens a page of `sonarmap view` in headless Chromium (SwiftShader's software WebGL, no GPU
/// needed) twice: once to read the page's own check (`<pre id="check">`, io/html_view.hpp) from
/// the DOM it dumps, once for a screenshot whose pixels are then counted with OpenCV.

#include <cstddef>
#include <filesystem>
#include <string>

namespace sonarmap::test {

/// What Chromium showed of one page.
struct BrowserCheck {
  bool skipped = false;  ///< no Chromium at that path: `message` says so and what to install
  std::string message;   ///< the page's check line, or why the check could not run
  std::size_t boxes = 0;            ///< boxes the page drew (`boxes=`)
  std::size_t stated = 0;           ///< boxes the page was given (`stated=`)
  std::size_t bands = 0;         ///< height bands holding boxes (`bands=`)
  std::size_t unseen_bands = 0;  ///< of those, bands that painted nothing when drawn alone (`unseen=`)
  std::size_t missing_px = 0;    ///< pixels bands paint alone but not together (`missing_px=`)
  std::size_t box_px = 0;           ///< pixels of a frame of the boxes alone not background (`box_px=`)
  std::size_t page_painted_px = 0;  ///< pixels of its first frame not background (`painted=`)
  bool ok = false;  ///< the page saw WebGL, drew the boxes it was given, and saw every band
  /// Pixels of the screenshot's centre (x 400…879, y 250…749, clear of the page's panels) that are
  /// not background, and of those the saturated ones (max − min channel > 60: boxes, not the grey grid).
  std::size_t centre_painted_px = 0;
  std::size_t centre_saturated_px = 0;
  std::size_t screenshot_colours = 0;  ///< distinct colours of the whole screenshot
};

/// Runs Chromium (the environment's SONARMAP_CHROMIUM, else the one CMake found) on `page` at 1280 × 800, writing its
/// screenshot to `screenshot`; `work_dir` holds its profile and captured output.
/// @throws std::runtime_error when Chromium cannot be started.
BrowserCheck checkInChromium(const std::filesystem::path& page, const std::filesystem::path& screenshot,
                             const std::filesystem::path& work_dir);

}  // namespace sonarmap::test
