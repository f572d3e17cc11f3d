#version 460
// The moment shadow map filtered resampling reads (peters2017 §5.2, Appendix D.1): four moments of
// the signed depth z = 2d − 1 of the host's shadow map, Θ4*-quantized into RGBA16_UNORM (§2.4).
// Footprint: one host texel per moment texel (the host map is single-sampled, so the "custom
// resolve" has one sample to average); the filtering is the bilinear lookup of the resampling,
// whose tent covers 2 × 2 host texels: the least that turns a silhouette's staircase into a ramp
// while keeping shafts as sharp as the Reference's texel walk (docs/PREFILTERED.md). A cleared
// texel (d = 1, no occluder) has z = 1, the far end of the signed range.
#extension GL_GOOGLE_include_directive : require

#include "prefiltered/prefiltered_common.glsl"
#include "prefiltered/moments.h"

layout(local_size_x = TYN_PF_TEXEL_GROUP, local_size_y = TYN_PF_TEXEL_GROUP) in;

layout(set = 0, binding = TYN_PF_BINDING_MOMENT_MAP_STORAGE, rgba16) uniform writeonly image2D moment_map_out;

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  int size = int(pf.host_map_size);
  if (any(greaterThanEqual(texel, ivec2(size)))) return;
  float z = tyn_signed_depth(texelFetch(shadow_maps[0], texel, 0).r);
  imageStore(moment_map_out, texel, tyn_quantize_moments4_64(tyn_moments4(z)));
}
