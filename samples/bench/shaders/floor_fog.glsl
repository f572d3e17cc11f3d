// The floor passes' work, shared by the fragment floor (floor.frag) and the compute floor
// (floor.comp) so that both compute the same thing and differ only in how they write the back buffer.
// A depth fog: out = in · f + fog · (1 − f) with f = exp(−density · view distance). What it computes
// does not matter; its memory traffic and its one invocation per pixel do.

layout(push_constant) uniform FloorConstants {
  vec4 fog;         // rgb: fog radiance, a: density per scene unit
  vec4 projection;  // P[2][2], P[3][2] of the host's projection: view z from clip depth
} floor_constants;

// The fog's transmittance f at a pixel whose clip depth is `depth`.
float floor_fog_transmittance(float depth) {
  // Perspective clip depth d = −P22 − P32 / z_view (w = −z_view): |z_view| = |P32 / (d + P22)|.
  float viewDistance = abs(floor_constants.projection.y) / max(abs(depth + floor_constants.projection.x), 1e-7);
  return exp(-floor_constants.fog.a * viewDistance);
}
