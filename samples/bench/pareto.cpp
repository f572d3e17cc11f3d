#include "pareto.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

namespace tyndall::samples::bench {

namespace {

bool finite(const PlotPoint& p) { return std::isfinite(p.x) && std::isfinite(p.y); }

nlohmann::ordered_json finiteOrNull(double value) {
  return std::isfinite(value) ? nlohmann::ordered_json(value) : nlohmann::ordered_json(nullptr);
}

}  // namespace

std::vector<std::size_t> paretoFront(const std::vector<PlotPoint>& points) {
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (finite(points[i])) order.push_back(i);
  }
  // By x, then y, then index: each point that is strictly below everything before it is on the
  // front, which leaves out equal-x and equal-y losers and all but the first of exact duplicates.
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return std::tie(points[a].x, points[a].y, a) < std::tie(points[b].x, points[b].y, b);
  });
  std::vector<std::size_t> front;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i : order) {
    if (points[i].y < best) {
      front.push_back(i);
      best = points[i].y;
    }
  }
  return front;
}

nlohmann::ordered_json plotJson(const std::string& file, const std::string& title, const std::vector<PlotPoint>& points) {
  const std::vector<std::size_t> front = paretoFront(points);
  std::vector<std::size_t> rank(points.size(), 0);
  for (std::size_t k = 0; k < front.size(); ++k) rank[front[k]] = k + 1;
  nlohmann::ordered_json plot;
  plot["file"] = file;
  plot["title"] = title;
  plot["points"] = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < points.size(); ++i) {
    const PlotPoint& p = points[i];
    nlohmann::ordered_json j;
    j["label"] = p.label;
    j["series"] = p.series;
    j["x"] = finiteOrNull(p.x);
    j["y"] = finiteOrNull(p.y);
    j["marker"] = p.marker;
    j["front"] = rank[i];
    plot["points"].push_back(j);
  }
  return plot;
}

}  // namespace tyndall::samples::bench
