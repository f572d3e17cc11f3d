// The Gauss–Legendre rule of the local lights' quadrature (common/medium.glsl), and how it cuts
// a segment into pieces. Shared with the unit tests, which check the error the comments quote.
#ifndef TYNDALL_GAUSS_LEGENDRE_H
#define TYNDALL_GAUSS_LEGENDRE_H

#include "common/cpp_glsl.h"

TYN_BEGIN

// Nodes ±x0 (weight w0) and ±x1 (weight w1) of the 4-point rule on [−1, 1] (Abramowitz & Stegun,
// Table 25.4), exact for polynomials of degree 7.
TYN_CONST float TYN_GAUSS4_X0 = 0.3399810435848563f;
TYN_CONST float TYN_GAUSS4_X1 = 0.8611363115940526f;
TYN_CONST float TYN_GAUSS4_W0 = 0.6521451548625461f;
TYN_CONST float TYN_GAUSS4_W1 = 0.3478548451374538f;

// Pieces of a segment of `length` whose closest point to the light is `d_near` away: none longer
// than half that distance, so that the 4-point rule follows the 1/d² peak. Along a ray passing
// the light at distance d, 1/d² is 1/(1 + s²) in units of d, and with these pieces the relative
// error of the 4-point rule is below 1.2·10⁻⁷ (LocalLightQuadrature.RuleErrorOnThePeak). At most
// 64 pieces (lavapipe's loop budget): a segment longer than 32 times its distance to the light
// gets longer pieces and a larger error.
TYN_FUNC int tyn_local_light_pieces(float length, float d_near) {
  return int(clamp(ceil(length / (0.5f * d_near)), 1.0f, 64.0f));
}

TYN_END

#endif
