// The epipolar passes' push constants and the numbers the passes and the C++ side agree on.
#ifndef TYNDALL_EPIPOLAR_CONSTANTS_H
#define TYNDALL_EPIPOLAR_CONSTANTS_H

#include "common/cpp_glsl.h"

TYN_BEGIN

// Workgroup sizes: one thread per slice, per fixed-up pixel of the debug view, per ray-marching
// sample; the refinement's threads of one slice. The fix-up runs groups of this size too: one
// thread per pixel, or (on a GPU) one group of TYN_SPLIT_MARCH_PARTS threads per pixel, so the two
// sizes are equal (epipolar_technique.cpp checks).
TYN_CONST uint TYN_EPIPOLAR_SLICE_GROUP = 64u;
TYN_CONST uint TYN_EPIPOLAR_REFINE_GROUP = 64u;
TYN_CONST uint TYN_EPIPOLAR_FIXUP_GROUP = 64u;
// Most groups of the indirect fix-up and march dispatches: the smallest maxComputeWorkGroupCount[0]
// Vulkan allows (fixup.comp and march.comp stride over the rest of their list).
TYN_CONST uint TYN_EPIPOLAR_MAX_GROUPS = 65535u;
// Threads sharing one sample's march on a GPU (march.comp, TYN_MARCH_PARTS; a CPU driver uses 1).
TYN_CONST uint TYN_EPIPOLAR_MARCH_PARTS_GPU = 8u;
TYN_CONST uint TYN_EPIPOLAR_MARCH_GROUP = 64u;
// Most samples per slice (EpipolarSettings::samplesPerSlice; the refinement's shared bit words and
// the 16-bit sample index of the march list's entries).
TYN_CONST uint TYN_EPIPOLAR_MAX_SAMPLES = 4096u;
// Interpolation source of a sample past the slice's sample count.
TYN_CONST uint TYN_EPIPOLAR_NO_SOURCE = 0xffffffffu;
// Near the epipole the ray-marching step is at most 1/this of the distance to it (slice_setup.comp):
// for a directional light, whose L_in there follows the phase lobe smoothly, and for a spot or point
// light, whose occluders can sit next to it and cut L_in at a scale proportional to that distance.
TYN_CONST float TYN_EPIPOLAR_NEAR_EPIPOLE_STEPS = 4.0f;
TYN_CONST float TYN_EPIPOLAR_NEAR_LOCAL_LIGHT_STEPS = 16.0f;
// The epipole density (EpipolarSettings::epipoleDensity) a spot or point light gets by default: with
// improved placement the samples then lie 1/16 px apart at the light and 1 px at the border, so that
// an occluder next to the light, which cuts L_in between two samples a pixel apart, falls between
// samples (docs/EPIPOLAR.md "Spot lights: where the error is"). A directional light's is 1 (uniform).
TYN_CONST float TYN_EPIPOLAR_LOCAL_LIGHT_DENSITY = 16.0f;
// An interval refine_intensity.comp refines is cut into this many (the initial step into quarters).
TYN_CONST uint TYN_EPIPOLAR_SUBDIVISIONS = 4u;
// Threads building one slice's min/max tree (one workgroup per slice).
TYN_CONST uint TYN_EPIPOLAR_TREE_GROUP = 128u;
// Largest L whose level 0 fits the tree pass's shared memory (L/2 nodes of 8 bytes: 16 KiB, half of
// lavapipe's 32 KiB) and whose tree fits one texture row (L − 1 texels).
TYN_CONST uint TYN_EPIPOLAR_TREE_MAX_SAMPLES = 4096u;

// Texels along each side of the fix-up's shadow-map blocks (shadow_blocks.comp, block_walk.glsl),
// even (the blocks pass gathers 2 × 2 texels), and the blocks pass's workgroup side. Small: a
// fixed-up pixel's ray crosses canopies and the ground below them, where only small blocks decide.
TYN_CONST uint TYN_EPIPOLAR_SHADOW_BLOCK = 4u;
TYN_CONST uint TYN_EPIPOLAR_SHADOW_BLOCK_GROUP = 8u;
// The same for the lights whose march walks its maps for every sample (a point light's six
// maps; tyn_epipolar_walks_maps): their rays cross wide open
// space, where large blocks decide (beyond 32 a point light's march gains little).
TYN_CONST uint TYN_EPIPOLAR_WALKED_SHADOW_BLOCK = 32u;
// The blocks are built when at least one pixel per this many texels of the map's side is fixed up.
// A walk crosses about a map side of texels and the blocks pass reads side² of them, so the
// threshold scales with the side; the pass pays for itself from about a side / 4 pixels.
TYN_CONST uint TYN_EPIPOLAR_SHADOW_BLOCK_PIXELS = 4u;
// Most steps of the fix-up's stepped march (EpipolarSettings::fixupSteps, fixup_steps.glsl). A
// local light's steps may each end a lit run integrated by quadrature, whose loops count against
// lavapipe's loop budget per invocation (docs/REFERENCE.md "Loop budget on lavapipe"): 256 steps in
// each of a point light's three crossed maps stay well inside it.
TYN_CONST uint TYN_EPIPOLAR_MAX_FIXUP_STEPS = 256u;

// Bindings of the epipolar passes' one descriptor set (epipolar_common.glsl declares them;
// EpipolarTechnique writes descriptor i of its array at binding i).
TYN_CONST uint TYN_EPIPOLAR_BINDING_FRAME = 0u;
TYN_CONST uint TYN_EPIPOLAR_BINDING_DEPTH = 1u;
TYN_CONST uint TYN_EPIPOLAR_BINDING_SHADOW_MAPS = 2u;
TYN_CONST uint TYN_EPIPOLAR_BINDING_SLICE_END_POINTS = 3u;
TYN_CONST uint TYN_EPIPOLAR_BINDING_COORDINATES = 4u;
TYN_CONST uint TYN_EPIPOLAR_BINDING_SAMPLE_SCATTERING = 5u;
TYN_CONST uint TYN_EPIPOLAR_BINDING_OUT_SCATTERING = 6u;
TYN_CONST uint TYN_EPIPOLAR_BINDING_SHADOW_BLOCKS = 7u;
TYN_CONST uint TYN_EPIPOLAR_BINDING_FIXUP_LIST = 8u;
TYN_CONST uint TYN_EPIPOLAR_BINDING_FIXUP_ARGS = 9u;
TYN_CONST uint TYN_EPIPOLAR_BINDING_INTERPOLATION_SOURCE = 10u;
TYN_CONST uint TYN_EPIPOLAR_BINDING_SLICE_UV = 11u;
TYN_CONST uint TYN_EPIPOLAR_BINDING_MIN_MAX_TREE = 12u;
TYN_CONST uint TYN_EPIPOLAR_BINDING_MARCH_LIST = 13u;
TYN_CONST uint TYN_EPIPOLAR_BINDING_DEBUG_IMAGE = 14u;
TYN_CONST uint TYN_EPIPOLAR_BINDING_LIGHT_COLOR = 15u;
TYN_CONST uint TYN_EPIPOLAR_BINDING_SCATTERING_LUT = 16u;
TYN_CONST uint TYN_EPIPOLAR_BINDING_LIGHT_COLOR_SUMS = 17u;
TYN_CONST uint TYN_EPIPOLAR_BINDING_COUNT = 18u;

// Push constants of the epipolar passes (std430): scalars grouped in 16-byte rows, at the same
// offsets in C++ (epipolar_technique.cpp static_asserts them).
struct EpipolarConstants {
  vec4 epipole;                         // the homogeneous epipole and its side (tyn_epipole)
  uint slice_count;                     // EpipolarSettings::slices
  uint samples_per_slice;               // EpipolarSettings::samplesPerSlice
  uint improved_placement;              // 1: EpipolarSettings::improvedSamplePlacement
  uint initial_sample_step;             // every this-many-th sample is ray-marched
  float epipole_density;                // EpipolarSettings::epipoleDensity, or the light's (≥ 1)
  float bilateral_depth_threshold;      // relative depth difference of the bilateral weights
  float fixup_weight_threshold;         // least bilateral weight before a pixel is fixed up
  float epipole_block_radius;           // pixels around an on-screen epipole always fixed up
  float depth_break_threshold;          // relative depth break that makes both neighbours marched
  float intensity_refinement_threshold; // relative L_in difference that subdivides an interval
  float slice_contrast_threshold;       // relative L_in difference between a pixel's two slices
                                        // that sends it to the fix-up (1: never)
  float near_epipole_steps;             // the march step is at most 1/this of the distance to the
                                        // epipole (TYN_EPIPOLAR_NEAR_*_STEPS)
  uint tree_samples;                    // 1D samples per slice L (a power of two ≥ the shadow-map
                                        // size); 0 for a point light, which marches no slice line
  uint tree_top_level;                  // highest tree level the march may use (yusov2013's
                                        // maximum step)
  uint tree_enabled;                    // 1: march along the min/max tree; 0: every cell
  uint colored_chunk;                   // cells per chunk of a coloured march
                                        // (tyn_min_max_add_colored); 0 without a light colour
  float arc_start;                      // the border arc the slices are spread over, in perimeter
  float arc_length;                     // pixels (epipolar_geometry.h "Slice arc"; a length ≥ the
                                        // perimeter is the whole border)
  uint fixup_steps;                     // the fix-up's steps per map (0: the texel walk)
  uint shadow_block_side;               // blocks along each side of each map in this frame's block
                                        // image (shadowBlockExtent); 0 when it has none
  float epipole_walk_radius;            // pixels around the epipole whose fix-up takes the texel
                                        // walk whatever fixup_steps (local lights: fixup.comp)
};

TYN_END

#endif
