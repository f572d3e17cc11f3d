// Push constants of the epipolar passes (shared by C++ and GLSL; 16-byte members).
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
// Near the epipole the ray-marching step is at most 1/this of the distance to it (refine.comp).
TYN_CONST float TYN_EPIPOLAR_NEAR_EPIPOLE_STEPS = 4.0f;
// An interval refine_intensity.comp refines is cut into this many (the initial step into quarters).
TYN_CONST uint TYN_EPIPOLAR_SUBDIVISIONS = 4u;
// Threads building one slice's min/max tree (one workgroup per slice).
TYN_CONST uint TYN_EPIPOLAR_TREE_GROUP = 128u;
// Largest L whose level 0 fits the tree pass's shared memory (L/2 nodes of 8 bytes: 16 KiB, half of
// lavapipe's 32 KiB) and whose tree fits one texture row (L − 1 texels).
TYN_CONST uint TYN_EPIPOLAR_TREE_MAX_SAMPLES = 4096u;

// Texels along each side of the fix-up's shadow-map blocks (shadow_blocks.comp, block_walk.glsl),
// even (the blocks pass gathers 2 × 2 texels), and the blocks pass's workgroup side. 4 against 8
// on lavapipe, Performance at 640x360 with 2048² maps: forest's fix-up 143 against 171 ms (the
// plain walk's 153: forest's blocks mostly hold a canopy and the ground below it, and the smaller
// ones decide more often), fence's 19 against 20 ms (plain 38).
TYN_CONST uint TYN_EPIPOLAR_SHADOW_BLOCK = 4u;
TYN_CONST uint TYN_EPIPOLAR_SHADOW_BLOCK_GROUP = 8u;
// The same for a point light's six maps, whose blocks its march walks for every sample: its rays
// cross wide open space lit by the lamp, where large blocks decide. On lavapipe, High at 640x360
// with 2048² maps on point-lamp (march + refined march, ms): no blocks 14,872; blocks of 4: 5,599;
// 8: 3,172; 16: 1,457; 32: 932; 64: 923 (the frame 15.2 s -> 1.10 s at 32), L_in the same to
// rounding.
TYN_CONST uint TYN_EPIPOLAR_POINT_SHADOW_BLOCK = 32u;
// The blocks are built when at least one pixel per this many texels of the map's side is fixed up.
// A walk crosses about a map side of texels and the blocks pass reads side² of them, so the
// threshold scales with the side. On lavapipe (Performance, 640x360, 2048² map) the pass took 6 ms
// and the block steps saved about 12 µs per fixed-up pixel on pillars and fence (4 ms for
// pillars' 300 pixels, 17 ms for fence's 1,400): worth it from about 500 pixels, a side / 4.
TYN_CONST uint TYN_EPIPOLAR_SHADOW_BLOCK_PIXELS = 4u;
// Most steps of the fix-up's stepped march (EpipolarSettings::fixupSteps, fixup_steps.glsl). A
// local light's steps may each end a lit run, integrated by quadrature whose loops spend lavapipe's
// loop budget of 65,535 iterations per invocation (docs/REFERENCE.md "Loop budget on lavapipe"):
// 256 steps in each of a point light's three crossed maps stay well inside it.
TYN_CONST uint TYN_EPIPOLAR_MAX_FIXUP_STEPS = 256u;

struct EpipolarConstants {
  vec4 epipole;      // homogeneous epipole (tyn_epipole): x, y, w, side
  uvec4 counts;      // x: slices; y: samples per slice; z: 1 = improved sample placement;
                     // w: initial sample step (every w-th sample is ray-marched)
  vec4 params;       // x: epipole density; y: bilateral depth threshold (relative);
                     // z: minimum bilateral weight before a pixel is fixed up;
                     // w: radius in pixels around an on-screen epipole that is always fixed up
  vec4 refinement;   // x: relative depth break between neighbouring samples that makes both
                     // of them ray-marched samples; y: relative L_in difference between
                     // neighbouring ray-marched samples that subdivides the interval (second round);
                     // z: relative L_in difference between a pixel's two slices that sends it to
                     // the fix-up pass (1: never)
  uvec4 tree;        // x: 1D samples per slice L (a power of two ≥ the shadow-map size), 0 when
                     //    the marched samples use the Reference's walk instead (point lights);
                     // y: highest tree level the march may use (yusov2013's maximum step);
                     // z: 1 = march along the min/max tree, 0 = the plain march (every cell);
                     // w: a coloured march's chunk in cells (tyn_min_max_add_colored)
  vec4 arc;          // xy: the border arc the slices are spread over, (start, length) in perimeter
                     //     pixels (epipolar_geometry.h "Slice arc"; length ≥ P: the whole border);
                     // z: the fix-up's steps per map (EpipolarSettings::fixupSteps; 0: the
                     //    Reference's texel walk); w: blocks along each side of each map in the
                     //    shadow-map block image this frame (shadowBlockExtent), 0 when the frame
                     //    has none (a spot light; a directional light's fix-up in steps)
};

TYN_END

#endif
