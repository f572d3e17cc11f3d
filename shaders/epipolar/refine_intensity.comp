#version 460
// Second round of sample refinement, on the values of the first: an interval between neighbouring
// ray-marched samples whose L_in differ by more than the threshold (relative to the larger) gets
// TYN_EPIPOLAR_SUBDIVISIONS − 1 more ray-marching samples, evenly spaced. Depth breaks catch where a
// surface ends; this catches where the light does: a shadow boundary or a spot cone's edge crossing
// the slice, and the fast falloff near a local light, which linear interpolation over the initial
// step would flatten. (engelhardt2010 §4.2 rejects an intensity criterion as the only one, since it
// can miss a shadow between two samples; here it only adds samples to the depth-based ones.)
// One workgroup per slice, as the first refinement (slice_setup.comp): each thread takes every TYN_EPIPOLAR_REFINE_GROUP-th
// sample, finds its interval from its own interpolation sources (left < k < right when it is not
// ray-marched) and decides alone whether it becomes a sample and what its new sources are; one
// atomic per slice reserves the slice's range of the list (one thread per slice walking its
// samples would be bound by latency on a GPU).
#extension GL_GOOGLE_include_directive : require
#include "epipolar/epipolar_common.glsl"
#include "epipolar/dispatch_chain.glsl"

layout(local_size_x = TYN_EPIPOLAR_REFINE_GROUP) in;

bool tyn_interpolation_suspect(vec3 a, vec3 b) {
  vec3 larger = max(a, b);
  vec3 difference = abs(a - b);
  float scale = max(larger.r, max(larger.g, larger.b));
  return max(difference.r, max(difference.g, difference.b)) > epipolar.intensity_refinement_threshold * scale;
}

// Spacing of the samples added between ray-marched samples k0 < k1 (≥ 1).
uint tyn_subdivision_step(uint k0, uint k1) { return max((k1 - k0) / TYN_EPIPOLAR_SUBDIVISIONS, 1u); }

// Sample k's interval (k0, k1) between ray-marched samples when it is subdivided; false for a
// ray-marched sample and an interval that is not.
bool tyn_subdivided_interval(uint k, uint slice, out uint k0, out uint k1) {
  uint sources = imageLoad(interpolation_source, ivec2(k, slice)).x;
  k0 = sources & 0xffffu;
  k1 = sources >> 16;
  if (!(k0 < k && k < k1) || k1 - k0 < 2u) return false;
  return tyn_interpolation_suspect(imageLoad(epipolar_scattering, ivec2(k0, slice)).rgb,
                                   imageLoad(epipolar_scattering, ivec2(k1, slice)).rgb);
}

shared uint tyn_added;
shared uint tyn_base;

void tyn_refine_slice(uint slice) {
  uint thread = gl_LocalInvocationIndex;
  vec4 end_points = imageLoad(slice_end_points, ivec2(slice, 0));
  uint count = tyn_slice_sample_count(end_points, tyn_output_extent(), epipolar.samples_per_slice, epipolar.epipole_density,
                                      epipolar.improved_placement != 0u);
  if (count < 3u) return;  // the whole workgroup: count is the slice's
  // Count first: the thread's new samples, then its offset in the slice's range.
  uint mine = 0u;
  for (uint k = thread; k < count; k += TYN_EPIPOLAR_REFINE_GROUP) {
    uint k0, k1;
    if (tyn_subdivided_interval(k, slice, k0, k1) && (k - k0) % tyn_subdivision_step(k0, k1) == 0u) ++mine;
  }
  if (thread == 0u) tyn_added = 0u;
  barrier();
  uint entry = atomicAdd(tyn_added, mine);
  barrier();
  if (thread == 0u) tyn_base = tyn_added > 0u ? atomicAdd(march_count, tyn_added) : 0u;
  barrier();
  if (tyn_added == 0u) return;
  entry += tyn_base;
  for (uint k = thread; k < count; k += TYN_EPIPOLAR_REFINE_GROUP) {
    uint k0, k1;
    if (!tyn_subdivided_interval(k, slice, k0, k1)) continue;
    uint step = tyn_subdivision_step(k0, k1);
    uint index = (k - k0) / step;
    bool marched = (k - k0) % step == 0u;
    if (marched) march_samples[entry++] = k | (slice << 16);
    uint left = k0 + index * step;
    uint right = marched ? k : min(k1, k0 + (index + 1u) * step);
    imageStore(interpolation_source, ivec2(k, slice), uvec4(left | (right << 16)));
  }
}

void main() {
  tyn_refine_slice(gl_WorkGroupID.x);
  // The last group starts the march's second round over the samples added here.
  if (tyn_last_group(TYN_DONE_REFINE_INTENSITY)) tyn_start_march_round(1u);
}
