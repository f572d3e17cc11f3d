#version 460
// Unwarp (engelhardt2010 §4.3, yusov2013): every pixel interpolates L_in from the two epipolar
// slices it lies between and the two samples around it on each, bilinearly, keeping only taps
// on the pixel's surface (a bilateral filter on depth, against the pixel's plane). On a slice
// where only one of the two is, the pixel extrapolates along the slice from that sample and the
// next one on its surface. A pixel left with too little weight (a depth break no sample saw), or
// whose two slices disagree by more than the slice-contrast threshold (a shaft or colour edge
// between them, narrower than their spacing), or on a surface so grazing in a local light's beam
// that its ray length changes by more than the bilateral tolerance within a pixel while its taps
// differ (TYN_GRAZING_CONTRAST), is appended to the fix-up list. A pixel off the
// slices' arc has L_in = 0. T is the composite's (exact per pixel). The samples that were not
// ray-marched are interpolated along their slice here, from the ones that were; the last workgroup
// sizes the fix-up.
#extension GL_GOOGLE_include_directive : require
#include "epipolar/epipolar_common.glsl"
#include "epipolar/dispatch_chain.glsl"

// The fix-up's shape (fixup.comp): a thread per pixel, or a workgroup per pixel.
layout(constant_id = 3) const bool TYN_FIXUP_SERIAL = false;

layout(local_size_x = TYN_PIXEL_GROUP_SIZE, local_size_y = TYN_PIXEL_GROUP_SIZE) in;

// Whether an epipolar sample lies on the pixel's surface: its view-ray length against that of
// the pixel's plane (epipolar_geometry.h) at the sample's position, within the bilateral threshold
// of the pixel's own ray length. Against the pixel's ray length alone, samples one pixel away on
// ground seen at a grazing angle (5-15% per pixel on spot-lamp's far ground) were rejected: with
// improved placement's one-pixel spacing the pixel then kept only the sample on its far side
// (always the same side over many pixels) and took its value, where L_in changes by 2-5% per pixel.
// `tolerance_scale` is the length the threshold is relative to (tyn_surface_tolerance_scale).
bool tyn_on_pixel_surface(vec4 coordinates, vec2 pixel_centre, float depth, vec2 slopes, float tolerance_scale) {
  if (coordinates.w < 0.5) return false;
  vec2 offset = tyn_pixel_from_ndc(coordinates.xy, tyn_output_extent()) - pixel_centre;
  float expected = tyn_view_distance(coordinates.xy, tyn_epipolar_depth_at(depth, slopes, offset));
  return abs(coordinates.z - expected) <= epipolar.bilateral_depth_threshold * tolerance_scale;
}

// The bilateral threshold is relative to the pixel's ray length, and next to a spot or point light
// to the surface's distance d from the light if that is shorter: a ray that ends Δs further there
// gathers about Δs/d more of its L_in (the light's 1/d² fall-off), so that a leaf a few per cent
// behind the pixel's, next to the lamp, is not the pixel's surface.
float tyn_surface_tolerance_scale(vec2 ndc, float distance) {
  if (frame.light_type == TYN_LIGHT_DIRECTIONAL) return distance;
  vec3 surface = frame.view_to_world[3].xyz + tyn_view_direction(ndc) * distance;
  return min(distance, length(surface - frame.light_position));
}

// L_in of sample k of a slice (yusov2013's interpolation along the slices): its own when it was
// ray-marched, else linear between its two interpolation sources, which lie on its surface (a depth
// break between them would have made a ray-marched sample).
vec3 tyn_sample_in_scattering(int k, int slice) {
  uint source = imageLoad(interpolation_source, ivec2(k, slice)).x;
  uint left = source & 0xffffu;
  uint right = source >> 16;
  if (left == uint(k)) return imageLoad(epipolar_scattering, ivec2(k, slice)).rgb;
  vec3 a = imageLoad(epipolar_scattering, ivec2(int(left), slice)).rgb;
  vec3 b = imageLoad(epipolar_scattering, ivec2(int(right), slice)).rgb;
  float w = float(uint(k) - left) / float(max(right - left, 1u));
  return mix(a, b, w);
}

// Whether two L_in differ in any channel by more than `threshold` of the larger.
bool tyn_epipolar_contrast(vec3 a, vec3 b, float threshold) {
  return any(greaterThan(abs(a - b), threshold * max(max(a, b), vec3(1e-30))));
}

// How much two taps on a grazing surface in a local light's beam may differ (of the larger) and
// still be interpolated: across the beam's footprint edge L_in changes by tens of per cent within
// a sample spacing, while along the surface elsewhere it changes by a few.
const float TYN_GRAZING_CONTRAST = 0.1;

// `target_pixel`: the L_in target's; its depth, ray and position are those of the output pixel it
// stands for (at reduced resolution one of its block's), in output pixels like the slices. True
// when the pixel goes to the fix-up (its L_in stored as 0 until then).
bool tyn_unwarp(uvec2 target_pixel) {
  uvec2 pixel = tyn_output_pixel(target_pixel);
  vec2 extent = tyn_output_extent();
  vec2 ndc = tyn_ndc_from_pixel(vec2(pixel) + 0.5, extent);
  float depth = texelFetch(depth_buffer, ivec2(pixel), 0).r;
  float distance = tyn_view_distance(ndc, depth);
  float tolerance_scale = tyn_surface_tolerance_scale(ndc, distance);

  vec2 pixel_centre = vec2(pixel) + 0.5;
  vec2 slopes = tyn_epipolar_depth_slopes(ivec2(pixel), depth);
  uint slices = epipolar.slice_count;
  float density = epipolar.epipole_density;
  // Next to the projected light, in-scattering varies faster than any sample spacing can follow
  // (1/d² of a local light, the phase peak): that block is ray-marched per pixel (klehm2014
  // Fig. 8).
  bool near_epipole = tyn_near_epipole(ndc, epipolar.epipole_block_radius);
  float slice_coordinate = tyn_arc_slice_coordinate_of(epipolar.epipole, ndc, slices, vec2(epipolar.arc_start, epipolar.arc_length), extent);
  if (slice_coordinate < 0.0) {
    if (!near_epipole) {
      // Off the slices' arc: the pixel's epipolar plane misses the lit volume (slice_arc.cpp).
      imageStore(out_scattering, ivec2(target_pixel), vec4(0.0));
      return false;
    }
    slice_coordinate = 0.0;  // interpolated from slice 0, then fixed up with the epipole block
  }
  uvec2 pair = tyn_slice_pair(slice_coordinate, slices);
  float second = fract(slice_coordinate);

  bool along_edge = false;
  vec3 slice_sum[2] = vec3[2](vec3(0.0), vec3(0.0));
  float slice_weight_sum[2] = float[2](0.0, 0.0);
  for (int s = 0; s < 2; ++s) {
    uint slice = s == 0 ? pair.x : pair.y;
    float slice_weight = s == 0 ? 1.0 - second : second;
    vec4 end_points = imageLoad(slice_end_points, ivec2(slice, 0));
    uint count = tyn_slice_sample_count(end_points, extent, epipolar.samples_per_slice, density,
                                        epipolar.improved_placement != 0u);
    if (count == 0u || slice_weight <= 0.0) continue;
    float fraction = tyn_slice_fraction(end_points, ndc);
    // A pixel before the slice's entry (the slice enters the screen further out, which happens
    // when the epipole is just off screen) would extrapolate from samples it does not lie between.
    float length_pixels = length((end_points.zw - end_points.xy) * 0.5 * extent);
    if (-fraction * length_pixels > 1.0) continue;
    float k = tyn_sample_coordinate(fraction, count, density);
    float k0 = floor(k);
    float k1 = min(k0 + 1.0, float(count - 1u));
    float along = k - k0;
    bool on_surface[2];
    vec3 values[2];
    vec4 taps[2];
    for (int t = 0; t < 2; ++t) {
      float index = t == 0 ? k0 : k1;
      float tap_weight = t == 0 ? 1.0 - along : along;
      vec4 coordinates = imageLoad(epipolar_coordinates, ivec2(int(index), int(slice)));
      on_surface[t] = tap_weight > 0.0 && tyn_on_pixel_surface(coordinates, pixel_centre, depth, slopes, tolerance_scale);
      values[t] = on_surface[t] ? tyn_sample_in_scattering(int(index), int(slice)) : vec3(0.0);
      taps[t] = coordinates;
    }
    if (on_surface[0] && on_surface[1]) {
      slice_sum[s] = slice_weight * mix(values[0], values[1], along);
      slice_weight_sum[s] = slice_weight;
      // A shaft edge between the two samples along the slice: the pixel's side of it is unknown,
      // so the interpolation errs by up to the jump. The slices crowd together near the epipole
      // and agree there, so the comparison across slices below cannot see it; next to a local light
      // the jump is many times the frame's mean L_in and such pixels dominate the error.
      if (epipolar.slice_contrast_threshold < 1.0 && along > 0.0 && along < 1.0 &&
          tyn_epipolar_contrast(values[0], values[1], epipolar.slice_contrast_threshold)) {
        along_edge = true;
      }
      // Ground seen at a grazing angle inside a local light's beam: both taps lie on the pixel's
      // plane, but its ray length changes by more than the bilateral tolerance within one pixel,
      // and L_in, which grows with the ray's length there, can change many-fold between the taps
      // (the beam's footprint on a distant floor is a pixel or two high). Linear interpolation of
      // that curve is off by its whole curvature, along the whole row; such a pixel is ray-marched.
      // Per pixel, not per tap, so that sparser samples on an ordinary floor do not qualify.
      if (frame.light_type != TYN_LIGHT_DIRECTIONAL && along > 0.0 && along < 1.0) {
        vec2 tap_offset = tyn_pixel_from_ndc(taps[1].xy, extent) - tyn_pixel_from_ndc(taps[0].xy, extent);
        float tap_spacing = max(length(tap_offset), 1.0);
        if (abs(taps[0].z - taps[1].z) > epipolar.bilateral_depth_threshold * tolerance_scale * tap_spacing &&
            tyn_epipolar_contrast(values[0], values[1], TYN_GRAZING_CONTRAST)) {
          along_edge = true;
        }
      }
    } else if (on_surface[0] || on_surface[1]) {
      // A depth break between the two samples: the pixel has a sample of its surface on one side
      // only, up to one sample spacing away. Its value alone would be off by L_in's gradient times
      // that distance, always on the same side along a silhouette, which matters next to a spot
      // light (L_in changing by several percent per pixel). The next sample beyond it, when on the
      // same surface too, gives the gradient along the slice: linear extrapolation, as the
      // interpolation on the other side of the pixel would have been linear. Its weight stays
      // the one sample's, so a pixel far from it still goes to the fix-up.
      int t = on_surface[0] ? 0 : 1;
      float index = t == 0 ? k0 : k1;
      float beyond = t == 0 ? k0 - 1.0 : k1 + 1.0;
      float reach = abs(k - index);  // in sample spacings
      vec3 value = values[t];
      if (reach > 0.0 && beyond >= 0.0 && beyond < float(count)) {
        vec4 coordinates = imageLoad(epipolar_coordinates, ivec2(int(beyond), int(slice)));
        if (tyn_on_pixel_surface(coordinates, pixel_centre, depth, slopes, tolerance_scale)) {
          vec3 next = tyn_sample_in_scattering(int(beyond), int(slice));
          value = max(value + (value - next) * reach, vec3(0.0));
        }
      }
      float tap_weight = slice_weight * (t == 0 ? 1.0 - along : along);
      slice_sum[s] = tap_weight * value;
      slice_weight_sum[s] = tap_weight;
    }
  }
  vec3 sum = slice_sum[0] + slice_sum[1];
  float weight_sum = slice_weight_sum[0] + slice_weight_sum[1];
  // Both slices seen: their interpolated L_in, compared channel by channel against the larger.
  bool slice_edge = false;
  if (epipolar.slice_contrast_threshold < 1.0 && slice_weight_sum[0] > 0.0 && slice_weight_sum[1] > 0.0) {
    vec3 a = slice_sum[0] / slice_weight_sum[0];
    vec3 b = slice_sum[1] / slice_weight_sum[1];
    slice_edge = tyn_epipolar_contrast(a, b, epipolar.slice_contrast_threshold);
  }
  slice_edge = slice_edge || along_edge;

  // Negated so that a NaN weight goes to the fix-up too.
  bool fixup = !(weight_sum >= epipolar.fixup_weight_threshold) || near_epipole || slice_edge;
  imageStore(out_scattering, ivec2(target_pixel), fixup ? vec4(0.0) : tyn_target_value(sum / weight_sum));
  return fixup;
}

// Sizes the indirect fix-up dispatch: one workgroup per flagged pixel when the fix-up splits each
// walk over its workgroup, one thread per listed quad when it does not
// (fixup.comp), up to the smallest maxComputeWorkGroupCount[0] Vulkan guarantees (the fix-up and
// its debug view loop over the rest): zero groups, and so no work, when none was flagged.
// Where a directional light's frame has a block image (EpipolarConstants::shadow_block_side) it also
// sizes the shadow-map blocks pass (shadow_blocks.comp, one z slice per cascade): the blocks read
// the whole maps, a cost the fix-up's block steps repay only when it walks enough rays
// (TYN_EPIPOLAR_SHADOW_BLOCK_PIXELS per map); otherwise zero groups, and the fix-up walks texel by
// texel or in steps. A walked light's blocks (point) are built before the march, which walks every
// sample: the groups written here for one are not read.
void tyn_size_fixup() {
  uint quads = atomicAdd(fixup_count, 0u);
  uint flagged = atomicAdd(fixup_pixel_count, 0u);
  // Split: as many groups as flagged pixels, each striding over the quads' four slots per entry,
  // so that few groups find no pixel to walk (an empty group still costs its start on a CPU driver).
  uint groups = TYN_FIXUP_SERIAL ? (quads + TYN_EPIPOLAR_FIXUP_GROUP - 1u) / TYN_EPIPOLAR_FIXUP_GROUP : flagged;
  fixup_groups[0] = min(groups, TYN_EPIPOLAR_MAX_GROUPS);
  fixup_groups[1] = 1u;
  fixup_groups[2] = 1u;
  uint side = epipolar.shadow_block_side;
  bool blocks = side != 0u && flagged * TYN_EPIPOLAR_SHADOW_BLOCK_PIXELS >= frame.shadow_map_size * frame.shadow_map_count;
  uint block_groups = (side + TYN_EPIPOLAR_SHADOW_BLOCK_GROUP - 1u) / TYN_EPIPOLAR_SHADOW_BLOCK_GROUP;
  shadow_block_groups[0] = blocks ? block_groups : 0u;
  shadow_block_groups[1] = blocks ? block_groups : 0u;
  shadow_block_groups[2] = frame.shadow_map_count;
}

// A thread per 2×2 quad of the L_in target, so that it lists the quad's flagged pixels in one entry
// without sharing them across threads.
void main() {
  uvec2 quad = gl_GlobalInvocationID.xy;
  uint mask = 0u;
  for (uint bit = 0u; bit < 4u; ++bit) {
    uvec2 pixel = quad * 2u + uvec2(bit & 1u, bit >> 1);
    if (all(lessThan(pixel, frame.target_extent)) && tyn_unwarp(pixel)) mask |= 1u << bit;
  }
  if (mask != 0u) {
    fixup_quads[atomicAdd(fixup_count, 1u)] = tyn_fixup_quad_entry(quad, mask);
    atomicAdd(fixup_pixel_count, bitCount(mask));
  }
  if (tyn_last_group(TYN_DONE_UNWARP)) tyn_size_fixup();
}
