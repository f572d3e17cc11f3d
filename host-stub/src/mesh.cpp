// Triangulation of scene objects into world-space triangle meshes for the stub host's raster passes.
// Front faces are counter-clockwise seen from outside, normals point outward.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numbers>
#include <string>
#include <type_traits>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <tiny_gltf.h>  // Debian's libtinygltf is a shared library: no TINYGLTF_IMPLEMENTATION here

#include "tyndall_host/scene.h"

namespace tyndall::host {
namespace {

// UV-sphere resolution. The worst silhouette error of a UV sphere is at the centre of an equatorial
// quad, whose plane lies at r·cos²(Δ/2) from the centre (Δ = 2π/segments = π/rings): the error is
// r·sin²(Δ/2). 128 × 64 gives 6.0e-4 r, under the 0.1% budget; 96 × 48 would give 1.07e-3 r.
constexpr int kSphereSegments = 128;
constexpr int kSphereRings = 64;
// glTF node hierarchies deeper than this are treated as cyclic (malformed) files.
constexpr int kMaxGltfNodeDepth = 64;

void addVertex(TriangleMesh& mesh, const glm::dvec3& position, const glm::dvec3& normal) {
  mesh.positions.emplace_back(position);
  mesh.normals.emplace_back(normal);
}

void addTriangle(TriangleMesh& mesh, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  mesh.indices.insert(mesh.indices.end(), {a, b, c});
}

// Appends the quad centre ± u ± v (normal `normal`, with cross(u, v) pointing along `normal`) as two
// counter-clockwise triangles.
void addQuad(TriangleMesh& mesh, const glm::dvec3& centre, const glm::dvec3& u, const glm::dvec3& v,
             const glm::dvec3& normal) {
  const auto base = static_cast<std::uint32_t>(mesh.positions.size());
  addVertex(mesh, centre - u - v, normal);
  addVertex(mesh, centre + u - v, normal);
  addVertex(mesh, centre + u + v, normal);
  addVertex(mesh, centre - u + v, normal);
  addTriangle(mesh, base, base + 1, base + 2);
  addTriangle(mesh, base, base + 2, base + 3);
}

// Two unit tangents with cross(t, b) = n, for a unit n.
std::pair<glm::dvec3, glm::dvec3> tangentBasis(const glm::dvec3& n) {
  // The world axis least aligned with n keeps the cross product well conditioned.
  const glm::dvec3 a = std::abs(n.x) < 0.577 ? glm::dvec3(1, 0, 0)
                       : std::abs(n.y) < 0.577 ? glm::dvec3(0, 1, 0)
                                               : glm::dvec3(0, 0, 1);
  const glm::dvec3 t = glm::normalize(glm::cross(a, n));
  return {t, glm::cross(n, t)};
}

TriangleMesh planeMesh(const Object& object, double halfSize, const glm::dvec3& planeCentre) {
  TriangleMesh mesh;
  const glm::dvec3 n = glm::normalize(object.normal);
  const glm::dvec3 centre = planeCentre - glm::dot(planeCentre - object.point, n) * n;
  const auto [t, b] = tangentBasis(n);
  addQuad(mesh, centre, t * halfSize, b * halfSize, n);
  return mesh;
}

TriangleMesh boxMesh(const Object& object) {
  TriangleMesh mesh;
  const glm::dmat3 rotation = rotationFromDegrees(object.rotationDegrees);
  for (int axis = 0; axis < 3; ++axis) {
    for (double side : {-1.0, 1.0}) {
      glm::dvec3 normal(0.0), u(0.0), v(0.0);
      normal[axis] = side;
      // (axis, axis+1, axis+2) is a cyclic permutation, so cross(e[axis+1], e[axis+2]) = e[axis];
      // the negative face swaps them to keep its triangles counter-clockwise from outside.
      u[(axis + (side > 0 ? 1 : 2)) % 3] = 1.0;
      v[(axis + (side > 0 ? 2 : 1)) % 3] = 1.0;
      addQuad(mesh, object.center + rotation * (normal * object.halfExtents),
              rotation * (u * object.halfExtents), rotation * (v * object.halfExtents),
              rotation * normal);
    }
  }
  return mesh;
}

glm::dvec3 sphereDirection(int ring, int segment) {
  const double theta = std::numbers::pi * ring / kSphereRings;          // colatitude from +y
  const double phi = 2.0 * std::numbers::pi * segment / kSphereSegments;
  // Exact poles and seam: keeps the pole vertices identical and the mesh watertight.
  const double sinTheta = ring == 0 || ring == kSphereRings ? 0.0 : std::sin(theta);
  const double cosTheta = ring == 0 ? 1.0 : ring == kSphereRings ? -1.0 : std::cos(theta);
  return {sinTheta * std::cos(phi), cosTheta, sinTheta * std::sin(phi)};
}

TriangleMesh sphereMesh(const Object& object) {
  TriangleMesh mesh;
  constexpr int kColumns = kSphereSegments + 1;  // the seam column is duplicated
  for (int ring = 0; ring <= kSphereRings; ++ring) {
    for (int segment = 0; segment <= kSphereSegments; ++segment) {
      const glm::dvec3 direction = sphereDirection(ring, segment % kSphereSegments);
      addVertex(mesh, object.center + object.radius * direction, direction);
    }
  }
  const auto index = [](int ring, int segment) { return static_cast<std::uint32_t>(ring * kColumns + segment); };
  for (int ring = 0; ring < kSphereRings; ++ring) {
    for (int segment = 0; segment < kSphereSegments; ++segment) {
      const std::uint32_t a = index(ring, segment), b = index(ring + 1, segment);
      const std::uint32_t c = index(ring + 1, segment + 1), d = index(ring, segment + 1);
      // The quads touching a pole degenerate to one triangle.
      if (ring != 0) addTriangle(mesh, a, d, c);
      if (ring != kSphereRings - 1) addTriangle(mesh, a, c, b);
    }
  }
  return mesh;
}

// ---- glTF -------------------------------------------------------------------------------------

// glTF cross-references are plain integers; a malformed file may hold any value.
template <typename T>
const T* lookup(const std::vector<T>& items, int index) {
  return index >= 0 && static_cast<std::size_t>(index) < items.size() ? &items[static_cast<std::size_t>(index)]
                                                                        : nullptr;
}

glm::dmat4 gltfNodeMatrix(const tinygltf::Node& node) {
  glm::dmat4 matrix(1.0);
  if (node.matrix.size() == 16) {  // glTF matrices are column-major, like glm
    for (std::size_t i = 0; i < 16; ++i) matrix[static_cast<int>(i / 4)][static_cast<int>(i % 4)] = node.matrix[i];
    return matrix;
  }
  if (node.translation.size() == 3) {
    matrix = glm::translate(matrix, glm::dvec3(node.translation[0], node.translation[1], node.translation[2]));
  }
  if (node.rotation.size() == 4) {  // glTF quaternions are (x, y, z, w); glm::dquat takes (w, x, y, z)
    const glm::dquat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
    // Exporters write slightly denormalised quaternions; a zero one is malformed and ignored.
    if (glm::length(q) > 0.0) matrix = matrix * glm::mat4_cast(glm::normalize(q));
  }
  if (node.scale.size() == 3) {
    matrix = glm::scale(matrix, glm::dvec3(node.scale[0], node.scale[1], node.scale[2]));
  }
  return matrix;
}

// The bytes of an accessor, checked against its buffer: element i starts at data + i·stride.
struct AccessorView {
  const unsigned char* data = nullptr;
  std::size_t stride = 0;
  std::size_t count = 0;
  int componentType = 0;
  bool normalized = false;
};

bool accessorView(const tinygltf::Model& model, int index, int expectedType, AccessorView& view,
                  std::string& error) {
  const std::string name = "accessor " + std::to_string(index);
  const tinygltf::Accessor* accessor = lookup(model.accessors, index);
  const tinygltf::BufferView* bufferView = accessor ? lookup(model.bufferViews, accessor->bufferView) : nullptr;
  const tinygltf::Buffer* buffer = bufferView ? lookup(model.buffers, bufferView->buffer) : nullptr;
  if (buffer == nullptr || accessor->sparse.isSparse) {
    error = name + " is missing, sparse or has no buffer (unsupported)";
    return false;
  }
  const int stride = accessor->ByteStride(*bufferView);
  const int elementSize =
      tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(accessor->componentType)) *
      tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(accessor->type));
  if (accessor->type != expectedType || stride <= 0 || elementSize <= 0) {
    error = name + " has an unexpected type or layout";
    return false;
  }
  const std::size_t begin = bufferView->byteOffset + accessor->byteOffset;
  const std::size_t end = accessor->count == 0 ? begin
                          : begin + static_cast<std::size_t>(stride) * (accessor->count - 1) +
                                static_cast<std::size_t>(elementSize);
  if (end > bufferView->byteOffset + bufferView->byteLength || end > buffer->data.size()) {
    error = name + " reads past the end of its buffer";
    return false;
  }
  view = {buffer->data.data() + begin, static_cast<std::size_t>(stride), accessor->count, accessor->componentType,
          accessor->normalized};
  return true;
}

// One component of a VEC3 element (glTF data need not be aligned). Integer components are
// KHR_mesh_quantization's: normalised ones map to [0, 1] or [−1, 1] as the glTF specification's
// decoding says, the others are taken as they are (the node transform scales them).
template <typename T>
double component(const unsigned char* at, bool normalized) {
  T value;
  std::memcpy(&value, at, sizeof(value));
  if constexpr (std::is_floating_point_v<T>) {
    return static_cast<double>(value);
  } else {
    if (!normalized) return static_cast<double>(value);
    constexpr double kMax = static_cast<double>(std::numeric_limits<T>::max());
    return std::is_signed_v<T> ? std::max(static_cast<double>(value) / kMax, -1.0) : static_cast<double>(value) / kMax;
  }
}

bool readVec3(const tinygltf::Model& model, int index, std::vector<glm::dvec3>& out, std::string& error) {
  AccessorView view;
  if (!accessorView(model, index, TINYGLTF_TYPE_VEC3, view, error)) return false;
  double (*read)(const unsigned char*, bool) = nullptr;
  std::size_t size = 0;
  switch (view.componentType) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: read = component<float>; size = 4; break;
    case TINYGLTF_COMPONENT_TYPE_BYTE: read = component<std::int8_t>; size = 1; break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: read = component<std::uint8_t>; size = 1; break;
    case TINYGLTF_COMPONENT_TYPE_SHORT: read = component<std::int16_t>; size = 2; break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: read = component<std::uint16_t>; size = 2; break;
    default:
      error = "accessor " + std::to_string(index) + " must hold floats, bytes or shorts";
      return false;
  }
  out.resize(view.count);
  for (std::size_t i = 0; i < view.count; ++i) {
    const unsigned char* at = view.data + i * view.stride;
    out[i] = glm::dvec3(read(at, view.normalized), read(at + size, view.normalized), read(at + 2 * size, view.normalized));
  }
  return true;
}

std::uint32_t readIndex(const AccessorView& view, std::size_t i) {
  const unsigned char* at = view.data + i * view.stride;
  if (view.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) return *at;
  if (view.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
    std::uint16_t value;
    std::memcpy(&value, at, sizeof(value));
    return value;
  }
  std::uint32_t value;
  std::memcpy(&value, at, sizeof(value));
  return value;
}

bool readIndices(const tinygltf::Model& model, const tinygltf::Primitive& primitive, std::size_t vertexCount,
                 std::vector<std::uint32_t>& out, std::string& error) {
  if (primitive.indices < 0) {  // non-indexed: vertices in order
    out.resize(vertexCount);
    for (std::size_t i = 0; i < vertexCount; ++i) out[i] = static_cast<std::uint32_t>(i);
    return true;
  }
  AccessorView view;
  if (!accessorView(model, primitive.indices, TINYGLTF_TYPE_SCALAR, view, error)) return false;
  if (view.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
      view.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      view.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
    error = "index accessor " + std::to_string(primitive.indices) + " has an invalid component type";
    return false;
  }
  out.resize(view.count);
  for (std::size_t i = 0; i < view.count; ++i) {
    out[i] = readIndex(view, i);
    if (out[i] >= vertexCount) {
      error = "index " + std::to_string(out[i]) + " is out of range";
      return false;
    }
  }
  return true;
}

// Strips and fans become lists; points and lines are not surfaces and give no triangles.
std::vector<std::uint32_t> triangleList(int mode, const std::vector<std::uint32_t>& indices) {
  std::vector<std::uint32_t> list;
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    list.assign(indices.begin(), indices.end() - static_cast<std::ptrdiff_t>(indices.size() % 3));
  } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
    for (std::size_t i = 2; i < indices.size(); ++i) {
      const bool odd = (i % 2) == 1;  // every other strip triangle is wound the other way round
      list.insert(list.end(), {indices[i - 2], indices[odd ? i : i - 1], indices[odd ? i - 1 : i]});
    }
  } else if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
    for (std::size_t i = 2; i < indices.size(); ++i) list.insert(list.end(), {indices[0], indices[i - 1], indices[i]});
  }
  return list;
}

// Appends the triangles of one primitive, transformed by `world`. Without normals in the file,
// flat normals are generated per face.
bool appendPrimitive(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                     const glm::dmat4& world, TriangleMesh& mesh, std::string& error) {
  const auto position = primitive.attributes.find("POSITION");
  if (position == primitive.attributes.end()) return true;  // nothing to draw
  std::vector<glm::dvec3> positions, normals;
  std::vector<std::uint32_t> indices;
  if (!readVec3(model, position->second, positions, error)) return false;
  const auto normal = primitive.attributes.find("NORMAL");
  if (normal != primitive.attributes.end() && !readVec3(model, normal->second, normals, error)) return false;
  if (!readIndices(model, primitive, positions.size(), indices, error)) return false;

  const glm::dmat3 linear(world);
  const double determinant = glm::determinant(linear);
  if (!std::isfinite(determinant)) {
    error = "a node transform is not finite";
    return false;
  }
  if (determinant == 0.0) return true;  // a zero scale is how glTF files hide a node: nothing to draw
  const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(linear));
  const bool mirrored = determinant < 0.0;  // a mirroring transform flips the winding
  const bool smooth = normals.size() == positions.size();
  const std::vector<std::uint32_t> triangles = triangleList(primitive.mode, indices);
  for (std::size_t i = 0; i + 2 < triangles.size(); i += 3) {
    const std::uint32_t corner[3] = {triangles[i], triangles[mirrored ? i + 2 : i + 1],
                                     triangles[mirrored ? i + 1 : i + 2]};
    glm::dvec3 p[3];
    for (int k = 0; k < 3; ++k) p[k] = glm::dvec3(world * glm::dvec4(positions[corner[k]], 1.0));
    const glm::dvec3 faceNormal = glm::cross(p[1] - p[0], p[2] - p[0]);
    if (!(glm::length(faceNormal) > 0.0)) continue;  // degenerate triangles add nothing
    const auto base = static_cast<std::uint32_t>(mesh.positions.size());
    for (int k = 0; k < 3; ++k) {
      const glm::dvec3 n = smooth ? normalMatrix * normals[corner[k]] : faceNormal;
      addVertex(mesh, p[k], glm::length(n) > 0.0 ? glm::normalize(n) : glm::normalize(faceNormal));
    }
    addTriangle(mesh, base, base + 1, base + 2);
  }
  return true;
}

bool appendNode(const tinygltf::Model& model, int nodeIndex, const glm::dmat4& parent, int depth,
                TriangleMesh& mesh, std::string& error) {
  const tinygltf::Node* node = lookup(model.nodes, nodeIndex);
  if (node == nullptr || depth > kMaxGltfNodeDepth) {
    error = "node " + std::to_string(nodeIndex) + " does not exist or the node graph has a cycle";
    return false;
  }
  const glm::dmat4 world = parent * gltfNodeMatrix(*node);
  if (node->mesh >= 0) {
    const tinygltf::Mesh* source = lookup(model.meshes, node->mesh);
    if (source == nullptr) {
      error = "mesh " + std::to_string(node->mesh) + " does not exist";
      return false;
    }
    for (const tinygltf::Primitive& primitive : source->primitives) {
      if (!appendPrimitive(model, primitive, world, mesh, error)) return false;
    }
  }
  for (int childIndex : node->children) {
    if (!appendNode(model, childIndex, world, depth + 1, mesh, error)) return false;
  }
  return true;
}

// The nodes to draw: the default scene's, else the first scene's, else every node nobody parents.
std::vector<int> gltfRootNodes(const tinygltf::Model& model) {
  if (const tinygltf::Scene* scene = lookup(model.scenes, model.defaultScene)) return scene->nodes;
  if (!model.scenes.empty()) return model.scenes.front().nodes;
  std::vector<bool> isChild(model.nodes.size(), false);
  for (const tinygltf::Node& node : model.nodes) {
    for (int childIndex : node.children) {
      if (lookup(model.nodes, childIndex) != nullptr) isChild[static_cast<std::size_t>(childIndex)] = true;
    }
  }
  std::vector<int> roots;
  for (std::size_t i = 0; i < isChild.size(); ++i) {
    if (!isChild[i]) roots.push_back(static_cast<int>(i));
  }
  return roots;
}

// The stub host shades with the scene's albedo, never a texture: images are not decoded, so that a
// file whose images are missing or in a format stb cannot read (KTX2, WebP) loads all the same.
bool skipImage(tinygltf::Image* /*image*/, int /*index*/, std::string* /*error*/, std::string* /*warning*/,
               int /*width*/, int /*height*/, const unsigned char* /*bytes*/, int /*size*/, void* /*user*/) {
  return true;
}

bool loadGltfModel(const std::filesystem::path& path, tinygltf::Model& model, std::string& error) {
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(skipImage, nullptr);
  std::string loaderError, warning;
  const bool binary = path.extension() == ".glb";
  const bool loaded = binary ? loader.LoadBinaryFromFile(&model, &loaderError, &warning, path.string())
                             : loader.LoadASCIIFromFile(&model, &loaderError, &warning, path.string());
  if (!loaded) error = "cannot load glTF '" + path.string() + "': " + loaderError;
  return loaded;
}

bool gltfMesh(const Object& object, TriangleMesh& mesh, std::string& error) {
  tinygltf::Model model;
  if (!loadGltfModel(object.path, model, error)) return false;
  // glTF node transforms first, then the object's scale, rotation and translation (DESIGN.md).
  glm::dmat4 placement = glm::translate(glm::dmat4(1.0), object.translation);
  placement = placement * glm::dmat4(rotationFromDegrees(object.rotationDegrees));
  placement = glm::scale(placement, glm::dvec3(object.scale));
  for (int root : gltfRootNodes(model)) {
    if (!appendNode(model, root, placement, 0, mesh, error)) {
      error = "glTF '" + object.path.string() + "': " + error;
      return false;
    }
  }
  if (mesh.indices.empty()) {
    error = "glTF '" + object.path.string() + "' holds no triangles";
    return false;
  }
  return true;
}

}  // namespace

bool triangulate(const Object& object, double planeHalfSize, const glm::dvec3& planeCentre,
                 std::vector<TriangleMesh>& out, std::string& error) {
  TriangleMesh mesh;
  switch (object.type) {
    case ObjectType::Plane:
      if (!(planeHalfSize > 0.0) || !std::isfinite(planeHalfSize)) {
        error = "the plane half-size must be finite and > 0";
        return false;
      }
      mesh = planeMesh(object, planeHalfSize, planeCentre);
      break;
    case ObjectType::Box:
      mesh = boxMesh(object);
      break;
    case ObjectType::Sphere:
      mesh = sphereMesh(object);
      break;
    case ObjectType::Gltf:
      if (!gltfMesh(object, mesh, error)) return false;
      break;
  }
  mesh.albedo = glm::vec3(object.albedo);
  out.push_back(std::move(mesh));
  return true;
}

}  // namespace tyndall::host
