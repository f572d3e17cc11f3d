// Scenes for the stub host, in the JSON format of DESIGN.md ("Scene JSON").
// Everything here is double precision: the CPU analytic reference uses the same structures.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace tyndall::host {

struct Camera {
  glm::dvec3 position{0.0, 1.0, 5.0};
  glm::dvec3 target{0.0, 1.0, 0.0};
  glm::dvec3 up{0.0, 1.0, 0.0};
  double fovYDegrees = 60.0;  ///< vertical field of view
  double nearPlane = 0.1;     ///< scene units, > 0
  double farPlane = 200.0;    ///< scene units, > near
};

enum class LightType { Directional, Spot, Point };

struct Light {
  LightType type = LightType::Directional;
  glm::dvec3 direction{0.0, -1.0, 0.0};  ///< unit; the direction the light travels
  glm::dvec3 position{0.0};
  glm::dvec3 color{1.0};
  double intensity = 1.0;
  double innerConeDegrees = 25.0;  ///< half-angle
  double outerConeDegrees = 30.0;  ///< half-angle
  /// Optional "colorTexture": a PNG laid over the light's shadow map (stained glass), resolved
  /// against the scene file's folder; directional and spot lights. Empty: none.
  std::filesystem::path colorTexture;
  /// Optional "shadowMap": {"size": N}: this light's shadow-map size (a power of two in
  /// [16, 16384]). 0: the scene's shadowMapSize.
  std::uint32_t shadowMapSize = 0;
  /// Optional "shadowMap": {"cascades": K}: a directional light's cascaded shadow maps, 1..4
  /// (spot and point lights take 1). 0: the scene's cascades.
  std::uint32_t cascades = 0;
  /// Optional "shadowMap": {"cascadeSplit": λ} in [0, 1] (directional lights). Unset: the scene's.
  std::optional<double> cascadeSplit;
};

enum class PhaseType { Isotropic, Rayleigh, HenyeyGreenstein, CornetteShanks };

struct MediumComponent {
  glm::dvec3 scattering{0.0};  ///< σ_s per scene unit
  glm::dvec3 absorption{0.0};  ///< σ_a per scene unit
  PhaseType phase = PhaseType::Isotropic;
  double g = 0.0;
};

enum class ObjectType { Plane, Box, Sphere, Gltf };

struct Object {
  ObjectType type = ObjectType::Box;
  glm::dvec3 point{0.0};            ///< plane
  glm::dvec3 normal{0.0, 1.0, 0.0}; ///< plane, unit
  glm::dvec3 center{0.0};           ///< box, sphere
  glm::dvec3 halfExtents{0.5};      ///< box
  glm::dvec3 rotationDegrees{0.0};  ///< box, gltf: about X, then Y, then Z (R = Rz·Ry·Rx)
  double radius = 0.5;              ///< sphere
  std::filesystem::path path;       ///< gltf, resolved against the scene file's folder
  glm::dvec3 translation{0.0};      ///< gltf
  double scale = 1.0;               ///< gltf
  glm::dvec3 albedo{0.6};           ///< optional "albedo": [r,g,b] (an extension of the format), linear
  /// Optional "opacity" α in (0, 1]: below 1 a translucent occluder, which multiplies the light
  /// crossing each of its surfaces by 1 − α. It shadows the light only: it is not in the depth
  /// buffer, so view rays pass it unattenuated (an engine draws it after its deferred passes).
  double opacity = 1.0;
  [[nodiscard]] bool translucent() const { return opacity < 1.0; }
};

/// Lights a scene holds at most ("lights": [LIGHT, …]); tyndall::kMaxLights, which the stub host
/// does not include.
inline constexpr std::size_t kMaxSceneLights = 8;
/// Cascades a directional light takes at most ("shadowMap": {"cascades": K}); tyndall::kMaxCascades.
inline constexpr std::uint32_t kMaxSceneCascades = 4;

struct Scene {
  Camera camera;
  Light light;                         ///< "light", or the first of "lights"
  std::vector<Light> additionalLights; ///< the second and later of "lights" (at most 7)
  std::vector<MediumComponent> medium;  ///< one or more components
  std::vector<Object> objects;
  std::uint32_t shadowMapSize = 2048;
  /// "shadowMap": {"cascades": K}: every directional light's cascade count (1..kMaxSceneCascades)
  /// unless the light sets its own; the maps split the camera's [near, far] (finest first).
  std::uint32_t cascades = 1;
  /// "shadowMap": {"cascadeSplit": λ} in [0, 1]: the split depths blend logarithmic (λ = 1) and
  /// uniform (λ = 0) splits of [near, far] (Zhang et al. 2006, "practical split scheme").
  double cascadeSplit = 0.8;
  std::filesystem::path sourcePath;     ///< the file it was loaded from (empty if built in code)
};

struct SceneLoadResult {
  std::optional<Scene> scene;
  std::string error;  ///< one line, set when `scene` is empty
};

/// Parses a scene file. Every value is validated (finite, in range, unit vectors normalised);
/// the error names the offending JSON path, e.g. "objects[3].radius must be > 0".
SceneLoadResult loadScene(const std::filesystem::path& path);
/// Same, from JSON text; relative glTF paths resolve against `baseDir`.
SceneLoadResult parseScene(const std::string& jsonText, const std::filesystem::path& baseDir);

/// R = Rz·Ry·Rx for rotationDegrees (x, y, z).
glm::dmat3 rotationFromDegrees(const glm::dvec3& degrees);

/// A triangle mesh in world space (counter-clockwise front faces, outward normals).
struct TriangleMesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<std::uint32_t> indices;
  glm::vec3 albedo{0.6f};
};

/// Triangulates an object. Spheres are tessellated finely enough for a silhouette error below
/// 0.1% of the radius; planes become a square of half-size `planeHalfSize` centred on the
/// projection of `planeCentre` onto the plane; glTF files are loaded with tinygltf (node
/// transforms, then scale, rotation, translation). Returns false with `error` on failure.
bool triangulate(const Object& object, double planeHalfSize, const glm::dvec3& planeCentre,
                 std::vector<TriangleMesh>& out, std::string& error);

}  // namespace tyndall::host
