#include "epipolar/epipolar_plan.h"

#include <algorithm>
#include <cstdio>

#include <glm/gtc/type_ptr.hpp>

#include "epipolar/epipolar_geometry.h"
#include "epipolar/epipolar_technique.h"
#include "epipolar/min_max_tree.h"
#include "epipolar/slice_arc.h"

namespace tyndall {

namespace {

// The epipole density a frame with `light` runs with: the settings' when set (≥ 1), else 1 for a
// directional light and TYN_EPIPOLAR_LOCAL_LIGHT_DENSITY for a spot or point light.
float effectiveEpipoleDensity(const EpipolarSettings& settings, LightType light) {
  if (settings.epipoleDensity > 0.0f) return settings.epipoleDensity;
  return light == LightType::Directional ? 1.0f : gpu::TYN_EPIPOLAR_LOCAL_LIGHT_DENSITY;
}

// Push constants of the epipolar passes; the epipole is found here, in C++, by the same code
// the shaders would run (shaders/epipolar/epipolar_geometry.h).
// `arc` is the frame's slice arc (slice_arc.h), found from the epipole computed here.
// `walked`: walksMaps() of the frame's light.
gpu::EpipolarConstants epipolarConstants(const FrameDesc& frame, const EpipolarSettings& settings, VkExtent2D extent,
                                         bool walked, SliceArc& arc) {
  const glm::mat4 viewProj = glm::make_mat4(frame.camera.projection.data()) * glm::make_mat4(frame.camera.view.data());
  const LightDesc& light = frame.light;
  const glm::vec4 lightClip =
      light.type == LightType::Directional
          ? gpu::tyn_epipole_clip_directional(viewProj, glm::normalize(glm::make_vec3(light.direction.data())))
          : gpu::tyn_epipole_clip_local(viewProj, glm::make_vec3(light.position.data()));
  gpu::EpipolarConstants k{};
  k.epipole = gpu::tyn_epipole(lightClip);
  arc = sliceArc(frame.camera, light, k.epipole, glm::vec2(float(extent.width), float(extent.height)));
  k.arc_start = arc.arc.x;
  k.arc_length = arc.arc.y;
  k.fixup_steps = settings.fixupSteps;
  k.slice_count = settings.slices;
  k.samples_per_slice = settings.samplesPerSlice;
  k.improved_placement = settings.improvedSamplePlacement ? 1u : 0u;
  k.initial_sample_step = settings.initialSampleStep;
  k.depth_break_threshold = settings.refinementThreshold;
  k.intensity_refinement_threshold = settings.intensityRefinementThreshold;
  k.slice_contrast_threshold = settings.sliceContrastThreshold;
  // A local light's occluders can sit next to it, where L_in changes within a pixel: denser
  // samples and a finer march step there (epipolar_constants.h).
  k.epipole_density = effectiveEpipoleDensity(settings, light.type);
  k.near_epipole_steps = light.type == LightType::Directional ? gpu::TYN_EPIPOLAR_NEAR_EPIPOLE_STEPS
                                                              : gpu::TYN_EPIPOLAR_NEAR_LOCAL_LIGHT_STEPS;
  k.bilateral_depth_threshold = settings.bilateralDepthThreshold;
  k.fixup_weight_threshold = settings.fixupWeightThreshold;
  k.epipole_block_radius = epipoleBlockRadius(settings, extent.height);
  // The default block's disc is where a local light's peak outshines the frame (docs/EPIPOLAR.md
  // "Fewer steps"): its pixels take the texel walk even with fixupSteps; a larger block asked for
  // takes the steps outside it.
  k.epipole_walk_radius = std::min(k.epipole_block_radius, epipoleBlockRadius(EpipolarSettings{}, extent.height));
  // Directional and spot lights march along each slice's line in their map (a directional light's
  // cascades: one line each, all maps the same size); a point light's rays cross six maps, so its
  // samples take the Reference's walk. The tree's level 0 lives in the build pass's shared memory,
  // which bounds L (maps larger than 4096² march every cell).
  if (!walked) {
    const int samples = gpu::tyn_min_max_sample_count(static_cast<int>(frame.shadowMaps[0].depth.extent.width));
    const bool tree = settings.minMaxTree && samples <= static_cast<int>(gpu::TYN_EPIPOLAR_TREE_MAX_SAMPLES);
    const int topLevel = std::min(gpu::tyn_min_max_level_for_max_step(static_cast<int>(settings.maxTreeStep)),
                                  gpu::tyn_min_max_highest_level(samples));
    // With a light-colour texture lit parts are integrated in chunks of coloredStep cells, each
    // uncoloured times its mean colour (min_max_tree.h, tyn_min_max_add_colored; light_color_sums.h).
    const std::uint32_t coloredChunk = frame.lightColor.empty() ? 0u : settings.coloredStep;
    k.tree_samples = static_cast<std::uint32_t>(samples);
    k.tree_top_level = static_cast<std::uint32_t>(topLevel);
    k.tree_enabled = tree ? 1u : 0u;
    k.colored_chunk = coloredChunk;
  }
  return k;
}

// How the epipolar technique marches this frame, for the stats.
EpipolarMarch epipolarMarch(const gpu::EpipolarConstants& k, const EpipolarSettings& settings, bool walked) {
  if (walked) return EpipolarMarch::PointLightBlockWalk;
  if (k.tree_enabled != 0) return EpipolarMarch::MinMaxTree;
  return settings.minMaxTree ? EpipolarMarch::CellsMapTooLarge : EpipolarMarch::CellsTreeOff;
}

}  // namespace

// The epipolar part of the note: how it marched, and where the slices went (slice_arc.h).
std::string epipolarNote(const EpipolarStats& s) {
  std::string note;
  switch (s.march) {
    case EpipolarMarch::MinMaxTree: break;
    case EpipolarMarch::CellsTreeOff: note = "; min/max tree off"; break;
    case EpipolarMarch::CellsMapTooLarge: note = "; shadow map above 4096^2: march without the min/max tree"; break;
    case EpipolarMarch::PointLightBlockWalk:
      note = "; point light: samples marched with the texel walk across blocks of " +
             std::to_string(gpu::TYN_EPIPOLAR_WALKED_SHADOW_BLOCK) + "^2 texels (no single slice line)";
      break;
  }
  if (s.linesPerSlice > 1) {
    note += "; " + std::to_string(s.linesPerSlice) + " cascades: each slice marched along its line in every cascade";
  }
  if (s.sliceBorderFraction >= 1.0f) return note;
  char line[120];
  std::snprintf(line, sizeof(line), "; slices over %.1f%% of the border (%s%s%s)", 100.0 * s.sliceBorderFraction,
                s.slicesFitSpotCone ? "spot cone" : "", s.slicesFitSpotCone && s.slicesFitOffScreenEpipole ? ", " : "",
                s.slicesFitOffScreenEpipole ? "epipole off screen" : "");
  return note + line;
}

EpipolarFramePlan planEpipolarFrame(const FrameDesc& frame, const EpipolarSettings& settings, VkExtent2D extent) {
  EpipolarFramePlan plan;
  SliceArc arc;
  plan.walksMaps = walksMaps(frame.light.type);
  plan.lineMaps = plan.walksMaps ? 0u : static_cast<std::uint32_t>(frame.shadowMaps.size());
  plan.constants = epipolarConstants(frame, settings, extent, plan.walksMaps, arc);
  gpu::EpipolarConstants& k = plan.constants;
  plan.stats = EpipolarStats{settings.slices,
                             settings.samplesPerSlice,
                             k.epipole_density,
                             epipolarMarch(k, settings, plan.walksMaps),
                             arc.fraction,
                             arc.cone,
                             arc.screen};
  plan.treeSamples = k.tree_enabled != 0 ? k.tree_samples : 0;
  // The light-colour texture's sums along the slices' lines, for the march along them.
  plan.colorSamples = k.colored_chunk != 0 ? k.tree_samples : 0;
  plan.stats.coloredChunkCells = !plan.walksMaps ? k.colored_chunk : 0;
  plan.stats.linesPerSlice = plan.lineMaps;
  // The blocks the walks cross (block_walk.glsl): a walked light's march walks every sample; a
  // directional light's fix-up (every cascade's blocks) only where it walks texel by texel (not in
  // steps).
  const bool blocks = plan.walksMaps || settings.fixupSteps == 0;
  plan.shadowBlocks = !frame.shadowMaps.empty() && blocks
                          ? shadowBlockExtent(frame.light.type, frame.shadowMaps[0].depth.extent.width,
                                              static_cast<std::uint32_t>(frame.shadowMaps.size()))
                          : VkExtent2D{0, 0};
  // Blocks along a map's side: unwarp.comp sizes a directional light's blocks pass by it.
  k.shadow_block_side = plan.shadowBlocks.width;
  return plan;
}

}  // namespace tyndall
