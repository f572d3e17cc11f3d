// G-buffer pass: linear albedo and world-space unit normal.
#version 460

layout(location = 0) in vec3 inNormal;
layout(location = 1) in vec3 inAlbedo;

layout(location = 0) out vec4 outAlbedo;
layout(location = 1) out vec4 outNormal;

void main() {
  vec3 n = normalize(inNormal);
  // Planes are single quads drawn without culling: seen from behind, shade the side we see.
  if (!gl_FrontFacing) n = -n;
  outAlbedo = vec4(inAlbedo, 1.0);
  outNormal = vec4(n, 1.0);
}
