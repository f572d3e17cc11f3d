// The benchmark's time-against-error plots as data: every configuration as a point (GPU time
// relative to the Reference, relative RMSE of L_in), its Pareto front and the profiles' picks.
// tyndall-bench writes them to pareto.json; scripts/plot-pareto.py draws them with matplotlib.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace tyndall::samples::bench {

struct PlotPoint {
  std::string label;   ///< the configuration, e.g. "epipolar slices=512,samples=256"
  std::string series;  ///< the technique ("epipolar", "prefiltered"): one colour and shape per series
  double x = 0.0;      ///< time as a ratio to the Reference (smaller is better), > 0
  double y = 0.0;      ///< relative RMSE of L_in (smaller is better), >= 0
  std::string marker;  ///< the profiles picked here (e.g. "Balanced/High (local)"), empty for none
};

/// Indices of the points on the Pareto front (no other point has x <= and y <= with one strictly
/// less; non-finite points never on it; of exact duplicates keep the first), sorted by increasing x.
std::vector<std::size_t> paretoFront(const std::vector<PlotPoint>& points);

/// One plot as pareto.json holds it: {"file", "title", "points": [{"label", "series", "x", "y",
/// "marker", "front"}]}, `front` the point's 1-based position along the front by increasing x (0:
/// off the front); a non-finite x or y is written as null (JSON has no NaN).
nlohmann::ordered_json plotJson(const std::string& file, const std::string& title, const std::vector<PlotPoint>& points);

}  // namespace tyndall::samples::bench
