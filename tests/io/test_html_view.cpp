// The 3D viewer's page: the payload states the map's counts and boxes, the page is deterministic and
// self-contained, and bad input is refused.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/io/html_view.hpp"

namespace sonarmap {
namespace {

constexpr ViewerScripts kScripts{"var THREE = {}; /* three */", "/* orbit controls */"};

OcTree16 smallTree() {
  OcTree16 tree(0.25);
  for (int i = 0; i < 7; ++i) tree.integrate(*tree.coder().keyOf({0.25 * i, 0.0, 0.5 * i}), true);
  for (int i = 0; i < 3; ++i) tree.integrate(*tree.coder().keyOf({0.0, 0.25 * i + 1.0, 0.0}), false);
  return tree;
}

/// The text between `before` and the next `after` in `text`, or "" when absent.
std::string between(const std::string& text, const std::string& before, const std::string& after) {
  const std::size_t start = text.find(before);
  if (start == std::string::npos) return "";
  const std::size_t end = text.find(after, start + before.size());
  return end == std::string::npos ? "" : text.substr(start + before.size(), end - start - before.size());
}

TEST(ioHtmlView, PayloadStatesTheMapsCountsAndBoxes) {
  const OcTree16 tree = smallTree();
  HtmlViewOptions options;
  options.title = "small.bt";
  options.trajectory_m = {{0.0, 0.0, 0.0}, {1.0, -2.0, 0.5}};
  options.trajectory_source = "nav.csv";
  const HtmlView view = renderHtmlView(tree, options, kScripts);
  EXPECT_EQ(view.occupied.boxes.size(), 7U);
  EXPECT_EQ(view.occupied.leaves, 7U);
  EXPECT_EQ(view.free.leaves, 3U);
  const std::string& html = view.html;
  EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0U);
  EXPECT_NE(html.find("<title>small.bt - sonarmap view</title>"), std::string::npos);
  EXPECT_NE(html.find("<script>var THREE = {}; /* three */</script>"), std::string::npos);
  EXPECT_NE(html.find("<script>/* orbit controls */</script>"), std::string::npos);
  EXPECT_EQ(html.find("@PAYLOAD@"), std::string::npos);
  EXPECT_EQ(html.find("@THREE_JS@"), std::string::npos);
  EXPECT_EQ(html.find("http"), std::string::npos) << "nothing is fetched from the network";
  const std::string payload = between(html, "<script type=\"application/json\" id=\"payload\">", "</script>");
  ASSERT_FALSE(payload.empty());
  EXPECT_NE(payload.find("\"resolution_m\":0.25"), std::string::npos) << payload;
  EXPECT_NE(payload.find("\"occupied_leaves\":7,\"free_leaves\":3,\"unknown_leaves\":0"), std::string::npos) << payload;
  EXPECT_NE(payload.find("\"nodes\":" + std::to_string(tree.counts().nodes)), std::string::npos);
  EXPECT_NE(payload.find("\"memory_bytes\":" + std::to_string(tree.memoryBytes())), std::string::npos);
  EXPECT_NE(payload.find("\"trajectory_m\":[0,0,0,1,-2,0.5],\"trajectory_source\":\"nav.csv\""), std::string::npos);
  // 7 boxes of 8 bytes: 56 bytes, 76 base64 characters with padding.
  const std::string data = between(payload, "\"occupied\":{\"boxes\":7,\"leaves\":7,\"level\":16,\"data\":\"", "\"");
  EXPECT_EQ(data.size(), 76U) << payload;
  // Occupied bounds: voxels from (0, 0, 0) to (1.5, 0, 3) with edge 0.25.
  EXPECT_NE(payload.find("\"occupied_bounds_m\":{\"min\":[0,0,0],\"max\":[1.75,0.25,3.25]}"), std::string::npos)
      << payload;
}

TEST(ioHtmlView, CapsDownsampleAndThePageSaysSo) {
  const OcTree16 tree = smallTree();
  HtmlViewOptions options;
  options.max_boxes = 2;
  options.max_free_boxes = 1;
  const HtmlView view = renderHtmlView(tree, options, kScripts);
  EXPECT_TRUE(view.occupied.downsampled());
  EXPECT_LE(view.occupied.boxes.size(), 2U);
  EXPECT_EQ(view.occupied.leaves, 7U);
  EXPECT_TRUE(view.free.downsampled());
  EXPECT_NE(view.html.find("\"occupied\":{\"boxes\":" + std::to_string(view.occupied.boxes.size()) +
                           ",\"leaves\":7,\"level\":" + std::to_string(view.occupied.level)),
            std::string::npos);
  EXPECT_NE(view.html.find("\"max_boxes\":2,\"max_free_boxes\":1"), std::string::npos);
}

TEST(ioHtmlView, SameInputGivesTheSameBytes) {
  const OcTree16 tree = smallTree();
  HtmlViewOptions options;
  options.title = "a <b> & \"c\"";
  const std::string first = renderHtmlView(tree, options, kScripts).html;
  EXPECT_EQ(first, renderHtmlView(tree, options, kScripts).html);
  EXPECT_NE(first.find("<h1>a &lt;b&gt; &amp; &quot;c&quot;</h1>"), std::string::npos);
  EXPECT_NE(first.find("\"title\":\"a \\u003cb\\u003e \\u0026 \\\"c\\\"\""), std::string::npos);
}

TEST(ioHtmlView, EmptyMapHasAPage) {
  const HtmlView view = renderHtmlView(OcTree16(0.1), {}, kScripts);
  EXPECT_TRUE(view.occupied.boxes.empty());
  EXPECT_NE(view.html.find("\"map_bounds_m\":null,\"occupied_bounds_m\":null"), std::string::npos);
}

TEST(ioHtmlView, BadInputIsRefused) {
  const OcTree16 tree = smallTree();
  EXPECT_THROW(renderHtmlView(tree, {}, {"", "x"}), ValueError);
  EXPECT_THROW(renderHtmlView(tree, {}, {"x", ""}), ValueError);
  EXPECT_THROW(renderHtmlView(tree, {}, {"var s = '</SCRIPT>';", "x"}), ValueError);
  HtmlViewOptions zero_cap;
  zero_cap.max_boxes = 0;
  EXPECT_THROW(renderHtmlView(tree, zero_cap, kScripts), ValueError);
  HtmlViewOptions bad_path;
  bad_path.trajectory_m = {{0.0, std::numeric_limits<double>::quiet_NaN(), 0.0}};
  EXPECT_THROW(renderHtmlView(tree, bad_path, kScripts), ValueError);
}

}  // namespace
}  // namespace sonarmap
