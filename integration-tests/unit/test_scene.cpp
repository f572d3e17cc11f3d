// Scene files: loading, validation errors, rotation order and triangulation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "scratch_path.h"
#include "tyndall_host/scene.h"

namespace tyndall::host {
namespace {

const std::filesystem::path kScenesDir = TYNDALL_SCENES_DIR;

// A valid scene whose parts can be replaced one at a time.
struct SceneParts {
  std::string camera = R"({"position": [0, 1, 5], "target": [0, 1, 0], "up": [0, 1, 0],
                          "fovYDegrees": 60, "near": 0.1, "far": 100})";
  std::string lightKey = "light";  // "lights": `light` holds a list; empty: no light
  std::string light = R"({"type": "directional", "direction": [0, -2, 0], "color": [1, 1, 1], "intensity": 2})";
  std::string medium = R"({"scattering": [0.1, 0.1, 0.1], "absorption": [0, 0, 0],
                          "phase": {"type": "henyey-greenstein", "g": 0.5}})";
  std::string objects = R"([{"type": "plane", "point": [0, 0, 0], "normal": [0, 3, 0]}])";
  std::string extra = R"(, "shadowMap": {"size": 1024})";

  std::string text() const {
    const std::string lights = lightKey.empty() ? "" : R"(, ")" + lightKey + R"(": )" + light;
    return R"({"camera": )" + camera + lights + R"(, "medium": )" + medium +
           R"(, "objects": )" + objects + extra + "}";
  }
};

// A "lights" list of `count` directional lights, intensities 1, 2, …
std::string directionalLights(int count) {
  std::string list;
  for (int i = 0; i < count; ++i) {
    list += std::string(i == 0 ? "" : ", ") + R"({"type": "directional", "direction": [0, -1, 0], "intensity": )" +
            std::to_string(i + 1) + "}";
  }
  return "[" + list + "]";
}

Scene parseOrFail(const std::string& text) {
  SceneLoadResult result = parseScene(text, kScenesDir);
  EXPECT_TRUE(result.scene.has_value()) << result.error;
  return result.scene.value_or(Scene{});
}

void expectNear(const glm::dvec3& actual, const glm::dvec3& expected, double tolerance) {
  EXPECT_NEAR(actual.x, expected.x, tolerance);
  EXPECT_NEAR(actual.y, expected.y, tolerance);
  EXPECT_NEAR(actual.z, expected.z, tolerance);
}

void expectNear(const glm::dmat3& actual, const glm::dmat3& expected, double tolerance) {
  for (int column = 0; column < 3; ++column) expectNear(actual[column], expected[column], tolerance);
}

// ---- loading ----------------------------------------------------------------------------------

TEST(SceneLoading, EverySampleSceneLoadsAndTriangulates) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(kScenesDir)) {
    if (entry.path().extension() == ".json") files.push_back(entry.path());
  }
  ASSERT_GE(files.size(), 9u) << "the sample scenes are missing from " << kScenesDir;
  for (const std::filesystem::path& file : files) {
    SCOPED_TRACE(file.string());
    const SceneLoadResult result = loadScene(file);
    ASSERT_TRUE(result.scene.has_value()) << result.error;
    EXPECT_EQ(result.scene->sourcePath, file);
    for (const Object& object : result.scene->objects) {
      std::vector<TriangleMesh> meshes;
      std::string error;
      ASSERT_TRUE(triangulate(object, 100.0, result.scene->camera.position, meshes, error)) << error;
      ASSERT_EQ(meshes.size(), 1u);
      EXPECT_FALSE(meshes[0].indices.empty());
    }
  }
}

TEST(SceneLoading, SampleScenesHaveTheirDocumentedContent) {
  const auto load = [](const char* name) {
    SceneLoadResult result = loadScene(kScenesDir / name);
    EXPECT_TRUE(result.scene.has_value()) << name << ": " << result.error;
    return result.scene.value_or(Scene{});
  };
  for (const char* name : {"pillars.json", "fence.json", "forest.json", "window-room.json", "spot-lamp.json",
                           "analytic-spheres.json", "analytic-boxes.json", "analytic-mixed.json", "gltf-tetrahedron.json"}) {
    const Scene scene = load(name);
    EXPECT_EQ(scene.shadowMapSize, 2048u) << name;
    EXPECT_LE(scene.camera.farPlane, 200.0) << name;
    if (std::string_view(name).starts_with("analytic-")) {
      EXPECT_EQ(scene.light.type, LightType::Directional) << name;
      EXPECT_LE(scene.camera.farPlane, 60.0) << name;  // small and fast
    }
  }
  const Scene forest = load("forest.json");
  EXPECT_GE(forest.objects.size(), 2000u);
  const Scene fence = load("fence.json");
  EXPECT_GE(fence.objects.size(), 40u);
  const Scene spot = load("spot-lamp.json");
  EXPECT_EQ(spot.light.type, LightType::Spot);
  EXPECT_DOUBLE_EQ(spot.light.innerConeDegrees, 20.0);
  EXPECT_DOUBLE_EQ(spot.light.outerConeDegrees, 30.0);
  const Scene street = load("street-dusk.json");
  EXPECT_EQ(street.light.type, LightType::Directional);
  ASSERT_EQ(street.additionalLights.size(), 3u);
  for (const Light& lamp : street.additionalLights) {
    EXPECT_EQ(lamp.type, LightType::Spot);
    EXPECT_EQ(lamp.shadowMapSize, 1024u);
    EXPECT_LT(lamp.direction.y, -0.99);  // hanging over the street, pointing down
  }
  const Scene colonnade = load("colonnade.json");
  EXPECT_EQ(colonnade.light.type, LightType::Directional);
  EXPECT_EQ(colonnade.cascades, 4u);
  EXPECT_EQ(colonnade.shadowMapSize, 1024u);
  EXPECT_DOUBLE_EQ(colonnade.camera.farPlane, 400.0);
  EXPECT_DOUBLE_EQ(colonnade.camera.position.y, 1.7);  // eye height
  EXPECT_EQ(colonnade.objects.size(), 61u);  // the ground and two rows of 30 pillars
  for (const Object& object : colonnade.objects) {
    // What the CPU analytic reference computes: planes, boxes and spheres.
    EXPECT_NE(object.type, ObjectType::Gltf);
  }
  const Scene mixed = load("analytic-mixed.json");
  ASSERT_EQ(mixed.medium.size(), 2u);
  EXPECT_EQ(mixed.medium[0].phase, PhaseType::Rayleigh);
  EXPECT_EQ(mixed.medium[1].phase, PhaseType::CornetteShanks);
  EXPECT_DOUBLE_EQ(mixed.medium[1].g, 0.75);
  EXPECT_NE(mixed.medium[0].scattering.r, mixed.medium[0].scattering.b);
}

TEST(SceneLoading, ParsesValuesAndNormalisesDirections) {
  SceneParts parts;
  parts.objects = R"([{"type": "plane", "point": [0, 0, 0], "normal": [0, 3, 4]},
                      {"type": "box", "center": [1, 2, 3], "halfExtents": [0.5, 1, 2], "rotationDegrees": [10, 20, 30],
                       "albedo": [0.1, 0.2, 0.3]},
                      {"type": "sphere", "center": [-1, 2, -3], "radius": 1.5}])";
  const Scene scene = parseOrFail(parts.text());
  expectNear(scene.light.direction, {0.0, -1.0, 0.0}, 1e-15);
  EXPECT_DOUBLE_EQ(scene.light.intensity, 2.0);
  ASSERT_EQ(scene.medium.size(), 1u);
  EXPECT_EQ(scene.medium[0].phase, PhaseType::HenyeyGreenstein);
  EXPECT_DOUBLE_EQ(scene.medium[0].g, 0.5);
  EXPECT_EQ(scene.shadowMapSize, 1024u);
  ASSERT_EQ(scene.objects.size(), 3u);
  expectNear(scene.objects[0].normal, {0.0, 0.6, 0.8}, 1e-15);
  EXPECT_EQ(scene.objects[1].type, ObjectType::Box);
  expectNear(scene.objects[1].rotationDegrees, {10.0, 20.0, 30.0}, 0.0);
  expectNear(scene.objects[1].albedo, {0.1, 0.2, 0.3}, 0.0);
  expectNear(scene.objects[2].albedo, glm::dvec3(0.6), 0.0);  // the default
  EXPECT_DOUBLE_EQ(scene.objects[2].radius, 1.5);
  EXPECT_TRUE(scene.sourcePath.empty());
}

TEST(SceneLoading, OptionalPartsTakeTheirDefaults) {
  SceneParts parts;
  parts.camera = R"({"position": [0, 1, 5], "target": [0, 1, 0]})";
  parts.medium = R"({"scattering": [0.1, 0.2, 0.3]})";
  parts.objects = "[]";  // an empty scene is allowed
  parts.extra = "";
  const Scene scene = parseOrFail(parts.text());
  EXPECT_DOUBLE_EQ(scene.camera.fovYDegrees, 60.0);
  EXPECT_DOUBLE_EQ(scene.camera.nearPlane, 0.1);
  EXPECT_DOUBLE_EQ(scene.camera.farPlane, 200.0);
  expectNear(scene.camera.up, {0.0, 1.0, 0.0}, 0.0);
  ASSERT_EQ(scene.medium.size(), 1u);
  EXPECT_EQ(scene.medium[0].phase, PhaseType::Isotropic);
  expectNear(scene.medium[0].absorption, glm::dvec3(0.0), 0.0);
  EXPECT_TRUE(scene.objects.empty());
  EXPECT_EQ(scene.shadowMapSize, 2048u);
}

TEST(SceneLoading, SpotAndPointLights) {
  SceneParts parts;
  parts.light = R"({"type": "spot", "position": [1, 5, 2], "direction": [0, -5, 0], "color": [1, 0.5, 0.25],
                    "intensity": 40, "innerConeDegrees": 10, "outerConeDegrees": 15})";
  const Scene spot = parseOrFail(parts.text());
  EXPECT_EQ(spot.light.type, LightType::Spot);
  expectNear(spot.light.position, {1.0, 5.0, 2.0}, 0.0);
  expectNear(spot.light.direction, {0.0, -1.0, 0.0}, 1e-15);
  EXPECT_DOUBLE_EQ(spot.light.outerConeDegrees, 15.0);
  parts.light = R"({"type": "point", "position": [1, 5, 2], "intensity": 40})";
  const Scene point = parseOrFail(parts.text());
  EXPECT_EQ(point.light.type, LightType::Point);
  expectNear(point.light.color, glm::dvec3(1.0), 0.0);
}

TEST(SceneLoading, LightsListBecomesTheLightAndTheAdditionalLightsInOrder) {
  SceneParts parts;
  parts.lightKey = "lights";
  parts.light = R"([{"type": "directional", "direction": [0, -2, 0], "intensity": 2},
                    {"type": "spot", "position": [1, 5, 2], "direction": [0, -1, 0], "intensity": 40,
                     "innerConeDegrees": 10, "outerConeDegrees": 15},
                    {"type": "point", "position": [-3, 4, 1], "color": [1, 0.5, 0.25], "intensity": 7}])";
  const Scene scene = parseOrFail(parts.text());
  EXPECT_EQ(scene.light.type, LightType::Directional);
  expectNear(scene.light.direction, {0.0, -1.0, 0.0}, 1e-15);
  EXPECT_DOUBLE_EQ(scene.light.intensity, 2.0);
  ASSERT_EQ(scene.additionalLights.size(), 2u);
  EXPECT_EQ(scene.additionalLights[0].type, LightType::Spot);
  expectNear(scene.additionalLights[0].position, {1.0, 5.0, 2.0}, 0.0);
  EXPECT_DOUBLE_EQ(scene.additionalLights[0].intensity, 40.0);
  EXPECT_DOUBLE_EQ(scene.additionalLights[0].outerConeDegrees, 15.0);
  EXPECT_EQ(scene.additionalLights[1].type, LightType::Point);
  expectNear(scene.additionalLights[1].color, {1.0, 0.5, 0.25}, 0.0);
  EXPECT_DOUBLE_EQ(scene.additionalLights[1].intensity, 7.0);

  // A list of one is the single light; "light" has no additional lights.
  parts.light = directionalLights(1);
  EXPECT_TRUE(parseOrFail(parts.text()).additionalLights.empty());
  EXPECT_TRUE(parseOrFail(SceneParts{}.text()).additionalLights.empty());
  parts.light = directionalLights(8);
  const Scene eight = parseOrFail(parts.text());
  ASSERT_EQ(eight.additionalLights.size(), 7u);
  EXPECT_DOUBLE_EQ(eight.additionalLights[6].intensity, 8.0);
}

TEST(SceneLoading, PerLightShadowMapSizeOverridesTheScenes) {
  SceneParts parts;
  parts.lightKey = "lights";
  parts.light = R"([{"type": "directional", "direction": [0, -1, 0], "intensity": 1},
                    {"type": "spot", "position": [0, 5, 0], "direction": [0, -1, 0], "intensity": 1,
                     "shadowMap": {"size": 512}}])";
  const Scene scene = parseOrFail(parts.text());
  EXPECT_EQ(scene.shadowMapSize, 1024u);
  EXPECT_EQ(scene.light.shadowMapSize, 0u);  // the scene's
  ASSERT_EQ(scene.additionalLights.size(), 1u);
  EXPECT_EQ(scene.additionalLights[0].shadowMapSize, 512u);

  // The single "light" takes one too.
  parts = SceneParts{};
  parts.light = R"({"type": "directional", "direction": [0, -1, 0], "intensity": 1, "shadowMap": {"size": 4096}})";
  EXPECT_EQ(parseOrFail(parts.text()).light.shadowMapSize, 4096u);
}

TEST(SceneLoading, CascadesDefaultToOneMapAndTheSplitTo0_8) {
  const Scene scene = parseOrFail(SceneParts{}.text());  // "shadowMap": {"size": 1024}
  EXPECT_EQ(scene.cascades, 1u);
  EXPECT_DOUBLE_EQ(scene.cascadeSplit, 0.8);
  EXPECT_EQ(scene.light.cascades, 0u);  // the scene's
  EXPECT_FALSE(scene.light.cascadeSplit.has_value());

  SceneParts parts;
  parts.extra = "";
  EXPECT_EQ(parseOrFail(parts.text()).cascades, 1u);
}

TEST(SceneLoading, ParsesCascadesAndTheirSplit) {
  SceneParts parts;
  parts.extra = R"(, "shadowMap": {"size": 512, "cascades": 3, "cascadeSplit": 0.5})";
  const Scene scene = parseOrFail(parts.text());
  EXPECT_EQ(scene.shadowMapSize, 512u);
  EXPECT_EQ(scene.cascades, 3u);
  EXPECT_DOUBLE_EQ(scene.cascadeSplit, 0.5);

  // Every key of "shadowMap" is optional: the size keeps its default.
  parts.extra = R"(, "shadowMap": {"cascades": 4})";
  const Scene cascadesOnly = parseOrFail(parts.text());
  EXPECT_EQ(cascadesOnly.shadowMapSize, 2048u);
  EXPECT_EQ(cascadesOnly.cascades, 4u);
  EXPECT_DOUBLE_EQ(cascadesOnly.cascadeSplit, 0.8);

  // The ends of the ranges.
  parts.extra = R"(, "shadowMap": {"cascades": 1, "cascadeSplit": 0})";
  EXPECT_DOUBLE_EQ(parseOrFail(parts.text()).cascadeSplit, 0.0);
  parts.extra = R"(, "shadowMap": {"cascades": 4, "cascadeSplit": 1})";
  EXPECT_DOUBLE_EQ(parseOrFail(parts.text()).cascadeSplit, 1.0);
}

TEST(SceneLoading, PerLightCascadesOverrideTheScenes) {
  SceneParts parts;
  parts.lightKey = "lights";
  parts.light = R"([{"type": "directional", "direction": [0, -1, 0], "intensity": 1,
                     "shadowMap": {"cascades": 4, "cascadeSplit": 0.25}},
                    {"type": "directional", "direction": [1, -1, 0], "intensity": 1},
                    {"type": "directional", "direction": [0, -1, 1], "intensity": 1, "shadowMap": {"size": 256}},
                    {"type": "spot", "position": [0, 5, 0], "direction": [0, -1, 0], "intensity": 1,
                     "shadowMap": {"cascades": 1}}])";
  parts.extra = R"(, "shadowMap": {"size": 1024, "cascades": 2, "cascadeSplit": 0.6})";
  const Scene scene = parseOrFail(parts.text());
  EXPECT_EQ(scene.cascades, 2u);
  EXPECT_DOUBLE_EQ(scene.cascadeSplit, 0.6);
  EXPECT_EQ(scene.light.cascades, 4u);
  ASSERT_TRUE(scene.light.cascadeSplit.has_value());
  EXPECT_DOUBLE_EQ(*scene.light.cascadeSplit, 0.25);
  EXPECT_EQ(scene.light.shadowMapSize, 0u);  // the scene's size, its own cascades
  ASSERT_EQ(scene.additionalLights.size(), 3u);
  EXPECT_EQ(scene.additionalLights[0].cascades, 0u);  // the scene's
  EXPECT_FALSE(scene.additionalLights[0].cascadeSplit.has_value());
  EXPECT_EQ(scene.additionalLights[1].shadowMapSize, 256u);
  EXPECT_EQ(scene.additionalLights[1].cascades, 0u);  // a size alone keeps the scene's cascades
  EXPECT_EQ(scene.additionalLights[2].cascades, 1u);  // one map, said explicitly, is fine for a spot
}

TEST(SceneLoading, RelativeGltfPathsResolveAgainstTheSceneFolder) {
  const SceneLoadResult result = loadScene(kScenesDir / "gltf-tetrahedron.json");
  ASSERT_TRUE(result.scene.has_value()) << result.error;
  const auto gltf = std::find_if(result.scene->objects.begin(), result.scene->objects.end(),
                                 [](const Object& o) { return o.type == ObjectType::Gltf; });
  ASSERT_NE(gltf, result.scene->objects.end());
  EXPECT_EQ(gltf->path, (kScenesDir / "assets" / "tetrahedron.gltf").lexically_normal());
  EXPECT_DOUBLE_EQ(gltf->scale, 1.5);
}

TEST(SceneLoading, FileErrorsNameTheFile) {
  const std::filesystem::path missing = kScenesDir / "no-such-scene.json";
  const SceneLoadResult result = loadScene(missing);
  EXPECT_FALSE(result.scene.has_value());
  EXPECT_NE(result.error.find(missing.string()), std::string::npos) << result.error;

  const std::filesystem::path bad = tyndall::test::scratchPath("bad-scene.json");
  SceneParts parts;
  parts.objects = R"([{"type": "sphere", "center": [0, 0, 0], "radius": -1}])";
  std::ofstream(bad) << parts.text();
  const SceneLoadResult badResult = loadScene(bad);
  std::filesystem::remove(bad);
  EXPECT_FALSE(badResult.scene.has_value());
  EXPECT_EQ(badResult.error, bad.string() + ": objects[0].radius must be > 0");
}

// ---- validation errors ------------------------------------------------------------------------

struct BadScene {
  const char* name;
  SceneParts parts;
  const char* expectedError;  // a substring of the error
};

SceneParts with(std::string SceneParts::*part, std::string value) {
  SceneParts parts;
  parts.*part = std::move(value);
  return parts;
}

SceneParts withLights(std::string list) {
  SceneParts parts = with(&SceneParts::light, std::move(list));
  parts.lightKey = "lights";
  return parts;
}

std::vector<BadScene> badScenes() {
  using P = SceneParts;
  const std::string box = R"({"type": "box", "center": [0, 0, 0], "halfExtents": [1, 1, 1]})";
  return {
      {"RadiusZero", with(&P::objects, "[" + box + "," + box + "," + box + R"(, {"type": "sphere", "center": [0, 0, 0], "radius": 0}])"),
       "objects[3].radius must be > 0"},
      {"UnknownObjectType", with(&P::objects, R"([{"type": "cone", "center": [0, 0, 0]}])"),
       "objects[0].type is an unknown object type 'cone'"},
      {"UnknownObjectKey", with(&P::objects, R"([{"type": "box", "center": [0, 0, 0], "halfExtent": [1, 1, 1]}])"),
       "objects[0].halfExtent is an unknown key"},
      {"MissingKey", with(&P::objects, R"([{"type": "box", "center": [0, 0, 0]}])"), "objects[0].halfExtents is missing"},
      {"NegativeHalfExtent", with(&P::objects, R"([{"type": "box", "center": [0, 0, 0], "halfExtents": [1, 1, -1]}])"),
       "objects[0].halfExtents[2] must be > 0"},
      {"ZeroNormal", with(&P::objects, R"([{"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 0]}])"),
       "objects[0].normal must have a non-zero length"},
      {"AlbedoAboveOne", with(&P::objects, R"([{"type": "sphere", "center": [0, 0, 0], "radius": 1, "albedo": [1.5, 0, 0]}])"),
       "objects[0].albedo[0] must be in [0, 1]"},
      {"StringRadius", with(&P::objects, R"([{"type": "sphere", "center": [0, 0, 0], "radius": "1"}])"),
       "objects[0].radius must be a number"},
      {"MissingGltfFile", with(&P::objects, R"([{"type": "gltf", "path": "assets/no-such-mesh.gltf"}])"),
       "objects[0].path names no readable file"},
      {"GltfScaleZero", with(&P::objects, R"([{"type": "gltf", "path": "assets/tetrahedron.gltf", "scale": 0}])"),
       "objects[0].scale must be > 0"},
      {"ObjectsNotArray", with(&P::objects, "{}"), "objects must be an array"},
      {"NegativeScattering", with(&P::medium, R"({"scattering": [0.1, -0.1, 0.1]})"), "medium.scattering[1] must be >= 0"},
      {"NegativeAbsorptionInComponent",
       with(&P::medium, R"({"components": [{"scattering": [0.1, 0.1, 0.1]}, {"scattering": [0, 0, 0], "absorption": [-1, 0, 0]}]})"),
       "medium.components[1].absorption[0] must be >= 0"},
      {"NoComponents", with(&P::medium, R"({"components": []})"), "medium.components must hold 1 to 4 components"},
      {"FiveComponents",
       with(&P::medium, R"({"components": [{"scattering": [0, 0, 0]}, {"scattering": [0, 0, 0]}, {"scattering": [0, 0, 0]},
                                             {"scattering": [0, 0, 0]}, {"scattering": [0, 0, 0]}]})"),
       "medium.components must hold 1 to 4 components"},
      {"GEqualsOne", with(&P::medium, R"({"scattering": [0.1, 0.1, 0.1], "phase": {"type": "henyey-greenstein", "g": 1}})"),
       "medium.phase.g must be in (-1, 1)"},
      {"GBelowMinusOne", with(&P::medium, R"({"scattering": [0.1, 0.1, 0.1], "phase": {"type": "cornette-shanks", "g": -1.5}})"),
       "medium.phase.g must be in (-1, 1)"},
      {"MissingG", with(&P::medium, R"({"scattering": [0.1, 0.1, 0.1], "phase": {"type": "henyey-greenstein"}})"),
       "medium.phase.g is missing"},
      {"UnknownPhase", with(&P::medium, R"({"scattering": [0.1, 0.1, 0.1], "phase": {"type": "mie"}})"),
       "medium.phase.type is an unknown phase type 'mie'"},
      {"NearZero", with(&P::camera, R"({"position": [0, 1, 5], "target": [0, 1, 0], "near": 0})"), "camera.near must be > 0"},
      {"NearNegative", with(&P::camera, R"({"position": [0, 1, 5], "target": [0, 1, 0], "near": -1})"), "camera.near must be > 0"},
      {"FarBelowNear", with(&P::camera, R"({"position": [0, 1, 5], "target": [0, 1, 0], "near": 1, "far": 1})"),
       "camera.far must be > camera.near"},
      {"FovZero", with(&P::camera, R"({"position": [0, 1, 5], "target": [0, 1, 0], "fovYDegrees": 0})"),
       "camera.fovYDegrees must be in (0, 180)"},
      {"Fov180", with(&P::camera, R"({"position": [0, 1, 5], "target": [0, 1, 0], "fovYDegrees": 180})"),
       "camera.fovYDegrees must be in (0, 180)"},
      {"TargetAtPosition", with(&P::camera, R"({"position": [0, 1, 5], "target": [0, 1, 5]})"),
       "camera.target must differ from camera.position"},
      {"UpAlongView", with(&P::camera, R"({"position": [0, 1, 5], "target": [0, 1, 0], "up": [0, 0, 2]})"),
       "camera.up must not be parallel to the view direction"},
      {"ShortVector", with(&P::camera, R"({"position": [0, 1], "target": [0, 1, 0]})"),
       "camera.position must be an array of 3 numbers"},
      {"ZeroLightDirection", with(&P::light, R"({"type": "directional", "direction": [0, 0, 0], "intensity": 1})"),
       "light.direction must have a non-zero length"},
      {"NegativeIntensity", with(&P::light, R"({"type": "directional", "direction": [0, -1, 0], "intensity": -1})"),
       "light.intensity must be >= 0"},
      {"UnknownLightType", with(&P::light, R"({"type": "area", "direction": [0, -1, 0], "intensity": 1})"),
       "light.type is an unknown light type 'area'"},
      {"ConeOnDirectional", with(&P::light, R"({"type": "directional", "direction": [0, -1, 0], "intensity": 1, "outerConeDegrees": 5})"),
       "light.outerConeDegrees is an unknown key"},
      {"InnerAboveOuter",
       with(&P::light, R"({"type": "spot", "position": [0, 5, 0], "direction": [0, -1, 0], "intensity": 1,
                           "innerConeDegrees": 30, "outerConeDegrees": 20})"),
       "light cone angles must satisfy 0 <= innerConeDegrees <= outerConeDegrees <= 80"},
      {"OuterAbove80",
       with(&P::light, R"({"type": "spot", "position": [0, 5, 0], "direction": [0, -1, 0], "intensity": 1,
                           "innerConeDegrees": 30, "outerConeDegrees": 85})"),
       "light cone angles must satisfy"},
      {"NegativeInner",
       with(&P::light, R"({"type": "spot", "position": [0, 5, 0], "direction": [0, -1, 0], "intensity": 1,
                           "innerConeDegrees": -1, "outerConeDegrees": 20})"),
       "light cone angles must satisfy"},
      {"SpotWithoutDirection", with(&P::light, R"({"type": "spot", "position": [0, 5, 0], "intensity": 1})"),
       "light.direction is missing"},
      {"ShadowMapNotPowerOfTwo", with(&P::extra, R"(, "shadowMap": {"size": 1000})"),
       "shadowMap.size must be a power of two in [16, 16384]"},
      {"ShadowMapTooSmall", with(&P::extra, R"(, "shadowMap": {"size": 8})"), "shadowMap.size must be a power of two in [16, 16384]"},
      {"ShadowMapTooLarge", with(&P::extra, R"(, "shadowMap": {"size": 32768})"), "shadowMap.size must be a power of two in [16, 16384]"},
      {"ShadowMapFraction", with(&P::extra, R"(, "shadowMap": {"size": 2048.5})"), "shadowMap.size must be an integer"},
      {"UnknownTopLevelKey", with(&P::extra, R"(, "lamps": [])"), "lamps is an unknown key"},
      {"LightAndLights", with(&P::extra, R"(, "lights": )" + directionalLights(2)),
       R"(a scene has "light" or "lights", not both)"},
      {"NoLightAtAll", with(&P::lightKey, ""), "light is missing"},
      {"LightsEmpty", withLights("[]"), "lights must hold 1 to 8 lights"},
      {"NineLights", withLights(directionalLights(9)), "lights must hold 1 to 8 lights"},
      {"LightsNotArray", withLights(R"({"type": "directional", "direction": [0, -1, 0], "intensity": 1})"),
       "lights must be an array"},
      {"ThirdLightNegativeIntensity",
       withLights(R"([{"type": "directional", "direction": [0, -1, 0], "intensity": 1},
                      {"type": "point", "position": [0, 5, 0], "intensity": 1},
                      {"type": "spot", "position": [0, 5, 0], "direction": [0, -1, 0], "intensity": -3}])"),
       "lights[2].intensity must be >= 0"},
      {"ThirdLightUnknownKey",
       withLights(R"([{"type": "directional", "direction": [0, -1, 0], "intensity": 1},
                      {"type": "point", "position": [0, 5, 0], "intensity": 1},
                      {"type": "point", "position": [0, 5, 0], "intensity": 1, "radius": 2}])"),
       "lights[2].radius is an unknown key"},
      {"ThirdLightShadowMapSize",
       withLights(R"([{"type": "directional", "direction": [0, -1, 0], "intensity": 1},
                      {"type": "point", "position": [0, 5, 0], "intensity": 1},
                      {"type": "point", "position": [0, 5, 0], "intensity": 1, "shadowMap": {"size": 1000}}])"),
       "lights[2].shadowMap.size must be a power of two in [16, 16384]"},
      {"LightShadowMapUnknownKey",
       with(&P::light, R"({"type": "directional", "direction": [0, -1, 0], "intensity": 1, "shadowMap": {"sizes": 64}})"),
       "light.shadowMap.sizes is an unknown key"},
      {"NaNLiteral", with(&P::extra, R"(, "shadowMap": {"size": NaN})"), "invalid JSON"},
      {"ZeroCascades", with(&P::extra, R"(, "shadowMap": {"cascades": 0})"), "shadowMap.cascades must be an integer in [1, 4]"},
      {"FiveCascades", with(&P::extra, R"(, "shadowMap": {"size": 1024, "cascades": 5})"),
       "shadowMap.cascades must be an integer in [1, 4]"},
      {"FractionalCascades", with(&P::extra, R"(, "shadowMap": {"cascades": 2.5})"), "shadowMap.cascades must be an integer"},
      {"CascadeSplitAboveOne", with(&P::extra, R"(, "shadowMap": {"cascades": 2, "cascadeSplit": 1.5})"),
       "shadowMap.cascadeSplit must be in [0, 1]"},
      {"CascadeSplitNegative", with(&P::extra, R"(, "shadowMap": {"cascadeSplit": -0.1})"),
       "shadowMap.cascadeSplit must be in [0, 1]"},
      {"CascadeSplitString", with(&P::extra, R"(, "shadowMap": {"cascadeSplit": "log"})"),
       "shadowMap.cascadeSplit must be a number"},
      {"CascadesOnSpotLight",
       with(&P::light, R"({"type": "spot", "position": [0, 5, 0], "direction": [0, -1, 0], "intensity": 1,
                           "shadowMap": {"cascades": 2}})"),
       "light.shadowMap.cascades must be 1 for a spot light"},
      {"CascadesOnPointLight",
       withLights(R"([{"type": "directional", "direction": [0, -1, 0], "intensity": 1, "shadowMap": {"cascades": 4}},
                      {"type": "point", "position": [0, 5, 0], "intensity": 1, "shadowMap": {"cascades": 3}}])"),
       "lights[1].shadowMap.cascades must be 1 for a point light"},
      {"CascadeSplitOnSpotLight",
       with(&P::light, R"({"type": "spot", "position": [0, 5, 0], "direction": [0, -1, 0], "intensity": 1,
                           "shadowMap": {"cascadeSplit": 0.5}})"),
       "light.shadowMap.cascadeSplit is for directional lights, not a spot light"},
      {"LightFiveCascades",
       with(&P::light, R"({"type": "directional", "direction": [0, -1, 0], "intensity": 1, "shadowMap": {"cascades": 5}})"),
       "light.shadowMap.cascades must be an integer in [1, 4]"},
      {"LightShadowMapUnknownCascadeKey",
       with(&P::light, R"({"type": "directional", "direction": [0, -1, 0], "intensity": 1, "shadowMap": {"splits": 4}})"),
       "light.shadowMap.splits is an unknown key (expected one of: size, cascades, cascadeSplit)"},
      {"OverflowingNumber", with(&P::objects, R"([{"type": "sphere", "center": [0, 0, 0], "radius": 1e999}])"), "invalid JSON"},
  };
}

class SceneValidation : public testing::TestWithParam<BadScene> {};

TEST_P(SceneValidation, RejectsWithTheJsonPath) {
  const BadScene& bad = GetParam();
  const SceneLoadResult result = parseScene(bad.parts.text(), kScenesDir);
  EXPECT_FALSE(result.scene.has_value());
  EXPECT_NE(result.error.find(bad.expectedError), std::string::npos)
      << "error: " << result.error << "\nexpected: " << bad.expectedError;
}

INSTANTIATE_TEST_SUITE_P(BadInputs, SceneValidation, testing::ValuesIn(badScenes()),
                         [](const testing::TestParamInfo<BadScene>& param) { return std::string(param.param.name); });

TEST(SceneValidation, TheBaseSceneOfTheBadInputsIsValid) {
  // Guards the table above: every failure must come from the one part it replaces.
  parseOrFail(SceneParts{}.text());
}

TEST(SceneValidation, MissingSectionIsNamed) {
  const SceneLoadResult result = parseScene(R"({"light": {}, "medium": {}, "objects": []})", kScenesDir);
  EXPECT_FALSE(result.scene.has_value());
  EXPECT_EQ(result.error, "camera is missing");
}

// ---- rotation order ---------------------------------------------------------------------------

// Explicit right-handed rotation matrices, written row by row (m[column][row] in glm).
glm::dmat3 rotationX(double degrees) {
  const double c = std::cos(glm::radians(degrees)), s = std::sin(glm::radians(degrees));
  glm::dmat3 m(1.0);
  m[1][1] = c; m[2][1] = -s;
  m[1][2] = s; m[2][2] = c;
  return m;
}

glm::dmat3 rotationY(double degrees) {
  const double c = std::cos(glm::radians(degrees)), s = std::sin(glm::radians(degrees));
  glm::dmat3 m(1.0);
  m[0][0] = c;  m[2][0] = s;
  m[0][2] = -s; m[2][2] = c;
  return m;
}

glm::dmat3 rotationZ(double degrees) {
  const double c = std::cos(glm::radians(degrees)), s = std::sin(glm::radians(degrees));
  glm::dmat3 m(1.0);
  m[0][0] = c; m[1][0] = -s;
  m[0][1] = s; m[1][1] = c;
  return m;
}

TEST(Rotation, QuarterTurnsAboutEachAxis) {
  const glm::dvec3 x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
  expectNear(rotationFromDegrees({90, 0, 0}) * y, z, 1e-15);   // right-handed about +x: y → z
  expectNear(rotationFromDegrees({0, 90, 0}) * z, x, 1e-15);   // about +y: z → x
  expectNear(rotationFromDegrees({0, 0, 90}) * x, y, 1e-15);   // about +z: x → y
  // X first, then Y: x stays on x, then turns to −z; y turns to z, then to x.
  expectNear(rotationFromDegrees({90, 90, 0}) * x, -z, 1e-15);
  expectNear(rotationFromDegrees({90, 90, 0}) * y, x, 1e-15);
}

TEST(Rotation, ComposesAsRzRyRx) {
  const glm::dvec3 angles[] = {{10, 20, 30}, {-75, 130, 45}, {200, -33, 91}, {0, 0, 0}};
  for (const glm::dvec3& a : angles) {
    SCOPED_TRACE(testing::Message() << a.x << ", " << a.y << ", " << a.z);
    const glm::dmat3 expected = rotationZ(a.z) * rotationY(a.y) * rotationX(a.x);
    expectNear(rotationFromDegrees(a), expected, 1e-14);
  }
  // The order matters: the reverse composition differs for a generic rotation.
  const glm::dmat3 reversed = rotationX(10) * rotationY(20) * rotationZ(30);
  EXPECT_GT(glm::length(rotationFromDegrees({10, 20, 30})[0] - reversed[0]), 0.05);
}

// ---- triangulation ----------------------------------------------------------------------------

TriangleMesh triangulateOne(const Object& object, double planeHalfSize = 10.0, glm::dvec3 planeCentre = glm::dvec3(0.0)) {
  std::vector<TriangleMesh> meshes;
  std::string error;
  EXPECT_TRUE(triangulate(object, planeHalfSize, planeCentre, meshes, error)) << error;
  EXPECT_EQ(meshes.size(), 1u);
  return meshes.empty() ? TriangleMesh{} : meshes.front();
}

struct Triangle {
  glm::dvec3 p[3];
  glm::dvec3 n[3];
  glm::dvec3 geometricNormal() const { return glm::normalize(glm::cross(p[1] - p[0], p[2] - p[0])); }
  glm::dvec3 centroid() const { return (p[0] + p[1] + p[2]) / 3.0; }
  double area() const { return 0.5 * glm::length(glm::cross(p[1] - p[0], p[2] - p[0])); }
};

std::vector<Triangle> triangles(const TriangleMesh& mesh) {
  EXPECT_EQ(mesh.indices.size() % 3, 0u);
  EXPECT_EQ(mesh.positions.size(), mesh.normals.size());
  std::vector<Triangle> result;
  for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
    Triangle triangle;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t index = mesh.indices[i + static_cast<std::size_t>(k)];
      triangle.p[k] = glm::dvec3(mesh.positions.at(index));
      triangle.n[k] = glm::dvec3(mesh.normals.at(index));
    }
    result.push_back(triangle);
  }
  return result;
}

TEST(Triangulation, PlaneIsASquareCentredOnTheProjectedCentre) {
  Object plane;
  plane.type = ObjectType::Plane;
  plane.point = {1, 2, 3};
  plane.normal = glm::normalize(glm::dvec3(1, 2, -1));
  const glm::dvec3 requestedCentre(10, -4, 7);
  const double halfSize = 25.0;
  const TriangleMesh mesh = triangulateOne(plane, halfSize, requestedCentre);
  const std::vector<Triangle> tris = triangles(mesh);
  ASSERT_EQ(tris.size(), 2u);
  const glm::dvec3 projected = requestedCentre - glm::dot(requestedCentre - plane.point, plane.normal) * plane.normal;
  glm::dvec3 vertexMean(0.0);
  for (const glm::vec3& p : mesh.positions) vertexMean += glm::dvec3(p) / static_cast<double>(mesh.positions.size());
  expectNear(vertexMean, projected, 1e-4);
  double area = 0.0;
  for (const Triangle& t : tris) {
    expectNear(t.geometricNormal(), plane.normal, 1e-6);  // counter-clockwise seen from the normal side
    for (int k = 0; k < 3; ++k) {
      expectNear(t.n[k], plane.normal, 1e-6);
      EXPECT_NEAR(glm::dot(t.p[k] - plane.point, plane.normal), 0.0, 1e-4);
      EXPECT_NEAR(glm::length(t.p[k] - projected), halfSize * std::numbers::sqrt2, 1e-4);
    }
    area += t.area();
  }
  EXPECT_NEAR(area, 4.0 * halfSize * halfSize, 1e-2);
}

TEST(Triangulation, BoxHasTwelveOutwardTriangles) {
  Object box;
  box.type = ObjectType::Box;
  box.center = {1, -2, 3};
  box.halfExtents = {0.5, 1.0, 2.0};
  box.rotationDegrees = {25, -40, 70};
  box.albedo = {0.1, 0.2, 0.3};
  const TriangleMesh mesh = triangulateOne(box);
  const std::vector<Triangle> tris = triangles(mesh);
  ASSERT_EQ(tris.size(), 12u);
  const glm::dmat3 rotation = rotationFromDegrees(box.rotationDegrees);
  double area = 0.0;
  for (const Triangle& t : tris) {
    const glm::dvec3 n = t.geometricNormal();
    EXPECT_GT(glm::dot(t.centroid() - box.center, n), 0.0);  // outward winding
    for (int k = 0; k < 3; ++k) {
      expectNear(t.n[k], n, 1e-6);  // flat shading: the stored normal is the face's
      // Every vertex is a corner: ±h in each local axis.
      const glm::dvec3 local = glm::transpose(rotation) * (t.p[k] - box.center);
      for (int axis = 0; axis < 3; ++axis) EXPECT_NEAR(std::abs(local[axis]), box.halfExtents[axis], 1e-5);
    }
    area += t.area();
  }
  const glm::dvec3 h = box.halfExtents;
  EXPECT_NEAR(area, 8.0 * (h.x * h.y + h.y * h.z + h.z * h.x), 1e-4);
  EXPECT_EQ(mesh.albedo, glm::vec3(0.1f, 0.2f, 0.3f));
}

TEST(Triangulation, SphereIsOnTheSphereWithinTheSilhouetteBudget) {
  Object sphere;
  sphere.type = ObjectType::Sphere;
  sphere.center = {3, 1, -2};
  sphere.radius = 2.5;
  const TriangleMesh mesh = triangulateOne(sphere);
  const std::vector<Triangle> tris = triangles(mesh);
  ASSERT_GT(tris.size(), 1000u);
  for (const glm::vec3& p : mesh.positions) {
    EXPECT_NEAR(glm::length(glm::dvec3(p) - sphere.center), sphere.radius, 1e-6 * sphere.radius);
  }
  // The mesh is convex, so it contains the ball whose radius is the smallest distance from the
  // centre to a face plane: the silhouette, from any view, lies between that radius and r.
  double innerRadius = sphere.radius;
  double area = 0.0;
  for (const Triangle& t : tris) {
    const glm::dvec3 n = t.geometricNormal();
    const double planeDistance = glm::dot(t.p[0] - sphere.center, n);
    EXPECT_GT(planeDistance, 0.0);  // outward winding
    innerRadius = std::min(innerRadius, planeDistance);
    for (int k = 0; k < 3; ++k) expectNear(t.n[k], glm::normalize(t.p[k] - sphere.center), 1e-5);
    area += t.area();
  }
  EXPECT_GT(innerRadius, (1.0 - 1e-3) * sphere.radius);
  const double sphereArea = 4.0 * std::numbers::pi * sphere.radius * sphere.radius;
  EXPECT_NEAR(area / sphereArea, 1.0, 2e-3);  // closed: no missing faces
}

TEST(Triangulation, GltfTetrahedronKeepsItsNodeTransformThenTheObjectPlacement) {
  const SceneLoadResult result = loadScene(kScenesDir / "gltf-tetrahedron.json");
  ASSERT_TRUE(result.scene.has_value()) << result.error;
  const Object& object = result.scene->objects.at(1);
  ASSERT_EQ(object.type, ObjectType::Gltf);
  const TriangleMesh mesh = triangulateOne(object);
  const std::vector<Triangle> tris = triangles(mesh);
  ASSERT_EQ(tris.size(), 4u);

  // The file's vertices, its node translation (0, 1, 0), then scale, rotation, translation.
  const glm::dvec3 fileVertices[] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
  const glm::dmat3 rotation = rotationFromDegrees(object.rotationDegrees);
  std::vector<glm::dvec3> expected;
  for (const glm::dvec3& v : fileVertices) {
    expected.push_back(object.translation + rotation * (object.scale * (v + glm::dvec3(0, 1, 0))));
  }
  glm::dvec3 centre(0.0);
  for (const glm::dvec3& e : expected) centre += e / 4.0;
  for (const Triangle& t : tris) {
    const glm::dvec3 n = t.geometricNormal();
    EXPECT_GT(glm::dot(t.centroid() - centre, n), 0.0);  // outward
    for (int k = 0; k < 3; ++k) {
      expectNear(t.n[k], n, 1e-5);  // the file has no normals: flat ones are generated
      double nearest = 1e9;
      for (const glm::dvec3& e : expected) nearest = std::min(nearest, glm::length(t.p[k] - e));
      EXPECT_LT(nearest, 1e-5);
    }
  }
  EXPECT_EQ(mesh.albedo, glm::vec3(glm::dvec3(0.7, 0.6, 0.3)));
}

// The pergola (scripts/generate-gltf-assets.py) is laid out as exporters write real assets: a
// z-up centimetre model under a root that turns it y-up and scales it to metres, instanced meshes,
// a node placed by a matrix, a mirrored group, u8/u16/u32 and no indices, an interleaved view,
// two accessors in one view, a triangle strip, a mesh of two primitives, and camera and empty
// nodes. A misread stride, offset, index size, strip or mirror shows as a triangle whose winding
// disagrees with the file's normals, a wrong count or a wrong extent.
TEST(Triangulation, GltfPergolaReadsEveryLayoutAndTransformAsWritten) {
  const SceneLoadResult result = loadScene(kScenesDir / "gltf-pergola.json");
  ASSERT_TRUE(result.scene.has_value()) << result.error;
  const Object& object = result.scene->objects.at(1);
  ASSERT_EQ(object.type, ObjectType::Gltf);
  const std::vector<Triangle> tris = triangles(triangulateOne(object));
  // Boxes of 12 triangles: 8 posts, 2 beams, 25 slats, 6 strip bars, the planter's walls and
  // soil; 300 two-sided leaf cards of 4.
  EXPECT_EQ(tris.size(), (8u + 2u + 25u + 6u + 2u) * 12u + 300u * 4u);
  double lowest = 1e9, highest = -1e9;
  std::size_t disagreeing = 0;
  for (const Triangle& t : tris) {
    const glm::dvec3 n = t.geometricNormal();
    for (int k = 0; k < 3; ++k) {
      if (glm::dot(t.n[k], n) < 0.999) ++disagreeing;
      lowest = std::min(lowest, t.p[k].y);
      highest = std::max(highest, t.p[k].y);
    }
  }
  EXPECT_EQ(disagreeing, 0u) << "vertex normals against the triangles' winding";
  // Posts stand on the ground (asset z = 0); leaves reach 3 m (asset z ≤ 300 cm plus a card's
  // tilt: 4 cm · sin 0.5).
  EXPECT_NEAR(lowest, 0.0, 1e-5);
  EXPECT_GT(highest, 2.95);
  EXPECT_LT(highest, 3.02);
  // The slats span the asset's y ∈ [−180, 180] cm, which the root turns into world z before the
  // scene's 15° turn about y: the roof's horizontal extent is at most the 6.4 m × 3.6 m rectangle's
  // half-diagonal from the centre.
  for (const Triangle& t : tris) {
    for (int k = 0; k < 3; ++k) EXPECT_LT(glm::length(glm::dvec2(t.p[k].x, t.p[k].z)), std::hypot(3.2, 1.8) + 1e-4);
  }
}

std::string base64(const std::vector<unsigned char>& bytes) {
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string text;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t available = std::min<std::size_t>(3, bytes.size() - i);
    std::uint32_t chunk = 0;
    for (std::size_t k = 0; k < 3; ++k) chunk = (chunk << 8) | (k < available ? bytes[i + k] : 0u);
    for (std::size_t k = 0; k < 4; ++k) {
      text += k <= available ? kAlphabet[(chunk >> (18 - 6 * k)) & 63u] : '=';
    }
  }
  return text;
}

std::vector<unsigned char> bytesOf(const std::vector<float>& floats, const std::vector<std::uint16_t>& shorts = {}) {
  std::vector<unsigned char> bytes(floats.size() * sizeof(float) + shorts.size() * sizeof(std::uint16_t));
  std::memcpy(bytes.data(), floats.data(), floats.size() * sizeof(float));
  if (!shorts.empty()) {
    std::memcpy(bytes.data() + floats.size() * sizeof(float), shorts.data(), shorts.size() * sizeof(std::uint16_t));
  }
  return bytes;
}

// Writes a glTF file with `bytes` as its one embedded buffer, triangulates it as an object placed
// by `translation`, and removes the file again.
TriangleMesh triangulateGltf(const std::string& nodesScenesMeshes, const std::string& viewsAndAccessors,
                             const std::vector<unsigned char>& bytes, const glm::dvec3& translation = glm::dvec3(0.0)) {
  const std::string gltf = R"({"asset": {"version": "2.0"}, )" + nodesScenesMeshes + R"(,
    "buffers": [{"byteLength": )" + std::to_string(bytes.size()) +
                           R"(, "uri": "data:application/octet-stream;base64,)" + base64(bytes) + R"("}], )" +
                           viewsAndAccessors + "}";
  const std::filesystem::path file = tyndall::test::scratchPath("mesh.gltf");
  std::ofstream(file) << gltf;
  Object object;
  object.type = ObjectType::Gltf;
  object.path = file;
  object.translation = translation;
  const TriangleMesh mesh = triangulateOne(object);
  std::filesystem::remove(file);
  return mesh;
}

TEST(Triangulation, GltfNodeHierarchyAppliesMatrixAndTrsRecursively) {
  // One triangle with a normal, under a child node (rotation 90° about z, translation (0, 0, 1))
  // whose parent has a matrix (uniform scale 2, translation (1, 2, 3)).
  const std::vector<unsigned char> bytes = bytesOf({0, 0, 0, 1, 0, 0, 0, 1, 0,    // positions
                                                    0, 0, 1, 0, 0, 1, 0, 0, 1});  // normals
  const std::string s = std::to_string(std::sqrt(0.5));
  const TriangleMesh mesh = triangulateGltf(
      R"("scene": 0, "scenes": [{"nodes": [0]}],
         "nodes": [{"matrix": [2,0,0,0, 0,2,0,0, 0,0,2,0, 1,2,3,1], "children": [1]},
                   {"mesh": 0, "rotation": [0, 0, )" + s + ", " + s + R"(], "translation": [0, 0, 1]}],
         "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}}]}])",
      R"("bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 36}],
         "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
                       {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"}])",
      bytes, {10, 0, 0});
  const std::vector<Triangle> tris = triangles(mesh);
  ASSERT_EQ(tris.size(), 1u);
  // parent · child · v: (0,0,0) → (1,2,5); (1,0,0) → (1,4,5); (0,1,0) → (−1,2,5); then +(10, 0, 0).
  expectNear(tris[0].p[0], {11, 2, 5}, 1e-5);
  expectNear(tris[0].p[1], {11, 4, 5}, 1e-5);
  expectNear(tris[0].p[2], {9, 2, 5}, 1e-5);
  for (int k = 0; k < 3; ++k) expectNear(tris[0].n[k], {0, 0, 1}, 1e-5);  // the file's normals, transformed
}

TEST(Triangulation, GltfMirroringNodeKeepsTrianglesOutward) {
  // The sample tetrahedron (counter-clockwise from outside) under a node that mirrors x.
  const std::vector<unsigned char> bytes =
      bytesOf({1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1}, {0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2});
  const TriangleMesh mesh = triangulateGltf(
      R"("nodes": [{"mesh": 0, "scale": [-1, 1, 1]}],
         "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}])",
      R"("bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 24}],
         "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, -1, -1], "max": [1, 1, 1]},
                       {"bufferView": 1, "componentType": 5123, "count": 12, "type": "SCALAR"}])",
      bytes);
  const std::vector<Triangle> tris = triangles(mesh);
  ASSERT_EQ(tris.size(), 4u);
  for (const Triangle& t : tris) {
    EXPECT_GT(glm::dot(t.centroid(), t.geometricNormal()), 0.0);  // the centre is the origin
    for (int k = 0; k < 3; ++k) expectNear(t.n[k], t.geometricNormal(), 1e-5);
  }
}

TEST(Triangulation, GltfTriangleStripBecomesConsistentlyWoundTriangles) {
  // A strip of four vertices zig-zagging along x: two triangles wound alike (both facing −z).
  const std::vector<unsigned char> bytes = bytesOf({0, 0, 0, 0, 1, 0, 1, 0, 0, 1, 1, 0});
  const TriangleMesh mesh = triangulateGltf(
      R"("nodes": [{"mesh": 0}], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "mode": 5}]}])",
      R"("bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}],
         "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}])",
      bytes);
  const std::vector<Triangle> tris = triangles(mesh);
  ASSERT_EQ(tris.size(), 2u);
  for (const Triangle& t : tris) expectNear(t.geometricNormal(), {0, 0, -1}, 1e-6);
}

TEST(Triangulation, GltfQuantizedPositionsAndNormalsAreDecoded) {
  // KHR_mesh_quantization: positions as unnormalised unsigned shorts (the node scales them by 1/2)
  // and normals as normalised signed bytes (127 is 1.0, −128 clamps to −1.0).
  std::vector<unsigned char> bytes;
  auto put16 = [&](std::uint16_t v) {
    bytes.push_back(static_cast<unsigned char>(v & 0xffu));
    bytes.push_back(static_cast<unsigned char>(v >> 8));
  };
  for (int v : {0, 0, 0, 2, 0, 0, 0, 2, 0}) put16(static_cast<std::uint16_t>(v));  // 18 bytes
  bytes.insert(bytes.end(), 2, 0);                                 // align the normals to 4 bytes
  for (int i = 0; i < 3; ++i) {
    for (int v : {0, 0, 127, 0}) bytes.push_back(static_cast<unsigned char>(static_cast<std::int8_t>(v)));  // stride 4
  }
  const TriangleMesh mesh = triangulateGltf(
      R"("extensionsUsed": ["KHR_mesh_quantization"], "extensionsRequired": ["KHR_mesh_quantization"],
         "nodes": [{"mesh": 0, "scale": [0.5, 0.5, 0.5]}],
         "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}}]}])",
      R"("bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 18}, {"buffer": 0, "byteOffset": 20, "byteLength": 12, "byteStride": 4}],
         "accessors": [{"bufferView": 0, "componentType": 5123, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [2, 2, 0]},
                       {"bufferView": 1, "componentType": 5120, "normalized": true, "count": 3, "type": "VEC3"}])",
      bytes);
  const std::vector<Triangle> tris = triangles(mesh);
  ASSERT_EQ(tris.size(), 1u);
  expectNear(tris[0].p[0], {0, 0, 0}, 1e-6);
  expectNear(tris[0].p[1], {1, 0, 0}, 1e-6);
  expectNear(tris[0].p[2], {0, 1, 0}, 1e-6);
  for (int k = 0; k < 3; ++k) expectNear(tris[0].n[k], {0, 0, 1}, 1e-6);
}

TEST(Triangulation, GltfZeroScaleNodeIsHiddenNotAnError) {
  // Two nodes share the triangle; the one scaled to zero (how files hide a node) draws nothing.
  const std::vector<unsigned char> bytes = bytesOf({0, 0, 0, 1, 0, 0, 0, 1, 0});
  const TriangleMesh mesh = triangulateGltf(
      R"("nodes": [{"mesh": 0, "scale": [0, 0, 0]}, {"mesh": 0, "translation": [0, 0, 3]}],
         "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}])",
      R"("bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}],
         "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}])",
      bytes);
  const std::vector<Triangle> tris = triangles(mesh);
  ASSERT_EQ(tris.size(), 1u);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(tris[0].p[k].z, 3.0, 1e-6);
}

TEST(Triangulation, GltfImagesAreNotDecoded) {
  // A texture whose image no decoder reads (bytes that are not a PNG) and one whose file is
  // missing: the stub host never samples textures, so the mesh loads.
  const std::vector<unsigned char> bytes = bytesOf({0, 0, 0, 1, 0, 0, 0, 1, 0});
  const TriangleMesh mesh = triangulateGltf(
      R"("nodes": [{"mesh": 0}],
         "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "material": 0}]}],
         "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
         "textures": [{"source": 0}, {"source": 1}],
         "images": [{"uri": "data:image/png;base64,bm90IGEgcG5n"}, {"uri": "no-such-image.ktx2"}])",
      R"("bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}],
         "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}])",
      bytes);
  EXPECT_EQ(triangles(mesh).size(), 1u);
}

TEST(Triangulation, MissingGltfFileFailsWithItsName) {
  Object object;
  object.type = ObjectType::Gltf;
  object.path = kScenesDir / "assets" / "no-such-mesh.gltf";
  std::vector<TriangleMesh> meshes;
  std::string error;
  EXPECT_FALSE(triangulate(object, 10.0, glm::dvec3(0.0), meshes, error));
  EXPECT_TRUE(meshes.empty());
  EXPECT_NE(error.find("no-such-mesh.gltf"), std::string::npos) << error;
}

}  // namespace
}  // namespace tyndall::host
