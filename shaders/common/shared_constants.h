// The constant blocks shared by the C++ side and the shaders (std140), and the named values both
// sides use in them.
#ifndef TYNDALL_SHARED_CONSTANTS_H
#define TYNDALL_SHARED_CONSTANTS_H

#include "common/cpp_glsl.h"

TYN_BEGIN

TYN_CONST uint TYN_MAX_MEDIUM_COMPONENTS = 4u;
TYN_CONST uint TYN_MAX_SHADOW_MAPS = 6u;
TYN_CONST uint TYN_MAX_CASCADES = 4u;  // a directional light's cascaded shadow maps
TYN_CONST uint TYN_MAX_TRANSLUCENT_LAYERS = 8u;  // depth-peeled translucent layers per map

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

// Bindings that every pass's descriptor set starts with (the composite's has no shadow maps).
TYN_CONST uint TYN_BINDING_FRAME = 0u;        // FrameConstants (uniform buffer)
TYN_CONST uint TYN_BINDING_DEPTH = 1u;        // the host's depth buffer
TYN_CONST uint TYN_BINDING_SHADOW_MAPS = 2u;  // TYN_MAX_SHADOW_MAPS shadow maps
// The Reference's (reference/reference_scattering.comp, reference_technique.cpp).
TYN_CONST uint TYN_REFERENCE_BINDING_OUT_SCATTERING = 3u;
TYN_CONST uint TYN_REFERENCE_BINDING_LIGHT_COLOR = 4u;
TYN_CONST uint TYN_REFERENCE_BINDING_TRANSLUCENT_LAYERS = 5u;    // TYN_MAX_SHADOW_MAPS 2D arrays
TYN_CONST uint TYN_REFERENCE_BINDING_TRANSLUCENT_OVERFLOW = 6u;  // one uint: 1 once a ray met one
TYN_CONST uint TYN_REFERENCE_BINDING_COUNT = 7u;
// The composite's and its T AOV's (composite/, composite_pass.cpp): L_in read, or T written.
TYN_CONST uint TYN_COMPOSITE_BINDING_TARGET = 2u;
TYN_CONST uint TYN_COMPOSITE_BINDING_COUNT = 3u;
// The compute composite's back buffer (storage, read and written in place).
TYN_CONST uint TYN_COMPOSITE_BINDING_COLOR = 3u;  // also the L_in AOV upsample's output
TYN_CONST uint TYN_COMPOSITE_COMPUTE_BINDING_COUNT = 4u;
// The light sum's (composite/light_sum.comp, light_sum_pass.cpp): an additional light's L_in added
// to the frame's.
TYN_CONST uint TYN_LIGHT_SUM_BINDING_SUM = 0u;
TYN_CONST uint TYN_LIGHT_SUM_BINDING_LIGHT = 1u;
TYN_CONST uint TYN_LIGHT_SUM_BINDING_COUNT = 2u;

// One component of the medium (std140: 32 bytes, C++ the same).
struct MediumComponentConstants {
  vec3 scattering;   // σ_s per scene unit, RGB
  float g;           // anisotropy of its phase function (Henyey–Greenstein, Cornette–Shanks)
  uint phase_type;   // TYN_PHASE_*
  uint pad0;
  uint pad1;
  uint pad2;
};

// The frame's camera, light and medium, bound as a uniform buffer by every pass. Scalars are
// grouped in 16-byte rows (a vec3 and a scalar share one), so std140 and C++ place every member at
// the same offset (frame_setup.cpp static_asserts them).
struct FrameConstants {
  mat4 view_to_world;                        // camera position in column 3
  mat4 clip_to_view;                         // inverse of the host's projection
  mat4 world_to_shadow[TYN_MAX_SHADOW_MAPS]; // world → shadow clip (depth [0,1])
  vec3 light_position;     // spot/point position (scene units)
  // The L_in targets hold L_in · target_scale, a power of two that brings the frame's typical L_in
  // near 1 (frame_setup.cpp, scatteringTargetScale): half floats keep their 2^-11 relative
  // precision from 2^-14 to 2^15 times it whatever the lights' units. Every light's is the frame's.
  float target_scale;
  vec3 light_direction;    // unit direction the light travels (directional, spot)
  float cos_outer_cone;    // spot: cos of the outer half-angle (falloff 0 outside)
  vec3 light_radiance;     // colour · intensity
  float cos_inner_cone;    // spot: cos of the inner half-angle (falloff 1 inside)
  vec3 extinction;         // σ_t = Σ (σ_s + σ_a) per scene unit
  float target_unscale;    // 1 / target_scale (exact: a power of two)
  MediumComponentConstants medium[TYN_MAX_MEDIUM_COMPONENTS];
  float near_ndc_depth;    // NDC depth of the near plane
  float far_ndc_depth;     // NDC depth of the far plane (the sky)
  uint far_at_infinity;    // 1: the far plane is at infinity
  float sky_distance;      // with far_at_infinity: the distance of the sky (scene units)
  uint light_type;         // TYN_LIGHT_*
  uint medium_component_count;
  uint shadow_map_count;   // 1 (spot), 1..4 cascades (directional) or 6 (point)
  uint shadow_map_size;    // texels along each side of every map
  uvec2 output_extent;     // pixels
  uint translucent_layer_count;  // 0, or depth-peeled translucent layers per map (texel_walk.glsl)
  uint has_light_color;    // 1 when a light-colour texture is bound (common/light_color.glsl)
  // The L_in target (ScatteringResolution): target pixel p stands for output pixel
  // p · target_stride + target_offset (view_ray.glsl's tyn_output_pixel); stride 1 at full resolution.
  uvec2 target_extent;
  uint target_stride;      // 1, 2 or 4
  uint target_offset;      // target_stride / 2: the block's pixel right and below its centre
  // A directional light's cascades (shadow_map_count > 1): cascade i serves view depths up to
  // cascade_far[i] (i < count − 1; the last serves everything beyond). View depth of a world point
  // p: dot(view_depth_axis.xyz, p) + view_depth_axis.w.
  vec4 cascade_far;
  vec4 view_depth_axis;
};

TYN_END

#endif
