// A translucent surface blended over the back buffer with its opacity: albedo · (ambient + E ·
// max(0, n·l)) from the scene's first light, unshadowed and without a spot cone (the stub host's
// picture of glass and smoke; the scattering is Tyndall's).
#version 460
#extension GL_GOOGLE_include_directive : require
#include "host_shared.glsl"

layout(push_constant) uniform Push { ForwardPush push; };
layout(location = 0) in vec3 inWorld;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec4 inAlbedoOpacity;
layout(location = 0) out vec4 outColor;

void main() {
  vec3 n = normalize(inNormal);
  if (!gl_FrontFacing) n = -n;
  vec3 toLight = -push.light.xyz;
  vec3 irradiance = push.radiance.rgb;
  if (push.light.w > 0.5) {  // a spot or point light at push.light.xyz
    vec3 d = push.light.xyz - inWorld;
    float distance2 = max(dot(d, d), 1e-12);
    toLight = d * inversesqrt(distance2);
    irradiance /= distance2;
  }
  vec3 light = push.ambient.rgb + irradiance * max(dot(n, toLight), 0.0);
  outColor = vec4(inAlbedoOpacity.rgb * light, inAlbedoOpacity.a);
}
