// Lighting pass: reads the G-buffer, writes the HDR back buffer (scene-linear radiance).
//   out = albedo · (ambient + E · max(0, n·l) · visibility)
// with E = colour · intensity (directional) or I / d² (· cone falloff for spots). No medium
// attenuation here: that is the post-process's business. A scene with several lights runs this
// once per light; the later runs (params.additive.x = 1) are blended additively and add only
// albedo · E · max(0, n·l) · visibility.
#version 460
#extension GL_GOOGLE_include_directive : require
#include "host_shared.glsl"

layout(set = 0, binding = 0, std140) uniform Lighting { LightingParams params; };
layout(set = 0, binding = 1) uniform sampler2D gDepth;
layout(set = 0, binding = 2) uniform sampler2D gAlbedo;
layout(set = 0, binding = 3) uniform sampler2D gNormal;
layout(set = 0, binding = 4) uniform sampler2DShadow shadowMaps[kHostMaxShadowMaps];
// The light's colour texture over shadow map 0's square (stained glass); 1×1 white without one.
layout(set = 0, binding = 5) uniform sampler2D lightColor;

layout(location = 0) out vec4 outColor;

// Every depth convention has clip z = P22·z + P32 and clip w = −z, so z = −P32 / (depth + P22):
// exact for standard/reverse and finite/infinite far alike, no matrix inverse in float.
float host_view_z(float depth) { return -params.projection.w / (depth + params.projection.z); }

vec3 host_world_position(vec2 fragCoord, float viewZ) {
  vec2 ndc = fragCoord / vec2(params.mode.zw) * 2.0 - 1.0;
  vec3 viewPos = vec3(ndc.x * -viewZ / params.projection.x, ndc.y * -viewZ / params.projection.y, viewZ);
  return (params.viewToWorld * vec4(viewPos, 1.0)).xyz;
}

// Comparison sampler: 1 where ref ≤ stored (lit), bilinear 2×2 PCF where the format filters.
float host_sample_shadow(int map, vec3 coord) {
  // Sampler arrays may only be indexed by constant expressions on devices without
  // shaderSampledImageArrayDynamicIndexing (lavapipe has none), hence the switch.
  switch (map) {
    case 0: return texture(shadowMaps[0], coord);
    case 1: return texture(shadowMaps[1], coord);
    case 2: return texture(shadowMaps[2], coord);
    case 3: return texture(shadowMaps[3], coord);
    case 4: return texture(shadowMaps[4], coord);
    default: return texture(shadowMaps[5], coord);
  }
}

// A directional light's cascade for a point at `viewDepth` along the camera's −Z: the one whose
// [near, far) holds it, the first for nearer points and the last for farther ones.
int host_cascade(float viewDepth) {
  const int last = params.mode.y - 1;
  int cascade = 0;
  while (cascade < last && viewDepth >= params.cascadeFar[cascade]) ++cascade;
  return cascade;
}

// Visibility of the light from the surface point `world` at `viewDepth` with normal `n` (1 lit,
// 0 shadowed).
float host_shadow(vec3 world, float viewDepth, vec3 n, vec3 toLight) {
  const int type = params.mode.x;
  int map = 0;
  // World-space size of one shadow texel at this point.
  float footprint = params.shadow.x;
  if (type == kHostLightPoint) {
    vec3 d = world - params.lightPosition.xyz;
    vec3 a = abs(d);
    if (a.x >= a.y && a.x >= a.z) {
      map = d.x >= 0.0 ? 0 : 1;
      footprint *= a.x;
    } else if (a.y >= a.z) {
      map = d.y >= 0.0 ? 2 : 3;
      footprint *= a.y;
    } else {
      map = d.z >= 0.0 ? 4 : 5;
      footprint *= a.z;
    }
  } else if (type == kHostLightSpot) {
    footprint *= max(dot(world - params.lightPosition.xyz, params.lightDirection.xyz), 0.0);
  } else if (params.mode.y > 1) {  // directional cascades
    map = host_cascade(viewDepth);
    footprint = params.cascadeFootprint[map];
  }

  // Slope-scaled bias: across the PCF footprint (about one texel either side) a surface tilted
  // by θ from the light changes depth by footprint · tan θ, so the point is moved towards the
  // light by that much (tan θ capped: at grazing angles n·l makes the light negligible anyway),
  // plus half a texel along the normal against the texel-centre quantisation.
  float cosTheta = clamp(dot(n, toLight), 1e-3, 1.0);
  float tanTheta = min(sqrt(1.0 - cosTheta * cosTheta) / cosTheta, 8.0);
  vec3 biased = world + n * (0.5 * footprint) + toLight * (footprint * (1.0 + 1.5 * tanTheta));

  vec4 clip = params.worldToShadowClip[map] * vec4(biased, 1.0);
  if (clip.w <= 0.0) return type == kHostLightDirectional ? 1.0 : 0.0;
  vec3 ndc = clip.xyz / clip.w;
  if (type == kHostLightPoint) {
    // The face was chosen before biasing; a biased point may leave it by a texel at a cube edge,
    // where the neighbouring faces share the same depths.
    ndc.xy = clamp(ndc.xy, vec2(-1.0), vec2(1.0));
  } else if (any(greaterThan(abs(ndc.xy), vec2(1.0)))) {
    // Outside a directional map: no caster there (the map is fitted to them). Outside a spot's
    // frustum: outside its cone (the frustum is 5° wider).
    return type == kHostLightDirectional ? 1.0 : 0.0;
  }
  return host_sample_shadow(map, vec3(ndc.xy * 0.5 + 0.5, ndc.z));
}

// The light's colour filter at a point (Tyndall's FrameDesc::lightColor contract: shadow map 0's
// UV square, bilinear, unfiltered outside it). A point light has none (white texel).
vec3 host_light_color(vec3 world) {
  if (params.mode.x == kHostLightPoint) return vec3(1.0);
  vec4 clip = params.worldToShadowClip[0] * vec4(world, 1.0);
  if (clip.w <= 0.0) return vec3(1.0);
  vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return vec3(1.0);
  return textureLod(lightColor, uv, 0.0).rgb;
}

void main() {
  const ivec2 px = ivec2(gl_FragCoord.xy);
  const float depth = texelFetch(gDepth, px, 0).r;
  const bool additive = params.additive.x != 0;
  if (depth == params.sky.a) {  // nothing drawn: the depth still holds its clear value
    outColor = additive ? vec4(0.0) : vec4(params.sky.rgb, 1.0);
    return;
  }
  const vec3 albedo = texelFetch(gAlbedo, px, 0).rgb;
  const vec3 n = normalize(texelFetch(gNormal, px, 0).xyz);
  const float viewZ = host_view_z(depth);
  const vec3 world = host_world_position(gl_FragCoord.xy, viewZ);

  const int type = params.mode.x;
  vec3 toLight;
  vec3 irradiance;  // E at the point, before the cosine and the shadow
  if (type == kHostLightDirectional) {
    toLight = -params.lightDirection.xyz;
    irradiance = params.lightRadiance.rgb;
  } else {
    vec3 d = params.lightPosition.xyz - world;
    float distance2 = max(dot(d, d), 1e-12);
    toLight = d * inversesqrt(distance2);
    irradiance = params.lightRadiance.rgb / distance2;
    if (type == kHostLightSpot) {
      float cosAngle = dot(params.lightDirection.xyz, -toLight);
      float cosOuter = params.spotCone.x;
      float cosInner = params.spotCone.y;
      // smoothstep is undefined for equal edges: a hard cone then.
      irradiance *= cosInner > cosOuter ? smoothstep(cosOuter, cosInner, cosAngle)
                                        : step(cosOuter, cosAngle);
    }
  }

  vec3 light = additive ? vec3(0.0) : params.ambient.rgb;
  const float nDotL = dot(n, toLight);
  if (nDotL > 0.0 && any(greaterThan(irradiance, vec3(0.0)))) {
    light += irradiance * host_light_color(world) * nDotL * host_shadow(world, -viewZ, n, toLight);
  }
  outColor = vec4(albedo * light, 1.0);
}
