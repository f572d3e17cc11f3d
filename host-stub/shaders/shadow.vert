// Shadow pass: depth only, no fragment shader. Depth clamp is on in the pipeline, so casters
// nearer than the fitted near plane still write (clamped to 0) instead of being clipped away.
#version 460
#extension GL_GOOGLE_include_directive : require
#include "host_shared.glsl"

layout(location = 0) in vec3 inPosition;
layout(push_constant) uniform Push { MeshPush push; };

void main() { gl_Position = push.clipFromWorld * vec4(inPosition, 1.0); }
