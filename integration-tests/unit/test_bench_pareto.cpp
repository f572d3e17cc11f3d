// tyndall-bench's plots as data: the Pareto front, each point's place on it in pareto.json, and the
// plots writeReports lists (per size, per kind of light, the profiles' picks marked).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scratch_path.h"
#include "pareto.h"
#include "report.h"

namespace tyndall::samples::bench {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

PlotPoint point(double x, double y, std::string series = "s", std::string label = "p", std::string marker = "") {
  return {std::move(label), std::move(series), x, y, std::move(marker)};
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

// ---- pareto.json ----

TEST(BenchParetoJson, RanksTheFrontByTimeAndWritesNonFiniteAsNull) {
  const std::vector<PlotPoint> points = {point(2.0, 0.5, "e", "slow"), point(3.0, 3.0, "e", "dominated"),
                                         point(0.5, 3.0, "p", "fast", "Performance"), point(kNaN, 1.0, "e", "broken")};
  const nlohmann::ordered_json plot = plotJson("pareto-x", "a title", points);
  EXPECT_EQ(plot.at("file"), "pareto-x");
  EXPECT_EQ(plot.at("title"), "a title");
  const nlohmann::ordered_json& p = plot.at("points");
  ASSERT_EQ(p.size(), points.size());
  EXPECT_EQ(p[0].at("front"), 2);
  EXPECT_EQ(p[1].at("front"), 0);
  EXPECT_EQ(p[2].at("front"), 1);
  EXPECT_EQ(p[3].at("front"), 0);
  EXPECT_TRUE(p[3].at("x").is_null());
  EXPECT_DOUBLE_EQ(p[0].at("x").get<double>(), 2.0);
  EXPECT_DOUBLE_EQ(p[0].at("y").get<double>(), 0.5);
  EXPECT_EQ(p[2].at("series"), "p");
  EXPECT_EQ(p[2].at("label"), "fast");
  EXPECT_EQ(p[2].at("marker"), "Performance");
  EXPECT_EQ(p[0].at("marker"), "");
}

Row measuredRow(const std::string& scene, const std::string& light, const std::string& parameters, double ratio,
                double rmse) {
  Row r;
  r.scene = scene;
  r.light = light;
  r.width = 64;
  r.height = 36;
  r.shadowMap = 256;
  r.technique = "epipolar";
  r.parameters = parameters;
  r.configuration = "epipolar " + parameters;
  r.measured = true;
  r.totalMilliseconds = 100.0 * ratio;
  r.referenceMilliseconds = 100.0;
  r.timeRatioToReference = ratio;
  r.floorMilliseconds = 1.0;
  r.timeRatioToFloor = 1.0;
  r.relativeRmse = rmse;
  return r;
}

nlohmann::json writtenParetoJson(const std::vector<Row>& rows) {
  ReportContext context;
  context.chooseWidth = 64;
  context.chooseHeight = 36;
  context.chooseShadowMap = 256;
  context.incumbents = Incumbents{};
  const std::filesystem::path dir = tyndall::test::scratchPath("pareto-json");
  std::string error;
  EXPECT_TRUE(writeReports(rows, context, dir.string(), error)) << error;
  std::ifstream in(dir / "pareto.json");
  nlohmann::json json = nlohmann::json::parse(in, nullptr, false);
  std::filesystem::remove_all(dir);
  return json;
}

// A point of `plot` by label; null when absent.
nlohmann::json pointOf(const nlohmann::json& plot, const std::string& label) {
  for (const nlohmann::json& p : plot.at("points")) {
    if (p.at("label") == label) return p;
  }
  return nullptr;
}

TEST(BenchParetoJson, APlotPerSizeAndPerKindOfLightWithThePicksMarked) {
  // Per kind of light: a fast, coarse configuration and a slow, accurate one, and one dominated.
  std::vector<Row> rows;
  for (const auto& [scene, light] : {std::pair{"sun", "directional"}, std::pair{"lamp", "spot"}}) {
    rows.push_back(measuredRow(scene, light, "fast", 0.01, 0.07));
    rows.push_back(measuredRow(scene, light, "accurate", 0.05, 0.01));
    rows.push_back(measuredRow(scene, light, "dominated", 0.06, 0.05));
  }
  const nlohmann::json json = writtenParetoJson(rows);
  ASSERT_TRUE(json.is_object());
  const nlohmann::json& plots = json.at("plots");
  ASSERT_EQ(plots.size(), 3u);
  EXPECT_EQ(plots[0].at("file"), "pareto-64x36-256");
  EXPECT_EQ(plots[1].at("file"), "pareto-64x36-256-directional");
  EXPECT_EQ(plots[2].at("file"), "pareto-64x36-256-local");
  for (const nlohmann::json& plot : plots) {
    SCOPED_TRACE(plot.at("file").get<std::string>());
    ASSERT_EQ(plot.at("points").size(), 3u);
    EXPECT_EQ(pointOf(plot, "epipolar fast").at("front"), 1);
    EXPECT_EQ(pointOf(plot, "epipolar accurate").at("front"), 2);
    EXPECT_EQ(pointOf(plot, "epipolar dominated").at("front"), 0);
    EXPECT_EQ(pointOf(plot, "epipolar dominated").at("marker"), "");
    // Performance (8%, 50x) takes the fast one; High and Balanced (12x, 25x) the accurate one.
    EXPECT_NE(pointOf(plot, "epipolar fast").at("marker").get<std::string>().find("Performance"), std::string::npos);
    EXPECT_NE(pointOf(plot, "epipolar accurate").at("marker").get<std::string>().find("High"), std::string::npos);
  }
  // The plot over every scene names the local lights' picks as such; the local plot has only those.
  EXPECT_EQ(pointOf(plots[0], "epipolar fast").at("marker"), "Performance/Performance (local)");
  EXPECT_EQ(pointOf(plots[2], "epipolar fast").at("marker"), "Performance (local)");
  EXPECT_EQ(pointOf(plots[1], "epipolar fast").at("marker"), "Performance");
}

TEST(BenchParetoJson, OneKindOfLightGivesOnePlot) {
  const nlohmann::json json = writtenParetoJson({measuredRow("sun", "directional", "a", 0.01, 0.07)});
  ASSERT_TRUE(json.is_object());
  ASSERT_EQ(json.at("plots").size(), 1u);
  EXPECT_EQ(json.at("plots")[0].at("file"), "pareto-64x36-256");
  EXPECT_EQ(json.at("plots")[0].at("points")[0].at("front"), 1);
}

}  // namespace
}  // namespace tyndall::samples::bench
