#include "frame_setup.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>

#include <glm/gtc/matrix_access.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "epipolar/epipolar_technique.h"
#include "prefiltered/prefiltered_technique.h"
#include "technique_selection.h"

namespace tyndall {

// The shaders' light types are tyndall::LightType's values.
static_assert(gpu::TYN_LIGHT_DIRECTIONAL == static_cast<std::uint32_t>(LightType::Directional));
static_assert(gpu::TYN_LIGHT_SPOT == static_cast<std::uint32_t>(LightType::Spot));
static_assert(gpu::TYN_LIGHT_POINT == static_cast<std::uint32_t>(LightType::Point));
// FrameConstants' std140 offsets (shaders/common/shared_constants.h), row by row.
static_assert(sizeof(gpu::MediumComponentConstants) == 32);
static_assert(offsetof(gpu::FrameConstants, light_position) == 8 * 64);
static_assert(offsetof(gpu::FrameConstants, cos_outer_cone) == 8 * 64 + 16 + 12);
static_assert(offsetof(gpu::FrameConstants, cos_inner_cone) == 8 * 64 + 32 + 12);
static_assert(offsetof(gpu::FrameConstants, extinction) == 8 * 64 + 48);
static_assert(offsetof(gpu::FrameConstants, medium) == 8 * 64 + 64);
static_assert(offsetof(gpu::FrameConstants, near_ndc_depth) == 8 * 64 + 64 + 4 * 32);
static_assert(offsetof(gpu::FrameConstants, light_type) == 8 * 64 + 64 + 4 * 32 + 16);
static_assert(offsetof(gpu::FrameConstants, shadow_map_size) == 8 * 64 + 64 + 4 * 32 + 16 + 12);
static_assert(offsetof(gpu::FrameConstants, output_extent) == 8 * 64 + 64 + 4 * 32 + 32);
static_assert(offsetof(gpu::FrameConstants, has_light_color) == 8 * 64 + 64 + 4 * 32 + 32 + 12);
static_assert(offsetof(gpu::FrameConstants, target_extent) == 8 * 64 + 64 + 4 * 32 + 48);
static_assert(offsetof(gpu::FrameConstants, target_offset) == 8 * 64 + 64 + 4 * 32 + 48 + 12);
static_assert(offsetof(gpu::FrameConstants, cascade_far) == 8 * 64 + 64 + 4 * 32 + 64);
static_assert(offsetof(gpu::FrameConstants, view_depth_axis) == 8 * 64 + 64 + 4 * 32 + 80);
static_assert(kMaxCascades == gpu::TYN_MAX_CASCADES && kMaxCascades <= kMaxShadowMaps);
static_assert(sizeof(gpu::FrameConstants) == 2 * 64 + 6 * 64 + 4 * 16 + 4 * 32 + 4 * 16 + 2 * 16,
              "FrameConstants must match its std140 layout");
static_assert(kMaxMediumComponents == gpu::TYN_MAX_MEDIUM_COMPONENTS);
static_assert(kMaxShadowMaps == gpu::TYN_MAX_SHADOW_MAPS);

namespace {

bool finite(const Float3& v) {
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}
bool nonNegative(const Float3& v) { return v[0] >= 0.0f && v[1] >= 0.0f && v[2] >= 0.0f; }
glm::dvec3 toVec(const Float3& v) { return {v[0], v[1], v[2]}; }

glm::dmat4 toMat(const Mat4& m) { return glm::dmat4(glm::make_mat4(m.data())); }

bool finite(const Mat4& m) {
  for (float x : m) {
    if (!std::isfinite(x)) return false;
  }
  return true;
}

// A matrix is usable when finite and not singular. Singular is judged after scaling every column
// and then every row to unit length, so that the test does not depend on units: a view matrix's
// translation column is the camera's distance from the origin, and a directional light's
// orthographic matrix scales by the inverse of the scene's size — a test against the largest
// column (|det| > 1e-12 · scale⁴) rejected cameras ~1000 units from the origin.
bool invertible(glm::dmat4 m) {
  for (int c = 0; c < 4; ++c) {
    const double length = glm::length(m[c]);
    if (!(length > 0.0) || !std::isfinite(length)) return false;
    m[c] /= length;
  }
  for (int r = 0; r < 4; ++r) {
    const double length = std::sqrt(m[0][r] * m[0][r] + m[1][r] * m[1][r] + m[2][r] * m[2][r] + m[3][r] * m[3][r]);
    if (!(length > 0.0)) return false;
    for (int c = 0; c < 4; ++c) m[c][r] /= length;
  }
  const double det = glm::determinant(m);
  return std::isfinite(det) && std::abs(det) > 1e-12;
}

Outcome invalid(std::string message) { return failure(Status::InvalidArgument, std::move(message)); }

// Checks an image's handles, extent and layout. Formats are checked by the caller. Outputs
// written by transfer need no view.
Outcome checkImage(const ImageRef& image, const char* name, bool needsView = true) {
  if (image.image == VK_NULL_HANDLE || (needsView && image.view == VK_NULL_HANDLE)) {
    return invalid(std::string(name) + (needsView ? " has a null image or view" : " has a null image"));
  }
  if (image.extent.width == 0 || image.extent.height == 0) {
    return invalid(std::string(name) + " has a zero extent");
  }
  if (image.layout == VK_IMAGE_LAYOUT_UNDEFINED || image.layout == VK_IMAGE_LAYOUT_PREINITIALIZED) {
    return invalid(std::string(name) + ".layout must be its current layout, not UNDEFINED/PREINITIALIZED");
  }
  return {};
}

Outcome checkSampledDepth(const Gpu& gpu, const ImageRef& image, const char* name) {
  if (Outcome o = checkImage(image, name); !o) return o;
  if (!isDepthFormat(image.format) ||
      (gpu.optimalFeatures(image.format) & VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT) == 0) {
    return failure(Status::UnsupportedFormat,
                   std::string(name) + " must be a sampled depth format (D16, D32, X8_D24, D24S8, D32S8), got VkFormat " +
                       std::to_string(static_cast<int>(image.format)));
  }
  return {};
}

Outcome checkExtent(const ImageRef& image, VkExtent2D extent, const char* name) {
  if (image.extent.width != extent.width || image.extent.height != extent.height) {
    return invalid(std::string(name) + " is " + std::to_string(image.extent.width) + "x" +
                   std::to_string(image.extent.height) + " but the context's output extent is " +
                   std::to_string(extent.width) + "x" + std::to_string(extent.height) + " (call resize)");
  }
  return {};
}

Outcome checkOutputImage(const Gpu& gpu, const ImageRef& image, VkExtent2D extent, const char* name) {
  if (image.empty()) return {};
  if (Outcome o = checkImage(image, name, false); !o) return o;
  if (Outcome o = checkExtent(image, extent, name); !o) return o;
  if ((gpu.optimalFeatures(image.format) & VK_FORMAT_FEATURE_BLIT_DST_BIT) == 0 || isDepthFormat(image.format)) {
    return failure(Status::UnsupportedFormat, std::string(name) + " needs a colour format with BLIT_DST support");
  }
  return {};
}

// `prefix` names the light in messages: "" for FrameDesc::light, "additionalLights[i]." after it.
Outcome checkLight(const LightDesc& light, std::uint32_t shadowMapCount, const std::string& prefix) {
  auto invalid = [&](const std::string& message) { return tyndall::invalid(prefix + message); };
  if (!finite(light.color) || !nonNegative(light.color)) return invalid("light.color must be finite and >= 0");
  if (!std::isfinite(light.intensity) || light.intensity < 0.0f) return invalid("light.intensity must be finite and >= 0");
  const bool needsDirection = light.type == LightType::Directional || light.type == LightType::Spot;
  if (needsDirection && (!finite(light.direction) || glm::length(toVec(light.direction)) == 0.0)) {
    return invalid("light.direction must be finite and non-zero");
  }
  if (light.type != LightType::Directional && !finite(light.position)) {
    return invalid("light.position must be finite");
  }
  if (light.type == LightType::Spot) {
    const float inner = light.innerConeRadians;
    const float outer = light.outerConeRadians;
    if (!std::isfinite(inner) || !std::isfinite(outer) || inner < 0.0f || inner > outer ||
        outer >= 1.5707963f) {
      return invalid("light.innerConeRadians/outerConeRadians must satisfy 0 <= inner <= outer < pi/2");
    }
  }
  switch (light.type) {
    case LightType::Directional:
      if (shadowMapCount < 1 || shadowMapCount > kMaxCascades) {
        return invalid("shadowMaps: a directional light needs 1 to " + std::to_string(kMaxCascades) +
                       " shadow maps (cascades), got " + std::to_string(shadowMapCount));
      }
      break;
    case LightType::Spot:
      if (shadowMapCount != 1) return invalid("shadowMaps: a spot light needs exactly 1 shadow map");
      break;
    case LightType::Point:
      if (shadowMapCount != 6) return invalid("shadowMaps: a point light needs exactly 6 shadow maps (cube faces)");
      break;
    default:
      return invalid("light.type is not a LightType");
  }
  return {};
}

Outcome checkMedium(std::span<const MediumComponent> medium) {
  if (medium.empty() || medium.size() > kMaxMediumComponents) {
    return invalid("medium needs 1 to " + std::to_string(kMaxMediumComponents) + " components");
  }
  for (std::size_t i = 0; i < medium.size(); ++i) {
    const MediumComponent& c = medium[i];
    const std::string name = "medium[" + std::to_string(i) + "]";
    if (!finite(c.scattering) || !nonNegative(c.scattering)) return invalid(name + ".scattering must be finite and >= 0");
    if (!finite(c.absorption) || !nonNegative(c.absorption)) return invalid(name + ".absorption must be finite and >= 0");
    if (static_cast<std::uint32_t>(c.phase) > static_cast<std::uint32_t>(PhaseFunction::CornetteShanks)) {
      return invalid(name + ".phase is not a PhaseFunction");
    }
    if (!std::isfinite(c.g) || c.g <= -1.0f || c.g >= 1.0f) return invalid(name + ".g must be in (-1, 1)");
  }
  return {};
}

// A directional light's cascades: each a range 0 ≤ near < far, each starting exactly where the one
// before ends (the host hands both sides the same split value, so equality is exact).
Outcome checkCascades(const LightSetup& light, const std::string& prefix) {
  if (!hasCascades(light.light.type, light.shadowMaps.size())) return {};
  for (std::size_t i = 0; i < light.shadowMaps.size(); ++i) {
    const ShadowMapDesc& map = light.shadowMaps[i];
    const std::string name = prefix + "shadowMaps[" + std::to_string(i) + "]";
    if (!std::isfinite(map.viewDepthNear) || !std::isfinite(map.viewDepthFar) || map.viewDepthNear < 0.0f ||
        !(map.viewDepthFar > map.viewDepthNear)) {
      return invalid(name + ".viewDepthNear/viewDepthFar must be finite with 0 <= near < far (a cascade's view depths)");
    }
    if (i > 0 && map.viewDepthNear != light.shadowMaps[i - 1].viewDepthFar) {
      return invalid(name + ".viewDepthNear must equal shadowMaps[" + std::to_string(i - 1) +
                     "].viewDepthFar: cascades are ordered, finest first, and touch (no gap, no overlap)");
    }
  }
  return {};
}

// Map `i`'s translucent layers (ShadowMapDesc::translucentLayers): as many as map 0's, the map's
// size, (depth, α) in R32G32_SFLOAT.
Outcome checkTranslucentLayers(const LightSetup& light, std::size_t i, const std::string& name) {
  const ShadowMapDesc& map = light.shadowMaps[i];
  const std::uint32_t count = light.shadowMaps[0].translucentLayerCount;
  if (map.translucentLayerCount != count) {
    return invalid(name + ".translucentLayerCount must equal shadowMaps[0]'s: every map of a light has as many "
                          "translucent layers");
  }
  if (map.translucentLayers.empty() != (count == 0)) {
    return invalid(name + ".translucentLayers and translucentLayerCount go together: an image with 1 to " +
                   std::to_string(kMaxTranslucentLayers) + " layers, or none with 0");
  }
  if (count == 0) return {};
  if (count > kMaxTranslucentLayers) {
    return invalid(name + ".translucentLayerCount must be at most " + std::to_string(kMaxTranslucentLayers));
  }
  const std::string field = name + ".translucentLayers";
  if (Outcome o = checkImage(map.translucentLayers, field.c_str()); !o) return o;
  if (map.translucentLayers.format != VK_FORMAT_R32G32_SFLOAT) {
    return failure(Status::UnsupportedFormat, field + " must be R32G32_SFLOAT (depth, opacity), got VkFormat " +
                                                  std::to_string(static_cast<int>(map.translucentLayers.format)));
  }
  if (map.translucentLayers.extent.width != map.depth.extent.width ||
      map.translucentLayers.extent.height != map.depth.extent.height) {
    return invalid(field + " must be the size of its shadow map");
  }
  return {};
}

// A light's colour texture and shadow maps; `prefix` as for checkLight.
Outcome checkLightImages(const Gpu& gpu, const LightSetup& light, const std::string& prefix) {
  if (!light.lightColor.empty()) {
    if (Outcome o = checkImage(light.lightColor, (prefix + "lightColor").c_str()); !o) return o;
    if (isDepthFormat(light.lightColor.format) ||
        (gpu.optimalFeatures(light.lightColor.format) & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT) == 0) {
      return failure(Status::UnsupportedFormat, prefix + "lightColor needs a colour format with linear filtering, got VkFormat " +
                                                    std::to_string(static_cast<int>(light.lightColor.format)));
    }
    if (light.light.type == LightType::Point) {
      return failure(Status::UnsupportedFeature, prefix + "lightColor: a point light has no single map to lay it over");
    }
    if (light.shadowMaps.size() > 1) {
      return failure(Status::UnsupportedFeature, prefix + "lightColor: a light with cascades has no single map to lay it over");
    }
  }
  const std::uint32_t mapSize = light.shadowMaps.empty() ? 0 : light.shadowMaps[0].depth.extent.width;
  for (std::size_t i = 0; i < light.shadowMaps.size(); ++i) {
    const ShadowMapDesc& map = light.shadowMaps[i];
    const std::string name = prefix + "shadowMaps[" + std::to_string(i) + "]";
    if (Outcome o = checkSampledDepth(gpu, map.depth, (name + ".depth").c_str()); !o) return o;
    if (map.depth.extent.width != map.depth.extent.height || map.depth.extent.width != mapSize) {
      return invalid(name + ".depth must be square and all shadow maps the same size");
    }
    if (!finite(map.worldToShadowClip) || !invertible(toMat(map.worldToShadowClip))) {
      return invalid(name + ".worldToShadowClip must be finite and invertible");
    }
    if (Outcome o = checkTranslucentLayers(light, i, name); !o) return o;
  }
  return checkCascades(light, prefix);
}

// This light's fields of the constants; `worldToView` gives its cascades' view depths.
void setLightConstants(const LightSetup& l, const glm::dmat4& worldToView, gpu::FrameConstants& k) {
  for (std::size_t i = 0; i < l.shadowMaps.size(); ++i) {
    k.world_to_shadow[i] = glm::make_mat4(l.shadowMaps[i].worldToShadowClip.data());
  }
  const LightDesc& light = l.light;
  const glm::vec3 direction =
      light.type == LightType::Point ? glm::vec3(0.0f, -1.0f, 0.0f) : glm::vec3(glm::normalize(toVec(light.direction)));
  k.light_position = glm::vec3(toVec(light.position));
  k.light_direction = direction;
  k.cos_outer_cone = std::cos(light.outerConeRadians);
  k.light_radiance = glm::vec3(toVec(light.color)) * light.intensity;
  k.cos_inner_cone = std::cos(light.innerConeRadians);
  k.light_type = static_cast<std::uint32_t>(light.type);
  k.shadow_map_count = static_cast<std::uint32_t>(l.shadowMaps.size());
  k.shadow_map_size = l.shadowMaps.empty() ? 0 : l.shadowMaps[0].depth.extent.width;
  k.has_light_color = l.lightColor.empty() ? 0u : 1u;
  k.translucent_layer_count = l.shadowMaps.empty() ? 0u : l.shadowMaps[0].translucentLayerCount;
  // View depth is −z in view space: row 2 of the world → view matrix, negated.
  k.view_depth_axis = -glm::vec4(glm::row(worldToView, 2));
  k.cascade_far = glm::vec4(std::numeric_limits<float>::max());
  if (light.type == LightType::Directional) {
    for (std::size_t i = 0; i + 1 < l.shadowMaps.size(); ++i) k.cascade_far[int(i)] = l.shadowMaps[i].viewDepthFar;
  }
}

}  // namespace

Outcome prepareFrame(const Gpu& gpu, VkExtent2D outputExtent, const FrameDesc& frame,
                     FrameSetup& out) {
  out = FrameSetup{};
  if (static_cast<std::uint32_t>(frame.profile) > static_cast<std::uint32_t>(Profile::Auto)) {
    return invalid("profile is not a Profile");
  }
  if (!std::isfinite(frame.autoBudgetMilliseconds) || frame.autoBudgetMilliseconds <= 0.0f) {
    return invalid("autoBudgetMilliseconds must be finite and > 0");
  }
  if (static_cast<std::uint32_t>(frame.technique) > static_cast<std::uint32_t>(Technique::Prefiltered)) {
    return invalid("technique is not a Technique");
  }
  if (frame.epipolar != nullptr) {
    if (Outcome o = validateEpipolarSettings(*frame.epipolar); !o) return o;
  }
  if (frame.prefiltered != nullptr) {
    if (Outcome o = validatePrefilteredSettings(*frame.prefiltered); !o) return o;
  }
  if (frame.resolution && !isScatteringResolution(*frame.resolution)) {
    return invalid("resolution is not a ScatteringResolution");
  }

  // Camera.
  if (!finite(frame.camera.view) || !invertible(toMat(frame.camera.view))) {
    return invalid("camera.view must be finite and invertible");
  }
  const glm::dmat4 projection = toMat(frame.camera.projection);
  if (Outcome o = analyzeProjection(projection, out.projection); !o) return o;
  if (out.projection.infiniteFar &&
      (!std::isfinite(frame.camera.infiniteFarSkyDistance) || frame.camera.infiniteFarSkyDistance <= 0.0f)) {
    return invalid("camera.infiniteFarSkyDistance must be finite and > 0 with an infinite far plane");
  }

  if (Outcome o = checkLight(frame.light, static_cast<std::uint32_t>(frame.shadowMaps.size()), ""); !o) return o;
  if (Outcome o = checkMedium(frame.medium); !o) return o;

  // Images.
  if (Outcome o = checkSampledDepth(gpu, frame.depth, "depth"); !o) return o;
  if (Outcome o = checkExtent(frame.depth, outputExtent, "depth"); !o) return o;
  if (Outcome o = checkImage(frame.color, "color"); !o) return o;
  if (Outcome o = checkExtent(frame.color, outputExtent, "color"); !o) return o;
  if ((gpu.optimalFeatures(frame.color.format) & VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT) == 0) {
    return failure(Status::UnsupportedFormat,
                   "color must be a format with COLOR_ATTACHMENT_BLEND support, got VkFormat " +
                       std::to_string(static_cast<int>(frame.color.format)));
  }
  if (Outcome o = checkOutputImage(gpu, frame.scatteringOutput, outputExtent, "scatteringOutput"); !o) return o;
  if (Outcome o = checkOutputImage(gpu, frame.transmittanceOutput, outputExtent, "transmittanceOutput"); !o) return o;
  if (static_cast<std::uint32_t>(frame.debugView) > static_cast<std::uint32_t>(DebugView::FixedUpPixels)) {
    return invalid("debugView is not a DebugView");
  }
  if (frame.debugView != DebugView::None && frame.debugOutput.empty()) {
    return invalid("debugView needs a debugOutput image");
  }
  if (Outcome o = checkOutputImage(gpu, frame.debugOutput, outputExtent, "debugOutput"); !o) return o;
  // Lights: the first, then the additional ones, each with its maps and colour texture.
  if (frame.additionalLights.size() > kMaxLights - 1) {
    return invalid("additionalLights holds " + std::to_string(frame.additionalLights.size()) + " lights; at most " +
                   std::to_string(kMaxLights - 1) + " (kMaxLights with FrameDesc::light)");
  }
  out.lights.push_back({{}, frame.light, frame.shadowMaps, frame.lightColor, LightSkipped::No});
  for (const LightInput& light : frame.additionalLights) {
    out.lights.push_back({{}, light.light, light.shadowMaps, light.lightColor, LightSkipped::No});
  }
  for (std::size_t i = 0; i < out.lights.size(); ++i) {
    const std::string prefix = i == 0 ? std::string() : "additionalLights[" + std::to_string(i - 1) + "].";
    const LightSetup& l = out.lights[i];
    if (i > 0) {  // the first light was checked with the camera
      if (Outcome o = checkLight(l.light, static_cast<std::uint32_t>(l.shadowMaps.size()), prefix); !o) return o;
    }
    if (Outcome o = checkLightImages(gpu, l, prefix); !o) return o;
  }

  // Constants.
  gpu::FrameConstants k{};
  const glm::dmat4 viewToWorld = glm::inverse(toMat(frame.camera.view));
  const glm::dmat4 clipToView = glm::inverse(projection);
  k.view_to_world = glm::mat4(viewToWorld);
  k.clip_to_view = glm::mat4(clipToView);

  glm::vec3 extinction(0.0f);
  glm::vec3 scattering(0.0f);
  for (std::size_t i = 0; i < frame.medium.size(); ++i) {
    const MediumComponent& c = frame.medium[i];
    const glm::vec3 sigmaS = glm::vec3(toVec(c.scattering));
    extinction += sigmaS + glm::vec3(toVec(c.absorption));
    scattering += sigmaS;
    k.medium[i].scattering = sigmaS;
    k.medium[i].g = c.g;
    k.medium[i].phase_type = static_cast<std::uint32_t>(c.phase);
  }
  k.extinction = extinction;
  out.scattering = scattering;
  out.extinction = extinction;
  k.near_ndc_depth = out.projection.nearNdc;
  k.far_ndc_depth = out.projection.farNdc;
  k.far_at_infinity = out.projection.infiniteFar ? 1u : 0u;
  k.sky_distance = frame.camera.infiniteFarSkyDistance;
  k.medium_component_count = static_cast<std::uint32_t>(frame.medium.size());
  out.attenuates = glm::length(extinction) > 0.0f;
  k.output_extent = glm::uvec2(outputExtent.width, outputExtent.height);
  k.target_extent = k.output_extent;  // full resolution until the context sets the technique's
  k.target_stride = 1;
  k.target_offset = 0;
  k.target_scale = 1.0f;  // until the context knows the target's format (scatteringTargetScale)
  k.target_unscale = 1.0f;
  // Each light: the shared constants with its own fields, and whether it has anything to add.
  const bool mediumScatters = glm::length(scattering) > 0.0f;
  for (LightSetup& l : out.lights) {
    l.constants = k;
    setLightConstants(l, toMat(frame.camera.view), l.constants);
    const LightDesc& light = l.light;
    if (!(light.intensity > 0.0f && glm::length(glm::vec3(toVec(light.color))) > 0.0f)) {
      l.skipped = LightSkipped::Off;
    } else if (!mediumScatters) {
      l.skipped = LightSkipped::NothingScatters;
    } else if (light.type == LightType::Spot &&
               spotConeMissesView(viewToWorld, clipToView, toVec(light.position),
                                  glm::normalize(toVec(light.direction)), light.outerConeRadians)) {
      l.skipped = LightSkipped::OutsideView;
    }
    out.scatters = out.scatters || l.skipped == LightSkipped::No;
    if (light.type != LightType::Directional) {
      const glm::dvec4 clip = projection * toMat(frame.camera.view) * glm::dvec4(toVec(light.position), 1.0);
      if (clip.w > 0.0) {
        const glm::dvec2 ndc = glm::dvec2(clip) / clip.w;
        l.imagePixel = (ndc * 0.5 + 0.5) * glm::dvec2(outputExtent.width, outputExtent.height);
      }
    }
  }
  return {};
}

float scatteringTargetScale(const FrameSetup& setup) {
  constexpr double kInverseFourPi = 0.25 / 3.14159265358979323846;
  // Powers of two whose products with any float L_in stay within float range.
  constexpr int kLargestExponent = 64;
  double typical = 0.0;
  for (const LightSetup& l : setup.lights) {
    if (l.skipped != LightSkipped::No) continue;
    const gpu::FrameConstants& k = l.constants;
    const glm::dvec3 camera(k.view_to_world[3]);
    double length = l.light.type == LightType::Directional
                        ? (setup.projection.infiniteFar ? double(k.sky_distance) : setup.projection.farDistance)
                        : glm::length(glm::dvec3(k.light_position) - camera);
    length = std::max(length, setup.projection.nearDistance);
    const double irradiance = l.light.type == LightType::Directional ? 1.0 : 1.0 / (length * length);
    for (int c = 0; c < 3; ++c) {
      const double sigmaT = setup.extinction[c];
      const double path = sigmaT > 0.0 ? std::min(1.0 / sigmaT, length) : length;
      typical = std::max(typical, double(k.light_radiance[c]) * irradiance * double(setup.scattering[c]) * path *
                                      kInverseFourPi);
    }
  }
  if (!(typical > 0.0) || !std::isfinite(typical)) return 1.0f;
  const int exponent = std::clamp(-static_cast<int>(std::lround(std::log2(typical))), -kLargestExponent, kLargestExponent);
  return std::ldexp(1.0f, exponent);
}

}  // namespace tyndall
