#version 460
// Debug view DebugView::FixedUpPixels: the pixels of the fix-up list, red (same indirect dispatch
// as the fix-up pass: its groups' threads stride over the list's quads).
#extension GL_GOOGLE_include_directive : require
#include "epipolar/epipolar_common.glsl"

layout(local_size_x = TYN_EPIPOLAR_FIXUP_GROUP) in;

void main() {
  for (uint index = gl_GlobalInvocationID.x; index < fixup_count; index += gl_NumWorkGroups.x * TYN_EPIPOLAR_FIXUP_GROUP) {
    uint entry = fixup_quads[index];
    for (uint bit = 0u; bit < 4u; ++bit) {
      if (tyn_fixup_quad_flags(entry, bit)) {
        imageStore(debug_image, ivec2(tyn_fixup_quad_pixel(entry, bit)), vec4(1.0, 0.1, 0.05, 1.0));
      }
    }
  }
}
