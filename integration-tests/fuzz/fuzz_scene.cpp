// libFuzzer target: the scene loader (DESIGN.md "Scene JSON") on arbitrary text. A scene either
// loads or is rejected with a one-line error naming the field; one that loads has finite values,
// and its glTF objects (resolved against samples/scenes) triangulate or fail with an error.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "tyndall_host/scene.h"

namespace {

void require(bool condition, const char* what) {
  if (!condition) {
    std::fprintf(stderr, "fuzz_scene: %s\n", what);
    std::abort();
  }
}

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tyndall::host;
  const std::string text(reinterpret_cast<const char*>(data), size);
  const SceneLoadResult loaded = parseScene(text, TYNDALL_SCENES_DIR);
  if (!loaded.scene) {
    require(!loaded.error.empty(), "a rejected scene without an error");
    require(loaded.error.find('\n') == std::string::npos, "an error of more than one line");
    return 0;
  }
  const Scene& scene = *loaded.scene;
  require(finite(scene.camera.position) && finite(scene.camera.target), "a camera that is not finite");
  require(scene.camera.nearPlane > 0.0 && scene.camera.farPlane > scene.camera.nearPlane, "near/far out of order");
  require(!scene.medium.empty(), "a scene without a medium");
  for (const MediumComponent& m : scene.medium) {
    require(finite(m.scattering) && finite(m.absorption), "a medium that is not finite");
  }
  for (const Object& object : scene.objects) {
    std::vector<TriangleMesh> meshes;
    std::string error;
    // Planes become a square around a point; a huge one is still two triangles.
    if (!triangulate(object, 100.0, scene.camera.position, meshes, error)) {
      require(!error.empty(), "a failed triangulation without an error");
      continue;
    }
    for (const TriangleMesh& mesh : meshes) {
      require(mesh.indices.size() % 3 == 0, "a mesh whose indices are not triangles");
      for (std::uint32_t index : mesh.indices) require(index < mesh.positions.size(), "an index out of range");
    }
  }
  return 0;
}
