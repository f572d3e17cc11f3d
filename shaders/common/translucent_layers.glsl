// Translucent occluders as depth-peeled layers (ShadowMapDesc::translucentLayers): per shadow-map
// texel, the surfaces in front of the opaque depth, nearest the light first, each (depth, α), then
// one overflow layer. A technique that integrates them defines TYN_WALK_TRANSLUCENT and includes
// this file before common/texel_walk.glsl, with `translucent_layers[]` (sampler2DArray array) in scope.
#ifndef TYNDALL_TRANSLUCENT_LAYERS_GLSL
#define TYNDALL_TRANSLUCENT_LAYERS_GLSL

// (depth, α) of layer `layer` of map `map`'s texel; (1, 0) where it holds no surface. A sampler
// array may only be indexed by constants (as tyn_shadow_texel).
vec2 tyn_translucent_layer(uint map, ivec2 texel, uint layer) {
  ivec3 at = ivec3(texel, int(layer));
  switch (map) {
    case 0u: return texelFetch(translucent_layers[0], at, 0).rg;
    case 1u: return texelFetch(translucent_layers[1], at, 0).rg;
    case 2u: return texelFetch(translucent_layers[2], at, 0).rg;
    case 3u: return texelFetch(translucent_layers[3], at, 0).rg;
    case 4u: return texelFetch(translucent_layers[4], at, 0).rg;
    default: return texelFetch(translucent_layers[5], at, 0).rg;
  }
}

// Set by the walk when a ray's lit part lies behind a surface of the overflow layer: a surface
// past the count was left out there.
bool tyn_translucent_overflowed = false;

#endif
