// Translucent peel pass (translucent_pass.cpp): the translucent objects' surfaces, with their
// opacity. Depth clamp is on, as in the shadow pass, so both passes give a surface the same depth.
#version 460
#extension GL_GOOGLE_include_directive : require
#include "host_shared.glsl"

layout(location = 0) in vec3 inPosition;
layout(location = 1) in float inOpacity;
layout(push_constant) uniform Push { PeelPush push; };
layout(location = 0) out float outOpacity;

void main() {
  gl_Position = push.clipFromWorld * vec4(inPosition, 1.0);
  outOpacity = inOpacity;
}
