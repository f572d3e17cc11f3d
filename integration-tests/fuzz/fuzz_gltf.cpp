// libFuzzer target: a glTF object from arbitrary bytes, as a binary .glb (when the bytes start with
// the magic "glTF") or as .gltf JSON (buffers as data: URIs or files), through the host's loader and
// triangulation. It either fails with an error or yields triangles whose indices are in range.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "tyndall_host/scene.h"

namespace {

void require(bool condition, const char* what) {
  if (!condition) {
    std::fprintf(stderr, "fuzz_gltf: %s\n", what);
    std::abort();
  }
}

// The loader reads files: the input goes to a file of this process's own.
std::filesystem::path inputPath(bool binary) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path();
  return dir / ("tyndall-fuzz-gltf-" + std::to_string(getpid()) + (binary ? ".glb" : ".gltf"));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tyndall::host;
  const bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
  const std::filesystem::path path = inputPath(binary);
  {
    std::ofstream file(path, std::ios::binary | std::ios::trunc);
    file.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  Object object;
  object.type = ObjectType::Gltf;
  object.path = path;
  std::vector<TriangleMesh> meshes;
  std::string error;
  const bool ok = triangulate(object, 100.0, glm::dvec3(0.0), meshes, error);
  std::filesystem::remove(path);
  if (!ok) {
    require(!error.empty(), "a failed load without an error");
    return 0;
  }
  for (const TriangleMesh& mesh : meshes) {
    require(mesh.indices.size() % 3 == 0, "a mesh whose indices are not triangles");
    require(mesh.normals.size() == mesh.positions.size(), "normals and positions differ in number");
    for (std::uint32_t index : mesh.indices) require(index < mesh.positions.size(), "an index out of range");
  }
  return 0;
}
