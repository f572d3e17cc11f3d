// Forward pass over the lit back buffer: the translucent objects (forward_pass.cpp).
#version 460
#extension GL_GOOGLE_include_directive : require
#include "host_shared.glsl"

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec3 inAlbedo;
layout(location = 3) in float inOpacity;
layout(push_constant) uniform Push { ForwardPush push; };

layout(location = 0) out vec3 outWorld;
layout(location = 1) out vec3 outNormal;
layout(location = 2) out vec4 outAlbedoOpacity;

void main() {
  gl_Position = push.clipFromWorld * vec4(inPosition, 1.0);
  outWorld = inPosition;
  outNormal = inNormal;
  outAlbedoOpacity = vec4(inAlbedo, inOpacity);
}
