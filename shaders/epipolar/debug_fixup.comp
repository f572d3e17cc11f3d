#version 460
// Debug view DebugView::FixedUpPixels: the pixels of the fix-up list, red (same indirect dispatch
// as the fix-up pass).
#extension GL_GOOGLE_include_directive : require
#include "epipolar/epipolar_common.glsl"

layout(local_size_x = TYN_EPIPOLAR_FIXUP_GROUP) in;

void main() {
  uint index = gl_GlobalInvocationID.x;
  if (index >= fixup_count) return;
  uint packed = fixup_pixels[index];
  imageStore(debug_image, ivec2(packed & 0xffffu, packed >> 16), vec4(1.0, 0.1, 0.05, 1.0));
}
