// tyndall-bench's summaries over the scenes and the profile choice from them, on made-up rows.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "scratch_path.h"
#include "report.h"
#include "sweep.h"

namespace tyndall::samples::bench {
namespace {

Row row(const std::string& scene, const std::string& technique, const std::string& parameters, double ms,
        double referenceMs, double rmse) {
  Row r;
  r.scene = scene;
  r.width = 64;
  r.height = 36;
  r.shadowMap = 256;
  r.technique = technique;
  r.parameters = parameters;
  r.configuration = technique + " " + parameters;
  r.measured = true;
  r.totalMilliseconds = ms;
  r.referenceMilliseconds = referenceMs;
  r.timeRatioToReference = ms / referenceMs;
  r.floorMilliseconds = 1.0;
  r.timeRatioToFloor = ms;
  r.relativeRmse = rmse;
  return r;
}

TEST(BenchSummary, MediansOverTheScenesAndTheWorstScene) {
  std::vector<Row> rows{row("a", "epipolar", "x", 1.0, 100.0, 0.01), row("b", "epipolar", "x", 3.0, 100.0, 0.05),
                        row("c", "epipolar", "x", 2.0, 100.0, 0.02)};
  Row skipped = row("d", "epipolar", "x", 50.0, 100.0, 0.9);
  skipped.measured = false;  // skipped rows do not count
  rows.push_back(skipped);
  Row otherSize = row("a", "epipolar", "x", 50.0, 100.0, 0.9);
  otherSize.width = 128;  // another group
  rows.push_back(otherSize);
  const std::vector<Summary> s = summarize(rows, 64, 36, 256);
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s[0].scenes, 3u);
  EXPECT_DOUBLE_EQ(s[0].milliseconds, 2.0);
  EXPECT_DOUBLE_EQ(s[0].timeRatioToReference, 0.02);
  EXPECT_DOUBLE_EQ(s[0].relativeRmse, 0.02);
  EXPECT_DOUBLE_EQ(s[0].worstRelativeRmse, 0.05);
  EXPECT_EQ(s[0].worstScene, "b");
  EXPECT_DOUBLE_EQ(s[0].timeSpread, 1.0);  // (3 − 1) / 2
}

TEST(BenchSummary, OverTheScenesOfOneKindOfLight) {
  // Two directional scenes and a spot one: the kinds' summaries see only their scenes, so a
  // configuration fast on the directional ones is not slowed by the spot scene's cost, nor the spot
  // scene's choice decided by the directional ones.
  std::vector<Row> rows{row("sun-a", "epipolar", "x", 1.0, 100.0, 0.01), row("sun-b", "epipolar", "x", 3.0, 100.0, 0.03),
                        row("lamp", "epipolar", "x", 50.0, 100.0, 0.2)};
  rows[0].light = rows[1].light = "directional";
  rows[2].light = "spot";
  EXPECT_EQ(lightClassOf(rows[0]), LightClass::Directional);
  EXPECT_EQ(lightClassOf(rows[2]), LightClass::Local);
  Row point = rows[2];
  point.light = "point";
  EXPECT_EQ(lightClassOf(point), LightClass::Local);
  Row street = rows[2];
  street.light = "several";
  EXPECT_FALSE(lightClassOf(street).has_value());
  const std::vector<Summary> all = summarize(rows, 64, 36, 256);
  ASSERT_EQ(all.size(), 1u);
  EXPECT_EQ(all[0].scenes, 3u);
  EXPECT_DOUBLE_EQ(all[0].milliseconds, 3.0);
  const std::vector<Summary> sun = summarize(rows, 64, 36, 256, LightClass::Directional);
  ASSERT_EQ(sun.size(), 1u);
  EXPECT_EQ(sun[0].scenes, 2u);
  EXPECT_DOUBLE_EQ(sun[0].milliseconds, 2.0);
  EXPECT_DOUBLE_EQ(sun[0].worstRelativeRmse, 0.03);
  const std::vector<Summary> lamp = summarize(rows, 64, 36, 256, LightClass::Local);
  ASSERT_EQ(lamp.size(), 1u);
  EXPECT_EQ(lamp[0].scenes, 1u);
  EXPECT_EQ(lamp[0].worstScene, "lamp");
  // Only the spot scene's 2× speedup counts for the local row: no profile's speed goal is met.
  for (const ProfileChoiceResult& c : chooseProfiles(lamp)) EXPECT_FALSE(c.speedMet);
  EXPECT_TRUE(chooseProfiles(sun)[0].speedMet);  // High: 50× over the directional scenes
}

TEST(BenchChoice, MostAccurateThatMeetsEachSpeedGoal) {
  // Speedups 10×, 20×, 40×, 100× at errors 1%, 3%, 6%, 12%; the floor is 1 ms.
  std::vector<Row> rows{row("a", "epipolar", "slow", 10.0, 100.0, 0.01), row("a", "epipolar", "mid", 5.0, 100.0, 0.03),
                        row("a", "epipolar", "fast", 2.5, 100.0, 0.06), row("a", "prefiltered", "cheap", 1.0, 100.0, 0.12)};
  const std::vector<Summary> s = summarize(rows, 64, 36, 256);
  const std::vector<ProfileChoiceResult> c = chooseProfiles(s);
  ASSERT_EQ(c.size(), 3u);
  ASSERT_TRUE(c[0].summary && c[1].summary && c[2].summary);
  EXPECT_EQ(s[*c[0].summary].parameters, "mid");  // High: >= 12× (10× is too slow), the most accurate
  EXPECT_TRUE(c[0].speedMet);
  EXPECT_FALSE(c[0].errorMet);  // 3% > 2%
  EXPECT_EQ(s[*c[1].summary].parameters, "fast");  // Balanced: >= 25×
  EXPECT_FALSE(c[1].errorMet);                     // 6% > 4%
  EXPECT_EQ(s[*c[2].summary].parameters, "cheap");  // Performance: >= 50× and within 4× the floor
  EXPECT_TRUE(c[2].speedMet);
  EXPECT_TRUE(c[2].floorMet);
  EXPECT_FALSE(c[2].errorMet);  // 12% > 8%, within Performance's per-scene bar of 16%
}

TEST(BenchChoice, PerformancesPerSceneBarRulesOutAFastButWrongCandidate) {
  // "wrong" is fast enough for every goal but misses 16% on scene a, where "right" meets it.
  std::vector<Row> rows{row("a", "epipolar", "wrong", 1.0, 100.0, 0.20), row("a", "epipolar", "right", 1.5, 100.0, 0.10)};
  const std::vector<Summary> s = summarize(rows, 64, 36, 256);
  const std::vector<ProfileChoiceResult> c = chooseProfiles(s);
  ASSERT_TRUE(c[2].summary);
  EXPECT_EQ(s[*c[2].summary].parameters, "right");
  EXPECT_TRUE(c[2].speedMet);
}

TEST(BenchChoice, TheFloorGoalRulesOutASlowPerformanceCandidate) {
  Row slowOverFloor = row("a", "epipolar", "accurate", 1.5, 100.0, 0.01);
  slowOverFloor.timeRatioToFloor = 6.0;  // 66× faster than the Reference but 6× the floor
  std::vector<Row> rows{slowOverFloor, row("a", "epipolar", "rough", 1.0, 100.0, 0.05)};
  const std::vector<Summary> s = summarize(rows, 64, 36, 256);
  const std::vector<ProfileChoiceResult> c = chooseProfiles(s);
  EXPECT_EQ(s[*c[0].summary].parameters, "accurate");  // High has no floor goal
  EXPECT_EQ(s[*c[2].summary].parameters, "rough");
  EXPECT_TRUE(c[2].errorMet);
}

TEST(BenchChoice, AFloorGoalNoneMeetsKeepsTheSpeedupGoalsMostAccurate) {
  // Both are fast enough for Performance's 50× and neither is within 4× the floor: the more
  // accurate one, not the faster (as on a CPU driver, where no technique comes near the floor).
  Row accurate = row("a", "epipolar", "accurate", 1.9, 100.0, 0.04);
  Row rough = row("a", "epipolar", "rough", 1.8, 100.0, 0.05);
  accurate.timeRatioToFloor = 30.0;
  rough.timeRatioToFloor = 28.0;
  Row slow = row("a", "epipolar", "slow", 2.5, 100.0, 0.01);  // 40×: too slow for Performance
  slow.timeRatioToFloor = 40.0;
  const std::vector<Summary> s = summarize({accurate, rough, slow}, 64, 36, 256);
  const std::vector<ProfileChoiceResult> c = chooseProfiles(s);
  ASSERT_TRUE(c[2].summary);
  EXPECT_EQ(s[*c[2].summary].parameters, "accurate");
  EXPECT_TRUE(c[2].speedMet);
  EXPECT_FALSE(c[2].floorMet);
}

TEST(BenchChoice, ThePerSceneBarHoldsWhereSomeConfigurationMeetsIt) {
  // X is more accurate by the median but misses High's 3% on scene b, which Y meets; on scene c
  // neither meets any bar, so c decides nothing.
  std::vector<Row> rows{row("a", "epipolar", "X", 2.0, 100.0, 0.002), row("b", "epipolar", "X", 2.0, 100.0, 0.05),
                        row("c", "epipolar", "X", 2.0, 100.0, 0.004), row("a", "epipolar", "Y", 3.0, 100.0, 0.01),
                        row("b", "epipolar", "Y", 3.0, 100.0, 0.025), row("c", "epipolar", "Y", 3.0, 100.0, 0.3)};
  rows[2].relativeRmse = 0.5;  // X on c: missed by both
  const std::vector<Summary> s = summarize(rows, 64, 36, 256);
  const std::vector<ProfileChoiceResult> c = chooseProfiles(s);
  EXPECT_EQ(s[*c[0].summary].parameters, "Y");  // High: X misses 3% on b
  // Balanced: both meet 6% on a and b and miss it on c, which then decides nothing (else neither
  // would be eligible); Y's median is lower.
  EXPECT_EQ(s[*c[1].summary].parameters, "Y");
}

TEST(BenchChoice, AConfigurationThatSkippedAScenePassesNoBarThere) {
  // P (a directional-only technique) is faster and more accurate on a but did not run on the spot
  // scene b, where E meets every bar: P is never chosen, although by its own scenes it would be.
  std::vector<Row> rows{row("a", "prefiltered", "P", 1.0, 100.0, 0.001), row("a", "epipolar", "E", 2.0, 100.0, 0.01),
                        row("b", "epipolar", "E", 2.0, 100.0, 0.01)};
  Row skipped = row("b", "prefiltered", "P", 0.0, 100.0, 0.0);
  skipped.measured = false;  // directional lights only
  rows.push_back(skipped);
  const std::vector<Summary> s = summarize(rows, 64, 36, 256);
  for (const ProfileChoiceResult& choice : chooseProfiles(s)) {
    ASSERT_TRUE(choice.summary);
    EXPECT_EQ(s[*choice.summary].parameters, "E") << choice.goal.name();
  }
}

// Performance's incumbent ("table", the profile table's configuration) and a more accurate
// challenger at the given speedups over the Reference; the floor pass is 1 ms.
std::vector<Summary> incumbentAndChallenger(double tableSpeedup, double challengerSpeedup, double referenceMs = 100.0) {
  return summarize({row("a", "epipolar", "table", referenceMs / tableSpeedup, referenceMs, 0.043),
                    row("a", "epipolar", "challenger", referenceMs / challengerSpeedup, referenceMs, 0.032)},
                   64, 36, 256);
}

const std::map<Profile, std::string> kTable{{Profile::Performance, "epipolar table"}};

TEST(BenchChoice, AChallengerInsideTheMarginDoesNotReplaceTheIncumbent) {
  // 52× clears Performance's 50× but not 50 × 1.25: the table's 55× configuration stays, although
  // the plain goals (no incumbent) would take the more accurate challenger.
  std::vector<Summary> s = incumbentAndChallenger(55.0, 52.0);
  EXPECT_EQ(s[*chooseProfiles(s)[2].summary].parameters, "challenger");
  const ProfileChoiceResult kept = chooseProfiles(s, kTable)[2];
  EXPECT_EQ(s[*kept.summary].parameters, "table");
  EXPECT_EQ(kept.incumbent, "epipolar table");
  EXPECT_TRUE(kept.speedMet);
  // Past the margin (70× >= 62.5×) the more accurate challenger replaces it.
  s = incumbentAndChallenger(55.0, 70.0);
  const ProfileChoiceResult replaced = chooseProfiles(s, kTable)[2];
  EXPECT_EQ(s[*replaced.summary].parameters, "challenger");
  EXPECT_EQ(replaced.incumbent, "epipolar table");
  // The other profiles have no incumbent here: the plain goals.
  EXPECT_TRUE(chooseProfiles(s, kTable)[0].incumbent.empty());
}

TEST(BenchChoice, AChallengerBarelyMoreAccurateDoesNotReplaceTheIncumbent) {
  // Balanced: the table's at 35× and 0.86%, a challenger past the speed margin (40× >= 31.25×)
  // but only 7% more accurate stays out; 12% more accurate, it replaces the table's.
  const std::map<Profile, std::string> table{{Profile::Balanced, "epipolar table"}};
  const auto balanced = [&](double challengerRmse) {
    const std::vector<Summary> s = summarize({row("a", "epipolar", "table", 100.0 / 35.0, 100.0, 0.0086),
                                              row("a", "epipolar", "challenger", 100.0 / 40.0, 100.0, challengerRmse)},
                                             64, 36, 256);
    return s[*chooseProfiles(s, table)[1].summary].parameters;
  };
  EXPECT_EQ(balanced(0.0080), "table");
  EXPECT_EQ(balanced(0.0076), "challenger");
  // Performance: a challenger that meets the floor goal the table's misses replaces it however
  // little more accurate it is (1000 ms Reference: the table's at 100× is 10 × the floor, the
  // challenger at 400× is 2.5 ×, within 4 / 1.25).
  const std::map<Profile, std::string> performance{{Profile::Performance, "epipolar table"}};
  const std::vector<Summary> s = summarize({row("a", "epipolar", "table", 10.0, 1000.0, 0.043),
                                            row("a", "epipolar", "challenger", 2.5, 1000.0, 0.0425)},
                                           64, 36, 256);
  const ProfileChoiceResult c = chooseProfiles(s, performance)[2];
  EXPECT_EQ(s[*c.summary].parameters, "challenger");
  EXPECT_TRUE(c.floorMet);
}

TEST(BenchChoice, TheFloorGoalHasTheMarginToo) {
  // Both are far above 50× (1000 ms Reference); the table's is at 3 × the floor, the challenger at
  // 3.6 ×, within 4 but not within 4 / 1.25 = 3.2.
  const std::vector<Summary> s = incumbentAndChallenger(1000.0 / 3.0, 1000.0 / 3.6, 1000.0);
  EXPECT_EQ(s[*chooseProfiles(s)[2].summary].parameters, "challenger");
  const ProfileChoiceResult kept = chooseProfiles(s, kTable)[2];
  EXPECT_EQ(s[*kept.summary].parameters, "table");
  EXPECT_TRUE(kept.floorMet);
}

TEST(BenchChoice, AnIncumbentThatMissesItsGoalLeavesThePlainGoalsToDecide) {
  // The table's configuration measured 45×: no configuration clears the margin, so the plain goals
  // pick the challenger at 52×, which the document reports as replacing the table's.
  std::vector<Summary> s = incumbentAndChallenger(45.0, 52.0);
  const ProfileChoiceResult c = chooseProfiles(s, kTable)[2];
  EXPECT_EQ(s[*c.summary].parameters, "challenger");
  EXPECT_EQ(c.incumbent, "epipolar table");
  EXPECT_TRUE(c.speedMet);
  // An incumbent this run did not measure changes nothing.
  s = incumbentAndChallenger(55.0, 52.0);
  const ProfileChoiceResult unmeasured = chooseProfiles(s, {{Profile::Performance, "epipolar gone"}})[2];
  EXPECT_EQ(s[*unmeasured.summary].parameters, "challenger");
  EXPECT_TRUE(unmeasured.incumbent.empty());
}

TEST(BenchChoice, NothingFastEnoughTakesTheFastest) {
  std::vector<Row> rows{row("a", "epipolar", "p", 50.0, 100.0, 0.30), row("a", "epipolar", "q", 20.0, 100.0, 0.25)};
  Row broken = row("a", "epipolar", "nan", 0.5, 100.0, 0.001);
  broken.nonFinite = 3;  // never chosen
  rows.push_back(broken);
  const std::vector<Summary> s = summarize(rows, 64, 36, 256);
  for (const ProfileChoiceResult& choice : chooseProfiles(s)) {
    ASSERT_TRUE(choice.summary);
    EXPECT_EQ(s[*choice.summary].parameters, "q");
    EXPECT_FALSE(choice.speedMet);
  }
}

// A profile runs as the profile table's row (the incumbent) where the run measured it, even when
// the run would choose another (a GPU's run: the profiles still run the table), and as the run's
// choice where the table's row was not measured: choice.json's asItRuns, which the document's
// per-scene table shows.
TEST(BenchReport, TheProfilesAsTheyRunAreTheTablesRows) {
  std::vector<Row> rows{row("a", "epipolar", "table", 5.0, 100.0, 0.01), row("a", "epipolar", "challenger", 1.0, 100.0, 0.005)};
  for (Row& r : rows) r.light = "directional";
  const auto highAsItRuns = [&](const ReportContext& context) {
    const std::filesystem::path dir = tyndall::test::scratchPath("bench-as-it-runs");
    std::string error;
    EXPECT_TRUE(writeReports(rows, context, dir.string(), error)) << error;
    std::ifstream in(dir / "choice.json");
    const nlohmann::json choice = nlohmann::json::parse(in, nullptr, false);
    std::filesystem::remove_all(dir);
    EXPECT_TRUE(choice.is_array());
    if (!choice.is_array()) return std::string();
    for (const nlohmann::json& entry : choice) {
      if (entry.at("profile") == "High" && entry.at("lights") == "directional") {
        EXPECT_EQ(entry.at("parameters"), "challenger");  // the choice, whichever row runs
        return entry.at("asItRuns").get<std::string>();
      }
    }
    ADD_FAILURE() << "choice.json has no High, directional entry";
    return std::string();
  };
  ReportContext context;
  context.chooseWidth = 64;
  context.chooseHeight = 36;
  context.chooseShadowMap = 256;
  context.incumbents = Incumbents{{LightClass::Directional, {{Profile::High, "epipolar table"}}}};
  // 100× past the margin and twice as accurate: the choice replaces the table's row for High...
  const std::vector<Summary> s = summarize(rows, 64, 36, 256, LightClass::Directional);
  EXPECT_EQ(s[*chooseProfiles(s, context.incumbents->at(LightClass::Directional))[0].summary].parameters, "challenger");
  // ...but High as it runs is the table's row.
  EXPECT_EQ(highAsItRuns(context), "epipolar table");
  // Without the table's row in the run, the run's choice.
  context.incumbents = Incumbents{{LightClass::Directional, {{Profile::High, "epipolar not-measured"}}}};
  EXPECT_EQ(highAsItRuns(context), "epipolar challenger");
}

// × floor is against the floor of the composite's kind; a compute composite whose floor was not
// measured (no STORAGE back buffer, or the device cannot write it) falls back to the fragment floor.
TEST(BenchFloor, TheRatioIsAgainstTheFloorOfTheCompositesKind) {
  Row r = row("a", "epipolar", "x", 6.0, 100.0, 0.01);
  r.floorMilliseconds = 2.0;
  r.computeFloorMilliseconds = 1.5;
  r.composite = "fragment";
  EXPECT_DOUBLE_EQ(compositeFloorMilliseconds(r), 2.0);
  r.composite = "compute";
  EXPECT_DOUBLE_EQ(compositeFloorMilliseconds(r), 1.5);
  r.computeFloorMilliseconds = 0.0;
  r.computeFloorNote = "compute floor not measured: the back buffer has no STORAGE usage";
  EXPECT_DOUBLE_EQ(compositeFloorMilliseconds(r), 2.0);
}

// results.json keeps both floors, the composite and the command counts; a file written before the
// rows had them still loads, with the defaults.
TEST(BenchReport, ResultsKeepTheFloorsTheCompositeAndTheCountsAndOldFilesLoad) {
  Row r = row("a", "epipolar", "x", 6.0, 100.0, 0.01);
  r.light = "directional";
  r.floorMilliseconds = 2.0;
  r.computeFloorMilliseconds = 1.5;
  r.composite = "compute";
  r.timeRatioToFloor = 4.0;
  r.dispatches = 17;
  r.barriers = 9;
  Row skipped = row("a", "prefiltered", "y", 0.0, 100.0, 0.0);
  skipped.light = "directional";
  skipped.measured = false;
  skipped.computeFloorNote = "compute floor not measured: the back buffer has no STORAGE usage";
  ReportContext context;
  context.chooseWidth = 64;
  context.chooseHeight = 36;
  context.chooseShadowMap = 256;
  const std::filesystem::path dir = tyndall::test::scratchPath("bench-floors");
  std::string error;
  ASSERT_TRUE(writeReports({r, skipped}, context, dir.string(), error)) << error;

  std::vector<Row> read;
  ReportContext readContext;
  ASSERT_TRUE(readResults((dir / "results.json").string(), read, readContext, error)) << error;
  ASSERT_EQ(read.size(), 2u);
  EXPECT_DOUBLE_EQ(read[0].floorMilliseconds, 2.0);
  EXPECT_DOUBLE_EQ(read[0].computeFloorMilliseconds, 1.5);
  EXPECT_EQ(read[0].composite, "compute");
  EXPECT_EQ(read[0].dispatches, 17u);
  EXPECT_EQ(read[0].barriers, 9u);
  EXPECT_EQ(read[1].computeFloorNote, skipped.computeFloorNote);

  // The same file without the new keys, as earlier runs wrote it.
  nlohmann::json old;
  {
    std::ifstream in(dir / "results.json");
    old = nlohmann::json::parse(in);
  }
  for (nlohmann::json& j : old.at("rows")) {
    for (const char* key : {"computeFloorMilliseconds", "computeFloorNote", "composite", "dispatches", "barriers"}) {
      ASSERT_EQ(j.erase(key), 1u) << key;
    }
  }
  std::ofstream(dir / "old.json") << old.dump();
  read.clear();
  ASSERT_TRUE(readResults((dir / "old.json").string(), read, readContext, error)) << error;
  std::filesystem::remove_all(dir);
  ASSERT_EQ(read.size(), 2u);
  EXPECT_DOUBLE_EQ(read[0].floorMilliseconds, 2.0);
  EXPECT_DOUBLE_EQ(read[0].computeFloorMilliseconds, 0.0);
  EXPECT_EQ(read[0].computeFloorNote, "");
  EXPECT_EQ(read[0].composite, "none");
  EXPECT_EQ(read[0].dispatches, 0u);
  EXPECT_EQ(read[0].barriers, 0u);
}

// The default sweep measures reduced resolutions of both techniques, so that the profile table can
// choose them where they are on the Pareto front.
TEST(BenchGrid, TheDefaultSweepHasReducedResolutions) {
  std::vector<Configuration> grid;
  std::string error;
  ASSERT_TRUE(builtInGrid("default", grid, error)) << error;
  std::map<std::string, int> reduced;
  for (const Configuration& c : grid) {
    const ScatteringResolution r = c.epipolar ? c.epipolar->resolution
                                   : c.prefiltered ? c.prefiltered->resolution
                                                   : ScatteringResolution::Full;
    if (r != ScatteringResolution::Full) ++reduced[c.techniqueName() + " " + to_string(r)];
  }
  EXPECT_GE(reduced["epipolar half"], 2);
  EXPECT_GE(reduced["epipolar quarter"], 1);
  EXPECT_GE(reduced["prefiltered half"], 1);
}

// A scene of several lights: each light's passes summed (its light_sum too), the shared ones apart;
// a row of one light (no "lightI/" passes) is not listed, and without such rows there is no table.
TEST(BenchReport, PerLightCostSumsEachLightsPasses) {
  Row several = row("street", "epipolar", "x", 4.0, 100.0, 0.01);
  several.passMilliseconds = {{"light0/epipolar_march", 1.0}, {"light0/epipolar_unwarp", 0.5},
                              {"light1/epipolar_march", 2.0}, {"light1/light_sum", 0.25}, {"composite", 0.125}};
  Row single = row("pillars", "epipolar", "x", 2.0, 100.0, 0.01);
  single.passMilliseconds = {{"epipolar_march", 1.0}, {"composite", 0.125}};
  EXPECT_EQ(perLightMarkdown({single}), "");
  const std::string table = perLightMarkdown({single, several});
  EXPECT_NE(table.find("| light 0 ms | light 1 ms | shared ms |"), std::string::npos) << table;
  EXPECT_NE(table.find("| street | 64×36 | 256² | epipolar | `x` | 4.000 | 1.500 | 2.250 | 0.125 |"), std::string::npos)
      << table;
  EXPECT_EQ(table.find("| pillars |"), std::string::npos) << table;
}

}  // namespace
}  // namespace tyndall::samples::bench
