#include "prefiltered/prefiltered_plan.h"

#include <cstdio>
#include <limits>

#include <glm/gtc/type_ptr.hpp>

#include "common/epipole.h"
#include "prefiltered/rectification_setup.h"

namespace tyndall {

namespace {

std::string printed(const char* fmt, double value) {
  char text[64];
  std::snprintf(text, sizeof(text), fmt, value);
  return text;
}

}  // namespace

Outcome planPrefilteredFrame(const FrameDesc& frame, const PrefilteredSettings& settings, VkExtent2D extent,
                             PrefilteredFramePlan& plan) {
  plan = PrefilteredFramePlan{};
  // Rectification (double precision on the CPU, rectification_setup.h).
  const glm::dmat4 view(glm::make_mat4(frame.camera.view.data()));
  const glm::dmat4 projection(glm::make_mat4(frame.camera.projection.data()));
  prefiltered::ViewFrustum frustum;
  if (Outcome o = prefiltered::buildViewFrustum(view, projection, frame.camera.infiniteFarSkyDistance, frustum); !o) {
    return o;
  }
  const glm::dvec3 lightDirection = glm::normalize(
      glm::dvec3(frame.light.direction[0], frame.light.direction[1], frame.light.direction[2]));
  const prefiltered::NonLinearRectification rect = prefiltered::computeNonLinearRectification(frustum, lightDirection);
  const prefiltered::ProjectiveRectification proj = prefiltered::computeProjectiveRectification(frustum, rect);
  bool projective = false;
  std::string rectNote;
  const std::string stretch = proj.constructible ? printed("%.2f", proj.texelStretch) : std::string("inf");
  plan.decisions.projectiveTexelStretch =
      proj.constructible ? proj.texelStretch : std::numeric_limits<double>::infinity();
  plan.decisions.choice = RectificationChoice::Requested;
  switch (settings.rectification) {
    case PrefilteredRectification::Automatic:
      plan.decisions.choice = RectificationChoice::Automatic;
      projective = prefiltered::useProjectiveRectification(proj);
      rectNote = projective ? "projective rectification (automatic: texel stretch " + stretch + " <= 2)"
                            : proj.constructible
                                  ? "non-linear rectification (automatic: projective texel stretch " + stretch + " > 2)"
                                  : "non-linear rectification (automatic: the light axis is in the frustum)";
      break;
    case PrefilteredRectification::NonLinear:
      rectNote = "non-linear rectification (set)";
      break;
    case PrefilteredRectification::Projective:
      projective = proj.constructible;
      if (!projective) plan.decisions.choice = RectificationChoice::ProjectiveImpossible;
      rectNote = projective ? "projective rectification (set; texel stretch " + stretch + ")"
                            : "projective rectification impossible (the light axis is in the frustum): non-linear instead";
      break;
  }

  // Extinction of the prefix weights: one grey set, or one set per distinct channel.
  glm::dvec3 sigmaT(0.0);
  for (const MediumComponent& c : frame.medium) {
    for (int i = 0; i < 3; ++i) sigmaT[i] += double(c.scattering[i]) + double(c.absorption[i]);
  }
  const prefiltered::PrefixSumExtinction extinction =
      prefiltered::choosePrefixSumExtinction(sigmaT, frustum.maxRayLength);
  gpu::PrefilteredConstants k{};
  std::uint32_t sets = 1;
  std::string extinctionNote;
  if (!extinction.perChannel) {
    k.set_extinction = glm::vec3(static_cast<float>(extinction.sigma));
    k.channel_set = glm::uvec3(0u);
    extinctionNote = extinction.distinctChannels == 1
                         ? "grey extinction"
                         : "one grey extinction for the prefix weights (visibility error <= " +
                               printed("%.4f", extinction.greyMaxError) + ")";
  } else {
    sets = 0;
    for (int c = 0; c < 3; ++c) {
      std::uint32_t set = sets;
      for (int earlier = 0; earlier < c; ++earlier) {
        if (sigmaT[earlier] == sigmaT[c]) set = k.channel_set[earlier];
      }
      if (set == sets) k.set_extinction[static_cast<int>(sets++)] = static_cast<float>(sigmaT[c]);
      k.channel_set[c] = set;
    }
    extinctionNote = std::to_string(sets) + " prefix-sum sets, one per extinction (grey would err by " +
                     printed("%.3f", extinction.greyMaxError) + ")";
  }

  // The epipole and its block (on screen: the CPU records the passes, the GPU sizes them).
  const glm::mat4 viewProj = glm::make_mat4(frame.camera.projection.data()) * glm::make_mat4(frame.camera.view.data());
  k.epipole = gpu::tyn_epipole(gpu::tyn_epipole_clip_directional(viewProj, glm::vec3(lightDirection)));
  bool blockOnScreen = false;
  if (settings.epipoleBlockPixels > 0 && k.epipole.z > 0.0f) {
    const glm::vec2 size(static_cast<float>(extent.width), static_cast<float>(extent.height));
    const glm::vec2 ndc = glm::clamp(glm::vec2(k.epipole.x, k.epipole.y) / k.epipole.z, glm::vec2(-4.0f), glm::vec2(4.0f));
    const glm::vec2 centre = (ndc * 0.5f + 0.5f) * size;
    const glm::vec2 lo = glm::floor(centre - 0.5f * static_cast<float>(settings.epipoleBlockPixels) + 0.5f);
    const glm::vec2 hi = lo + static_cast<float>(settings.epipoleBlockPixels);
    blockOnScreen = hi.x > 0.0f && hi.y > 0.0f && lo.x < size.x && lo.y < size.y;
  }

  const std::uint32_t mapSize = frame.shadowMaps[0].depth.extent.width;
  k.nonlinear = prefiltered::toGpu(rect);
  k.projective = prefiltered::toGpu(proj);
  k.map_columns = settings.columns;
  k.map_rows = settings.rows;
  k.projective_map = projective ? 1u : 0u;
  k.rows_wrap = !projective && rect.fullCircle ? 1u : 0u;
  k.filtered_resampling = settings.filteredResampling ? 1u : 0u;
  k.spacing = static_cast<std::uint32_t>(settings.spacing);
  k.prefix_sum_sets = sets;
  k.host_map_size = mapSize;
  const bool segmented = settings.segmentedReconstruction && settings.rayWeightTaps > 1;
  const bool trimmed = segmented && settings.depthBounds && settings.trimmedSegments;
  const std::uint32_t walk = trimmed ? settings.texelWalkSteps : 0u;
  k.epipole_block_pixels = settings.epipoleBlockPixels;
  k.ray_weight_taps = settings.rayWeightTaps;
  k.segmented = segmented ? 1u : 0u;
  k.trimmed = trimmed ? 1u : 0u;
  k.overestimation = settings.adaptiveOverestimation ? -1.0f : settings.overestimation;
  k.depth_bounds = settings.depthBounds ? 1u : 0u;
  k.short_ray_columns = settings.shortRayColumns;
  k.texel_walk_steps = walk;

  plan.texelWalkSteps = walk;
  plan.decisions.rectification = projective ? Rectification::Projective : Rectification::NonLinear;
  plan.decisions.prefixSumSets = sets;
  plan.decisions.rowDepthBounds = settings.depthBounds;
  plan.decisions.segments = segmented ? settings.rayWeightTaps : 0u;
  plan.decisions.trimmedSegments = trimmed;
  plan.decisions.texelWalkSteps = walk;
  plan.decisions.shortRayColumns = settings.shortRayColumns;
  plan.decisions.epipoleBlockMarched = blockOnScreen;
  plan.note = std::string("; ") + to_string(settings.basis) + ", " + std::to_string(settings.rows) + " rows x " +
          std::to_string(settings.columns) + " columns, " + rectNote + ", " + extinctionNote +
          (settings.filteredResampling ? ", filtered resampling" : ", nearest resampling") +
          (settings.depthBounds ? ", row depth bounds" : "") +
          (segmented ? ", segmented reconstruction (" + std::to_string(settings.rayWeightTaps) + " segments)" : "") +
          (trimmed ? ", trimmed segments" : "") +
          (walk > 0 ? ", texel walk of " + std::to_string(walk) + " steps" : "") +
          (settings.shortRayColumns > 0
               ? ", rays within " + std::to_string(settings.shortRayColumns) + " columns ray-marched"
               : "") +
          (blockOnScreen ? ", epipole block " + std::to_string(settings.epipoleBlockPixels) + " px ray-marched" : "");
  plan.constants = k;
  return {};
}

}  // namespace tyndall
