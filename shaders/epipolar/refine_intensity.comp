#version 460
// Second round of sample refinement, on the values of the first: an interval between neighbouring
// ray-marched samples whose L_in differ by more than the threshold (relative to the larger) gets
// TYN_EPIPOLAR_SUBDIVISIONS − 1 more ray-marching samples, evenly spaced. Depth breaks catch where a
// surface ends; this catches where the light does: a shadow boundary or a spot cone's edge crossing
// the slice, and the fast falloff near a local light, which linear interpolation over the initial
// step would flatten. (engelhardt2010 §4.2 rejects an intensity criterion as the only one, since it
// can miss a shadow between two samples; here it only adds samples to the depth-based ones.)
// One thread per slice: it lists the new samples and updates the interpolation sources.
#extension GL_GOOGLE_include_directive : require
#include "epipolar/epipolar_common.glsl"

layout(local_size_x = TYN_EPIPOLAR_SLICE_GROUP) in;

bool tyn_interpolation_suspect(vec3 a, vec3 b) {
  vec3 larger = max(a, b);
  vec3 difference = abs(a - b);
  float scale = max(larger.r, max(larger.g, larger.b));
  return max(difference.r, max(difference.g, difference.b)) > epipolar.refinement.y * scale;
}

// Spacing of the samples added between ray-marched samples k0 < k1 (≥ 1).
uint tyn_subdivision_step(uint k0, uint k1) { return max((k1 - k0) / TYN_EPIPOLAR_SUBDIVISIONS, 1u); }

// The ray-marched sample after k0 (the right source of k0 + 1).
uint tyn_next_marched(uint k0, uint slice) { return imageLoad(interpolation_source, ivec2(k0 + 1u, slice)).x >> 16; }

bool tyn_subdivided(uint k0, uint k1, uint slice) {
  if (k1 - k0 < 2u) return false;
  return tyn_interpolation_suspect(imageLoad(epipolar_scattering, ivec2(k0, slice)).rgb,
                                   imageLoad(epipolar_scattering, ivec2(k1, slice)).rgb);
}

void main() {
  uint slice = gl_GlobalInvocationID.x;
  if (slice >= epipolar.counts.x) return;
  vec4 end_points = imageLoad(slice_end_points, ivec2(slice, 0));
  uint count = tyn_slice_sample_count(end_points, tyn_output_extent(), epipolar.counts.y, epipolar.params.x,
                                      epipolar.counts.z != 0u);
  if (count < 3u) return;
  // Count first, so that one atomic reserves the slice's range of the list.
  uint added = 0u;
  for (uint k0 = 0u; k0 + 1u < count;) {
    uint k1 = tyn_next_marched(k0, slice);
    if (tyn_subdivided(k0, k1, slice)) added += (k1 - k0 - 1u) / tyn_subdivision_step(k0, k1);
    k0 = k1;
  }
  if (added == 0u) return;
  uint entry = atomicAdd(march_count, added);
  for (uint k0 = 0u; k0 + 1u < count;) {
    uint k1 = tyn_next_marched(k0, slice);
    if (tyn_subdivided(k0, k1, slice)) {
      uint step = tyn_subdivision_step(k0, k1);
      uint left = k0;
      for (uint k = k0 + 1u; k < k1; ++k) {
        bool marched = (k - k0) % step == 0u;
        if (marched) {
          left = k;
          march_samples[entry++] = k | (slice << 16);
        }
        uint right = marched ? k : min(k1, k0 + ((k - k0) / step + 1u) * step);
        imageStore(interpolation_source, ivec2(k, slice), uvec4(left | (right << 16)));
      }
    }
    k0 = k1;
  }
}
