// The benchmark's speed–accuracy plot: every configuration as a point (GPU time relative to the
// Reference, relative RMSE of L_in), its Pareto front as a staircase, the named quality presets
// highlighted. Written as SVG, or rasterised to RGBA8 for a PNG with a built-in bitmap font, so the
// benchmark needs no font or drawing library.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace tyndall::samples::bench {

struct PlotPoint {
  std::string label;   ///< e.g. "epipolar slices=512 samples=256": listed for Pareto points, SVG tooltip for all
  std::string series;  ///< the technique ("reference", "epipolar", "prefiltered"): one colour and shape per series
  double x = 0.0;      ///< time as a ratio to the Reference (smaller is better), > 0
  double y = 0.0;      ///< relative RMSE of L_in (smaller is better), >= 0
  std::string marker;  ///< optional: non-empty (e.g. "High", "Balanced") to draw the point larger, annotated with it
};

/// On a log axis, values <= 0 (a Reference compared with itself has y == 0) are drawn at the axis
/// minimum and counted in a note under the legend. Points with a non-finite x or y are not drawn
/// (also counted in a note) and never on the front. Ranges come from the drawable points with a 5%
/// margin, at least one decade on a log axis and a tenth of the magnitude on a linear one.
struct PlotSpec {
  std::string title;
  std::string xLabel = "time / Reference time";
  std::string yLabel = "relative RMSE of L_in";
  bool logX = true;
  bool logY = true;
};

struct Rgb8 {
  std::uint8_t r = 0;
  std::uint8_t g = 0;
  std::uint8_t b = 0;
  bool operator==(const Rgb8&) const = default;
};

/// Background of both outputs, and the colour of the Pareto staircase.
inline constexpr Rgb8 kPlotBackground{255, 255, 255};
inline constexpr Rgb8 kFrontColour{64, 64, 64};
/// Colour of the series-th series, series counted in order of first appearance in the points.
/// Okabe–Ito palette (cycles after 6 colours; shapes cycle after 4, so 12 series stay distinct).
Rgb8 seriesColour(std::size_t series);

/// Indices of the points on the Pareto front (no other point has x <= and y <= with one strictly
/// less; non-finite points never on it; of exact duplicates keep the first), sorted by increasing x.
std::vector<std::size_t> paretoFront(const std::vector<PlotPoint>& points);

/// SVG canvas size in user units (px).
inline constexpr std::uint32_t kSvgWidth = 960;
inline constexpr std::uint32_t kSvgHeight = 600;

/// The plot as a standalone SVG document (no XML declaration; starts with "<svg", ends with
/// "</svg>\n"): axes with ticks (log decades with 1-2-5 minor labels where they fit), axis labels,
/// title, one colour and shape per series with a legend, every drawable point as one element with
/// class="point" and a <title> tooltip, the Pareto front as a staircase (class="front") with its
/// points numbered and listed under the legend, highlighted markers annotated. Byte-identical for
/// identical input, whatever the C locale.
std::string plotSvg(const std::vector<PlotPoint>& points, const PlotSpec& spec);

/// The same plot rasterised to 8-bit RGBA, opaque, row 0 at the top, width*height*4 bytes (empty
/// when either is 0). Text in a built-in 5x7 bitmap font (printable ASCII; other bytes drawn as
/// '?'), scaled by max(1, min(width / 600, height / 400)), so 1200x800 and up read comfortably.
void plotRgba8(const std::vector<PlotPoint>& points, const PlotSpec& spec, std::uint32_t width, std::uint32_t height,
               std::vector<std::uint8_t>& rgba8);

/// Where plotRgba8 puts the centre of a point (x, y) in a width x height image: continuous pixel
/// coordinates, pixel (i, j) covering [i, i+1) x [j, j+1). Clamped to the plot area like the points.
struct PixelPosition {
  double column = 0.0;
  double row = 0.0;
};
PixelPosition rasterPosition(const std::vector<PlotPoint>& points, const PlotSpec& spec, std::uint32_t width,
                             std::uint32_t height, double x, double y);

}  // namespace tyndall::samples::bench
