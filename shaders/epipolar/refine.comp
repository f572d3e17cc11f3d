#version 460
// Sample refinement (engelhardt2010 §4.2, yusov2013 "Sample refinement"): along each slice, every
// `initial step`-th sample (denser near the epipole, see tyn_march_step) and the last one are
// ray-marched, and so are both samples on either side of a depth break (relative difference of
// view-ray length above the threshold). Every other sample is interpolated from the nearest
// ray-marched sample on each side: the interpolation source. The ray-marching samples are listed
// for the march pass (shadow_test.comp first takes out those whose whole ray is in shadow).
//
// One workgroup per slice, as in yusov2013: the threads flag the slice's samples in parallel, one
// bit per sample packed into 32-bit words in shared memory; each sample then finds its two sources
// with findMSB / findLSB over the words, and each ray-marching sample is written to the march list
// at its rank along the slice (a prefix count of the words' bits), in one range per slice reserved
// by one atomic. Only workgroup barriers and shared memory: nothing depends on a subgroup width
// (lavapipe's is 8). A serial walk, one thread per slice, would run 256–1024 threads in all (one
// per slice), each over 256–512 samples: a GPU nearly idle.
#extension GL_GOOGLE_include_directive : require
#include "epipolar/epipolar_common.glsl"

layout(local_size_x = TYN_EPIPOLAR_REFINE_GROUP) in;

// One bit per sample (TYN_EPIPOLAR_MAX_SAMPLES = 4096 samples: 128 words), and per word the
// ray-marching samples before it.
const uint TYN_REFINE_WORDS = TYN_EPIPOLAR_MAX_SAMPLES / 32u;
shared uint tyn_marked_words[TYN_REFINE_WORDS];
shared uint tyn_rank[TYN_REFINE_WORDS];
shared uint tyn_base;

bool tyn_depth_break(float a, float b) {
  return abs(a - b) > epipolar.depth_break_threshold * min(a, b);
}

// The ray-marching step at sample k: the initial step, but near the epipole at most
// 1/TYN_EPIPOLAR_NEAR_EPIPOLE_STEPS of the distance to it (a power of two, so the steps nest).
// L_in of a local light grows like 1/(distance to the epipole) there and a phase lobe peaks there:
// linear interpolation of 1/r over a step Δ ≤ r/8 is off by at most Δ²/(4r²) < 0.4%, where a fixed
// step next to the light would interpolate from the light's own (unbounded) value.
uint tyn_march_step(vec2 here, vec2 next) {
  uint step = epipolar.initial_sample_step;
  if (epipolar.epipole.z > 0.0) {
    vec2 extent = tyn_output_extent();
    float to_epipole = length((here - tyn_epipole_ndc(epipolar.epipole)) * 0.5 * extent);
    float spacing = max(length((next - here) * 0.5 * extent), 1e-6);
    uint steps = uint(clamp(to_epipole / (TYN_EPIPOLAR_NEAR_EPIPOLE_STEPS * spacing), 1.0, float(step)));
    step = min(step, 1u << findMSB(steps));
  }
  return step;
}

bool tyn_marched(uint k, uint count, uint slice) {
  if (k == 0u || k + 1u == count) return true;
  vec4 here = imageLoad(epipolar_coordinates, ivec2(k, slice));
  vec4 after = imageLoad(epipolar_coordinates, ivec2(k + 1u, slice));
  if (k % tyn_march_step(vec2(here.x, here.y), vec2(after.x, after.y)) == 0u) return true;
  float before = imageLoad(epipolar_coordinates, ivec2(k - 1u, slice)).z;
  return tyn_depth_break(before, here.z) || tyn_depth_break(here.z, after.z);
}

// The last ray-marching sample at or before k (sample 0 is one, so the scan ends).
uint tyn_left_source(uint k) {
  uint word = k >> 5u;
  uint bits = tyn_marked_words[word] & (0xffffffffu >> (31u - (k & 31u)));
  while (bits == 0u) bits = tyn_marked_words[--word];
  return word * 32u + uint(findMSB(bits));
}

// The first ray-marching sample at or after k (the slice's last sample is one).
uint tyn_right_source(uint k) {
  uint word = k >> 5u;
  uint bits = tyn_marked_words[word] & (0xffffffffu << (k & 31u));
  while (bits == 0u) bits = tyn_marked_words[++word];
  return word * 32u + uint(findLSB(bits));
}

void main() {
  uint slice = gl_WorkGroupID.x;
  uint thread = gl_LocalInvocationIndex;
  vec4 end_points = imageLoad(slice_end_points, ivec2(slice, 0));
  uint count = tyn_slice_sample_count(end_points, tyn_output_extent(), epipolar.samples_per_slice, epipolar.epipole_density,
                                      epipolar.improved_placement != 0u);
  uint words = (count + 31u) / 32u;
  for (uint w = thread; w < words; w += TYN_EPIPOLAR_REFINE_GROUP) tyn_marked_words[w] = 0u;
  barrier();
  for (uint k = thread; k < count; k += TYN_EPIPOLAR_REFINE_GROUP) {
    if (tyn_marched(k, count, slice)) atomicOr(tyn_marked_words[k >> 5u], 1u << (k & 31u));
  }
  barrier();
  if (thread == 0u) {
    uint total = 0u;
    for (uint w = 0u; w < words; ++w) {
      tyn_rank[w] = total;
      total += uint(bitCount(tyn_marked_words[w]));
    }
    tyn_base = total > 0u ? atomicAdd(march_count, total) : 0u;
  }
  barrier();
  for (uint k = thread; k < epipolar.samples_per_slice; k += TYN_EPIPOLAR_REFINE_GROUP) {
    if (k >= count) {
      imageStore(interpolation_source, ivec2(k, slice), uvec4(TYN_EPIPOLAR_NO_SOURCE));
      continue;
    }
    uint left = tyn_left_source(k);
    uint right = tyn_right_source(k);
    imageStore(interpolation_source, ivec2(k, slice), uvec4(left | (right << 16)));
    if (left == k) {
      uint below = tyn_marked_words[k >> 5u] & ((1u << (k & 31u)) - 1u);
      march_samples[tyn_base + tyn_rank[k >> 5u] + uint(bitCount(below))] = k | (slice << 16);
    }
  }
}
