#version 460
// Unwarp (engelhardt2010 §4.3, yusov2013): every pixel interpolates L_in from the two epipolar
// slices it lies between and the two samples around it on each, bilinearly, keeping only taps
// whose view-ray length is close to the pixel's (a bilateral filter on depth). A pixel left
// with too little weight (a depth break no sample saw), or whose two slices disagree by more than
// the slice-contrast threshold (a shaft or colour edge between them, narrower than their spacing),
// is appended to the fix-up list. T is exact per pixel.
#extension GL_GOOGLE_include_directive : require
#include "epipolar/epipolar_common.glsl"

layout(local_size_x = TYN_PIXEL_GROUP_SIZE, local_size_y = TYN_PIXEL_GROUP_SIZE) in;

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(pixel, frame.extent.xy))) return;
  vec2 extent = tyn_output_extent();
  vec2 ndc = tyn_ndc_from_pixel(vec2(pixel) + 0.5, extent);
  float depth = texelFetch(depth_buffer, ivec2(pixel), 0).r;
  float distance = tyn_view_distance(ndc, depth);
  imageStore(out_transmittance, ivec2(pixel), vec4(exp(-frame.extinction.rgb * distance), 1.0));
  if (frame.extent.z == 0u) {
    imageStore(out_scattering, ivec2(pixel), vec4(0.0));
    return;
  }

  uint slices = epipolar.counts.x;
  float density = epipolar.params.x;
  float slice_coordinate = tyn_slice_coordinate(epipolar.epipole, ndc, slices, extent);
  uvec2 pair = tyn_slice_pair(slice_coordinate, slices);
  float second = fract(slice_coordinate);

  vec3 slice_sum[2] = vec3[2](vec3(0.0), vec3(0.0));
  float slice_weight_sum[2] = float[2](0.0, 0.0);
  for (int s = 0; s < 2; ++s) {
    uint slice = s == 0 ? pair.x : pair.y;
    float slice_weight = s == 0 ? 1.0 - second : second;
    vec4 end_points = imageLoad(slice_end_points, ivec2(slice, 0));
    uint count = tyn_slice_sample_count(end_points, extent, epipolar.counts.y, density,
                                        epipolar.counts.z != 0u);
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
    for (int t = 0; t < 2; ++t) {
      float index = t == 0 ? k0 : k1;
      float tap_weight = slice_weight * (t == 0 ? 1.0 - along : along);
      vec4 coordinates = imageLoad(epipolar_coordinates, ivec2(int(index), int(slice)));
      // Taps on another surface than the pixel's do not count: relative ray-length difference.
      bool same_surface = abs(coordinates.z - distance) <= epipolar.params.y * distance;
      if (coordinates.w < 0.5 || !same_surface || tap_weight <= 0.0) continue;
      vec3 value = tap_weight * imageLoad(epipolar_scattering, ivec2(int(index), int(slice))).rgb;
      slice_sum[s] += value;
      slice_weight_sum[s] += tap_weight;
    }
  }
  vec3 sum = slice_sum[0] + slice_sum[1];
  float weight_sum = slice_weight_sum[0] + slice_weight_sum[1];
  // Both slices seen: their interpolated L_in, compared channel by channel against the larger.
  bool slice_edge = false;
  if (epipolar.refinement.z < 1.0 && slice_weight_sum[0] > 0.0 && slice_weight_sum[1] > 0.0) {
    vec3 a = slice_sum[0] / slice_weight_sum[0];
    vec3 b = slice_sum[1] / slice_weight_sum[1];
    slice_edge = any(greaterThan(abs(a - b), epipolar.refinement.z * max(max(a, b), vec3(1e-30))));
  }

  // Next to the projected light, in-scattering varies faster than any sample spacing can follow
  // (1/d² of a local light, the phase peak): that block is ray-marched per pixel (klehm2014
  // Fig. 8). The light may sit just off screen and still have such pixels; at infinity it has none.
  bool near_epipole = epipolar.epipole.z > 1e-6 &&
                      length((ndc - tyn_epipole_ndc(epipolar.epipole)) * 0.5 * extent) <= epipolar.params.w;
  if (weight_sum >= epipolar.params.z && !near_epipole && !slice_edge) {
    imageStore(out_scattering, ivec2(pixel), vec4(sum / weight_sum, 0.0));
  } else {
    uint slot = atomicAdd(fixup_count, 1u);
    fixup_pixels[slot] = pixel.x | (pixel.y << 16);
    imageStore(out_scattering, ivec2(pixel), vec4(0.0));
  }
}
