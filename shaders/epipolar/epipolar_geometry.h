// Epipolar geometry of the light-shaft technique (engelhardt2010 §4.1, §5.1; yusov2013 "Sample
// generation", "Optimized sample placement", "Slice origin and direction"), as pure functions that
// the compute passes and the unit tests share.
//
// Conventions
// - Screen positions are Vulkan NDC: x right, y DOWN, both in [−1, 1]; pixel (px, py) has its
//   centre at ((px + 0.5)/W·2 − 1, (py + 0.5)/H·2 − 1). `extent` is (W, H) in pixels, W, H ≥ 2.
// - Everything is built on the "sample rectangle" [−1 + 1/W, 1 − 1/W] × [−1 + 1/H, 1 − 1/H]:
//   the hull of the pixel centres (yusov2013 "Optimized sample placement"). A sample outside it
//   would interpolate nothing a pixel needs.
// - The epipole (projected light) is kept homogeneous (common/epipole.h).
// - Slice i of N (any N ≥ 1; coverage of every pixel by a valid slice needs
//   N ≥ perimeter / min(W − 1, H − 1), i.e. N ≥ 6 for 16:9; use ≥ 64 in practice) exits the
//   screen at perimeter distance i·P/N pixels from the top-left corner of the sample rectangle,
//   clockwise on screen (top edge left → right, right edge top → bottom, bottom edge right → left,
//   left edge bottom → top), P = 2(W − 1) + 2(H − 1). Evenly by LENGTH in pixels rather than N/4
//   per edge (Yusov's by-index choice): neighbouring slices are then equally far apart, in pixels,
//   along every edge whatever the aspect ratio, so the gap the unwarp pass interpolates across is
//   bounded by the same P/N pixels everywhere. The slice coordinate is continuous: slice c ∈
//   [0, N) exits at c·P/N, so the unwarp pass inverts it exactly, and slice N wraps to slice 0.
//   That is the layout on the whole border; a frame may spread its slices over one arc of it
//   instead ("Slice arc" below), evenly by length there too.
// - Sampling along a slice always goes from the epipole side (entry) to the border (exit),
//   whether the light is in front of or behind the camera; for a light behind the camera, light
//   therefore travels on screen from the exit towards the entry. Ray marching does not care,
//   and the sample placement and its inverse stay one formula.
#ifndef TYNDALL_EPIPOLAR_GEOMETRY_H
#define TYNDALL_EPIPOLAR_GEOMETRY_H

#include "common/cpp_glsl.h"
#include "common/epipole.h"

TYN_BEGIN

// End points of a culled slice: far outside any screen, so that a pass can tell them from a real
// slice after a round trip through an RGBA32F texture (tyn_slice_valid).
TYN_CONST float TYN_EPIPOLAR_INVALID_COORD = -1.0e4f;
// A slice whose visible part is shorter than this many pixels is culled when the epipole is off
// screen: it is a line grazing a corner or an edge, which can hold no sample a pixel needs (its
// neighbour covers the pixels there), and float rounding of the clip (~1e-4 px at 4K) cannot
// make a slice with no visible part look valid.
TYN_CONST float TYN_EPIPOLAR_MIN_SLICE_PIXELS = 1.0e-2f;
// "No bound" for the line/rectangle clip; finite, so products with 0 stay 0.
TYN_CONST float TYN_EPIPOLAR_UNBOUNDED = 1.0e30f;
// Perimeter pixels past a partial arc's ends that still count as on it: the rounding of a border
// point's round trip (~1e-3 px on a 4K border); the arc's own guard is wider (slice_arc.cpp).
TYN_CONST float TYN_EPIPOLAR_ARC_SLACK = 1.0f / 64.0f;
// Epipole density factors beyond this make the first sample spacing vanish in float.
TYN_CONST float TYN_EPIPOLAR_MAX_DENSITY = 1000.0f;

// ---------------------------------------------------------------------------------------------
// Screen

// NDC of a point given in pixel coordinates (pixel centres at half-integers), written exactly as
// the passes compute pixel centres, so exit points and pixel centres agree bit for bit.
TYN_FUNC vec2 tyn_ndc_from_pixel(vec2 pixel, vec2 extent) { return pixel / extent * 2.0f - 1.0f; }

TYN_FUNC vec2 tyn_pixel_from_ndc(vec2 ndc, vec2 extent) { return (ndc + 1.0f) * 0.5f * extent; }

// The sample rectangle (lo.x, lo.y, hi.x, hi.y): the first and last pixel centres.
TYN_FUNC vec4 tyn_epipolar_screen_rect(vec2 extent) {
  return vec4(tyn_ndc_from_pixel(vec2(0.5f), extent), tyn_ndc_from_pixel(extent - 0.5f, extent));
}

// Parameter interval [t0, t1] of the line origin + t·dir inside the rectangle (slab method);
// empty when t0 > t1. An axis along which the line does not move constrains nothing if the line
// is inside that slab, and empties the interval otherwise.
TYN_FUNC vec2 tyn_line_rect_interval(vec2 origin, vec2 dir, vec4 rect) {
  float t0 = -TYN_EPIPOLAR_UNBOUNDED;
  float t1 = TYN_EPIPOLAR_UNBOUNDED;
  if (dir.x != 0.0f) {
    float ta = (rect.x - origin.x) / dir.x;
    float tb = (rect.z - origin.x) / dir.x;
    t0 = max(t0, min(ta, tb));
    t1 = min(t1, max(ta, tb));
  } else if (origin.x < rect.x || origin.x > rect.z) {
    t0 = TYN_EPIPOLAR_UNBOUNDED;
    t1 = -TYN_EPIPOLAR_UNBOUNDED;
  }
  if (dir.y != 0.0f) {
    float ta = (rect.y - origin.y) / dir.y;
    float tb = (rect.w - origin.y) / dir.y;
    t0 = max(t0, min(ta, tb));
    t1 = min(t1, max(ta, tb));
  } else if (origin.y < rect.y || origin.y > rect.w) {
    t0 = TYN_EPIPOLAR_UNBOUNDED;
    t1 = -TYN_EPIPOLAR_UNBOUNDED;
  }
  return vec2(t0, t1);
}

// ---------------------------------------------------------------------------------------------
// Epipole (tyn_epipole and the rest of common/epipole.h)

// Inside the sample rectangle (borders included); tested as lo·w ≤ (x, y) ≤ hi·w to need no
// division, so an epipole at infinity is simply off screen.
TYN_FUNC bool tyn_epipole_on_screen(vec4 epipole, vec2 extent) {
  vec4 rect = tyn_epipolar_screen_rect(extent);
  return epipole.z > 0.0f && epipole.x >= rect.x * epipole.z && epipole.x <= rect.z * epipole.z &&
         epipole.y >= rect.y * epipole.z && epipole.y <= rect.w * epipole.z;
}

// Direction (not normalised) of the epipolar line through p, pointing away from the epipole:
// w·(p − epipole) for a finite epipole, and −(x, y) (away from the point at infinity) as w → 0.
TYN_FUNC vec2 tyn_epipolar_direction(vec4 epipole, vec2 p) {
  return epipole.z * p - vec2(epipole.x, epipole.y);
}

// ---------------------------------------------------------------------------------------------
// Exit points

// P: perimeter of the sample rectangle in pixels.
TYN_FUNC float tyn_border_length_pixels(vec2 extent) {
  return 2.0f * ((extent.x - 1.0f) + (extent.y - 1.0f));
}

// The point at perimeter distance s ∈ [0, P] from the top-left corner of the sample rectangle,
// clockwise (see the header comment). Computed in pixel coordinates so that the fixed coordinate
// of each edge is bit-identical to tyn_epipolar_screen_rect's bound.
TYN_FUNC vec2 tyn_border_point(float s, vec2 extent) {
  vec2 size = extent - 1.0f;  // edge lengths in pixels
  vec2 q;
  if (s <= size.x) {
    q = vec2(0.5f + s, 0.5f);
  } else if (s <= size.x + size.y) {
    q = vec2(extent.x - 0.5f, 0.5f + (s - size.x));
  } else if (s <= 2.0f * size.x + size.y) {
    q = vec2(extent.x - 0.5f - (s - size.x - size.y), extent.y - 0.5f);
  } else {
    q = vec2(0.5f, extent.y - 0.5f - min(s - 2.0f * size.x - size.y, size.y));
  }
  return tyn_ndc_from_pixel(q, extent);
}

// Inverse of tyn_border_point: the perimeter distance in [0, P) of a point on the sample
// rectangle. The edge is the nearest one, so a point a rounding error off the border still maps
// to the right place; the perimeter position is continuous across corners, so the choice at a
// corner does not matter. The top-left corner is 0 (reached from the left edge as P, wrapped).
TYN_FUNC float tyn_border_position(vec2 border_point, vec2 extent) {
  vec2 size = extent - 1.0f;
  vec2 from_lo = tyn_pixel_from_ndc(border_point, extent) - 0.5f;  // from the left / top edge
  vec2 from_hi = size - from_lo;                                  // from the right / bottom edge
  float d_top = abs(from_lo.y);
  float d_right = abs(from_hi.x);
  float d_bottom = abs(from_hi.y);
  float d_left = abs(from_lo.x);
  float nearest = min(min(d_top, d_right), min(d_bottom, d_left));
  float s;
  if (nearest == d_top) {
    s = clamp(from_lo.x, 0.0f, size.x);
  } else if (nearest == d_right) {
    s = size.x + clamp(from_lo.y, 0.0f, size.y);
  } else if (nearest == d_bottom) {
    s = size.x + size.y + clamp(from_hi.x, 0.0f, size.x);
  } else {
    s = 2.0f * size.x + size.y + clamp(from_hi.y, 0.0f, size.y);
  }
  float p = tyn_border_length_pixels(extent);
  return s >= p ? s - p : s;
}

// ---------------------------------------------------------------------------------------------
// Slice arc: the part of the border the slices are spread over
//
// arc = (start, length) in perimeter pixels, start ∈ [0, P). length ≥ P: the whole border, as
// above (slice i of N at start + i·P/N, slice N wrapping to slice 0). length < P: one arc of it,
// slice i at start + i·length/(N − 1) (wrapped past P), the first and last slices on its ends and
// no seam; the rest of the border has no slice. The frame's arc is the part whose epipolar planes
// can meet the lit volume (a spot light's cone seen from outside, the exit points an off-screen
// epipole leaves valid; slice_arc.cpp finds it, conservatively), so that all N slices sample the
// shafts instead of spreading over directions where L_in is zero.

TYN_FUNC bool tyn_arc_is_whole_border(vec2 arc, vec2 extent) {
  return arc.y >= tyn_border_length_pixels(extent);
}

// Perimeter distance of (continuous) slice `slice` on the arc.
TYN_FUNC float tyn_arc_border_position(float slice, uint num_slices, vec2 arc, vec2 extent) {
  float p = tyn_border_length_pixels(extent);
  float s = tyn_arc_is_whole_border(arc, extent)
                ? arc.x + slice / float(num_slices) * p
                : arc.x + slice / float(max(num_slices, 2u) - 1u) * arc.y;
  return s > p ? s - p : s;
}

TYN_FUNC vec2 tyn_arc_exit_point(float slice, uint num_slices, vec2 arc, vec2 extent) {
  return tyn_border_point(tyn_arc_border_position(slice, num_slices, arc, extent), extent);
}

// Inverse of tyn_arc_border_position: the continuous slice coordinate of perimeter distance s,
// in [0, N) for the whole border, in [0, N − 1] on a partial arc, and −1 off a partial arc (no
// slice there: L_in is zero).
TYN_FUNC float tyn_arc_slice_coordinate(float s, uint num_slices, vec2 arc, vec2 extent) {
  float p = tyn_border_length_pixels(extent);
  float n = float(num_slices);
  float from_start = s - arc.x;
  if (from_start < 0.0f) from_start += p;
  if (tyn_arc_is_whole_border(arc, extent)) {
    float c = from_start / p * n;
    return c >= n ? c - n : c;
  }
  if (from_start > arc.y + TYN_EPIPOLAR_ARC_SLACK) return -1.0f;
  return min(from_start / arc.y * float(max(num_slices, 2u) - 1u), n - 1.0f);
}

// The slices on the whole border from its top-left corner (the header comment's layout).
TYN_FUNC vec2 tyn_whole_border_arc(vec2 extent) { return vec2(0.0f, tyn_border_length_pixels(extent)); }

// Exit point of (continuous) slice `slice` ∈ [0, N] when the slices cover the whole border.
TYN_FUNC vec2 tyn_exit_point(float slice, uint num_slices, vec2 extent) {
  return tyn_arc_exit_point(slice, num_slices, tyn_whole_border_arc(extent), extent);
}

// Inverse of tyn_exit_point: the continuous slice coordinate in [0, N) of a point on the sample
// rectangle, slices covering the whole border.
TYN_FUNC float tyn_border_slice_coordinate(vec2 border_point, uint num_slices, vec2 extent) {
  return tyn_arc_slice_coordinate(tyn_border_position(border_point, extent), num_slices,
                                  tyn_whole_border_arc(extent), extent);
}

// ---------------------------------------------------------------------------------------------
// Slice end points

TYN_FUNC bool tyn_slice_valid(vec4 end_points) { return end_points.x > TYN_EPIPOLAR_INVALID_COORD * 0.5f; }

// End points (entry.xy, exit.xy) of the slice whose exit point is `exit_point` (from
// tyn_exit_point). Returns false, and the TYN_EPIPOLAR_INVALID_COORD sentinel, when the slice is
// culled: its segment from the epipole to the exit point misses the sample rectangle (or only
// grazes it for less than TYN_EPIPOLAR_MIN_SLICE_PIXELS), which happens only when the epipole is
// off screen; e.g. every exit point on the edges facing an off-screen epipole is culled, because
// the line enters the screen there instead of leaving it.
// - epipole on screen: entry = epipole, always valid (a slice may then be arbitrarily short, down
//   to zero length when the epipole lies on the border at the exit point; its samples all sit on
//   the epipole, which is harmless).
// - otherwise: entry = the first crossing of the segment epipole → exit with the rectangle.
TYN_FUNC bool tyn_slice_end_points(vec4 epipole, vec2 exit_point, vec2 extent,
                                   TYN_INOUT(vec4) end_points) {
  if (tyn_epipole_on_screen(epipole, extent)) {
    end_points = vec4(tyn_epipole_ndc(epipole), exit_point);
    return true;
  }
  // The line exit + s·d with d pointing away from the epipole: the epipole is at s = −1/w (at −∞
  // for w = 0) and the exit point at s = 0, so the segment is s ∈ [−1/w, 0].
  vec2 d = tyn_epipolar_direction(epipole, exit_point);
  vec2 range = tyn_line_rect_interval(exit_point, d, tyn_epipolar_screen_rect(extent));
  float s_entry = epipole.z > 0.0f ? max(range.x, -1.0f / epipole.z) : range.x;
  float s_exit = min(range.y, 0.0f);
  float visible_pixels = (s_exit - s_entry) * length(d * extent * 0.5f);
  if (!(visible_pixels > TYN_EPIPOLAR_MIN_SLICE_PIXELS)) {
    end_points = vec4(TYN_EPIPOLAR_INVALID_COORD);
    return false;
  }
  end_points = vec4(exit_point + d * s_entry, exit_point);
  return true;
}

// ---------------------------------------------------------------------------------------------
// Sample placement: sample k of a slice with `sample_count` valid samples lies at
// entry·(1 − f) + exit·f with f = tyn_sample_fraction(k); written that way (not mix) so that
// k = 0 and k = sample_count − 1 land exactly on the entry and the exit.
//
// Epipole density ρ ≥ 1 (1 = uniform): f(t) = t − b·t·(1 − t), t = k/(count − 1),
// b = (ρ − 1)/(ρ + 1). f(0) = 0 and f(1) = 1 exactly; f'(t) = (1 − b) + 2b·t > 0, so it is
// monotonic; the spacing grows linearly from the entry to the exit, the last spacing being
// f'(1)/f'(0) = (1 + b)/(1 − b) = ρ times the first. Denser samples near the epipole follow the
// inscattering, which varies fastest there (phase function peak, spot falloff, 1/d²). Values
// below 1 are treated as 1 and values above TYN_EPIPOLAR_MAX_DENSITY as that.

TYN_FUNC float tyn_epipole_density_bend(float epipole_density) {
  float rho = clamp(epipole_density, 1.0f, TYN_EPIPOLAR_MAX_DENSITY);
  return (rho - 1.0f) / (rho + 1.0f);
}

// Number of valid samples of a slice: 0 for a culled slice; max_samples (≥ 2) normally; with
// improved placement (yusov2013), a short slice uses only as many samples as keep its largest
// spacing at most one pixel, ceil(length·f'max) + 1, so that short slices (epipole near the
// border) do not waste ray-marching samples on sub-pixel steps. Samples k ≥ count are invalid;
// the last valid one lands exactly on the exit point.
TYN_FUNC uint tyn_slice_sample_count(vec4 end_points, vec2 extent, uint max_samples,
                                     float epipole_density, bool improved_placement) {
  if (!tyn_slice_valid(end_points)) return 0u;
  if (!improved_placement) return max_samples;
  vec2 along = vec2(end_points.z - end_points.x, end_points.w - end_points.y);
  float length_pixels = length(along * extent * 0.5f);
  float steepest = 1.0f + tyn_epipole_density_bend(epipole_density);  // f'(1)
  float needed = ceil(length_pixels * steepest) + 1.0f;
  return uint(clamp(needed, 2.0f, float(max_samples)));
}

// f(k / (count − 1)) ∈ [0, 1]; the sample index k may be fractional.
TYN_FUNC float tyn_sample_fraction(float sample_index, uint sample_count, float epipole_density) {
  if (sample_count < 2u) return 0.0f;
  float t = sample_index / float(sample_count - 1u);
  float b = tyn_epipole_density_bend(epipole_density);
  return t - b * t * (1.0f - t);
}

TYN_FUNC vec2 tyn_sample_position(vec4 end_points, float sample_index, uint sample_count,
                                  float epipole_density) {
  float f = tyn_sample_fraction(sample_index, sample_count, epipole_density);
  return vec2(end_points.x, end_points.y) * (1.0f - f) + vec2(end_points.z, end_points.w) * f;
}

// ---------------------------------------------------------------------------------------------
// Inverse (unwarp): screen pixel → slice coordinates

// Perimeter distance of the border point of the epipolar line through p (NDC): the line from the
// epipole through p is followed beyond p to the sample rectangle. p is clamped to the rectangle
// first (pixel centres are in it anyway). At the epipole itself every slice passes through p; the
// horizontal direction is then used, and p sits at the entry of whichever slice that gives.
TYN_FUNC float tyn_line_border_position(vec4 epipole, vec2 p, vec2 extent) {
  vec4 rect = tyn_epipolar_screen_rect(extent);
  vec2 q = clamp(p, vec2(rect.x, rect.y), vec2(rect.z, rect.w));
  vec2 d = tyn_epipolar_direction(epipole, q);
  float scale = max(abs(d.x), abs(d.y));
  d = scale > 1.0e-30f ? d / scale : vec2(1.0f, 0.0f);
  float t_exit = tyn_line_rect_interval(q, d, rect).y;
  vec2 border = clamp(q + d * max(t_exit, 0.0f), vec2(rect.x, rect.y), vec2(rect.z, rect.w));
  return tyn_border_position(border, extent);
}

// Continuous slice coordinate of the epipolar line through p (NDC) for slices on `arc`: in [0, N)
// on the whole border, −1 when p's line leaves the screen off a partial arc. p lies between
// slices tyn_slice_pair(c) with weight fract(c) on the second (on the whole border c ∈ [N − 1, N)
// blends slice N − 1 with slice 0: the seam needs no special case).
TYN_FUNC float tyn_arc_slice_coordinate_of(vec4 epipole, vec2 p, uint num_slices, vec2 arc, vec2 extent) {
  return tyn_arc_slice_coordinate(tyn_line_border_position(epipole, p, extent), num_slices, arc, extent);
}

// The same with the slices covering the whole border.
TYN_FUNC float tyn_slice_coordinate(vec4 epipole, vec2 p, uint num_slices, vec2 extent) {
  return tyn_arc_slice_coordinate_of(epipole, p, num_slices, tyn_whole_border_arc(extent), extent);
}

// The two slices a continuous slice coordinate lies between.
TYN_FUNC uvec2 tyn_slice_pair(float slice_coordinate, uint num_slices) {
  uint first = min(uint(slice_coordinate), num_slices - 1u);
  return uvec2(first, (first + 1u) % num_slices);
}

// Position of p along a slice, projected orthogonally: 0 at the entry, 1 at the exit
// (unclamped). For a p on the slice's line this is the fraction f of tyn_sample_position.
TYN_FUNC float tyn_slice_fraction(vec4 end_points, vec2 p) {
  vec2 entry = vec2(end_points.x, end_points.y);
  vec2 along = vec2(end_points.z, end_points.w) - entry;
  return dot(p - entry, along) / max(dot(along, along), 1.0e-30f);
}

// Continuous sample index k ∈ [0, count − 1] of a fraction f (clamped to [0, 1]): inverse of
// tyn_sample_fraction. Solves b·t² + (1 − b)·t − f = 0 with the root written as
// 2f / ((1 − b) + sqrt((1 − b)² + 4b·f)), which has no cancellation as b → 0 (uniform).
TYN_FUNC float tyn_sample_coordinate(float fraction, uint sample_count, float epipole_density) {
  if (sample_count < 2u) return 0.0f;
  float f = clamp(fraction, 0.0f, 1.0f);
  float b = tyn_epipole_density_bend(epipole_density);
  float t = 2.0f * f / ((1.0f - b) + sqrt((1.0f - b) * (1.0f - b) + 4.0f * b * f));
  return t * float(sample_count - 1u);
}

// ---------------------------------------------------------------------------------------------
// The surface around a pixel, as a plane of the depth buffer (coordinates and unwarp passes)
//
// A plane's depth-buffer values are an affine function of the screen position, for any
// projection and depth convention (a projective map takes planes to planes), so three
// neighbouring pixel centres on one plane have a zero second difference. The passes use this to
// know the surface between pixel centres, which a point-sampled depth buffer does not say:
// - a sample's view ray must end on the surface at the sample's own position, not at the depth
//   of the pixel it falls in (slice_setup.comp);
// - the unwarp's bilateral test asks whether a tap lies on the pixel's surface, so it compares the
//   tap's view-ray length with the pixel's plane where the tap is, not with the pixel's own ray
//   length (unwarp.comp).
// Both matter on ground seen at a grazing angle, whose ray length changes by more than the
// bilateral threshold per pixel (5–15% per pixel on the far ground of spot-lamp's view), and
// where the ray ends inside a local light's beam, L_in changes with the ray's length
// (integration-tests/extremes/test_spot_extremes.cpp has the measurements).
// The slope along an axis is the central difference where the pixel, its two neighbours and the
// next pixel on one side lie on one plane; else the one-sided difference towards the side where
// the pixel and the next three pixels do (a silhouette: the surface goes on only on that side);
// else 0, a point sample as without planes (a sliver, a crease where either side could be the
// pixel's surface, the screen border). "On one plane": the plane through two of the pixels predicts the
// third one's view-space z (its view-ray length, up to the direction's factor) to within the
// tolerance of the z step between them. Relative to the step, not to the distance, because the
// prediction's error grows with the slope, and thin occluders in front of a far background can
// line up within a few percent of the distance while being three surfaces (their z steps still
// differ by tens of percent). Float rounding of nearly constant depths fails the test too,
// harmlessly (the slope is then about 0 anyway).

// View-space z of a depth-buffer value d: (a·d + b) / (c·d + e) with to_view_z = (a, b, c, e), the
// z and w rows of the inverse projection at the pixel's NDC x, y. Any depth convention.
TYN_FUNC float tyn_depth_view_z(float d, vec4 to_view_z) {
  return (to_view_z.x * d + to_view_z.y) / (to_view_z.z * d + to_view_z.w);
}

// Whether the third of three equally spaced pixels with depth-buffer values a, b, c lies on the
// plane through the first two, whose depth there is 2b − a (see above). A plane that leaves
// `range` (the depth buffer's [min, max]) by then is behind the far plane or the camera: not one
// the third pixel can lie on (so a pixel of sky beside a silhouette, whose depth is the range's
// end, is not taken for the silhouette's plane). The sky of an infinite far plane has no finite z:
// never on a plane (the comparison below would be ∞ ≤ ∞).
TYN_FUNC bool tyn_depth_on_plane_of(float a, float b, float c, vec4 to_view_z, vec2 range, float tolerance) {
  float predicted = 2.0f * b - a;
  if (!(predicted >= range.x && predicted <= range.y)) return false;
  float z_b = tyn_depth_view_z(b, to_view_z);
  float z_c = tyn_depth_view_z(c, to_view_z);
  float z_predicted = tyn_depth_view_z(predicted, to_view_z);
  float largest = max(max(abs(z_b), abs(z_c)), abs(z_predicted));
  if (!(largest < TYN_EPIPOLAR_UNBOUNDED)) return false;
  return abs(z_predicted - z_c) <= tolerance * abs(z_c - z_b);
}

// Slope of the depth buffer per pixel along one axis at a pixel of depth d, from the pixels one,
// two and three before it along the axis (m1, m2, m3) and after it (p1, p2, p3); before.xyz and
// after.xyz say whether m1..m3 and p1..p3 are on screen. See above for the choice; a plane needs
// four pixels in a row on it, not three, because in a forest of thin occluders three surfaces line
// up within the tolerance now and then (a pixel of one trunk between two others, whose z steps
// agree within 2%), and two such coincidences in a row are far rarer.
TYN_FUNC float tyn_depth_plane_slope(float m3, float m2, float m1, float d, float p1, float p2, float p3,
                                     bvec3 before, bvec3 after, vec4 to_view_z, vec2 range, float tolerance) {
  // Tested lazily, the central plane first: most pixels are inside a surface and need two tests.
  bool m2_d = before.y && tyn_depth_on_plane_of(m2, m1, d, to_view_z, range, tolerance);
  if (before.x && after.x && tyn_depth_on_plane_of(m1, d, p1, to_view_z, range, tolerance) &&
      (m2_d || (after.y && tyn_depth_on_plane_of(p2, p1, d, to_view_z, range, tolerance)))) {
    return 0.5f * (p1 - m1);
  }
  bool d_p2 = after.y && tyn_depth_on_plane_of(p2, p1, d, to_view_z, range, tolerance);
  bool on_before = m2_d && before.z && tyn_depth_on_plane_of(m3, m2, m1, to_view_z, range, tolerance);
  bool on_after = d_p2 && after.z && tyn_depth_on_plane_of(p3, p2, p1, to_view_z, range, tolerance);
  if (on_before && !on_after) return d - m1;
  if (on_after && !on_before) return p1 - d;
  return 0.0f;
}

// Depth-buffer value of the plane through a pixel (depth, slopes per pixel along x and y) at
// `offset` pixels from its centre, kept within `range` (the depth buffer's [min, max]: the near
// and far planes' values in either order): a grazing plane extended past its horizon would
// otherwise name a point behind the camera; clamped, it ends at the far plane (or the sky), as
// the pixels beyond the horizon do.
TYN_FUNC float tyn_depth_on_plane(float depth, vec2 slopes, vec2 offset, vec2 range) {
  return clamp(depth + dot(slopes, offset), range.x, range.y);
}

// ---------------------------------------------------------------------------------------------
// Slice in shadow-map UV (yusov2013 "Slice origin and direction")
//
// Every view ray of a slice lies in the slice's epipolar plane, which contains the camera C and
// the light (its position, or its direction at infinity). Seen from the light, that plane is a
// line ℓ of the shadow map, the same for every ray of the slice: that is what makes a 1D min/max
// tree per slice possible. The construction below is Yusov's plane intersection done in the
// shadow map's homogeneous 2D coordinates: ℓ is the line through the images of C and of the
// exit ray's direction S1 (c = M·(C, 1), s = M·(S1, 0), in homogeneous UV), ℓ = c × s; the light
// itself projects to (0, 0, 0) (or, for a directional light, its direction does), so any third
// point of the plane lands on ℓ too. Along a ray C + t·v of the slice, v = a·S1 + b·(light
// direction) with a ≥ 0, the image moves along ℓ by d/dt (uv) ∝ a·(s.xy·c.w − c.xy·s.w) = a·(ℓ.y,
// −ℓ.x): one direction for every ray, whether the camera is in front of the light's plane
// (c.w > 0), on it or behind it. That is the returned direction.
// Origin, where marching starts for every ray of the slice:
// - the camera's image when the camera is in front of the light (c.w > 0; always so for an
//   orthographic directional shadow matrix) and inside the region;
// - otherwise the first point of ℓ inside the region after the camera's image (c.w > 0), or,
//   when the camera is on or behind the light's plane (c.w ≤ 0), the first point of ℓ inside the
//   region, since those rays' images come in from infinity against the direction. This is the
//   image of the cone side through which every ray of the slice enters (yusov2013).
// The region is the shadow map [0, 1]² intersected with the spot cone's image, a circle (see
// tyn_spot_cone_uv); pass a radius ≤ 0 for no cone (directional light, point-light faces).
// Supported: directional lights with an orthographic shadow matrix whose projection direction is
// the light direction; spot lights and point-light faces with a perspective shadow matrix whose
// centre is the light position; camera inside, outside, or behind the cone, at any distance.
// Not supported (returns false): the camera exactly at the light position, and a slice whose
// exit ray points exactly at the light (its plane is undefined; such a slice has zero length on
// screen). IMPORTANT: the circle is exact only for a shadow frustum symmetric about the spot axis
// (as the host stub builds it); otherwise pass a circle that contains the cone's image.
// UV: u = x_ndc·0.5 + 0.5, v = y_ndc·0.5 + 0.5 (v grows with the shadow map's rows).

// The spot cone's image in shadow UV, (centre.xy, radius): the image of the axis and of one
// generator, cos_outer = cos(outer half-angle) > 0.
TYN_FUNC vec3 tyn_spot_cone_uv(mat4 world_to_shadow, vec3 position, vec3 axis, float cos_outer) {
  vec3 a = normalize(axis);
  vec3 side = normalize(abs(a.y) < 0.9f ? cross(a, vec3(0.0f, 1.0f, 0.0f))
                                        : cross(a, vec3(1.0f, 0.0f, 0.0f)));
  float tan_outer = sqrt(max(1.0f - cos_outer * cos_outer, 0.0f)) / cos_outer;
  vec4 centre = world_to_shadow * vec4(position + a, 1.0f);
  vec4 rim = world_to_shadow * vec4(position + a + side * tan_outer, 1.0f);
  vec2 centre_uv = vec2(centre.x, centre.y) / centre.w * 0.5f + 0.5f;
  vec2 rim_uv = vec2(rim.x, rim.y) / rim.w * 0.5f + 0.5f;
  return vec3(centre_uv, length(rim_uv - centre_uv));
}

// Homogeneous UV (u·w, v·w, w) of a shadow clip position, scaled to unit length (the scale is
// positive, so the sign of w, which tells in front of / behind the light, is kept).
TYN_FUNC vec3 tyn_shadow_uv_homogeneous(vec4 clip) {
  vec3 h = vec3(0.5f * (clip.x + clip.w), 0.5f * (clip.y + clip.w), clip.w);
  float largest = max(max(abs(h.x), abs(h.y)), abs(h.z));
  return largest > 0.0f ? normalize(h / largest) : vec3(0.0f);
}

// origin_direction = (origin.uv, unit direction.uv); uv_length = UV distance from the origin to
// where ℓ leaves the region. exit_ray: world direction of the view ray through the slice's exit
// point (any positive length). Returns false when no ray of the slice reaches the region or the
// slice is degenerate (see above); origin_direction is then vec4(TYN_EPIPOLAR_INVALID_COORD).
TYN_FUNC bool tyn_slice_shadow_uv(mat4 world_to_shadow, vec3 camera_pos, vec3 exit_ray,
                                  vec3 cone_uv, TYN_INOUT(vec4) origin_direction,
                                  TYN_INOUT(float) uv_length) {
  origin_direction = vec4(TYN_EPIPOLAR_INVALID_COORD);
  uv_length = 0.0f;
  vec3 c = tyn_shadow_uv_homogeneous(world_to_shadow * vec4(camera_pos, 1.0f));
  vec3 s = tyn_shadow_uv_homogeneous(world_to_shadow * vec4(exit_ray, 0.0f));
  vec3 line = cross(c, s);  // line · (u, v, 1) = 0
  vec2 dir = vec2(line.y, -line.x);
  float dir_length = length(dir);
  // |c| = |s| = 1, so dir_length is the sine of the angle between the two images: near zero the
  // plane is undefined (camera at the light, or exit ray towards the light / along its direction).
  if (!(dir_length > 1.0e-6f)) return false;
  dir = dir / dir_length;
  // A point of ℓ: the nearest to the map centre, so that the clip parameters stay small.
  vec2 centre = vec2(0.5f);
  vec2 normal = vec2(line.x, line.y) / dir_length;
  vec2 p0 = centre - normal * ((dot(vec2(line.x, line.y), centre) + line.z) / dir_length);
  vec2 range = tyn_line_rect_interval(p0, dir, vec4(0.0f, 0.0f, 1.0f, 1.0f));
  if (cone_uv.z > 0.0f) {
    vec2 to_p0 = p0 - vec2(cone_uv.x, cone_uv.y);
    float half_b = dot(to_p0, dir);
    float disc = half_b * half_b - (dot(to_p0, to_p0) - cone_uv.z * cone_uv.z);
    if (disc < 0.0f) return false;
    float root = sqrt(disc);
    range = vec2(max(range.x, -half_b - root), min(range.y, -half_b + root));
  }
  if (c.z > 0.0f) range.x = max(range.x, dot(vec2(c.x, c.y) / c.z - p0, dir));
  if (!(range.x <= range.y)) return false;
  origin_direction = vec4(p0 + dir * range.x, dir);
  uv_length = range.y - range.x;
  return true;
}

TYN_END

#endif
