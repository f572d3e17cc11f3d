// Constant blocks shared by the stub host's C++ code and its shaders: one definition, so the two
// cannot drift. Only 16-byte types (vec4, ivec4, mat4) so std140 equals the C++ layout.
#ifndef TYNDALL_HOST_SHARED_GLSL
#define TYNDALL_HOST_SHARED_GLSL

#ifdef __cplusplus
#include <glm/glm.hpp>
namespace tyndall::host::gpu {
using vec4 = glm::vec4;
using ivec4 = glm::ivec4;
using mat4 = glm::mat4;
#define HOST_CONST inline constexpr
#else
#define HOST_CONST const
#endif

HOST_CONST int kHostLightDirectional = 0;
HOST_CONST int kHostLightSpot = 1;
HOST_CONST int kHostLightPoint = 2;
HOST_CONST int kHostMaxShadowMaps = 6;
HOST_CONST int kHostMaxCascades = 4;  // a directional light's maps (kMaxSceneCascades)

// Push constants of the shadow and G-buffer passes.
struct MeshPush {
  mat4 clipFromWorld;
};

// Push constants of the translucent peel pass: x of `layer` is the layer being peeled.
struct PeelPush {
  mat4 clipFromWorld;
  ivec4 layer;
};

// Push constants of the forward pass of translucent objects: `light` xyz is the direction a
// directional light travels (w = 0) or a spot or point light's position (w = 1); `radiance` its
// E or I; `ambient` the ambient irradiance.
struct ForwardPush {
  mat4 clipFromWorld;
  vec4 light;
  vec4 radiance;
  vec4 ambient;
};

// Uniform block of the lighting pass (set 0, binding 0).
struct LightingParams {
  mat4 worldToShadowClip[6];  // point lights: faces +X, −X, +Y, −Y, +Z, −Z
  mat4 viewToWorld;
  // x = P[0][0], y = P[1][1], z = P[2][2], w = P[3][2] of the camera projection: every depth
  // convention (standard/reverse, finite/infinite) gives view z = −w / (depth + z).
  vec4 projection;
  vec4 lightPosition;   // xyz, scene units (spot, point)
  vec4 lightDirection;  // xyz, unit, the direction the light travels
  vec4 lightRadiance;   // rgb: colour · intensity (E for directional, I for spot/point)
  vec4 spotCone;        // x: cos(outer half-angle), y: cos(inner half-angle)
  // x: shadow texel footprint (directional: scene units; spot/point: scene units per unit of
  // distance along the frustum axis, 2 tan(fov/2) / N); y: N
  vec4 shadow;
  vec4 sky;             // rgb: radiance of sky pixels; a: depth clear value (marks sky pixels)
  vec4 ambient;         // rgb: ambient irradiance
  ivec4 mode;           // x: light type, y: shadow map count, z: width, w: height
  // x: 1 for the second and later lights of a scene, drawn with additive blending over the first:
  // they add their direct light only (no sky, no ambient). 0 for the first light.
  ivec4 additive;
  // A directional light's cascades (mode.y > 1 maps, finest first), element c for cascade c:
  // cascadeFar[c] is the view depth (scene units along the camera's −Z) where cascade c ends and
  // c + 1 begins (HostShadowMap::viewDepthFar); cascadeFootprint[c] is the world size of one texel
  // of map c, in scene units (what shadow.x is for a single map).
  vec4 cascadeFar;
  vec4 cascadeFootprint;
};

#ifdef __cplusplus
static_assert(sizeof(MeshPush) == 64);
static_assert(sizeof(LightingParams) == 7 * 64 + 12 * 16);
static_assert(kHostMaxCascades <= kHostMaxShadowMaps);
}  // namespace tyndall::host::gpu
#undef HOST_CONST
#endif

#endif  // TYNDALL_HOST_SHARED_GLSL
