// Scene files (DESIGN.md, "Scene JSON"): parsing and validation.
//
// The parser is strict: every key must be known, every number finite and in range, so that a typo
// ("halfExtent") or a nonsensical value fails loudly with the JSON path of the culprit instead of
// silently rendering a default. Internally a SceneError exception unwinds to parseScene, which turns
// it into SceneLoadResult::error; nothing throws across the public functions.
#include "tyndall_host/scene.h"

#include <cmath>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <optional>
#include <string_view>

#include <nlohmann/json.hpp>

namespace tyndall::host {
namespace {

using Json = nlohmann::json;

// Shadow-map sizes outside this range are either useless (< 16 texels) or beyond what any GPU
// allocates as a single depth image (Vulkan's maxImageDimension2D is 16384 on current desktop GPUs).
constexpr std::uint32_t kMinShadowMapSize = 16;
constexpr std::uint32_t kMaxShadowMapSize = 16384;
// Spot cones wider than this make the spot frustum's projection degenerate (tan → ∞ at 90°).
constexpr double kMaxConeDegrees = 80.0;
// Medium components a frame carries at most (tyndall::kMaxMediumComponents, plugin/include/tyndall/tyndall.h;
// the stub host does not depend on the plugin).
constexpr std::size_t kMaxMediumComponents = 4;
// |cross(forward, up)| below this means `up` does not define a camera roll.
constexpr double kParallelEpsilon = 1e-9;

struct SceneError {
  std::string message;
};

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw SceneError{path + " " + what};
}

std::string child(const std::string& path, std::string_view key) {
  return path.empty() ? std::string(key) : path + "." + std::string(key);
}

std::string element(const std::string& path, std::size_t index) {
  return path + "[" + std::to_string(index) + "]";
}

std::string joinKeys(std::initializer_list<std::string_view> keys) {
  std::string joined;
  for (std::string_view key : keys) {
    joined += (joined.empty() ? "" : ", ") + std::string(key);
  }
  return joined;
}

const Json& requireObject(const Json& value, const std::string& path) {
  if (!value.is_object()) fail(path.empty() ? "the scene" : path, "must be a JSON object");
  return value;
}

// Rejects keys outside `allowed`: a misspelt optional key would otherwise be ignored silently.
void requireKnownKeys(const Json& object, const std::string& path,
                      std::initializer_list<std::string_view> allowed) {
  for (const auto& [key, value] : object.items()) {
    bool known = false;
    for (std::string_view name : allowed) known = known || key == name;
    if (!known) fail(child(path, key), "is an unknown key (expected one of: " + joinKeys(allowed) + ")");
  }
}

const Json* findMember(const Json& object, std::string_view key) {
  const auto it = object.find(key);
  return it == object.end() ? nullptr : &*it;
}

const Json& requireMember(const Json& object, const std::string& path, std::string_view key) {
  const Json* value = findMember(object, key);
  if (value == nullptr) fail(child(path, key), "is missing");
  return *value;
}

double toNumber(const Json& value, const std::string& path) {
  if (!value.is_number()) fail(path, "must be a number");
  const double number = value.get<double>();
  if (!std::isfinite(number)) fail(path, "must be a finite number");
  return number;
}

glm::dvec3 toVec3(const Json& value, const std::string& path) {
  if (!value.is_array() || value.size() != 3) fail(path, "must be an array of 3 numbers");
  return {toNumber(value[0], element(path, 0)), toNumber(value[1], element(path, 1)),
          toNumber(value[2], element(path, 2))};
}

std::string toString(const Json& value, const std::string& path) {
  if (!value.is_string()) fail(path, "must be a string");
  return value.get<std::string>();
}

double readNumber(const Json& object, const std::string& path, std::string_view key) {
  return toNumber(requireMember(object, path, key), child(path, key));
}

double readNumber(const Json& object, const std::string& path, std::string_view key, double fallback) {
  const Json* value = findMember(object, key);
  return value == nullptr ? fallback : toNumber(*value, child(path, key));
}

glm::dvec3 readVec3(const Json& object, const std::string& path, std::string_view key) {
  return toVec3(requireMember(object, path, key), child(path, key));
}

glm::dvec3 readVec3(const Json& object, const std::string& path, std::string_view key,
                    const glm::dvec3& fallback) {
  const Json* value = findMember(object, key);
  return value == nullptr ? fallback : toVec3(*value, child(path, key));
}

void requirePositive(double value, const std::string& path) {
  if (!(value > 0.0)) fail(path, "must be > 0");
}

void requireNonNegative(double value, const std::string& path) {
  if (!(value >= 0.0)) fail(path, "must be >= 0");
}

void requireNonNegative(const glm::dvec3& value, const std::string& path) {
  for (int i = 0; i < 3; ++i) requireNonNegative(value[i], element(path, static_cast<std::size_t>(i)));
}

void requireInUnitRange(const glm::dvec3& value, const std::string& path) {
  for (int i = 0; i < 3; ++i) {
    if (!(value[i] >= 0.0 && value[i] <= 1.0)) {
      fail(element(path, static_cast<std::size_t>(i)), "must be in [0, 1]");
    }
  }
}

glm::dvec3 normalizedDirection(const glm::dvec3& value, const std::string& path) {
  const double length = glm::length(value);
  if (!(length > 0.0) || !std::isfinite(length)) fail(path, "must have a non-zero length");
  return value / length;
}

glm::dvec3 readDirection(const Json& object, const std::string& path, std::string_view key) {
  return normalizedDirection(readVec3(object, path, key), child(path, key));
}

Camera parseCamera(const Json& json) {
  const std::string path = "camera";
  requireObject(json, path);
  requireKnownKeys(json, path, {"position", "target", "up", "fovYDegrees", "near", "far"});
  Camera camera;
  camera.position = readVec3(json, path, "position");
  camera.target = readVec3(json, path, "target");
  camera.up = normalizedDirection(readVec3(json, path, "up", camera.up), child(path, "up"));
  camera.fovYDegrees = readNumber(json, path, "fovYDegrees", camera.fovYDegrees);
  camera.nearPlane = readNumber(json, path, "near", camera.nearPlane);
  camera.farPlane = readNumber(json, path, "far", camera.farPlane);

  const glm::dvec3 view = camera.target - camera.position;
  if (!(glm::length(view) > 0.0)) fail(child(path, "target"), "must differ from camera.position");
  if (glm::length(glm::cross(glm::normalize(view), camera.up)) < kParallelEpsilon) {
    fail(child(path, "up"), "must not be parallel to the view direction");
  }
  if (!(camera.fovYDegrees > 0.0 && camera.fovYDegrees < 180.0)) {
    fail(child(path, "fovYDegrees"), "must be in (0, 180)");
  }
  requirePositive(camera.nearPlane, child(path, "near"));
  if (!(camera.farPlane > camera.nearPlane)) fail(child(path, "far"), "must be > camera.near");
  return camera;
}

LightType parseLightType(const Json& json, const std::string& path) {
  const std::string name = toString(requireMember(json, path, "type"), child(path, "type"));
  if (name == "directional") return LightType::Directional;
  if (name == "spot") return LightType::Spot;
  if (name == "point") return LightType::Point;
  fail(child(path, "type"), "is an unknown light type '" + name + "' (expected directional, spot or point)");
}

void parseCone(const Json& json, const std::string& path, Light& light) {
  light.innerConeDegrees = readNumber(json, path, "innerConeDegrees", light.innerConeDegrees);
  light.outerConeDegrees = readNumber(json, path, "outerConeDegrees", light.outerConeDegrees);
  if (!(light.innerConeDegrees >= 0.0 && light.innerConeDegrees <= light.outerConeDegrees &&
        light.outerConeDegrees <= kMaxConeDegrees)) {
    fail(path, "cone angles must satisfy 0 <= innerConeDegrees <= outerConeDegrees <= 80");
  }
}

// What a "shadowMap" object sets; each key is optional and what it leaves out keeps its default
// (the scene's) or the scene's value (a light's).
struct ShadowMapFields {
  std::optional<std::uint32_t> size;
  std::optional<std::uint32_t> cascades;
  std::optional<double> cascadeSplit;
};

std::int64_t toInteger(const Json& value, const std::string& path) {
  if (!value.is_number_integer()) fail(path, "must be an integer");
  return value.get<std::int64_t>();
}

std::uint32_t parseShadowMapSize(const Json& json, const std::string& path) {
  const std::int64_t value = toInteger(json, path);
  const bool powerOfTwo = value > 0 && (value & (value - 1)) == 0;
  if (!powerOfTwo || value < kMinShadowMapSize || value > kMaxShadowMapSize) {
    fail(path, "must be a power of two in [16, 16384]");
  }
  return static_cast<std::uint32_t>(value);
}

ShadowMapFields parseShadowMap(const Json& json, const std::string& path) {
  requireObject(json, path);
  requireKnownKeys(json, path, {"size", "cascades", "cascadeSplit"});
  ShadowMapFields fields;
  if (const Json* size = findMember(json, "size")) fields.size = parseShadowMapSize(*size, child(path, "size"));
  if (const Json* cascades = findMember(json, "cascades")) {
    const std::string cascadesPath = child(path, "cascades");
    const std::int64_t value = toInteger(*cascades, cascadesPath);
    if (value < 1 || value > kMaxSceneCascades) fail(cascadesPath, "must be an integer in [1, 4]");
    fields.cascades = static_cast<std::uint32_t>(value);
  }
  if (const Json* split = findMember(json, "cascadeSplit")) {
    const std::string splitPath = child(path, "cascadeSplit");
    const double value = toNumber(*split, splitPath);
    if (!(value >= 0.0 && value <= 1.0)) fail(splitPath, "must be in [0, 1]");
    fields.cascadeSplit = value;
  }
  return fields;
}

// A light's own "shadowMap": cascades split only a directional light's map, so a spot or point
// light refuses more than one rather than ignoring it.
void parseLightShadowMap(const Json& json, const std::string& path, Light& light) {
  const ShadowMapFields fields = parseShadowMap(json, path);
  light.shadowMapSize = fields.size.value_or(0);
  const bool directional = light.type == LightType::Directional;
  const char* kind = light.type == LightType::Spot ? "a spot light" : "a point light";
  if (fields.cascades) {
    if (!directional && *fields.cascades > 1) {
      fail(child(path, "cascades"), std::string("must be 1 for ") + kind + " (only directional lights take cascades)");
    }
    light.cascades = *fields.cascades;
  }
  if (fields.cascadeSplit) {
    if (!directional) fail(child(path, "cascadeSplit"), std::string("is for directional lights, not ") + kind);
    light.cascadeSplit = fields.cascadeSplit;
  }
}

Light parseLight(const Json& json, const std::string& path, const std::filesystem::path& baseDir) {
  requireObject(json, path);
  Light light;
  light.type = parseLightType(json, path);
  if (light.type == LightType::Directional) {
    requireKnownKeys(json, path, {"type", "direction", "color", "intensity", "colorTexture", "shadowMap"});
    light.direction = readDirection(json, path, "direction");
  } else {
    requireKnownKeys(json, path, {"type", "position", "direction", "color", "intensity",
                                  "innerConeDegrees", "outerConeDegrees", "colorTexture", "shadowMap"});
    light.position = readVec3(json, path, "position");
    // A point light shines everywhere: its direction only orients the six shadow frusta.
    const bool needsDirection = light.type == LightType::Spot || findMember(json, "direction") != nullptr;
    if (needsDirection) light.direction = readDirection(json, path, "direction");
    parseCone(json, path, light);
  }
  light.color = readVec3(json, path, "color", light.color);
  requireNonNegative(light.color, child(path, "color"));
  light.intensity = readNumber(json, path, "intensity");
  requireNonNegative(light.intensity, child(path, "intensity"));
  if (const Json* texture = findMember(json, "colorTexture")) {
    const std::string texturePath = child(path, "colorTexture");
    if (light.type == LightType::Point) fail(texturePath, "needs a directional or spot light");
    const std::filesystem::path file = toString(*texture, texturePath);
    if (file.empty()) fail(texturePath, "must not be empty");
    light.colorTexture = (file.is_relative() ? baseDir / file : file).lexically_normal();
    std::error_code status;
    if (!std::filesystem::is_regular_file(light.colorTexture, status)) {
      fail(texturePath, "names no readable file ('" + light.colorTexture.string() + "')");
    }
  }
  if (const Json* shadowMap = findMember(json, "shadowMap")) {
    parseLightShadowMap(*shadowMap, child(path, "shadowMap"), light);
  }
  return light;
}

// "light": LIGHT or "lights": [LIGHT, …], exactly one of them; the first light becomes
// Scene::light so that code written for one light keeps reading it there.
void parseLights(const Json& json, const std::filesystem::path& baseDir, Scene& scene) {
  const Json* single = findMember(json, "light");
  const Json* list = findMember(json, "lights");
  if (single != nullptr && list != nullptr) {
    fail("lights", "cannot come with light (a scene has \"light\" or \"lights\", not both)");
  }
  if (single != nullptr) {
    scene.light = parseLight(*single, "light", baseDir);
    return;
  }
  if (list == nullptr) fail("light", "is missing (a scene has \"light\" or \"lights\")");
  const std::string path = "lights";
  if (!list->is_array()) fail(path, "must be an array");
  if (list->empty() || list->size() > kMaxSceneLights) fail(path, "must hold 1 to 8 lights");
  scene.light = parseLight((*list)[0], element(path, 0), baseDir);
  for (std::size_t i = 1; i < list->size(); ++i) {
    scene.additionalLights.push_back(parseLight((*list)[i], element(path, i), baseDir));
  }
}

PhaseType parsePhaseType(const std::string& name, const std::string& path) {
  if (name == "isotropic") return PhaseType::Isotropic;
  if (name == "rayleigh") return PhaseType::Rayleigh;
  if (name == "henyey-greenstein") return PhaseType::HenyeyGreenstein;
  if (name == "cornette-shanks") return PhaseType::CornetteShanks;
  fail(path, "is an unknown phase type '" + name +
                 "' (expected isotropic, rayleigh, henyey-greenstein or cornette-shanks)");
}

void parsePhase(const Json& json, const std::string& path, MediumComponent& component) {
  requireObject(json, path);
  requireKnownKeys(json, path, {"type", "g"});
  const std::string typePath = child(path, "type");
  component.phase = parsePhaseType(toString(requireMember(json, path, "type"), typePath), typePath);
  // g shapes only the Henyey–Greenstein and Cornette–Shanks lobes; |g| = 1 is a delta function.
  const bool needsG = component.phase == PhaseType::HenyeyGreenstein ||
                      component.phase == PhaseType::CornetteShanks;
  component.g = needsG ? readNumber(json, path, "g") : readNumber(json, path, "g", 0.0);
  if (!(component.g > -1.0 && component.g < 1.0)) fail(child(path, "g"), "must be in (-1, 1)");
}

MediumComponent parseMediumComponent(const Json& json, const std::string& path) {
  requireObject(json, path);
  requireKnownKeys(json, path, {"scattering", "absorption", "phase"});
  MediumComponent component;
  component.scattering = readVec3(json, path, "scattering");
  requireNonNegative(component.scattering, child(path, "scattering"));
  component.absorption = readVec3(json, path, "absorption", component.absorption);
  requireNonNegative(component.absorption, child(path, "absorption"));
  if (const Json* phase = findMember(json, "phase")) parsePhase(*phase, child(path, "phase"), component);
  return component;
}

std::vector<MediumComponent> parseMedium(const Json& json) {
  const std::string path = "medium";
  requireObject(json, path);
  const Json* components = findMember(json, "components");
  if (components == nullptr) {
    return {parseMediumComponent(json, path)};
  }
  requireKnownKeys(json, path, {"components"});
  const std::string listPath = child(path, "components");
  if (!components->is_array()) fail(listPath, "must be an array");
  if (components->empty() || components->size() > kMaxMediumComponents) {
    fail(listPath, "must hold 1 to 4 components");
  }
  std::vector<MediumComponent> medium;
  for (std::size_t i = 0; i < components->size(); ++i) {
    medium.push_back(parseMediumComponent((*components)[i], element(listPath, i)));
  }
  return medium;
}

void parsePlane(const Json& json, const std::string& path, Object& object) {
  requireKnownKeys(json, path, {"type", "point", "normal", "albedo"});
  object.point = readVec3(json, path, "point");
  object.normal = readDirection(json, path, "normal");
}

void parseBox(const Json& json, const std::string& path, Object& object) {
  requireKnownKeys(json, path, {"type", "center", "halfExtents", "rotationDegrees", "albedo", "opacity"});
  object.center = readVec3(json, path, "center");
  object.halfExtents = readVec3(json, path, "halfExtents");
  for (int i = 0; i < 3; ++i) {
    requirePositive(object.halfExtents[i], element(child(path, "halfExtents"), static_cast<std::size_t>(i)));
  }
  object.rotationDegrees = readVec3(json, path, "rotationDegrees", glm::dvec3(0.0));
}

void parseSphere(const Json& json, const std::string& path, Object& object) {
  requireKnownKeys(json, path, {"type", "center", "radius", "albedo", "opacity"});
  object.center = readVec3(json, path, "center");
  object.radius = readNumber(json, path, "radius");
  requirePositive(object.radius, child(path, "radius"));
}

void parseGltf(const Json& json, const std::string& path, const std::filesystem::path& baseDir,
               Object& object) {
  requireKnownKeys(json, path, {"type", "path", "translation", "rotationDegrees", "scale", "albedo", "opacity"});
  const std::string filePath = child(path, "path");
  const std::filesystem::path file = toString(requireMember(json, path, "path"), filePath);
  if (file.empty()) fail(filePath, "must not be empty");
  object.path = (file.is_relative() ? baseDir / file : file).lexically_normal();
  std::error_code status;
  if (!std::filesystem::is_regular_file(object.path, status)) {
    fail(filePath, "names no readable file ('" + object.path.string() + "')");
  }
  object.translation = readVec3(json, path, "translation", glm::dvec3(0.0));
  object.rotationDegrees = readVec3(json, path, "rotationDegrees", glm::dvec3(0.0));
  object.scale = readNumber(json, path, "scale", 1.0);
  requirePositive(object.scale, child(path, "scale"));
}

Object parseObject(const Json& json, const std::string& path, const std::filesystem::path& baseDir) {
  requireObject(json, path);
  Object object;
  const std::string typePath = child(path, "type");
  const std::string type = toString(requireMember(json, path, "type"), typePath);
  if (type == "plane") {
    object.type = ObjectType::Plane;
    parsePlane(json, path, object);
  } else if (type == "box") {
    object.type = ObjectType::Box;
    parseBox(json, path, object);
  } else if (type == "sphere") {
    object.type = ObjectType::Sphere;
    parseSphere(json, path, object);
  } else if (type == "gltf") {
    object.type = ObjectType::Gltf;
    parseGltf(json, path, baseDir, object);
  } else {
    fail(typePath, "is an unknown object type '" + type + "' (expected plane, box, sphere or gltf)");
  }
  object.albedo = readVec3(json, path, "albedo", object.albedo);
  requireInUnitRange(object.albedo, child(path, "albedo"));
  object.opacity = readNumber(json, path, "opacity", 1.0);
  if (!(object.opacity > 0.0 && object.opacity <= 1.0)) fail(child(path, "opacity"), "must be in (0, 1]");
  return object;
}

std::vector<Object> parseObjects(const Json& json, const std::filesystem::path& baseDir) {
  const std::string path = "objects";
  if (!json.is_array()) fail(path, "must be an array");
  std::vector<Object> objects;
  objects.reserve(json.size());
  for (std::size_t i = 0; i < json.size(); ++i) {
    objects.push_back(parseObject(json[i], element(path, i), baseDir));
  }
  return objects;
}

Scene parseSceneJson(const Json& json, const std::filesystem::path& baseDir) {
  requireObject(json, "");
  // "description" lets a scene file say what it is for; it is not used.
  requireKnownKeys(json, "", {"description", "camera", "light", "lights", "medium", "objects", "shadowMap"});
  if (const Json* description = findMember(json, "description")) toString(*description, "description");
  Scene scene;
  scene.camera = parseCamera(requireMember(json, "", "camera"));
  parseLights(json, baseDir, scene);
  scene.medium = parseMedium(requireMember(json, "", "medium"));
  scene.objects = parseObjects(requireMember(json, "", "objects"), baseDir);
  if (const Json* shadowMap = findMember(json, "shadowMap")) {
    const ShadowMapFields fields = parseShadowMap(*shadowMap, "shadowMap");
    scene.shadowMapSize = fields.size.value_or(scene.shadowMapSize);
    scene.cascades = fields.cascades.value_or(scene.cascades);
    scene.cascadeSplit = fields.cascadeSplit.value_or(scene.cascadeSplit);
  }
  return scene;
}

}  // namespace

SceneLoadResult parseScene(const std::string& jsonText, const std::filesystem::path& baseDir) {
  SceneLoadResult result;
  try {
    result.scene = parseSceneJson(Json::parse(jsonText), baseDir);
  } catch (const SceneError& error) {
    result.error = error.message;
  } catch (const Json::exception& error) {
    result.error = std::string("invalid JSON: ") + error.what();
  }
  return result;
}

SceneLoadResult loadScene(const std::filesystem::path& path) {
  std::error_code status;
  std::ifstream file(path, std::ios::binary);
  if (!std::filesystem::is_regular_file(path, status) || !file) {
    return {std::nullopt, path.string() + ": cannot open the file"};
  }
  const std::string text{std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
  if (file.bad()) return {std::nullopt, path.string() + ": cannot read the file"};
  SceneLoadResult result = parseScene(text, path.parent_path());
  if (result.scene) {
    result.scene->sourcePath = path;
  } else {
    result.error = path.string() + ": " + result.error;
  }
  return result;
}

glm::dmat3 rotationFromDegrees(const glm::dvec3& degrees) {
  const glm::dvec3 radians = glm::radians(degrees);
  const double cx = std::cos(radians.x), sx = std::sin(radians.x);
  const double cy = std::cos(radians.y), sy = std::sin(radians.y);
  const double cz = std::cos(radians.z), sz = std::sin(radians.z);
  // glm matrices are column-major: each group of three is one column (the image of a basis vector).
  const glm::dmat3 rx(1.0, 0.0, 0.0, 0.0, cx, sx, 0.0, -sx, cx);
  const glm::dmat3 ry(cy, 0.0, -sy, 0.0, 1.0, 0.0, sy, 0.0, cy);
  const glm::dmat3 rz(cz, sz, 0.0, -sz, cz, 0.0, 0.0, 0.0, 1.0);
  return rz * ry * rx;
}

}  // namespace tyndall::host
