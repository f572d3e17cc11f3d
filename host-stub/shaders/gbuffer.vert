// G-buffer pass: world-space geometry (all static meshes merged into one buffer).
#version 460
#extension GL_GOOGLE_include_directive : require
#include "host_shared.glsl"

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec3 inAlbedo;
layout(push_constant) uniform Push { MeshPush push; };

layout(location = 0) out vec3 outNormal;
layout(location = 1) out vec3 outAlbedo;

void main() {
  gl_Position = push.clipFromWorld * vec4(inPosition, 1.0);
  outNormal = inNormal;
  outAlbedo = inAlbedo;
}
