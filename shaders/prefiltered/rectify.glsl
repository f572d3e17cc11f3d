// Rectification (klehm2014 §4, peters2017 §5.1.1, §5.2): one thread per texel of the rectified map.
// A texel is a light ray (constant r and φ, or x and η for the projective map); its occluder is
// looked up in the host's shadow map and its depth re-expressed as the rectified depth of the map
// (inclination θ, or ζ = h/x), in which every view ray has one constant depth.
//   - plain: the host texel the light ray crosses (nearest), one depth;
//   - filtered resampling (peters2017 §5.2): a bilinear sample of the moment shadow map, turned into
//     two depths and weights by Algorithm 2 (tyn_two_depths_from_moments), each re-projected.
// The texel then stores the representation of that distribution (storage_variants.glsl), with the
// row depth bounds on the range of the host depths it was made from, and with the texel walk the
// distribution itself: its two depths and the second's weight (depth_bounds.h).
// Included by rectify_<variant>.comp after defining TYN_PF_BASIS.

#include "prefiltered/prefiltered_common.glsl"
#include "prefiltered/storage_variants.glsl"

layout(local_size_x = TYN_PF_TEXEL_GROUP, local_size_y = TYN_PF_TEXEL_GROUP) in;

// A light ray beyond every occluder (lit along its whole length).
const float TYN_PF_NO_OCCLUDER = 1.0;

// The rectified depth of host depth `host` on the light ray whose clip depth is depth0 at height 0,
// or no occluder for a host depth at or beyond `clear_from` (the clear value, 1, less any tolerance).
float tyn_pf_occluder_depth(float host, float clear_from, float radial, float depth0, float depth_per_h) {
  return host < clear_from ? tyn_pf_rectified_depth(radial, (host - depth0) / depth_per_h) : TYN_PF_NO_OCCLUDER;
}

void main() {
  uvec2 texel = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(texel, uvec2(pf.map_columns, pf.map_rows)))) return;
  vec2 tc = (vec2(texel) + 0.5) / vec2(uvec2(pf.map_columns, pf.map_rows));

  float radial;
  vec3 offset = tyn_pf_light_ray_offset(tc, radial);
  // The host map is orthographic along the light: clip x, y are constant along the light ray and
  // clip depth is affine in the light-frame height h, depth(h) = depth0 + h · depth_per_h.
  vec4 clip0 = frame.world_to_shadow[0] * vec4(pf.nonlinear.origin + offset, 1.0);
  float depth_per_h = (frame.world_to_shadow[0] * vec4(pf.nonlinear.axis_z, 0.0)).z;
  vec2 uv = clip0.xy / clip0.w * 0.5 + 0.5;

  vec2 depths = vec2(TYN_PF_NO_OCCLUDER);
  vec2 weights = vec2(1.0, 0.0);
  // The row depth bounds' range of this texel: the depths its value is made of.
  vec2 bounds = vec2(TYN_PF_NO_OCCLUDER);
  // Outside the host map's square there is no occluder information: lit (as the Reference).
  bool inside = all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0))) &&
                abs(depth_per_h) > 0.0;
  if (inside) {
    if (pf.filtered_resampling != 0u) {
      vec4 b = tyn_dequantize_moments4_64(texture(moment_shadow_map, uv));
      vec4 two = tyn_two_depths_from_moments(b.xyz);
      vec2 host = clamp(two.xy * 0.5 + 0.5, 0.0, 1.0);  // signed → [0, 1] host depth
      weights = two.zw;
      for (int k = 0; k < 2; ++k) {
        depths[k] = tyn_pf_occluder_depth(host[k], 1.0 - TYN_PF_CLEAR_DEPTH_TOLERANCE, radial, clip0.z, depth_per_h);
      }
      if (tyn_pf_depth_bounds()) {
        // The bilinear lookup mixes these 2 × 2 host texels (the moment map has one texel per
        // host texel), so their depths bound the distribution it stands for. Not Algorithm 2's
        // two depths: from 16-bit moments of one surface it returns a second depth of tiny
        // weight anywhere the rounding puts it, which would make every row look mixed.
        vec4 quad = textureGather(shadow_maps[0], uv, 0);
        vec2 host_range = vec2(min(min(quad.x, quad.y), min(quad.z, quad.w)),
                               max(max(quad.x, quad.y), max(quad.z, quad.w)));
        bounds = tyn_depth_bounds_empty();
        for (int k = 0; k < 2; ++k) {
          float d = tyn_pf_occluder_depth(host_range[k], 1.0, radial, clip0.z, depth_per_h);
          bounds = tyn_depth_bounds_merge(bounds, vec2(d));
        }
      }
    } else {
      int size = int(pf.host_map_size);
      ivec2 host_texel = clamp(ivec2(floor(uv * float(size))), ivec2(0), ivec2(size - 1));
      float host = texelFetch(shadow_maps[0], host_texel, 0).r;
      // A texel at the clear value (1) has no occluder (as in the Reference's walk).
      depths.x = tyn_pf_occluder_depth(host, 1.0, radial, clip0.z, depth_per_h);
      bounds = depths.xx;
    }
  }
  if (tyn_pf_depth_bounds()) {
    imageStore(depth_bounds_texels, ivec2(texel), vec4(tyn_depth_bounds_quantize(bounds), 0.0, 0.0));
  }
  if (tyn_pf_texel_walk()) imageStore(texel_depths, ivec2(texel), vec4(depths, weights.y, 0.0));
  for (uint slot = 0u; slot < TYN_PF_SLOTS; ++slot) {
    tyn_pf_store_rectified(ivec2(texel), slot, tyn_pf_slot(slot, depths, weights));
  }
}
