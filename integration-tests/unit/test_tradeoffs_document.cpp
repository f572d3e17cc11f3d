// docs/TRADEOFFS.md's choice and the plugin's profile table (plugin/src/profiles.cpp) must say the
// same: a profile is the measured point the document names, not a number typed in twice. The
// choice is read as data, docs/data/tradeoffs-lavapipe-choice.json, which `scripts/measure.sh
// tradeoffs` writes with the document from the same run (tyndall-bench's choice.json).
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

TEST(TradeoffsDocument, AgreesWithTheProfileTable) {
  const std::string path = std::string(TYNDALL_DOCS_DIR) + "/data/tradeoffs-lavapipe-choice.json";
  const std::map<std::pair<std::string, std::string>, ChosenRow> rows = choiceData(path);
  ASSERT_FALSE(rows.empty()) << path << " is missing or holds no choice";
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
      const std::string codeParameters = code.technique == Technique::Prefiltered ? samples::describe(code.prefiltered)
                                                                                    : samples::describe(code.epipolar);
      EXPECT_EQ(chosen.parameters, codeParameters);
      // The bench's incumbents (the configurations challengers must beat by a margin) name the same.
      EXPECT_EQ(samples::bench::profileTableConfigurations(lights).at(profile),
                chosen.technique + " " + chosen.parameters);
    }
  }
}

// The committed choice is the one tyndall-bench makes from the kept rows today
// (docs/data/tradeoffs-lavapipe-results.json, which TRADEOFFS.md was written from), so that neither
// the data nor the choice rule can change without the other being written again.
TEST(TradeoffsDocument, TheChoiceDataIsTheKeptRowsChoice) {
  const std::string docs(TYNDALL_DOCS_DIR);
  std::vector<samples::bench::Row> rows;
  samples::bench::ReportContext context;
  std::string error;
  ASSERT_TRUE(samples::bench::readResults(docs + "/data/tradeoffs-lavapipe-results.json", rows, context, error)) << error;
  const std::filesystem::path dir = tyndall::test::scratchPath("tradeoffs-choice");
  ASSERT_TRUE(samples::bench::writeReports(rows, context, dir.string(), error)) << error;
  std::ifstream written(dir / "choice.json");
  std::ifstream committed(docs + "/data/tradeoffs-lavapipe-choice.json");
  const nlohmann::json writtenJson = nlohmann::json::parse(written, nullptr, false);
  const nlohmann::json committedJson = nlohmann::json::parse(committed, nullptr, false);
  std::filesystem::remove_all(dir);
  ASSERT_TRUE(writtenJson.is_array());
  EXPECT_EQ(committedJson, writtenJson) << "write it again: FROM=docs/data/tradeoffs-lavapipe-results.json "
                                           "scripts/measure.sh tradeoffs";
}

}  // namespace
}  // namespace tyndall
