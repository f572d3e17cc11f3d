// tyndall-bench's plot: the Pareto front, the SVG (well-formed, escaped, finite for degenerate
// input) and the raster (size, background, series colours, where points and the staircase land).
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <clocale>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "plot.h"

namespace tyndall::samples::bench {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

PlotPoint point(double x, double y, std::string series = "s", std::string label = "p", std::string marker = "") {
  return {std::move(label), std::move(series), x, y, std::move(marker)};
}

std::size_t occurrences(const std::string& text, const std::string& what) {
  std::size_t count = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++count;
  return count;
}

// ---- Pareto front ----

TEST(BenchParetoFront, EmptyInputGivesAnEmptyFront) { EXPECT_TRUE(paretoFront({}).empty()); }

TEST(BenchParetoFront, ASinglePointIsTheFront) {
  EXPECT_EQ(paretoFront({point(0.5, 0.1)}), std::vector<std::size_t>{0});
}

TEST(BenchParetoFront, LeavesOutDominatedPointsAndSortsByX) {
  const std::vector<PlotPoint> points = {
      point(2.0, 0.5),   // 0: front
      point(3.0, 3.0),   // 1: dominated by all of 0, 2, 3
      point(0.5, 3.0),   // 2: front (fastest)
      point(1.0, 1.0),   // 3: front
      point(1.5, 1.2),   // 4: dominated by 3
      point(4.0, 0.0),   // 5: front (exact), although slowest
      point(5.0, 0.25),  // 6: dominated by 5
  };
  EXPECT_EQ(paretoFront(points), (std::vector<std::size_t>{2, 3, 0, 5}));
}

TEST(BenchParetoFront, AnEqualCoordinateDoesNotSaveTheWorsePoint) {
  // Same time, more error; same error, more time: both dominated (x <= and y <=, one strictly).
  const std::vector<PlotPoint> points = {point(1.0, 2.0), point(1.0, 1.0), point(3.0, 1.0), point(0.5, 4.0)};
  EXPECT_EQ(paretoFront(points), (std::vector<std::size_t>{3, 1}));
}

TEST(BenchParetoFront, KeepsTheFirstOfExactDuplicates) {
  const std::vector<PlotPoint> points = {point(2.0, 2.0), point(1.0, 1.0, "a"), point(1.0, 1.0, "b"),
                                         point(1.0, 1.0, "c")};
  EXPECT_EQ(paretoFront(points), std::vector<std::size_t>{1});
}

TEST(BenchParetoFront, NonFinitePointsAreNeverOnItNorHideOthers) {
  // Each non-finite point would dominate the finite ones if it were compared.
  const std::vector<PlotPoint> points = {point(kNaN, 0.0), point(1.0, 1.0),   point(-kInf, 0.5),
                                         point(0.5, kNaN), point(0.1, -kInf), point(2.0, 0.5),
                                         point(kInf, 0.0)};
  EXPECT_EQ(paretoFront(points), (std::vector<std::size_t>{1, 5}));
  EXPECT_TRUE(paretoFront({point(kNaN, 1.0), point(1.0, kInf)}).empty());
}

// ---- SVG ----

bool entityAt(const std::string& doc, std::size_t at) {
  for (const char* entity : {"&amp;", "&lt;", "&gt;", "&quot;", "&apos;"}) {
    if (doc.compare(at, std::strlen(entity), entity) == 0) return true;
  }
  return false;
}

// Well-formedness for the subset of XML the plot writes: one root element; tags nest and match;
// attribute values are double-quoted; text and values hold no raw '<' or '>' and no '&' but the
// five predefined entities.
::testing::AssertionResult wellFormed(const std::string& doc) {
  const auto fail = [&](const char* what, std::size_t at) {
    return ::testing::AssertionFailure() << what << " at " << at << ": " << doc.substr(at, 60);
  };
  const auto nameChar = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == ':' || c == '-'; };
  std::vector<std::string> open;
  bool rootClosed = false;
  std::size_t i = 0;
  while (i < doc.size()) {
    const char c = doc[i];
    if (c == '<') {
      if (rootClosed) return fail("second root", i);
      std::size_t j = i + 1;
      const bool closing = j < doc.size() && doc[j] == '/';
      if (closing) ++j;
      const std::size_t nameStart = j;
      while (j < doc.size() && nameChar(doc[j])) ++j;
      const std::string name = doc.substr(nameStart, j - nameStart);
      if (name.empty()) return fail("tag without a name", i);
      bool selfClosing = false;
      for (;;) {
        while (j < doc.size() && doc[j] == ' ') ++j;
        if (j >= doc.size()) return fail("unterminated tag", i);
        if (doc[j] == '>') {
          ++j;
          break;
        }
        if (doc.compare(j, 2, "/>") == 0 && !closing) {
          selfClosing = true;
          j += 2;
          break;
        }
        if (closing) return fail("attribute on a closing tag", j);
        const std::size_t attributeStart = j;
        while (j < doc.size() && nameChar(doc[j])) ++j;
        if (j == attributeStart || doc.compare(j, 2, "=\"") != 0) return fail("bad attribute", attributeStart);
        for (j += 2; j < doc.size() && doc[j] != '"'; ++j) {
          if (doc[j] == '<' || doc[j] == '>') return fail("raw < or > in an attribute", j);
          if (doc[j] == '&' && !entityAt(doc, j)) return fail("raw & in an attribute", j);
        }
        if (j >= doc.size()) return fail("unterminated attribute", attributeStart);
        ++j;
      }
      if (closing) {
        if (open.empty() || open.back() != name) return fail("mismatched closing tag", i);
        open.pop_back();
        rootClosed = open.empty();
      } else if (!selfClosing) {
        open.push_back(name);
      } else if (open.empty()) {
        rootClosed = true;
      }
      i = j;
      continue;
    }
    if (open.empty() && !std::isspace(static_cast<unsigned char>(c))) return fail("text outside the root", i);
    if (c == '>') return fail("raw > in text", i);
    if (c == '&' && !entityAt(doc, i)) return fail("raw & in text", i);
    ++i;
  }
  if (!open.empty()) return ::testing::AssertionFailure() << "unclosed <" << open.back() << ">";
  if (!rootClosed) return ::testing::AssertionFailure() << "no root element";
  return ::testing::AssertionSuccess();
}

// The markup without text content: where numbers are written (labels may say anything).
std::string markupOnly(const std::string& doc) {
  std::string markup;
  bool inTag = false;
  for (char c : doc) {
    if (c == '<') inTag = true;
    if (inTag) markup += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (c == '>') inTag = false;
  }
  return markup;
}

std::vector<PlotPoint> threeSeries() {
  return {point(1.0, 0.0, "reference", "reference"),
          point(0.2, 0.02, "epipolar", "epipolar slices=512", "Balanced"),
          point(0.1, 0.05, "epipolar", "epipolar slices=256"),
          point(0.3, 0.04, "epipolar", "epipolar slices=1024"),
          point(0.05, 0.03, "prefiltered", "prefiltered res=256"),
          point(0.02, 0.08, "prefiltered", "prefiltered res=128")};
}

TEST(BenchPlotSvg, IsAWellFormedDocumentWithOneElementPerDrawablePoint) {
  std::vector<PlotPoint> points = threeSeries();
  points.push_back(point(kNaN, 0.1, "epipolar"));
  points.push_back(point(0.5, kInf, "prefiltered"));
  PlotSpec spec;
  spec.title = "sweep";
  const std::string svg = plotSvg(points, spec);
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  ASSERT_GE(svg.size(), 7u);
  EXPECT_EQ(svg.substr(svg.size() - 7), "</svg>\n");
  EXPECT_TRUE(wellFormed(svg));
  EXPECT_EQ(occurrences(svg, "class=\"point\""), threeSeries().size());
  EXPECT_EQ(occurrences(svg, "class=\"front\""), 1u);
  EXPECT_NE(svg.find("Balanced</text>"), std::string::npos);  // annotated, after its front number
  EXPECT_NE(svg.find(">sweep<"), std::string::npos);
  EXPECT_NE(svg.find("2 non-finite"), std::string::npos);
  EXPECT_EQ(svg, plotSvg(points, spec));  // deterministic
}

TEST(BenchPlotSvg, EscapesLabelsSeriesAndTitle) {
  PlotSpec spec;
  spec.title = "A & B";
  const std::vector<PlotPoint> points = {point(0.5, 0.1, "s<1>", "odd <&> \"label\" 'x'"), point(0.1, 0.2)};
  const std::string svg = plotSvg(points, spec);
  EXPECT_TRUE(wellFormed(svg));
  EXPECT_NE(svg.find("odd &lt;&amp;&gt; &quot;label&quot; &apos;x&apos;"), std::string::npos);
  EXPECT_NE(svg.find("s&lt;1&gt;"), std::string::npos);
  EXPECT_NE(svg.find("A &amp; B"), std::string::npos);
  EXPECT_EQ(svg.find("<&>"), std::string::npos);
  EXPECT_EQ(svg.find("<1>"), std::string::npos);
}

TEST(BenchPlotSvg, LabelsLogDecadesWithTwosAndFives) {
  const std::string svg = plotSvg({point(0.012, 0.012), point(0.9, 0.9)}, PlotSpec{});
  for (const char* label : {">0.01<", ">0.02<", ">0.05<", ">0.1<", ">0.2<", ">0.5<", ">1<"}) {
    EXPECT_NE(svg.find(label), std::string::npos) << label;
  }
}

TEST(BenchPlotSvg, DegenerateInputsGiveFiniteNumbers) {
  PlotSpec linear;
  linear.logX = false;
  linear.logY = false;
  const struct {
    const char* name;
    std::vector<PlotPoint> points;
    PlotSpec spec;
  } cases[] = {
      {"empty", {}, PlotSpec{}},
      {"single point", {point(0.3, 0.02)}, PlotSpec{}},
      {"all equal", {point(0.3, 0.02), point(0.3, 0.02), point(0.3, 0.02)}, PlotSpec{}},
      {"all equal, linear", {point(2.0, 2.0), point(2.0, 2.0)}, linear},
      {"zeros, linear", {point(0.0, 0.0)}, linear},
      {"y = 0 on a log axis", {point(1.0, 0.0, "reference"), point(0.1, 0.05)}, PlotSpec{}},
      {"only y = 0 on a log axis", {point(1.0, 0.0)}, PlotSpec{}},
      {"x = 0 on a log axis", {point(0.0, 0.1)}, PlotSpec{}},
      {"only non-finite", {point(kNaN, 1.0), point(1.0, kInf), point(-kInf, kNaN)}, PlotSpec{}},
      {"near the double range", {point(1e308, -1e308), point(-1e308, 1e308)}, linear},
      {"tiny and huge", {point(5e-324, 1e-300), point(1e300, 1e300)}, PlotSpec{}},
  };
  for (const auto& c : cases) {
    const std::string svg = plotSvg(c.points, c.spec);
    EXPECT_TRUE(wellFormed(svg)) << c.name;
    const std::string markup = markupOnly(svg);
    EXPECT_EQ(markup.find("nan"), std::string::npos) << c.name;
    EXPECT_EQ(markup.find("inf"), std::string::npos) << c.name;
    std::size_t finite = 0;
    for (const PlotPoint& p : c.points) finite += std::isfinite(p.x) && std::isfinite(p.y) ? 1 : 0;
    EXPECT_EQ(occurrences(svg, "class=\"point\""), finite) << c.name;
  }
}

TEST(BenchPlotSvg, DoesNotDependOnTheCLocale) {
  const std::vector<PlotPoint> points = threeSeries();
  const std::string expected = plotSvg(points, PlotSpec{});
  const std::string saved = std::setlocale(LC_NUMERIC, nullptr);
  bool found = false;
  for (const char* name : {"de_DE.UTF-8", "de_DE.utf8", "fr_FR.UTF-8", "fr_FR.utf8", "German_Germany.1252"}) {
    if (std::setlocale(LC_NUMERIC, name) != nullptr) {
      found = true;
      break;
    }
  }
  if (!found) GTEST_SKIP() << "no locale with a decimal comma is installed";
  const std::string measured = plotSvg(points, PlotSpec{});
  std::setlocale(LC_NUMERIC, saved.c_str());
  EXPECT_EQ(measured, expected);
}

// ---- Raster ----

Rgb8 pixelAt(const std::vector<std::uint8_t>& rgba8, std::uint32_t width, std::uint32_t column, std::uint32_t row) {
  const std::size_t i = (static_cast<std::size_t>(row) * width + column) * 4;
  return {rgba8[i], rgba8[i + 1], rgba8[i + 2]};
}

Rgb8 pixelAt(const std::vector<std::uint8_t>& rgba8, std::uint32_t width, PixelPosition p) {
  return pixelAt(rgba8, width, static_cast<std::uint32_t>(p.column), static_cast<std::uint32_t>(p.row));
}

TEST(BenchPlotRgba8, HasTheRequestedSizeIsOpaqueAndHasABackgroundCorner) {
  constexpr std::uint32_t kWidth = 640;
  constexpr std::uint32_t kHeight = 480;
  std::vector<std::uint8_t> rgba8;
  plotRgba8(threeSeries(), PlotSpec{}, kWidth, kHeight, rgba8);
  ASSERT_EQ(rgba8.size(), std::size_t{kWidth} * kHeight * 4);
  for (std::size_t i = 3; i < rgba8.size(); i += 4) ASSERT_EQ(rgba8[i], 255) << "pixel " << i / 4;
  EXPECT_EQ(pixelAt(rgba8, kWidth, 0, 0), kPlotBackground);
  EXPECT_EQ(pixelAt(rgba8, kWidth, kWidth - 1, kHeight - 1), kPlotBackground);
  EXPECT_EQ(pixelAt(rgba8, kWidth, kWidth - 1, 0), kPlotBackground);
  // Something is drawn: not all background.
  const auto background = static_cast<std::size_t>(std::count(rgba8.begin(), rgba8.end(), std::uint8_t{255}));
  EXPECT_LT(background, rgba8.size());
}

TEST(BenchPlotRgba8, EverySeriesColourIsPresent) {
  constexpr std::uint32_t kWidth = 800;
  constexpr std::uint32_t kHeight = 600;
  std::vector<std::uint8_t> rgba8;
  plotRgba8(threeSeries(), PlotSpec{}, kWidth, kHeight, rgba8);
  ASSERT_EQ(rgba8.size(), std::size_t{kWidth} * kHeight * 4);
  for (std::size_t s = 0; s < 3; ++s) {
    std::size_t count = 0;
    for (std::uint32_t row = 0; row < kHeight; ++row) {
      for (std::uint32_t column = 0; column < kWidth; ++column) {
        count += pixelAt(rgba8, kWidth, column, row) == seriesColour(s) ? 1 : 0;
      }
    }
    EXPECT_GT(count, 20u) << "series " << s;  // points and the legend's symbol
  }
  EXPECT_NE(seriesColour(0), seriesColour(1));
  EXPECT_NE(seriesColour(1), seriesColour(2));
  EXPECT_NE(seriesColour(0), kPlotBackground);
}

TEST(BenchPlotRgba8, LonePointsAreDrawnInTheirSeriesColourWhereTheyLie) {
  constexpr std::uint32_t kWidth = 1000;
  constexpr std::uint32_t kHeight = 700;
  const std::vector<PlotPoint> points = {point(0.01, 0.5, "a"), point(0.1, 0.05, "b", "p", "High"),
                                         point(1.0, 0.005, "c"), point(0.5, 0.4, "a")};
  std::vector<std::uint8_t> rgba8;
  plotRgba8(points, PlotSpec{}, kWidth, kHeight, rgba8);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const PixelPosition p = rasterPosition(points, PlotSpec{}, kWidth, kHeight, points[i].x, points[i].y);
    ASSERT_GE(p.column, 0.0);
    ASSERT_LT(p.column, kWidth);
    ASSERT_GE(p.row, 0.0);
    ASSERT_LT(p.row, kHeight);
    const std::size_t series = points[i].series == "a" ? 0 : points[i].series == "b" ? 1 : 2;
    EXPECT_EQ(pixelAt(rgba8, kWidth, p), seriesColour(series)) << "point " << i;
  }
  // Faster is further left, less error further down.
  const PixelPosition fast = rasterPosition(points, PlotSpec{}, kWidth, kHeight, 0.01, 0.5);
  const PixelPosition slow = rasterPosition(points, PlotSpec{}, kWidth, kHeight, 1.0, 0.005);
  EXPECT_LT(fast.column, slow.column);
  EXPECT_LT(fast.row, slow.row);
}

TEST(BenchPlotRgba8, FrontStaircaseGoesRightThenDown) {
  constexpr std::uint32_t kWidth = 800;
  constexpr std::uint32_t kHeight = 600;
  const std::vector<PlotPoint> points = {point(0.1, 0.1), point(1.0, 0.01)};
  std::vector<std::uint8_t> rgba8;
  plotRgba8(points, PlotSpec{}, kWidth, kHeight, rgba8);
  const PixelPosition first = rasterPosition(points, PlotSpec{}, kWidth, kHeight, 0.1, 0.1);
  const PixelPosition second = rasterPosition(points, PlotSpec{}, kWidth, kHeight, 1.0, 0.01);
  const double middleColumn = 0.5 * (first.column + second.column);
  const double middleRow = 0.5 * (first.row + second.row);
  EXPECT_EQ(pixelAt(rgba8, kWidth, {middleColumn, first.row}), kFrontColour);    // along the top step
  EXPECT_EQ(pixelAt(rgba8, kWidth, {second.column, middleRow}), kFrontColour);   // down the riser
  EXPECT_NE(pixelAt(rgba8, kWidth, {middleColumn, second.row}), kFrontColour);   // not the other way round
  EXPECT_NE(pixelAt(rgba8, kWidth, {first.column, middleRow}), kFrontColour);
}

TEST(BenchPlotRgba8, ZeroErrorOnALogAxisIsDrawnAtTheAxisMinimum) {
  constexpr std::uint32_t kWidth = 800;
  constexpr std::uint32_t kHeight = 600;
  const std::vector<PlotPoint> points = {point(1.0, 0.0, "reference"), point(0.1, 0.01, "epipolar"),
                                         point(0.2, 0.1, "epipolar")};
  std::vector<std::uint8_t> rgba8;
  plotRgba8(points, PlotSpec{}, kWidth, kHeight, rgba8);
  const PixelPosition zero = rasterPosition(points, PlotSpec{}, kWidth, kHeight, 1.0, 0.0);
  const PixelPosition lowest = rasterPosition(points, PlotSpec{}, kWidth, kHeight, 1.0, 0.01);
  const PixelPosition tiny = rasterPosition(points, PlotSpec{}, kWidth, kHeight, 1.0, 1e-30);
  EXPECT_GT(zero.row, lowest.row);
  EXPECT_EQ(zero.row, tiny.row);  // clamped like anything below the axis
  EXPECT_TRUE(std::isfinite(zero.row));
  EXPECT_EQ(pixelAt(rgba8, kWidth, zero), seriesColour(0));
}

TEST(BenchPlotRgba8, SpellsCommonTypographyInTheAsciiFont) {
  const auto render = [](const std::string& title, const std::string& label) {
    PlotSpec spec;
    spec.title = title;
    std::vector<std::uint8_t> rgba8;
    plotRgba8({point(0.5, 0.1, "s", label)}, spec, 640, 400, rgba8);
    return rgba8;
  };
  EXPECT_EQ(render("1920\u00d71080, 2048\u00b2 \u2013 3 \u00b5s", "a\u2264b"),
            render("1920x1080, 2048^2 - 3 us", "a<=b"));
  // Unknown code points and broken UTF-8 are one '?' each.
  EXPECT_EQ(render("\u6f22 \xe2\x82 x", "\x80"), render("? ? x", "?"));
  EXPECT_NE(render("1920\u00d71080", "p"), render("1920?1080", "p"));
}

TEST(BenchPlotRgba8, DegenerateSizesAndInputsDoNotBreak) {
  std::vector<std::uint8_t> rgba8(16, 7);
  plotRgba8(threeSeries(), PlotSpec{}, 0, 0, rgba8);
  EXPECT_TRUE(rgba8.empty());
  plotRgba8(threeSeries(), PlotSpec{}, 0, 100, rgba8);
  EXPECT_TRUE(rgba8.empty());
  plotRgba8(threeSeries(), PlotSpec{}, 3, 2, rgba8);
  EXPECT_EQ(rgba8.size(), 3u * 2u * 4u);
  plotRgba8({}, PlotSpec{}, 64, 48, rgba8);
  EXPECT_EQ(rgba8.size(), 64u * 48u * 4u);
  plotRgba8({point(kNaN, kNaN), point(0.5, 0.5)}, PlotSpec{}, 64, 48, rgba8);
  EXPECT_EQ(rgba8.size(), 64u * 48u * 4u);
}

}  // namespace
}  // namespace tyndall::samples::bench
