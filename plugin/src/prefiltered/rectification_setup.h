// Per-frame CPU set-up of the rectified shadow maps of prefiltered single scattering, in double
// precision: the view frustum, the light frame and the tight bounds of the non-linear
// rectification (peters2017 §5.1.1, Appendix A), klehm2014 §4.2's projective rectification matrix
// with the measure that decides whether it may be used, and the choice between one grey
// extinction and per-channel prefix sums. The conventions are those of
// shaders/prefiltered/rectification.h, whose parameter blocks toGpu() fills.
#pragma once

#include <array>
#include <limits>

#include <glm/glm.hpp>

#include "prefiltered/rectification.h"
#include "tyndall/tyndall.h"

namespace tyndall::prefiltered {

/// The volume whose in-scattering is computed: the view rays from the camera position to the far
/// plane, or, with an infinite far plane, to the sky distance (DESIGN.md "Radiometry",
/// shaders/common/view_ray.glsl). The near plane does not bound it (integration starts at the
/// camera); its corners only matter to the projective rectification.
struct ViewFrustum {
  glm::dvec3 position{0.0};                ///< camera position, world
  glm::dvec3 forward{0.0, 0.0, -1.0};      ///< unit view axis, world
  glm::dvec3 up{0.0, 1.0, 0.0};            ///< unit camera up (a fallback for the light frame)
  /// Corners in the order NDC (−1, −1), (1, −1), (1, 1), (−1, 1): consecutive corners share an
  /// edge. Far corners: on the far plane, or, with an infinite far plane, on the plane at view
  /// distance skyDistance (that pyramid contains every ray of length ≤ skyDistance).
  std::array<glm::dvec3, 4> nearCorners{};
  std::array<glm::dvec3, 4> farCorners{};
  bool infiniteFar = false;
  /// With an infinite far plane: the ray length sky pixels integrate to; the volume is then the
  /// frustum cone cut by the sphere of that radius. Surfaces farther away lie outside the maps
  /// (the lookups clamp to the row's end; see rectification.h).
  double skyDistance = 0.0;
  double maxRayLength = 0.0;  ///< longest view ray of the volume (scene units)
};

/// Builds the frustum from the host's matrices (any convention camera.h detects).
/// skyDistance is used only with an infinite far plane and must then be finite and > 0.
Outcome buildViewFrustum(const glm::dmat4& view, const glm::dmat4& projection, double skyDistance,
                         ViewFrustum& out);

/// The non-linear rectification of one frame (peters2017 §5.1.1, Appendix A).
struct NonLinearRectification {
  glm::dvec3 origin{0.0};  ///< camera position
  glm::dvec3 axisX{1.0, 0.0, 0.0}, axisY{0.0, 1.0, 0.0}, axisZ{0.0, 0.0, 1.0};  ///< light frame
  double rMax = 0.0;       ///< largest r over the volume (r_min = 0: the camera's light ray)
  double phiExtent = 0.0;  ///< Δφ: φ ∈ [−Δφ/2, Δφ/2]; 2π when fullCircle
  bool fullCircle = false; ///< the light axis (either way) lies in the frustum
  double thetaMin = 0.0, thetaMax = 0.0;                ///< exact inclination range of the frustum
  double thetaMinGuarded = 0.0, thetaMaxGuarded = 0.0;  ///< stretched by TYN_RECT_THETA_GUARD
  std::array<glm::dvec3, 4> sidePlanes{};               ///< inward unit normals through the camera
};

/// Appendix A: r_max from the far corners (the maximum of the convex r over the pyramid is at a
/// vertex), or skyDistance·max sin θ over the cone for a spherical far end; Δφ from the largest
/// pairwise azimuth angle of the corners, the full circle when the light direction or its opposite
/// lies in the frustum (tested against the four side planes, boundary included); θ extrema at the
/// corners, at the critical points of the far rectangle's edges, or 0 / π inside. lightDirection:
/// the direction the light travels, any length > 0.
NonLinearRectification computeNonLinearRectification(const ViewFrustum& frustum,
                                                     const glm::dvec3& lightDirection);

gpu::NonLinearRectificationParams toGpu(const NonLinearRectification& rect);

/// Above this texel stretch the projective rectification is switched off for the non-linear one:
/// its coarsest texel (in slice angle or in inclination) would be more than twice as coarse as
/// the non-linear map's at the same resolution, i.e. it would lose more than one mip level of
/// resolution somewhere in the frustum. (klehm2014 §4.2 switches "for close-to-degenerated
/// cases, easily detectable as distance of the epipole to screen border" without a number.)
/// For a 16:9, 60° camera and a light in its vertical plane the stretch is 1.29 with the light
/// overhead and reaches 2 at 53.6° elevation, the epipole 1.28 half-heights from the screen centre
/// (printed by ProjectiveRectification.CriterionSeparatesOnScreenFromFarOffScreenEpipoles).
inline constexpr double kProjectiveMaxTexelStretch = 2.0;

/// klehm2014 §4.2's projective rectification of one frame, in the light frame of the non-linear
/// one (same bisectrix), so that rows of both are the same slices φ = atan η.
struct ProjectiveRectification {
  bool constructible = false;     ///< false when the light axis meets the frustum (x_n ≤ 0)
  glm::dmat4 worldToClip{1.0};    ///< see rectification.h
  double xNear = 0.0, xFar = 0.0; ///< light-frame x of the first and last column (all 8 corners)
  double etaLo = 0.0, etaHi = 0.0;               ///< row range, symmetric about the bisectrix
  double zetaLo = 0.0, zetaHi = 0.0;             ///< depth range of the frustum, ζ = h/x
  double zetaLoGuarded = 0.0, zetaHiGuarded = 0.0;  ///< with the same 10% guard as θ
  /// The switch criterion (projectiveTexelStretch); +∞ when not constructible.
  double texelStretch = std::numeric_limits<double>::infinity();
};

/// Builds the matrix: the light frame's view transform, then a perspective projection along x_L
/// with near = min x and far = max x of the 8 frustum corners, left/right from η = y/x and
/// top/bottom from ζ = h/x at the corners (klehm2014 §4.2). Far corners of an infinite far plane
/// are those of ViewFrustum (at view distance skyDistance: conservative, not tight).
ProjectiveRectification computeProjectiveRectification(const ViewFrustum& frustum,
                                                       const NonLinearRectification& rect);

/// The criterion, the texel stretch: how many times the angle of a non-linear texel of the same
/// map size the coarsest projective texel spans, in slice angle φ or in inclination θ, over the
/// frustum. The projective map is uniform in η = tan φ and ζ = cot θ / cos φ where the non-linear
/// one is uniform in φ and θ, so a projective row spans |dφ/dη| = cos²φ ≤ 1 (1 on the bisectrix)
/// and a depth texel |dθ/dζ| = sin²θ·cos φ ≤ 1 times its η or ζ size:
///   stretch = max(η range / Δφ, ζ range / θ range · max_frustum sin²θ·cos φ)   (unguarded ranges).
/// ≥ 1 in practice (1.29 for a 16:9, 60° camera with the light overhead); it grows without bound
/// as the epipole approaches the screen (Δφ → π, ζ range → ∞). +∞ when not constructible.
double projectiveTexelStretch(const ProjectiveRectification& proj, const NonLinearRectification& rect);

inline bool useProjectiveRectification(const ProjectiveRectification& proj) {
  return proj.constructible && proj.texelStretch <= kProjectiveMaxTexelStretch;
}

gpu::ProjectiveRectificationParams toGpu(const ProjectiveRectification& proj);

/// Above this worst-case visibility error a grey extinction is not used for the prefix-sum
/// weights and one set per distinct channel is built instead. 0.01 is of the order of what the
/// unorm8 Fourier storage already allows in the worst case (Σ_k |a_k|/255 ≤ 0.0084 for M = 32,
/// Fourier.PacksIntoUnorm8). A haze σ_t = (1, 1.2, 1.5)e-4 over 200 units costs 0.0006; a
/// Rayleigh-like (0.058, 0.135, 0.331) 0.0085 over 0.5 units and 0.30 over 50 (PrefixSums tests).
inline constexpr double kGreyExtinctionMaxError = 0.01;

/// How the transmittance weights of the prefix sums handle RGB extinction.
struct PrefixSumExtinction {
  double sigma = 0.0;          ///< grey σ_t for the weights when one set is shared
  double greyMaxError = 0.0;   ///< worst visibility error of sharing it, over rays ≤ maxRayLength
  int distinctChannels = 1;    ///< number of different σ_t values among R, G, B
  bool perChannel = false;     ///< true: one prefix-sum set per distinct channel (exact)
};

/// σ_grey minimises the largest tyn_weighted_average_max_error(σ_grey·L, σ_c·L) over the channels
/// c, at L = maxRayLength (the error grows with the ray's length: the integrand is the same
/// function of the optical depths, which grow with it; the unit test checks the growth).
PrefixSumExtinction choosePrefixSumExtinction(const glm::dvec3& sigmaT, double maxRayLength);

}  // namespace tyndall::prefiltered
