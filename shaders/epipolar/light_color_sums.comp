#version 460
// The light-colour texture's prefix sums along each slice's line (light_color_sums.h), one
// workgroup per slice: each thread sums a run of consecutive cells, storing its running sums; the
// runs' totals give each run its offset; each thread adds its offset to its own sums. A thread
// reads back only texels it wrote itself, so no barrier is needed between its store and its load.
#extension GL_GOOGLE_include_directive : require
#include "epipolar/epipolar_common.glsl"
#include "epipolar/light_color_sums.h"
#include "common/light_color.glsl"
#include "epipolar/min_max_tree.h"

layout(local_size_x = TYN_EPIPOLAR_TREE_GROUP) in;

shared vec3 tyn_run_totals[TYN_EPIPOLAR_TREE_GROUP];

void main() {
  int slice = int(gl_WorkGroupID.x);
  vec4 origin_direction = imageLoad(slice_uv, ivec2(slice, 0));
  // Uniform across the workgroup: the march does not read the sums of a slice without a line.
  if (!tyn_slice_valid(origin_direction)) return;
  int sample_count = int(epipolar.tree_samples);
  int thread = int(gl_LocalInvocationIndex);
  int group = int(TYN_EPIPOLAR_TREE_GROUP);
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
