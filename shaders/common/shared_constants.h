// The constant blocks shared by the C++ side and the shaders (std140; every member is 16-byte
// aligned so C++ and GLSL layouts agree; the C++ side static_asserts the sizes).
#ifndef TYNDALL_SHARED_CONSTANTS_H
#define TYNDALL_SHARED_CONSTANTS_H

#include "common/cpp_glsl.h"

TYN_BEGIN

TYN_CONST uint TYN_MAX_MEDIUM_COMPONENTS = 4u;
TYN_CONST uint TYN_MAX_SHADOW_MAPS = 6u;

TYN_CONST uint TYN_LIGHT_DIRECTIONAL = 0u;
TYN_CONST uint TYN_LIGHT_SPOT = 1u;
TYN_CONST uint TYN_LIGHT_POINT = 2u;

TYN_CONST uint TYN_PHASE_ISOTROPIC = 0u;
TYN_CONST uint TYN_PHASE_RAYLEIGH = 1u;
TYN_CONST uint TYN_PHASE_HENYEY_GREENSTEIN = 2u;
TYN_CONST uint TYN_PHASE_CORNETTE_SHANKS = 3u;

// Workgroup size of the per-pixel compute passes (8×8 suits lavapipe's 8-wide subgroups and GPUs).
TYN_CONST uint TYN_PIXEL_GROUP_SIZE = 8u;
// Threads that share one view ray's walk where only a few pixels are marched
// (common/split_march.glsl): a power of two; 64 parts of a ray across a 2048² map walk about 64
// texels each.
TYN_CONST uint TYN_SPLIT_MARCH_PARTS = 64u;

struct FrameConstants {
  mat4 view_to_world;                        // camera position in column 3
  mat4 clip_to_view;                         // inverse of the host's projection
  mat4 world_to_shadow[TYN_MAX_SHADOW_MAPS]; // world → shadow clip (depth [0,1])
  vec4 light_position;    // xyz: spot/point position (scene units)
  vec4 light_direction;   // xyz: unit direction the light travels; w: cos(outer cone)
  vec4 light_radiance;    // rgb: colour · intensity; w: cos(inner cone)
  vec4 extinction;        // rgb: σ_t = Σ (σ_s + σ_a) per scene unit
  vec4 scattering[TYN_MAX_MEDIUM_COMPONENTS];  // rgb: σ_s of a component; w: its g
  uvec4 phase_type[TYN_MAX_MEDIUM_COMPONENTS]; // x: TYN_PHASE_* of a component
  vec4 depth_params;      // x: NDC depth of the near plane; y: of the far plane (sky);
                          // z: 1 if the far plane is at infinity; w: sky distance then
  uvec4 counts;           // x: light type; y: medium components; z: shadow maps; w: shadow map size
  uvec4 extent;           // xy: output extent in pixels; z: unused (0; a frame without
                          // in-scattering runs no technique); w: 1 when a light-colour texture
                          // is bound (common/light_color.glsl)
};

TYN_END

#endif
