// tyndall-render's command line (DESIGN.md "The sample renderer"): outputs on success, a non-zero
// exit status with nothing written on bad input.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "test_support.h"

namespace tyndall::test {
namespace {

namespace fs = std::filesystem;

int run(std::vector<std::string> args) {
  args.insert(args.begin(), "tyndall-render");
  std::vector<const char*> argv;
  for (const std::string& a : args) argv.push_back(a.c_str());
  return samples::runTyndallRender(static_cast<int>(argv.size()), argv.data());
}

// Parses without rendering; a failure is reported with its reason.
bool parse(std::vector<const char*> args, samples::RenderOptions& options) {
  args.insert(args.begin(), "tyndall-render");
  bool help = false;
  std::string error;
  const bool ok = samples::parseCommandLine(static_cast<int>(args.size()), args.data(), options, help, error);
  EXPECT_TRUE(ok) << error;
  return ok;
}

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("tyndall-cli-" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(RenderCli, WritesEveryOutput) {
  const fs::path dir = scratch("ok");
  const std::string scene = std::string(TYNDALL_SCENES_DIR) + "/analytic-spheres.json";
  ASSERT_EQ(run({scene, "--profile", "reference", "--width", "40", "--height", "24", "--shadow-map-size", "512",
                 "--frames", "3", "--output", (dir / "a.png").string(), "--output-hdr", (dir / "a.exr").string(),
                 "--aov-scattering", (dir / "s.exr").string(), "--aov-transmittance", (dir / "t.exr").string(),
                 "--timings", (dir / "t.json").string(), "--validation"}),
            0);
  for (const char* file : {"a.png", "a.exr", "s.exr", "t.exr", "t.json"}) {
    EXPECT_TRUE(fs::exists(dir / file)) << file;
  }
  host::ImageRgba32f scattering;
  std::string error;
  ASSERT_TRUE(host::readExr((dir / "s.exr").string(), scattering, error)) << error;
  EXPECT_EQ(scattering.width, 40u);
  EXPECT_EQ(scattering.height, 24u);

  std::ifstream in(dir / "t.json");
  const nlohmann::json timings = nlohmann::json::parse(in);
  EXPECT_EQ(timings["framesRendered"], 3);
  EXPECT_EQ(timings["framesTimed"], 3);
  EXPECT_EQ(timings["technique"], "reference");
  EXPECT_GT(timings["passMilliseconds"]["reference_scattering"].get<double>(), 0.0);
  EXPECT_GT(timings["totalMilliseconds"].get<double>(), 0.0);
  // Which composite ran and the frame's command counts: the plugin decides them, the JSON reports them.
  ASSERT_TRUE(timings.contains("composite"));
  ASSERT_TRUE(timings["composite"].is_string());
  const std::string composite = timings["composite"].get<std::string>();
  EXPECT_TRUE(composite == "fragment" || composite == "compute") << composite;
  ASSERT_TRUE(timings.contains("dispatches"));
  EXPECT_TRUE(timings["dispatches"].is_number_unsigned());
  ASSERT_TRUE(timings.contains("barriers"));
  EXPECT_TRUE(timings["barriers"].is_number_unsigned());
  EXPECT_EQ(timings["scatteringResolution"], "full");
  EXPECT_EQ(timings["resolutionChange"], "none");
}

TEST(RenderCli, BadInputFailsAndWritesNothing) {
  const fs::path dir = scratch("bad");
  const std::string scene = std::string(TYNDALL_SCENES_DIR) + "/analytic-spheres.json";
  const std::string png = (dir / "x.png").string();
  const fs::path broken = dir / "broken.json";
  std::ofstream(broken) << "{ \"camera\": { \"position\": [0, 1, 5] ";
  const std::vector<std::vector<std::string>> cases = {
      {},
      {scene, "--width", "0"},
      {scene, "--height", "abc"},
      {scene, "--profile", "ultra"},
      {scene, "--technique", "magic"},
      {scene, "--shadow-map-size", "1000"},
      {scene, "--cascades", "0"},
      {scene, "--cascades", "5"},
      {scene, "--cascades", "two"},
      {scene, "--translucent-layers", "0"},
      {scene, "--translucent-layers", "9"},
      {scene, "--frames", "0"},
      {scene, "--profile", "auto", "--budget-ms", "0"},
      {scene, "--profile", "auto", "--budget-ms", "-2"},
      {scene, "--profile", "auto", "--budget-ms", "nan"},
      {scene, "--unknown-flag"},
      {scene, "--pipelines", "lazy"},
      {scene, "--pipelines"},
      {scene, "--output"},
      {(dir / "missing.json").string()},
      {broken.string()},
  };
  for (std::vector<std::string> args : cases) {
    args.push_back("--output");
    args.push_back(png);
    EXPECT_NE(run(args), 0);
    EXPECT_FALSE(fs::exists(png));
  }
}

// --pipelines picks when the context compiles (RenderOptions::pipelineCreation); at-create without it.
TEST(RenderCli, PipelinesOption) {
  samples::RenderOptions defaults, lazy, eager;
  ASSERT_TRUE(parse({"scene.json"}, defaults));
  EXPECT_EQ(defaults.pipelineCreation, PipelineCreation::AtCreate);
  ASSERT_TRUE(parse({"scene.json", "--pipelines", "on-first-use"}, lazy));
  EXPECT_EQ(lazy.pipelineCreation, PipelineCreation::OnFirstUse);
  ASSERT_TRUE(parse({"scene.json", "--pipelines", "on-first-use", "--pipelines", "at-create"}, eager));
  EXPECT_EQ(eager.pipelineCreation, PipelineCreation::AtCreate);
}

// --no-storage-back-buffer reaches the host's settings; without it the back buffer may take STORAGE.
TEST(RenderCli, NoStorageBackBufferOption) {
  samples::RenderOptions defaults, noStorage;
  ASSERT_TRUE(parse({"scene.json"}, defaults));
  EXPECT_TRUE(defaults.storageBackBuffer);
  EXPECT_TRUE(samples::renderSettingsFor(defaults, false).storageBackBuffer);
  ASSERT_TRUE(parse({"scene.json", "--no-storage-back-buffer"}, noStorage));
  EXPECT_FALSE(noStorage.storageBackBuffer);
  EXPECT_FALSE(samples::renderSettingsFor(noStorage, false).storageBackBuffer);
}

}  // namespace
}  // namespace tyndall::test
