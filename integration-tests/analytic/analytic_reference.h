// The CPU double-precision analytic reference: a test oracle for directional-light scenes of planes,
// boxes and spheres. It computes DESIGN.md's radiometry ("Radiometry") exactly: the shadowed parts
// of each view ray are found in closed form (no shadow map, no ray marching) and the attenuated
// in-scattering is integrated in closed form over the lit parts. It shares no code with the GPU
// techniques; its phase functions are its own.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "tyndall_host/scene.h"

namespace tyndall::analytic {

/// A scene-linear RGB image, row 0 at the top.
struct RgbImage {
  std::uint32_t width = 0, height = 0;
  std::vector<double> rgb;  ///< width · height · 3

  glm::dvec3 at(std::uint32_t x, std::uint32_t y) const {
    const std::size_t i = (static_cast<std::size_t>(y) * width + x) * 3;
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
  }
};

/// Per pixel: the in-scattered radiance L_in and the transmittance exp(−σ_t s) of a directional-light
/// scene of planes, boxes and spheres. Returns false with `error` for unsupported scenes
/// (more than one light, non-directional light, glTF objects, no medium, zero image size).
bool renderAnalytic(const host::Scene& scene, std::uint32_t width, std::uint32_t height,
                    RgbImage& scattering, RgbImage& transmittance, std::string& error);

/// The unit view direction through the centre of pixel (px, py), row 0 at the top (DESIGN.md):
/// dir = normalize(forward + right·(2(px+½)/W − 1)·tanH·W/H + up·(1 − 2(py+½)/H)·tanH).
glm::dvec3 cameraRayDirection(const host::Camera& camera, std::uint32_t px, std::uint32_t py,
                              std::uint32_t width, std::uint32_t height);

/// Distance along the ray origin + t·dir (dir unit) to the first opaque surface with t > 0; +∞ if
/// none (translucent objects are not in the depth buffer).
/// From inside a box or sphere this is the exit point (what a rasterizer without culling shows).
double firstSurfaceDistance(const host::Scene& scene, glm::dvec3 origin, glm::dvec3 dir);

/// The integration length s of a camera ray: the first surface, or the far plane
/// (far / dot(dir, forward)) when there is none or it lies beyond the far plane.
double viewRayLength(const host::Scene& scene, glm::dvec3 dir);

/// The parts of the segment origin + t·dir, t ∈ [0, tMax], from which the directional light is
/// blocked by some opaque object: sorted, merged, non-empty intervals.
std::vector<std::pair<double, double>> shadowedIntervals(const host::Scene& scene, glm::dvec3 origin,
                                                         glm::dvec3 dir, double tMax);

/// L_in along origin + t·dir, t ∈ [0, s], dir unit (DESIGN.md, "Radiometry"):
/// Σ_c σ_s,c · p_c(dot(dir, −lightDirection)) · E · ∫ T_l(t) exp(−σ_t t) dt, per RGB channel, T_l the
/// light's transmittance to the point: 0 behind an opaque object, (1 − α) per translucent surface.
glm::dvec3 inScattering(const host::Scene& scene, glm::dvec3 origin, glm::dvec3 dir, double s);

/// ∫_a^b exp(−σ t) dt for σ ≥ 0, accurate as σ → 0 (it tends to b − a); 0 when b ≤ a.
double attenuatedLength(double a, double b, double sigmaT);

/// σ_t = Σ_c (σ_s,c + σ_a,c) per RGB channel.
glm::dvec3 extinction(const host::Scene& scene);

/// The phase function normalised over the sphere (∫ p dω = 1), as a function of cos θ,
/// θ the angle between the view direction and the direction towards the light.
double phase(host::PhaseType type, double g, double cosTheta);

}  // namespace tyndall::analytic
