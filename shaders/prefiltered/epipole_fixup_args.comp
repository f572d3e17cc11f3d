#version 460
// Sizes the epipole block's indirect dispatch on the GPU: the block of pf.epipole_block_pixels
// output pixels centred on the epipole (the projected light, or where the shafts converge when it
// is behind the camera), in L_in target pixels, clipped to the screen; zero groups when the epipole
// is at infinity or the block misses the screen, so nothing runs. The CPU records this pass only when it finds the block on screen.
#extension GL_GOOGLE_include_directive : require

#include "prefiltered/prefiltered_common.glsl"

layout(local_size_x = 1) in;

void main() {
  ivec4 rect = ivec4(0);
  vec4 e = pf.epipole;
  if (e.z > 0.0 && pf.epipole_block_pixels > 0u) {
    vec2 extent = vec2(frame.target_extent);
    int block = int(max(pf.epipole_block_pixels / frame.target_stride, 1u));
    // Pixel coordinates of the epipole (pixel i spans [i, i + 1]); the division is safe because an
    // epipole farther than this is off screen by far more than any block.
    vec2 ndc = clamp(vec2(e.x, e.y) / e.z, vec2(-4.0), vec2(4.0));
    vec2 centre = (ndc * 0.5 + 0.5) * extent;
    ivec2 lo = ivec2(floor(centre - 0.5 * float(block) + 0.5));
    ivec2 hi = lo + ivec2(block);
    rect = ivec4(max(lo, ivec2(0)), min(hi, ivec2(frame.target_extent)));
  }
  // One workgroup per pixel (epipole_fixup.comp).
  ivec2 size = max(rect.zw - rect.xy, ivec2(0));
  fixup_args.rect_lo = rect.xy;
  fixup_args.rect_hi = rect.zw;
  fixup_args.groups = uvec3(size.x > 0 && size.y > 0 ? uvec2(size) : uvec2(0u), 1u);
}
