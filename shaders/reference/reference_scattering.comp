#version 460
// Reference technique: per-pixel brute force (common/texel_walk.glsl; its only hook the translucent
// layers, integrated exactly). Writes L_in for the composite pass, which computes the view ray's
// transmittance itself.
#extension GL_GOOGLE_include_directive : require

#include "common/shared_constants.h"

layout(local_size_x = TYN_PIXEL_GROUP_SIZE, local_size_y = TYN_PIXEL_GROUP_SIZE) in;

layout(set = 0, binding = TYN_BINDING_FRAME, std140) uniform FrameBlock { FrameConstants frame; };
layout(set = 0, binding = TYN_BINDING_DEPTH) uniform sampler2D depth_buffer;
layout(set = 0, binding = TYN_BINDING_SHADOW_MAPS) uniform sampler2D shadow_maps[TYN_MAX_SHADOW_MAPS];
layout(set = 0, binding = TYN_REFERENCE_BINDING_OUT_SCATTERING, rgba32f) uniform writeonly image2D out_scattering;
layout(set = 0, binding = TYN_REFERENCE_BINDING_LIGHT_COLOR) uniform sampler2D light_color;
layout(set = 0, binding = TYN_REFERENCE_BINDING_TRANSLUCENT_LAYERS) uniform sampler2DArray translucent_layers[TYN_MAX_SHADOW_MAPS];
layout(set = 0, binding = TYN_REFERENCE_BINDING_TRANSLUCENT_OVERFLOW, std430) buffer TranslucentOverflow {
  uint translucent_overflow;
};

#define TYN_WALK_TRANSLUCENT
#include "common/view_ray.glsl"
#include "common/translucent_layers.glsl"
#include "common/texel_walk.glsl"

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(pixel, frame.output_extent))) return;

  float depth = texelFetch(depth_buffer, ivec2(pixel), 0).r;
  TynViewRay ray = tyn_view_ray(pixel, depth);
  vec3 in_scattering = tyn_reference_in_scattering(ray.origin, ray.direction, ray.surface_distance);
  imageStore(out_scattering, ivec2(pixel), vec4(in_scattering * frame.target_scale, 0.0));
  if (tyn_translucent_overflowed) atomicOr(translucent_overflow, 1u);
}
