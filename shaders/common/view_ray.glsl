// View rays from the host's depth buffer (DESIGN.md "Radiometry"): the ray starts at the camera
// position, and a pixel without a surface integrates to the far plane, or to the configured sky
// distance when the far plane is at infinity. Needs `frame` (FrameConstants) in scope.
#ifndef TYNDALL_VIEW_RAY_GLSL
#define TYNDALL_VIEW_RAY_GLSL

struct TynViewRay {
  vec3 origin;     // camera position, world space
  vec3 direction;  // unit, world space
  float surface_distance;  // to the first surface (or the far plane / sky distance)
};

// Unit world-space direction of the view ray through a screen point (NDC). It comes from the
// near-plane point, which exists for every projection convention.
vec3 tyn_view_direction(vec2 ndc) {
  vec4 near_point = frame.clip_to_view * vec4(ndc, frame.near_ndc_depth, 1.0);
  vec3 view_dir = normalize(near_point.xyz / near_point.w);
  return normalize(mat3(frame.view_to_world) * view_dir);
}

// Length of the view ray through `ndc` to the surface at `depth` (a depth-buffer value).
float tyn_view_distance(vec2 ndc, float depth) {
  bool sky = depth == frame.far_ndc_depth;
  if (sky && frame.far_at_infinity != 0u) return frame.sky_distance;
  vec4 surface = frame.clip_to_view * vec4(ndc, depth, 1.0);
  return length(surface.xyz / surface.w);
}

TynViewRay tyn_view_ray_ndc(vec2 ndc, float depth) {
  TynViewRay ray;
  ray.origin = frame.view_to_world[3].xyz;
  ray.direction = tyn_view_direction(ndc);
  ray.surface_distance = tyn_view_distance(ndc, depth);
  return ray;
}

// NDC of a pixel's centre (integer pixel coordinates).
vec2 tyn_pixel_ndc(uvec2 pixel) { return (vec2(pixel) + 0.5) / vec2(frame.output_extent) * 2.0 - 1.0; }

// The output pixel that a pixel of the L_in target stands for (FrameConstants target_*): itself at
// full resolution; at half or quarter one pixel of each 2×2 or 4×4 block, whose depth and ray the
// technique computes L_in for, so that the composite's upsample knows where each value belongs.
uvec2 tyn_output_pixel(uvec2 target_pixel) {
  return min(target_pixel * frame.target_stride + frame.target_offset, frame.output_extent - 1u);
}

// pixel: integer pixel coordinates; depth: the host's depth-buffer value there.
TynViewRay tyn_view_ray(uvec2 pixel, float depth) { return tyn_view_ray_ndc(tyn_pixel_ndc(pixel), depth); }

// The view ray's transmittance exp(−σ_t s) per channel (DESIGN.md "Radiometry"). A function of the
// depth buffer alone: the composite computes it where it multiplies the back buffer, and the T AOV
// pass where the host asks for it, so no technique stores it.
vec3 tyn_view_transmittance(uvec2 pixel, float depth) {
  return exp(-frame.extinction * tyn_view_distance(tyn_pixel_ndc(pixel), depth));
}

#endif
