#version 460
// Everything a slice needs before its march, in one workgroup per slice (one dispatch, where each
// step was a pass of its own and a GPU waited on the launches and barriers between them, not on
// their work):
//   1. its entry and exit points (engelhardt2010 §4.1, yusov2013 "Sample generation"), spread
//      over the frame's border arc (epipolar_geometry.h "Slice arc"), or the culled sentinel;
//   2. for the lights that march along one line per map (directional, each of its cascades; spot),
//      its origin and direction in shadow-map UV (yusov2013 "Slice Origin and Direction"), its 1D
//      min/max tree when the march uses one (one per cascade, as yusov2013's cascaded version), and
//      with a light-colour texture the colour's prefix sums along the line;
//   3. the coordinates of its samples: screen position and view-ray length;
//   4. the refinement: which samples are ray-marched, the others' interpolation sources, and the
//      march list.
// The last group to finish starts the shadow test, or the march where there is none
// (dispatch_chain.glsl).
#extension GL_GOOGLE_include_directive : require
#define TYN_COORDINATES_COHERENT
#include "epipolar/epipolar_common.glsl"
uint g_tree_map;  // the map whose tree is being built
#define TYN_MIN_MAX_SHADOW_TEXEL(texel) tyn_epipolar_shadow_texel(g_tree_map, texel)
#include "epipolar/min_max_tree.h"
#include "epipolar/light_color_sums.h"
#include "common/light_color.glsl"
#include "epipolar/dispatch_chain.glsl"

// The colour sums' runs are TYN_EPIPOLAR_TREE_GROUP long (their float sums depend on it).
layout(local_size_x = TYN_EPIPOLAR_TREE_GROUP) in;
const uint TYN_SETUP_GROUP = TYN_EPIPOLAR_TREE_GROUP;

shared vec4 tyn_end_points;
shared vec4 tyn_lines[TYN_MAX_CASCADES];  // the slice's line in each map (tyn_epipolar_line_maps)

// ---- 2. The slice's line in the shadow map ---------------------------------------------------

// Every view ray of a slice lies in one epipolar plane, whose image in a shadow map is one line
// (a directional light's orthographic cascades share the light's direction: one line in each);
// the slice's tree is built along it and its samples are marched along it.
vec4 tyn_slice_line(vec4 end_points, uint map) {
  vec4 origin_direction = vec4(TYN_EPIPOLAR_INVALID_COORD);
  if (tyn_slice_valid(end_points)) {
    // A spot light's rays are bounded by its cone; a directional map is bounded by its square.
    vec3 cone = frame.light_type == TYN_LIGHT_SPOT
                    ? tyn_spot_cone_uv(frame.world_to_shadow[map], frame.light_position, frame.light_direction,
                                       frame.cos_outer_cone)
                    : vec3(0.0);
    float uv_length;
    tyn_slice_shadow_uv(frame.world_to_shadow[map], frame.view_to_world[3].xyz,
                        tyn_view_direction(vec2(end_points.z, end_points.w)), cone, origin_direction, uv_length);
  }
  return origin_direction;
}

// The 1D min/max binary tree (yusov2013 "Min/max binary tree construction"): level 0 from the
// shadow map along the line (each cell's conservative 2×2 footprint, so that the accelerated march
// equals the plain one), then each coarser level from the one below, up to the highest level the
// march may use. Levels ping-pong between two halves of shared memory; every level is also written
// to the tree's row of the tree texture (tyn_epipolar_tree_row).
// Level l (l even) at [0, L/2), level l + 1 at [L/2, 3L/4): 24 KiB for L = 4096.
shared vec2 tyn_nodes[TYN_EPIPOLAR_TREE_MAX_SAMPLES / 2 + TYN_EPIPOLAR_TREE_MAX_SAMPLES / 4];

void tyn_build_tree(int slice, uint map, vec4 origin_direction) {
  g_tree_map = map;
  int row = tyn_epipolar_tree_row(slice, map);
  int sample_count = int(epipolar.tree_samples);
  int top_level = int(epipolar.tree_top_level);
  int thread = int(gl_LocalInvocationIndex);
  int group = int(TYN_SETUP_GROUP);
  vec2 origin = vec2(origin_direction.x, origin_direction.y) * float(frame.shadow_map_size);
  vec2 step = tyn_min_max_step_texels(vec2(origin_direction.z, origin_direction.w));

  int nodes = tyn_min_max_level_nodes(sample_count, 0);
  for (int i = thread; i < nodes; i += group) {
    vec2 node = tyn_min_max_level0_node(origin, step, i);
    tyn_nodes[i] = node;
    imageStore(min_max_tree, ivec2(tyn_min_max_level_offset(sample_count, 0) + i, row), vec4(tyn_min_max_stored_bounds(node), 0.0, 0.0));
  }
  int from = 0;
  int to = sample_count / 2;
  for (int level = 1; level <= top_level; ++level) {
    barrier();
    nodes = tyn_min_max_level_nodes(sample_count, level);
    for (int i = thread; i < nodes; i += group) {
      vec2 node = tyn_min_max_merge(tyn_nodes[from + 2 * i], tyn_nodes[from + 2 * i + 1]);
      tyn_nodes[to + i] = node;
      imageStore(min_max_tree, ivec2(tyn_min_max_level_offset(sample_count, level) + i, row), vec4(tyn_min_max_stored_bounds(node), 0.0, 0.0));
    }
    int swap = from;
    from = to;
    to = swap;
  }
}

// The light-colour texture's prefix sums along the line (light_color_sums.h): each thread sums a
// run of consecutive cells, storing its running sums; the runs' totals give each run its offset;
// each thread adds its offset to its own sums. A thread reads back only texels it wrote itself, so
// no barrier is needed between its store and its load.
shared vec3 tyn_run_totals[TYN_SETUP_GROUP];

void tyn_build_color_sums(int slice, vec4 origin_direction) {
  int sample_count = int(epipolar.tree_samples);
  int thread = int(gl_LocalInvocationIndex);
  int group = int(TYN_SETUP_GROUP);
  float size = float(frame.shadow_map_size);
  vec2 origin = vec2(origin_direction.x, origin_direction.y) * size;
  vec2 step = tyn_min_max_step_texels(vec2(origin_direction.z, origin_direction.w));

  // L and the group are powers of two: runs of L / group cells, or one cell per thread when L is
  // smaller (the threads past L have none).
  int run = max(sample_count / group, 1);
  int first = thread * run;
  int last = min(first + run, sample_count);
  vec3 sum = vec3(0.0);
  for (int k = first; k < last; ++k) {
    sum += tyn_light_color_uv(tyn_min_max_cell_center(origin, step, k) / size);
    imageStore(light_color_sums, tyn_color_sums_texel(sample_count, slice, k), vec4(sum, 0.0));
  }
  tyn_run_totals[thread] = sum;
  barrier();
  vec3 offset = vec3(0.0);
  for (int i = 0; i < thread; ++i) offset += tyn_run_totals[i];
  if (thread == 0) return;
  for (int k = first; k < last; ++k) {
    ivec2 texel = tyn_color_sums_texel(sample_count, slice, k);
    imageStore(light_color_sums, texel, vec4(imageLoad(light_color_sums, texel).rgb + offset, 0.0));
  }
}

// ---- 3. Coordinates ----------------------------------------------------------------------------

// The screen position of sample k and the length of its view ray, to the surface of the pixel the
// sample falls in at the sample's own position.
vec4 tyn_sample_coordinates(vec4 end_points, uint k, uint count) {
  vec2 extent = tyn_output_extent();
  vec2 ndc = tyn_sample_position(end_points, float(k), count, epipolar.epipole_density);
  // Samples lie on the hull of the pixel centres: the pixel containing one is always on screen.
  uvec2 pixel = uvec2(clamp(floor(tyn_pixel_from_ndc(ndc, extent)), vec2(0.0), extent - 1.0));
  float pixel_depth = texelFetch(depth_buffer, ivec2(pixel), 0).r;
  // The pixel's depth is that of its centre, up to half a pixel away. On ground seen at a grazing
  // angle the ray length changes by several percent per pixel there, and improved placement's
  // one-pixel spacing keeps the samples at nearly the same offset from their pixels' centres over
  // many pixels, so a point-sampled depth biases every sample alike wherever L_in depends on the
  // ray's length (a ray ending inside a spot light's beam), which interpolation cannot average
  // out. The ray ends on the pixel's plane instead (epipolar_geometry.h), or at its depth where
  // it has none (a sliver one pixel wide, a crease).
  vec2 offset = tyn_pixel_from_ndc(ndc, extent) - (vec2(pixel) + 0.5);
  float depth = tyn_epipolar_depth_at(pixel_depth, tyn_epipolar_depth_slopes(ivec2(pixel), pixel_depth), offset);
  TynViewRay ray = tyn_view_ray_ndc(ndc, depth);
  return vec4(ndc, ray.surface_distance, 1.0);
}

// ---- 4. Refinement -----------------------------------------------------------------------------
// Sample refinement (engelhardt2010 §4.2, yusov2013 "Sample refinement"): along the slice, every
// `initial step`-th sample (denser near the epipole, see tyn_march_step) and the last one are
// ray-marched, and so are both samples on either side of a depth break (relative difference of
// view-ray length above the threshold). Every other sample is interpolated from the nearest
// ray-marched sample on each side: the interpolation source. The ray-marching samples are listed
// for the march (shadow_test.comp first takes out those whose whole ray is in shadow).
//
// As in yusov2013, the threads flag the slice's samples in parallel, one bit per sample packed into
// 32-bit words in shared memory; each sample then finds its two sources with findMSB / findLSB over
// the words, and each ray-marching sample is written to the march list at its rank along the slice
// (a prefix count of the words' bits), in one range per slice reserved by one atomic. Only
// workgroup barriers and shared memory: nothing depends on a subgroup width (lavapipe's is 8).

// One bit per sample (TYN_EPIPOLAR_MAX_SAMPLES = 4096 samples: 128 words), and per word the
// ray-marching samples before it.
const uint TYN_REFINE_WORDS = TYN_EPIPOLAR_MAX_SAMPLES / 32u;
shared uint tyn_marked_words[TYN_REFINE_WORDS];
shared uint tyn_rank[TYN_REFINE_WORDS];
shared uint tyn_base;

bool tyn_depth_break(float a, float b) { return abs(a - b) > epipolar.depth_break_threshold * min(a, b); }

// The ray-marching step at sample k: the initial step, but near the epipole at most
// 1/near_epipole_steps of the distance to it (a power of two, so the steps nest).
// L_in of a local light grows like 1/(distance to the epipole) there and a phase lobe peaks there:
// linear interpolation of 1/r over a step Δ is off by at most Δ²/(4r²) of it (1.6% for Δ = r/4,
// 0.1% for r/16), where a fixed step next to the light would interpolate from the light's own
// (unbounded) value.
uint tyn_march_step(vec2 here, vec2 next) {
  uint step = epipolar.initial_sample_step;
  if (epipolar.epipole.z > 0.0) {
    vec2 extent = tyn_output_extent();
    float to_epipole = length((here - tyn_epipole_ndc(epipolar.epipole)) * 0.5 * extent);
    float spacing = max(length((next - here) * 0.5 * extent), 1e-6);
    uint steps = uint(clamp(to_epipole / (epipolar.near_epipole_steps * spacing), 1.0, float(step)));
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

void tyn_refine(uint slice, uint count) {
  uint thread = gl_LocalInvocationIndex;
  uint words = (count + 31u) / 32u;
  for (uint w = thread; w < words; w += TYN_SETUP_GROUP) tyn_marked_words[w] = 0u;
  barrier();
  for (uint k = thread; k < count; k += TYN_SETUP_GROUP) {
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
  for (uint k = thread; k < epipolar.samples_per_slice; k += TYN_SETUP_GROUP) {
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

// ---- The next pass -----------------------------------------------------------------------------

// The camera in shadow on the 2×2 texel block around it (the footprint of a 1D cell there) in map 0
// (the first cascade serves the rays' first stretch, from the camera); a camera outside the map
// counts as lit.
bool tyn_camera_in_shadow_map() {
  vec4 h0 = frame.world_to_shadow[0] * vec4(frame.view_to_world[3].xyz, 1.0);
  if (h0.w <= 0.0 || abs(h0.x) > h0.w || abs(h0.y) > h0.w) return false;
  vec2 camera_texels = (vec2(h0.x, h0.y) / h0.w * 0.5 + 0.5) * float(frame.shadow_map_size);
  ivec2 t = tyn_min_max_footprint_origin(camera_texels);
  vec2 bounds = tyn_min_max_footprint_bounds(
      vec4(tyn_epipolar_shadow_texel(0u, t), tyn_epipolar_shadow_texel(0u, t + ivec2(1, 0)),
           tyn_epipolar_shadow_texel(0u, t + ivec2(0, 1)), tyn_epipolar_shadow_texel(0u, t + ivec2(1, 1))));
  return bounds.y < 1.0 && h0.z / h0.w > bounds.y;
}

// With a tree, the shadow test (shadow_test.comp) runs over the listed samples, or is skipped:
// every view ray starts at the camera, so where the camera is lit no ray is in shadow along its
// whole length, and an open-air view pays nothing for the test. Then, or without a tree, the
// march's first round starts at the refinement's entries themselves. Only a gate: the test is
// exact on its own.
void tyn_start_next_pass(bool tree) {
  bool test = tree && tyn_camera_in_shadow_map();
  uint count = atomicAdd(march_count, 0u);
  test_groups[0] = test ? (count + TYN_EPIPOLAR_MARCH_GROUP - 1u) / TYN_EPIPOLAR_MARCH_GROUP : 0u;
  test_groups[1] = 1u;
  test_groups[2] = 1u;
  march_first = 0u;
  march_round_end = test ? count : 0u;
  if (!test) tyn_start_march_round(0u);
}

void main() {
  uint slice = gl_WorkGroupID.x;
  uint thread = gl_LocalInvocationIndex;
  vec2 extent = tyn_output_extent();
  if (thread == 0u) {
    vec2 exit_point = tyn_arc_exit_point(float(slice), epipolar.slice_count, vec2(epipolar.arc_start, epipolar.arc_length), extent);
    vec4 end_points;
    tyn_slice_end_points(epipolar.epipole, exit_point, extent, end_points);
    imageStore(slice_end_points, ivec2(slice, 0), end_points);
    tyn_end_points = end_points;
    // A light whose maps are walked marches no slice line (tyn_epipolar_walks_maps).
    for (uint map = 0u; map < tyn_epipolar_line_maps(); ++map) {
      vec4 line = !tyn_epipolar_walks_maps() ? tyn_slice_line(end_points, map) : vec4(TYN_EPIPOLAR_INVALID_COORD);
      if (!tyn_epipolar_walks_maps()) imageStore(slice_uv, ivec2(slice, map), line);
      tyn_lines[map] = line;
    }
  }
  barrier();
  vec4 end_points = tyn_end_points;
  // Uniform across the workgroup: the march reads no tree or sums of a slice without a line.
  bool tree = !tyn_epipolar_walks_maps() && epipolar.tree_enabled != 0u;
  for (uint map = 0u; map < tyn_epipolar_line_maps(); ++map) {
    // The previous tree's last level is read from the shared nodes this one overwrites.
    if (map > 0u) barrier();
    if (tree && tyn_slice_valid(tyn_lines[map])) tyn_build_tree(int(slice), map, tyn_lines[map]);
  }
  // A light-colour texture comes with one map (cascades cannot take one).
  if (!tyn_epipolar_walks_maps() && epipolar.colored_chunk != 0u && tyn_slice_valid(tyn_lines[0])) {
    tyn_build_color_sums(int(slice), tyn_lines[0]);
  }

  uint count = tyn_slice_sample_count(end_points, extent, epipolar.samples_per_slice, epipolar.epipole_density,
                                      epipolar.improved_placement != 0u);
  for (uint k = thread; k < epipolar.samples_per_slice; k += TYN_SETUP_GROUP) {
    imageStore(epipolar_coordinates, ivec2(k, slice), k < count ? tyn_sample_coordinates(end_points, k, count) : vec4(0.0));
  }
  // The refinement reads the neighbours' coordinates, written by other threads.
  memoryBarrierImage();
  barrier();
  tyn_refine(slice, count);

  if (tyn_last_group(TYN_DONE_SETUP)) tyn_start_next_pass(tree);
}
