#version 460
// The spot light's semi-analytic scattering table (yusov2013 "Point light source – look-up table",
// epipolar/scattering_lut.h): one invocation per row (h), accumulating Ĝ from θ = π down. Recorded
// only in a frame whose medium differs from the table's.
#extension GL_GOOGLE_include_directive : require
#include "epipolar/epipolar_common.glsl"
#define TYN_SCATTERING_LUT_STORE(texel, value) imageStore(scattering_lut, texel, vec4(value, 0.0))
#define TYN_SCATTERING_LUT_FRAME
#include "epipolar/scattering_lut.h"

layout(local_size_x = TYN_EPIPOLAR_SLICE_GROUP) in;

void main() {
  int row = int(gl_GlobalInvocationID.x);
  if (row < TYN_SCATTERING_LUT_HEIGHT) tyn_scattering_lut_build_row(row, tyn_medium_from_frame());
}
