// One depth peel of the translucent surfaces (Everitt 2001, "Interactive order-independent
// transparency"): the depth test keeps the nearest surface strictly behind the previous layer and
// in front of the opaque depth; it is written as (depth, opacity).
#version 460
#extension GL_GOOGLE_include_directive : require
#include "host_shared.glsl"

layout(set = 0, binding = 0) uniform sampler2D opaqueDepth;
layout(set = 0, binding = 1) uniform sampler2D previousLayer;  // (depth, α); not read for layer 0
layout(push_constant) uniform Push { PeelPush push; };
layout(location = 0) in float inOpacity;
layout(location = 0) out vec2 outLayer;

void main() {
  ivec2 texel = ivec2(gl_FragCoord.xy);
  float z = gl_FragCoord.z;
  // At or behind the opaque surface the light is blocked already.
  if (z >= texelFetch(opaqueDepth, texel, 0).r) discard;
  if (push.layer.x > 0 && z <= texelFetch(previousLayer, texel, 0).r) discard;
  outLayer = vec2(z, inOpacity);
}
