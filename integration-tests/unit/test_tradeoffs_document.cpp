// The profile table's document (docs/TRADEOFFS-H200.md, the sweep on a GPU) and the plugin's
// profile table (plugin/src/profiles.cpp) must say the same: a profile is the measured point the
// document names, not a number typed in twice. The choice is read as data,
// docs/data/profile-table-choice.json, which `scripts/measure.sh tradeoffs` writes with that
// document from the same run (tyndall-bench's choice.json), beside the run's rows
// (docs/data/profile-table-results.json).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scratch_path.h"
#include "profiles.h"
#include "report.h"
#include "settings_text.h"

namespace tyndall {
namespace {

struct ChosenRow {
  std::string technique;
  std::string parameters;
};

// choice.json's entries by profile name ("High") and kind of light ("directional").
std::map<std::pair<std::string, std::string>, ChosenRow> choiceData(const std::string& path) {
  std::ifstream file(path);
  const nlohmann::json json = nlohmann::json::parse(file, nullptr, false);
  std::map<std::pair<std::string, std::string>, ChosenRow> rows;
  if (!json.is_array()) return rows;
  for (const nlohmann::json& entry : json) {
    rows[{entry.at("profile").get<std::string>(), entry.at("lights").get<std::string>()}] = {
        entry.at("technique").get<std::string>(), entry.at("parameters").get<std::string>()};
  }
  return rows;
}

// The size the table's run chose at (its results' chooseAt).
std::uint32_t chosenHeight() {
  std::vector<samples::bench::Row> rows;
  samples::bench::ReportContext context;
  std::string error;
  const bool read = samples::bench::readResults(std::string(TYNDALL_DOCS_DIR) + "/data/profile-table-results.json",
                                                rows, context, error);
  EXPECT_TRUE(read) << error;
  return read ? context.chooseHeight : 0;
}

TEST(TradeoffsDocument, AgreesWithTheProfileTable) {
  const std::string path = std::string(TYNDALL_DOCS_DIR) + "/data/profile-table-choice.json";
  const std::map<std::pair<std::string, std::string>, ChosenRow> rows = choiceData(path);
  ASSERT_FALSE(rows.empty()) << path << " is missing or holds no choice";
  const std::uint32_t height = chosenHeight();
  ASSERT_GT(height, 0u);
  for (LightClass lights : {LightClass::Directional, LightClass::Local}) {
    for (Profile profile : {Profile::High, Profile::Balanced, Profile::Performance}) {
      SCOPED_TRACE(std::string(to_string(profile)) + ", " + to_string(lights));
      const ProfileChoice& code = profileChoice(profile, lights);
      EXPECT_EQ(code.profile, profile);
      EXPECT_EQ(code.lights, lights);
      const std::string name = samples::bench::profileGoal(profile)->name();
      const std::pair<std::string, std::string> key{name, to_string(lights)};
      ASSERT_TRUE(rows.contains(key)) << path << " names no configuration for " << name << " with " << key.second
                                      << " lights";
      const ChosenRow& chosen = rows.at(key);
      EXPECT_EQ(chosen.technique, to_string(code.technique));
      // At the size it was chosen at the row runs exactly what was measured: its floor does not
      // bind there, and it is that size's target rows, so that no smaller output runs it coarser.
      const auto checkFloor = [&](const auto& settings) {
        if (settings.resolution == ScatteringResolution::Full) {
          EXPECT_EQ(settings.minimumRows, 0u);
          return;
        }
        const auto stride = static_cast<std::uint32_t>(settings.resolution);
        EXPECT_EQ(settings.minimumRows, (height + stride - 1) / stride);
        EXPECT_EQ(resolutionForRows(settings.resolution, settings.minimumRows, height), settings.resolution);
      };
      std::string codeParameters;
      if (code.technique == Technique::Prefiltered) {
        checkFloor(code.prefiltered);
        codeParameters = samples::describe(settingsAsRunAt(code.prefiltered, height));
      } else {
        checkFloor(code.epipolar);
        codeParameters = samples::describe(settingsAsRunAt(code.epipolar, height));
      }
      EXPECT_EQ(chosen.parameters, codeParameters);
      // The bench's incumbents (the configurations challengers must beat by a margin) name the same.
      EXPECT_EQ(samples::bench::profileTableConfigurations(lights, height).at(profile),
                chosen.technique + " " + chosen.parameters);
    }
  }
}

// The committed choice is the one tyndall-bench makes from the kept rows today
// (docs/data/profile-table-results.json, which docs/TRADEOFFS-H200.md was written from), so that
// neither the data nor the choice rule can change without the other being written again.
TEST(TradeoffsDocument, TheChoiceDataIsTheKeptRowsChoice) {
  const std::string docs(TYNDALL_DOCS_DIR);
  std::vector<samples::bench::Row> rows;
  samples::bench::ReportContext context;
  std::string error;
  ASSERT_TRUE(samples::bench::readResults(docs + "/data/profile-table-results.json", rows, context, error)) << error;
  const std::filesystem::path dir = tyndall::test::scratchPath("tradeoffs-choice");
  ASSERT_TRUE(samples::bench::writeReports(rows, context, dir.string(), error)) << error;
  std::ifstream written(dir / "choice.json");
  std::ifstream committed(docs + "/data/profile-table-choice.json");
  const nlohmann::json writtenJson = nlohmann::json::parse(written, nullptr, false);
  const nlohmann::json committedJson = nlohmann::json::parse(committed, nullptr, false);
  std::filesystem::remove_all(dir);
  ASSERT_TRUE(writtenJson.is_array());
  EXPECT_EQ(committedJson, writtenJson) << "write it again: FROM=docs/data/profile-table-results.json "
                                           "DOC=docs/TRADEOFFS-H200.md scripts/measure.sh tradeoffs";
}

}  // namespace
}  // namespace tyndall
