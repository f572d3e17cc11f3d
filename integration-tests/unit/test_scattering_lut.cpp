// The spot/point light scattering table of shaders/epipolar/scattering_lut.h, compiled as C++ from
// the shader source and run in float as a shader would: the reformulation's closed forms, the
// table's coordinates and normaliser, the build against adaptive double quadrature, the bilinear
// lookup, and the segment integrals (table, guard, quadrature, spot cone) against double-precision
// quadrature of the original integral ∫ P falloff e^{−σ(t + d)} / d² dt. The relative errors are
// printed per medium; the bounds are the accuracy the epipolar technique's 3% budget can afford
// to spend here (1e-3: a thirtieth).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <initializer_list>
#include <random>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "epipolar/scattering_lut.h"

namespace {

using namespace tyndall::gpu;

constexpr double kPi = 3.14159265358979323846;
// The target for a segment integral: a thirtieth of the technique's 3% budget.
constexpr double kSegmentBound = 1e-3;
// Contributions below this are beyond float's range once multiplied out (e^{−σ(t+d)} underflows
// near 1e-38); they are skipped rather than compared.
constexpr double kNegligible = 1e-30;

// ---- Double-precision references ----

double phaseDouble(uint type, double g, double mu) {
  if (type == TYN_PHASE_RAYLEIGH) return 3.0 / (16.0 * kPi) * (1.0 + mu * mu);
  if (type == TYN_PHASE_ISOTROPIC) return 1.0 / (4.0 * kPi);
  const double denom = std::pow(1.0 + g * g - 2.0 * g * mu, 1.5);
  if (type == TYN_PHASE_HENYEY_GREENSTEIN) return (1.0 - g * g) / (4.0 * kPi * denom);
  return 3.0 * (1.0 - g * g) / (8.0 * kPi * (2.0 + g * g)) * (1.0 + mu * mu) / denom;
}

// P(μ) = Σ σ_s p(μ) of one channel.
double mediumPhase(const TynMedium& m, int channel, double mu) {
  double sum = 0.0;
  for (uint c = 0; c < m.components; ++c) {
    sum += double(m.scattering[c][channel]) * phaseDouble(m.phase_type[c], double(m.scattering[c].w), mu);
  }
  return sum;
}

// Gauss–Kronrod 7–15 on [a, b]: the Kronrod estimate and |Kronrod − Gauss|.
std::pair<double, double> gaussKronrod(const std::function<double(double)>& f, double a, double b) {
  static const double xk[8] = {0.991455371120812639, 0.949107912342758525, 0.864864423359769073,
                               0.741531185599394440, 0.586087235467691130, 0.405845151377397167,
                               0.207784955007898468, 0.0};
  static const double wk[8] = {0.022935322010529225, 0.063092092629978553, 0.104790010322250184,
                               0.140653259715525919, 0.169004726639267903, 0.190350578064785410,
                               0.204432940075298892, 0.209482141084727828};
  static const double wg[4] = {0.129484966168869693, 0.279705391489276668, 0.381830050505118945,
                               0.417959183673469388};
  const double c = 0.5 * (a + b);
  const double half = 0.5 * (b - a);
  const double fc = f(c);
  double kronrod = wk[7] * fc;
  double gauss = wg[3] * fc;
  for (int j = 0; j < 7; ++j) {
    const double x = half * xk[j];
    const double sum = f(c - x) + f(c + x);
    kronrod += wk[j] * sum;
    if (j % 2 == 1) gauss += wg[j / 2] * sum;
  }
  return {kronrod * half, std::fabs(kronrod - gauss) * half};
}

// ∫_a^b f to a relative tolerance by globally adaptive Gauss–Kronrod: the panel with the largest
// error estimate is halved until the summed estimate is below `relative` of the total (or 4000
// halvings: roundoff, not the rule, then limits the estimate). [a, b] is first cut at the focus
// points (peaks, kinks, the scale of a steep exponential) and, when `towards_ends`, geometrically
// towards both ends of every piece down to 1e-14 of its length, so that a peak at an end is seen.
double integrate(const std::function<double(double)>& f, double a, double b, std::vector<double> focus = {},
                 double relative = 1e-11, bool towards_ends = true) {
  if (!(b > a)) return 0.0;
  std::vector<double> points{a, b};
  for (double p : focus) {
    if (p > a && p < b) points.push_back(p);
  }
  std::sort(points.begin(), points.end());
  struct Panel {
    double lo, hi, value, error;
    bool operator<(const Panel& other) const { return error < other.error; }
  };
  std::vector<Panel> heap;
  double total = 0.0;
  double total_error = 0.0;
  const auto add = [&](double lo, double hi) {
    if (!(hi > lo)) return;
    const auto [value, error] = gaussKronrod(f, lo, hi);
    heap.push_back({lo, hi, value, error});
    std::push_heap(heap.begin(), heap.end());
    total += value;
    total_error += error;
  };
  for (size_t i = 0; i + 1 < points.size(); ++i) {
    const double lo = points[i];
    const double hi = points[i + 1];
    if (!towards_ends) {
      add(lo, hi);
      continue;
    }
    const double mid = 0.5 * (lo + hi);
    std::vector<double> cuts{lo};
    for (double d = (hi - lo) * 1e-14; lo + d < mid; d *= 8.0) cuts.push_back(lo + d);
    cuts.push_back(mid);
    std::vector<double> upper;
    for (double d = (hi - lo) * 1e-14; hi - d > mid; d *= 8.0) upper.push_back(hi - d);
    cuts.insert(cuts.end(), upper.rbegin(), upper.rend());
    cuts.push_back(hi);
    for (size_t j = 0; j + 1 < cuts.size(); ++j) add(cuts[j], cuts[j + 1]);
  }
  for (int halvings = 0; halvings < 4000 && total_error > relative * std::fabs(total); ++halvings) {
    std::pop_heap(heap.begin(), heap.end());
    const Panel worst = heap.back();
    heap.pop_back();
    total -= worst.value;
    total_error -= worst.error;
    const double mid = 0.5 * (worst.lo + worst.hi);
    add(worst.lo, mid);
    add(mid, worst.hi);
  }
  return total;
}

// Ĝ(k, θ0) = ∫_{θ0}^{π} P e^{−k (tan(θ/2) − tan(θ0/2))} dθ for the angle given by u0 = π − θ0
// (exact in double; the tan difference as sin((θ − θ0)/2) / (cos(θ/2) cos(θ0/2))).
double gHatDouble(const TynMedium& m, int channel, double k, double u0) {
  const double theta0 = kPi - u0;
  const double cos_half0 = std::sin(0.5 * u0);
  const auto f = [&](double theta) {
    const double cos_half = std::sin(0.5 * (kPi - theta));
    const double w = k == 0.0 ? 0.0 : k * std::sin(0.5 * (theta - theta0)) / (cos_half * cos_half0);
    return mediumPhase(m, channel, std::cos(theta)) * std::exp(-w);
  };
  return integrate(f, theta0, kPi);
}

// r(z) = (1 + z) ψ(z), ψ(z) = 1 − z e^z E1(z), in double: E1 by its series below 1 and by its
// continued fraction (modified Lentz) above.
double rDouble(double z) {
  if (z == 0.0) return 1.0;
  double exp_e1;
  if (z < 1.0) {
    double sum = 0.0;
    double term = 1.0;
    for (int n = 1; n < 40; ++n) {
      term *= -z / n;
      sum += term / n;
    }
    exp_e1 = std::exp(z) * (-0.57721566490153286 - std::log(z) - sum);
  } else {
    // e^z E1(z) = 1 / (z + 1 − 1² / (z + 3 − 2² / (z + 5 − ...)))
    double b = z + 1.0;
    double c = 1e300;
    double d = 1.0 / b;
    exp_e1 = d;
    for (int i = 1; i < 300; ++i) {
      const double an = -double(i) * double(i);
      b += 2.0;
      d = 1.0 / (an * d + b);
      c = b + an / c;
      exp_e1 *= c * d;
      if (std::fabs(c * d - 1.0) < 1e-16) break;
    }
  }
  return (1.0 + z) * (1.0 - z * exp_e1);
}

// Ĝ(k, ·) at several angles of one row (given by u = π − θ0, any order), in one sweep from θ = π
// down: Ĝ(θ_p) = e^{−k (τ_q − τ_p)} Ĝ(θ_q) + ∫_{θ_p}^{θ_q} P e^{−k (τ − τ_p)} dθ between consecutive
// angles, each piece by the adaptive rule (the same integral as gHatDouble, far cheaper per value).
std::vector<double> gHatAlongRow(const TynMedium& m, int channel, double k, const std::vector<double>& us) {
  std::vector<size_t> order(us.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return us[a] < us[b]; });
  std::vector<double> result(us.size(), 0.0);
  double g = 0.0;
  double u_q = 0.0;
  for (size_t index : order) {
    const double u_p = us[index];
    if (u_p > u_q) {
      const double theta_p = kPi - u_p;
      const double cos_half_p = std::sin(0.5 * u_p);
      const auto f = [&](double theta) {
        const double cos_half = std::sin(0.5 * (kPi - theta));
        const double w = k == 0.0 ? 0.0 : k * std::sin(0.5 * (theta - theta_p)) / (cos_half * cos_half_p);
        return mediumPhase(m, channel, std::cos(theta)) * std::exp(-w);
      };
      const double carry = u_q == 0.0 || k == 0.0
                               ? (u_q == 0.0 ? 0.0 : 1.0)
                               : std::exp(-k * std::sin(0.5 * (u_p - u_q)) / (std::sin(0.5 * u_q) * cos_half_p));
      // The exponential falls by e at θ_p + 2 cos²(θ_p/2) / k: cut there and geometrically beyond.
      std::vector<double> focus;
      if (k > 0.0) {
        for (double d = 2.0 * cos_half_p * cos_half_p / k; d < u_p - u_q; d *= 4.0) focus.push_back(theta_p + d);
      }
      g = carry * g + integrate(f, theta_p, kPi - u_q, focus, 1e-11, u_q == 0.0);
      u_q = u_p;
    }
    result[index] = g;
  }
  return result;
}

// ---- The table, as a C++ accessor ----

struct LutTable {
  mutable std::vector<vec3> texels =
      std::vector<vec3>(size_t(TYN_SCATTERING_LUT_WIDTH) * size_t(TYN_SCATTERING_LUT_HEIGHT), vec3(-1.0f));
  static size_t index(ivec2 t) { return size_t(t.y) * size_t(TYN_SCATTERING_LUT_WIDTH) + size_t(t.x); }
  void store(ivec2 t, vec3 value) const { texels.at(index(t)) = value; }
  vec3 fetch(ivec2 t) const { return texels.at(index(t)); }
};

LutTable buildTable(const TynMedium& m) {
  LutTable table;
  for (int row = 0; row < TYN_SCATTERING_LUT_HEIGHT; ++row) tyn_scattering_lut_build_row(table, row, m);
  return table;
}

struct Component {
  uint type;
  float g;
};

TynMedium makeMedium(const std::vector<Component>& components, vec3 sigma_t) {
  TynMedium m{};
  m.sigma_t = sigma_t;
  m.components = uint(components.size());
  // Coloured σ_s so the three channels differ; the second component weaker.
  const vec3 colours[2] = {vec3(0.5f, 0.7f, 0.9f), vec3(0.3f, 0.25f, 0.2f)};
  for (size_t i = 0; i < components.size(); ++i) {
    m.scattering[i] = vec4(colours[i % 2], components[i].g);
    m.phase_type[i] = components[i].type;
  }
  return m;
}

struct NamedPhase {
  std::string name;
  std::vector<Component> components;
};

// The phase functions of the brief: isotropic, Rayleigh, HG g ∈ {−0.9, 0, 0.76, 0.99},
// Cornette–Shanks g = 0.9, and two components.
std::vector<NamedPhase> allPhases() {
  return {{"isotropic", {{TYN_PHASE_ISOTROPIC, 0.0f}}},
          {"rayleigh", {{TYN_PHASE_RAYLEIGH, 0.0f}}},
          {"hg-0.9", {{TYN_PHASE_HENYEY_GREENSTEIN, -0.9f}}},
          {"hg0", {{TYN_PHASE_HENYEY_GREENSTEIN, 0.0f}}},
          {"hg0.76", {{TYN_PHASE_HENYEY_GREENSTEIN, 0.76f}}},
          {"hg0.99", {{TYN_PHASE_HENYEY_GREENSTEIN, 0.99f}}},
          {"cs0.9", {{TYN_PHASE_CORNETTE_SHANKS, 0.9f}}},
          {"rayleigh+hg0.8", {{TYN_PHASE_RAYLEIGH, 0.0f}, {TYN_PHASE_HENYEY_GREENSTEIN, 0.8f}}}};
}

// σ_t ∈ {0, 1e-3, 0.1, 10} grey, and RGB with one channel zero.
std::vector<vec3> allExtinctions() {
  return {vec3(0.0f), vec3(1e-3f), vec3(0.1f), vec3(10.0f), vec3(0.1f, 0.0f, 10.0f)};
}

std::string describe(vec3 s) {
  char text[64];
  std::snprintf(text, sizeof text, "(%g,%g,%g)", double(s.x), double(s.y), double(s.z));
  return text;
}

// ---- A view ray and a light, in float as the shader gets them; the truth reads the same floats ----

struct Scene {
  vec3 origin;
  vec3 dir;  // unit (normalised in float)
  vec3 light;
  bool spot = false;
  vec3 axis = vec3(0.0f);
  float cos_outer = 0.0f;
  float cos_inner = 1.0f;
};

// ∫_{ta}^{tb} P falloff e^{−σ(t + d)} / d² dt in double, in t (the original integral), with the
// foot and any extra kinks as focus points.
double exactSegment(const TynMedium& m, int channel, const Scene& s, double ta, double tb,
                    std::vector<double> focus = {}) {
  const double sigma = double(m.sigma_t[channel]);
  // The ray's direction as a unit vector in double: the float one is unit to 6e-8 only, which in
  // cos θ = dot(v, ω_l) would be 3% of 1 − cos θ at θ = 2e-3 (and 1e-3 of a g = 0.99 phase there).
  double dir[3];
  const double norm = std::sqrt(double(s.dir.x) * double(s.dir.x) + double(s.dir.y) * double(s.dir.y) +
                                double(s.dir.z) * double(s.dir.z));
  for (int i = 0; i < 3; ++i) dir[i] = double(s.dir[i]) / norm;
  double foot = 0.0;
  for (int i = 0; i < 3; ++i) foot += (double(s.light[i]) - double(s.origin[i])) * dir[i];
  focus.push_back(foot);
  const auto f = [&](double t) {
    double to_light[3];
    double d2 = 0.0;
    double along = 0.0;
    for (int i = 0; i < 3; ++i) {
      to_light[i] = double(s.light[i]) - (double(s.origin[i]) + t * dir[i]);
      d2 += to_light[i] * to_light[i];
      along += to_light[i] * dir[i];
    }
    const double d = std::sqrt(d2);
    double falloff = 1.0;
    if (s.spot) {
      double cos_angle = 0.0;
      for (int i = 0; i < 3; ++i) cos_angle -= to_light[i] * double(s.axis[i]);
      cos_angle /= d;
      const double x = std::clamp((cos_angle - double(s.cos_outer)) /
                                      std::max(double(s.cos_inner) - double(s.cos_outer), 1e-6),
                                  0.0, 1.0);
      falloff = x * x * (3.0 - 2.0 * x);
    }
    return mediumPhase(m, channel, along / d) * falloff * std::exp(-sigma * (t + d)) / d2;
  };
  return integrate(f, ta, tb, focus);
}

// Lights in front of (t_L > 0), beside (t_L = 0) and behind (t_L < 0) the camera, near and far,
// at distances h from the ray from 1e-3 to 1e3.
const double kFeet[] = {-1000.0, -3.0, -0.5, 0.0, 0.5, 3.0, 1000.0};
const double kDistances[] = {1e-3, 1e-1, 1.0, 10.0, 1e3};

// Exactly representable geometry: the ray along +x from the origin, the light at (t_L, h, 0), so
// the float t_L and h are exact and the comparison measures the method, not the inputs.
Scene axisScene(double foot, double h) {
  Scene s;
  s.origin = vec3(0.0f);
  s.dir = vec3(1.0f, 0.0f, 0.0f);
  s.light = vec3(float(foot), float(h), 0.0f);
  return s;
}

// A general orientation. From float positions the shader's h carries an absolute error of about
// ε |L − C| (ε = 6e-8), a relative error |L − C| / h times larger; a ray passing 1e-3 from a light
// 1e3 away is not resolved by any float computation, so these scenes keep |L − C| ≤ 1e3 h (the
// axis scenes cover the rest exactly).
Scene orientedScene(double foot, double h, std::mt19937& rng) {
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  vec3 dir;
  do {
    dir = vec3(u(rng), u(rng), u(rng));
  } while (length(dir) < 0.2f || length(dir) > 1.0f);
  dir = normalize(dir);
  const vec3 normal = normalize(cross(dir, vec3(0.3f, 0.9f, -0.2f)));
  Scene s;
  s.origin = vec3(1.25f, -2.5f, 0.75f);
  s.dir = dir;
  s.light = s.origin + float(foot) * dir + float(h) * normal;
  return s;
}

// Sections of the ray: the whole ray, up to the foot, around and after it, before it, far past
// it, short ones, and random ones (seeded, so the set is fixed).
std::vector<std::pair<float, float>> sections(double foot, double h, std::mt19937& rng) {
  const double front = std::max(foot, 0.0);
  const double dist = std::sqrt(foot * foot + h * h);
  std::vector<std::pair<double, double>> s = {
      {0.0, 1e4},
      {0.0, front},
      {front, front + 5.0 * h},
      {std::max(0.0, foot - h), foot + h},
      {std::max(0.0, foot + 2.0 * h), foot + 20.0 * h},
      {std::max(0.0, foot - 20.0 * h), std::max(0.0, foot - 2.0 * h)},
      {std::max(0.0, foot + 100.0 * h), foot + 101.0 * h},
      {0.0, 0.1 * dist},
      {0.3 * dist, 0.31 * dist}};
  std::uniform_real_distribution<double> start(0.0, 3.0 * dist);
  std::uniform_real_distribution<double> log_length(std::log(1e-3 * dist), std::log(3.0 * dist));
  for (int i = 0; i < 6; ++i) {
    const double a = start(rng);
    s.emplace_back(a, a + std::exp(log_length(rng)));
  }
  std::vector<std::pair<float, float>> out;
  for (const auto& [a, b] : s) {
    if (float(b) > float(a)) out.emplace_back(float(a), float(b));
  }
  return out;
}

// ---- The shader's own sin, cos and atan2 (the built-ins' Vulkan accuracy is absolute) ----

// Relative accuracy from 1e-30 to π/2 (sin, cos) and for every quadrant of atan2 with y ≥ 0:
// within 4 float ulps (2.4e-7: the polynomials' rounding, Cephes' 1e-7 for atan) of double.
TEST(ScatteringLutMaths, TrigonometryIsRelativelyAccurate) {
  double worst_sin = 0.0;
  double worst_cos = 0.0;
  std::vector<double> xs;
  for (double x = 1e-30; x < 1.5707; x *= 1.07) xs.push_back(x);
  for (double x = 0.0; x <= 1.5707963; x += 1e-3) xs.push_back(x);
  for (double x : xs) {
    const float xf = float(x);
    const double sd = std::sin(double(xf));
    const double cd = std::cos(double(xf));
    if (sd > 0.0) worst_sin = std::max(worst_sin, std::fabs(double(tyn_precise_sin(xf)) - sd) / sd);
    worst_cos = std::max(worst_cos, std::fabs(double(tyn_precise_cos(xf)) - cd) / cd);
  }
  double worst_atan = 0.0;
  for (double y = 1e-30; y < 1e30; y *= 3.7) {
    for (double x : {-1e20, -3.0, -1.0, -1e-3, -1e-25, 0.0, 1e-25, 1e-3, 1.0, 3.0, 1e20}) {
      const float yf = float(y);
      const float xf = float(x);
      const double exact = std::atan2(double(yf), double(xf));
      if (exact < 1e-37) continue;  // below float's normal range
      const double got = double(tyn_precise_atan2(yf, xf));
      // Relative where the result is small, absolute (of π) near π, where callers use u instead.
      const double scale = exact <= kPi / 2.0 ? exact : kPi;
      worst_atan = std::max(worst_atan, std::fabs(got - exact) / scale);
    }
  }
  std::printf("maths: relative error sin %.1e, cos %.1e, atan2 %.1e\n", worst_sin, worst_cos, worst_atan);
  EXPECT_LT(worst_sin, 2.4e-7);
  EXPECT_LT(worst_cos, 2.4e-7);
  EXPECT_LT(worst_atan, 2.4e-7);
  EXPECT_EQ(tyn_precise_atan2(0.0f, 0.0f), 0.0f);
  EXPECT_EQ(tyn_precise_sin(0.0f), 0.0f);
}

// ---- The reformulation ----

// s = −h cot θ, d = h / sin θ, t + d = t_L + h tan(θ/2), θ increasing in t, and the integral in θ
// with Ĝ: every relation of the header's derivation, in double, against the direct quantities
// and the original integral.
TEST(ScatteringLutGeometry, ReformulationHoldsInDoublePrecision) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const double foot = 5.0 * uniform(rng);
    const double h = std::exp(4.0 * uniform(rng));
    double previous_theta = -1.0;
    for (double t = 0.0; t < 20.0; t += 0.37) {
      const double s = t - foot;
      const double d = std::sqrt(s * s + h * h);
      const double cos_theta = -s / d;  // dot(v, ω_l) with ω_l = (−s, h) / d in (v, n) coordinates
      const double theta = std::acos(cos_theta);
      EXPECT_NEAR(-h / std::tan(theta), s, 1e-9 * (d + h));
      EXPECT_NEAR(h / std::sin(theta), d, 1e-9 * d);
      EXPECT_NEAR(foot + h * std::tan(0.5 * theta), t + d, 1e-9 * (std::fabs(t) + d + std::fabs(foot)));
      EXPECT_GT(theta, previous_theta);
      previous_theta = theta;
    }
  }
  // The change of variables and the difference of Ĝ terms against the original integral.
  const TynMedium m = makeMedium({{TYN_PHASE_HENYEY_GREENSTEIN, 0.7f}}, vec3(0.3f));
  for (const auto& [foot, h, ta, tb] : std::vector<std::tuple<double, double, double, double>>{
           {2.0, 0.5, 0.0, 1.5}, {2.0, 0.5, 1.0, 6.0}, {-1.0, 2.0, 0.0, 10.0}, {4.0, 0.01, 3.9, 4.3}}) {
    const double sigma = 0.3;
    const auto f_t = [&](double t) {
      const double s = t - foot;
      const double d2 = s * s + h * h;
      return mediumPhase(m, 0, -s / std::sqrt(d2)) * std::exp(-sigma * (t + std::sqrt(d2))) / d2;
    };
    const double original = integrate(f_t, ta, tb, {foot});
    const double theta_a = std::atan2(h, foot - ta);
    const double theta_b = std::atan2(h, foot - tb);
    const auto f_theta = [&](double theta) {
      return mediumPhase(m, 0, std::cos(theta)) * std::exp(-sigma * (foot + h * std::tan(0.5 * theta)));
    };
    EXPECT_NEAR(integrate(f_theta, theta_a, theta_b) / h, original, 1e-9 * original);
    const auto tail = [&](double t, double theta) {
      const double d = std::sqrt((t - foot) * (t - foot) + h * h);
      return std::exp(-sigma * (t + d)) * gHatDouble(m, 0, sigma * h, kPi - theta);
    };
    EXPECT_NEAR((tail(ta, theta_a) - tail(tb, theta_b)) / h, original, 1e-8 * original);
  }
}

// The float point record: θ and u = π − θ each accurate on their own side, foot = s + d without
// cancellation, against double.
TEST(ScatteringLutGeometry, PointRecordIsAccurateInFloat) {
  for (double foot : kFeet) {
    for (double h : kDistances) {
      const TynLightRay r = tyn_light_ray(vec3(0.0f), vec3(1.0f, 0.0f, 0.0f), vec3(float(foot), float(h), 0.0f));
      EXPECT_FLOAT_EQ(r.t_light, float(foot));
      EXPECT_FLOAT_EQ(r.h, float(h));
      for (double t : {0.0, 0.5 * std::fabs(foot), std::fabs(foot) + 3.0 * h, 2.0 * std::fabs(foot) + 1e3 * h}) {
        const TynLightPoint p = tyn_light_point(r, float(t));
        const double s = double(float(t)) - double(float(foot));
        const double hd = double(float(h));
        const double d = std::sqrt(s * s + hd * hd);
        EXPECT_NEAR(p.theta, std::atan2(hd, -s), 4e-7 * std::atan2(hd, -s));
        EXPECT_NEAR(p.u, std::atan2(hd, s), 4e-7 * std::atan2(hd, s));
        // s + d cancels in double too when s < 0: compare with h² / (d − s) there.
        const double exact_foot = s >= 0.0 ? s + d : hd * hd / (d - s);
        EXPECT_NEAR(p.foot, exact_foot, 4e-7 * exact_foot);
      }
    }
  }
}

// The table's phase evaluation from half angles: equal to common/phase.h's for the same cos θ (so
// the two cannot drift apart), and accurate in the lobes where a float cos θ is not: HG g = 0.99
// within 0.03 rad of the light, where tyn_phase is off by up to 1e-3.
TEST(ScatteringLutPhase, PhaseFromHalfAngles) {
  const float gs[] = {-0.9f, 0.0f, 0.76f, 0.99f};
  for (uint type : {TYN_PHASE_ISOTROPIC, TYN_PHASE_RAYLEIGH, TYN_PHASE_HENYEY_GREENSTEIN, TYN_PHASE_CORNETTE_SHANKS}) {
    for (float g : gs) {
      for (float mu = -1.0f; mu <= 1.0f; mu += 0.0625f) {
        const float mine = tyn_phase_precise(type, g, mu, 1.0f - mu, 1.0f + mu);
        EXPECT_NEAR(mine, tyn_phase(type, g, mu), 1e-6f * tyn_phase(type, g, mu)) << type << " " << g << " " << mu;
      }
    }
  }
  const TynMedium m = makeMedium({{TYN_PHASE_HENYEY_GREENSTEIN, 0.99f}}, vec3(0.0f));
  double worst_plain = 0.0;
  double worst_half = 0.0;
  for (double theta = 1e-4; theta < 0.03; theta *= 1.05) {
    const double exact = mediumPhase(m, 0, std::cos(theta));
    const float t = float(theta);
    worst_plain = std::max(worst_plain, std::fabs(double(tyn_medium_phase_scattering(m, std::cos(t)).x) - exact) / exact);
    worst_half = std::max(worst_half,
                          std::fabs(double(tyn_medium_phase_scattering_at(m, vec2(t, float(kPi - theta))).x) - exact) / exact);
  }
  std::printf("phase HG 0.99 near the light: from cos θ %.1e, from half angles %.1e\n", worst_plain, worst_half);
  // A handful of float roundings (ε = 6e-8: the sines, the denominator's three operations, its 1.5
  // power, the quotient) against a 1e-3 error from the rounding of cos θ.
  EXPECT_LT(worst_half, 2e-6);
  EXPECT_GT(worst_plain, 1e-4);  // what the half angles buy
}

// ---- Coordinates and normaliser ----

TEST(ScatteringLutCoordinates, RoundTripAndEnds) {
  for (int i = 0; i < TYN_SCATTERING_LUT_HEIGHT - 1; ++i) {
    const float x = float(i) / float(TYN_SCATTERING_LUT_HEIGHT - 1);
    EXPECT_NEAR(tyn_scattering_lut_x(tyn_scattering_lut_k(x)), x, 2e-6f);
  }
  EXPECT_EQ(tyn_scattering_lut_x(0.0f), 0.0f);
  EXPECT_NEAR(tyn_scattering_lut_x(TYN_SCATTERING_LUT_K_MID), 0.5f, 1e-7f);
  EXPECT_GT(tyn_scattering_lut_x(1e30f), 0.999f);
  float previous = -1.0f;
  for (int j = 0; j < TYN_SCATTERING_LUT_WIDTH; ++j) {
    const float y = float(j) / float(TYN_SCATTERING_LUT_WIDTH - 1);
    const vec2 angle = tyn_scattering_lut_angle(y);
    EXPECT_NEAR(double(angle.x) + double(angle.y), kPi, 4e-7);
    EXPECT_NEAR(tyn_scattering_lut_y(angle.x, angle.y), y, 2e-6f);
    EXPECT_GT(angle.x, previous);
    previous = angle.x;
  }
  EXPECT_EQ(tyn_scattering_lut_angle(0.0f).x, 0.0f);
  EXPECT_EQ(tyn_scattering_lut_angle(1.0f).y, 0.0f);
  // The warp's spacing near θ = 0 resolves a g = 0.99 lobe (width 1 − g = 0.01) with ~40 nodes.
  EXPECT_LT(tyn_scattering_lut_angle(1.0f / float(TYN_SCATTERING_LUT_WIDTH - 1)).x, 2.5e-4f);
  // σ_ref: the largest channel, 1 without extinction.
  EXPECT_EQ(tyn_scattering_lut_sigma_ref(vec3(0.1f, 0.0f, 10.0f)), 10.0f);
  EXPECT_EQ(tyn_scattering_lut_sigma_ref(vec3(0.0f)), 1.0f);
}

// N(k, u) against A(k, u) = ∫_{θ0}^{π} e^{−k(tan(θ/2) − tan(θ0/2))} dθ (Ĝ for P ≡ 1): equal at
// k = 0, to O(u²) near θ = π, to leading order as k → ∞, within 20% between; and r(z) continuous where its two
// approximations meet (z = 1).
TEST(ScatteringLutNormaliser, FollowsThePhaseFreeIntegral) {
  const TynMedium one = makeMedium({{TYN_PHASE_ISOTROPIC, 0.0f}}, vec3(0.0f));
  const double scale = 1.0 / (double(one.scattering[0].x) * phaseDouble(TYN_PHASE_ISOTROPIC, 0.0, 0.0));
  double worst_middle = 0.0;
  for (double u : {1e-4, 1e-2, 0.3, 1.5, 3.0}) {
    for (double k : {0.0, 1e-5, 1e-3, 0.1, 1.0, 30.0, 1e4}) {
      const double a = gHatDouble(one, 0, k, u) * scale;
      const double n = double(tyn_scattering_lut_norm1(float(k), float(u)));
      const double ratio = n / a;
      if (k == 0.0) {
        EXPECT_NEAR(ratio, 1.0, 1e-6) << "u " << u;  // N = u = A
      } else if (u <= 1e-2) {
        // Near π: A = (2/τ0) ψ(k τ0) (1 + O(u²)) and N = u ψ(2k/u) (1 + O(u²)), plus r's
        // approximation (below).
        EXPECT_NEAR(ratio, 1.0, u * u + 1e-5) << "u " << u << " k " << k;
      } else if (k >= 1e4) {
        // Both → 2 sin²(u/2) / k; they differ at the next order, O(u / k + u²).
        EXPECT_NEAR(ratio, 1.0, 1e-3) << "u " << u;
      } else {
        EXPECT_NEAR(ratio, 1.0, 0.2) << "u " << u << " k " << k;
        worst_middle = std::max(worst_middle, std::fabs(ratio - 1.0));
      }
    }
  }
  std::printf("normaliser: N / A − 1 at most %.3f between the limits\n", worst_middle);
  // r against double: within 1e-5 everywhere (A&S 5.1.53/5.1.56 are good to 2e-7 and 2e-8; the
  // large-z numerator's leading coefficient 0.9999936 is rounded to 1 for r(∞) = 1 exactly), and
  // continuous where the two forms meet.
  double worst_r = 0.0;
  for (double z = 1e-6; z < 1e7; z *= 1.1) {
    const double r = z < 1.0 ? double(tyn_scattering_lut_r_small(float(z))) : double(tyn_scattering_lut_r_large(float(1.0 / z)));
    worst_r = std::max(worst_r, std::fabs(r - rDouble(z)));
  }
  std::printf("normaliser: r(z) within %.1e of (1 + z) ψ(z)\n", worst_r);
  EXPECT_LT(worst_r, 1e-5);
  EXPECT_NEAR(tyn_scattering_lut_r_small(1.0f), tyn_scattering_lut_r_large(1.0f), 1e-6f);
  EXPECT_EQ(tyn_scattering_lut_r_small(0.0f), 1.0f);
  EXPECT_EQ(tyn_scattering_lut_r_large(0.0f), 1.0f);
}

// ---- The build ----

// Ĝ = Q · N from the float build against adaptive double quadrature at sampled nodes. The product
// trapezoid's error is O(Δw² g''): ≤ 3e-5 measured; the bound 2e-4 leaves room for float's
// accumulation over the ~5400 sub-steps of a row. A node's value cannot be more accurate than the
// float phase function there, which at large k it becomes (Ĝ → P(θ0) N); that error, computed per
// node, is added to the bound (≤ 1e-6 with the half-angle evaluation; the plain cos θ one would
// add 7e-4 for HG g = 0.99 near θ = 0, see PhaseFromHalfAngles).
TEST(ScatteringLutBuild, MatchesAdaptiveQuadrature) {
  const std::vector<vec3> extinctions = {vec3(1.0f), vec3(0.1f, 0.0f, 10.0f)};
  for (const NamedPhase& phase : allPhases()) {
    for (vec3 sigma : extinctions) {
      const TynMedium m = makeMedium(phase.components, sigma);
      const LutTable table = buildTable(m);
      const float sigma_ref = tyn_scattering_lut_sigma_ref(sigma);
      double worst = 0.0;
      double worst_beyond_phase = 0.0;
      for (int i = 0; i < TYN_SCATTERING_LUT_HEIGHT - 1; i += 11) {
        const float h = tyn_scattering_lut_k(float(i) / float(TYN_SCATTERING_LUT_HEIGHT - 1)) / sigma_ref;
        std::vector<int> columns;
        std::vector<double> us;
        for (int j = 0; j < TYN_SCATTERING_LUT_WIDTH - 1; j += 13) {
          columns.push_back(j);
          us.push_back(double(tyn_scattering_lut_angle(float(j) / float(TYN_SCATTERING_LUT_WIDTH - 1)).y));
        }
        for (int c = 0; c < 3; ++c) {
          const double k = double(sigma[c]) * double(h);
          const std::vector<double> exact = gHatAlongRow(m, c, k, us);
          for (size_t n = 0; n < columns.size(); ++n) {
            const double got = double(table.fetch(ivec2(columns[n], i))[c]) *
                               double(tyn_scattering_lut_norm1(float(k), float(us[n])));
            const double error = std::fabs(got - exact[n]) / exact[n];
            const double mu = std::cos(kPi - us[n]);
            const vec2 angle = tyn_scattering_lut_angle(float(columns[n]) / float(TYN_SCATTERING_LUT_WIDTH - 1));
            const double phase_error =
                std::fabs(double(tyn_medium_phase_scattering_at(m, angle)[c]) - mediumPhase(m, c, mu)) /
                mediumPhase(m, c, mu);
            worst = std::max(worst, error);
            worst_beyond_phase = std::max(worst_beyond_phase, error - phase_error);
            EXPECT_LT(error, 2e-4 + phase_error) << phase.name << " row " << i << " column " << columns[n]
                                                 << " channel " << c;
          }
        }
      }
      std::printf("build %-15s σ %-14s: max relative error of Ĝ %.2e (%.2e beyond the float phase's own)\n",
                  phase.name.c_str(), describe(sigma).c_str(), worst, worst_beyond_phase);
    }
  }
}

// The limits the build writes: the last row (h = ∞) holds P(θ) for channels with σ > 0 and the
// σ = 0 value otherwise; the last column (θ = π) holds P(−1); without extinction every row is the
// same.
TEST(ScatteringLutBuild, LimitsAndRowsWithoutExtinction) {
  const TynMedium m = makeMedium({{TYN_PHASE_HENYEY_GREENSTEIN, 0.6f}}, vec3(0.5f, 0.0f, 2.0f));
  const LutTable table = buildTable(m);
  const int last_row = TYN_SCATTERING_LUT_HEIGHT - 1;
  for (int j = 0; j < TYN_SCATTERING_LUT_WIDTH; j += 97) {
    const vec2 angle = tyn_scattering_lut_angle(float(j) / float(TYN_SCATTERING_LUT_WIDTH - 1));
    const vec3 p = tyn_medium_phase_scattering_at(m, angle);
    const vec3 q = table.fetch(ivec2(j, last_row));
    EXPECT_NEAR(q.x, p.x, 1e-6f * p.x);
    EXPECT_NEAR(q.z, p.z, 1e-6f * p.z);
    EXPECT_EQ(q.y, table.fetch(ivec2(j, 0)).y);  // σ = 0: independent of h
  }
  const vec3 back = tyn_medium_phase_scattering(m, -1.0f);
  for (int i = 0; i < TYN_SCATTERING_LUT_HEIGHT; i += 51) {
    EXPECT_EQ(table.fetch(ivec2(TYN_SCATTERING_LUT_WIDTH - 1, i)), back);
  }
  const LutTable clear = buildTable(makeMedium({{TYN_PHASE_RAYLEIGH, 0.0f}}, vec3(0.0f)));
  for (int i = 1; i < TYN_SCATTERING_LUT_HEIGHT; i += 37) {
    for (int j = 0; j < TYN_SCATTERING_LUT_WIDTH; j += 101) {
      EXPECT_EQ(clear.fetch(ivec2(j, i)), clear.fetch(ivec2(j, 0)));
    }
  }
  for (const vec3& texel : table.texels) ASSERT_TRUE(texel.x >= 0.0f && std::isfinite(texel.x));
}

// The bilinear lookup of Ĝ at the centres of table cells (farthest from the nodes) against double
// quadrature: the parameterisation's interpolation error, reported per medium. Bound: 1e-3 of Ĝ
// where it can be seen (k = σ h ≤ 30: beyond, every contribution of the ray is below e^{−30} of the
// light's); the guard turns a lookup error ε into at most ε (2 − GUARD) / GUARD in a segment.
TEST(ScatteringLutInterpolation, CellCentresAgainstQuadrature) {
  for (const NamedPhase& phase : allPhases()) {
    const TynMedium m = makeMedium(phase.components, vec3(1.0f));
    const LutTable table = buildTable(m);
    double worst[2] = {0.0, 0.0};
    for (int i = 0; i < TYN_SCATTERING_LUT_HEIGHT - 2; i += 2) {
      const float x = (float(i) + 0.5f) / float(TYN_SCATTERING_LUT_HEIGHT - 1);
      const double k = double(tyn_scattering_lut_k(x));
      std::vector<float> ys;
      std::vector<double> us;
      for (int j = 0; j < TYN_SCATTERING_LUT_WIDTH - 1; j += 3) {
        ys.push_back((float(j) + 0.5f) / float(TYN_SCATTERING_LUT_WIDTH - 1));
        us.push_back(double(tyn_scattering_lut_angle(ys.back()).y));
      }
      const std::vector<double> exact = gHatAlongRow(m, 1, k, us);
      for (size_t n = 0; n < ys.size(); ++n) {
        const double got = double(tyn_scattering_lut_lookup(table, x, ys[n]).y) *
                           double(tyn_scattering_lut_norm1(float(k), float(us[n])));
        const double error = std::fabs(got - exact[n]) / exact[n];
        worst[k <= 30.0 ? 0 : 1] = std::max(worst[k <= 30.0 ? 0 : 1], error);
        if (k <= 30.0) {
          EXPECT_LT(error, 1e-3) << phase.name << " k " << k << " u " << us[n];
        }
      }
    }
    std::printf("lookup %-15s: max relative error of Ĝ at cell centres %.2e (k ≤ 30), %.2e (k > 30)\n",
                phase.name.c_str(), worst[0], worst[1]);
  }
}

// ---- Segments ----

struct Tally {
  double worst = 0.0;
  std::string where;
  int count = 0;          // values compared
  int sections = 0;       // sections integrated
  int by_quadrature = 0;  // of which the guard sent to quadrature
};

void record(Tally& tally, double error, const std::string& where) {
  ++tally.count;
  if (error > tally.worst) {
    tally.worst = error;
    tally.where = where;
  }
}

std::string sectionText(const Scene& s, double foot, double h, float ta, float tb, int channel) {
  char text[160];
  std::snprintf(text, sizeof text, "t_L %g h %g [%g, %g] channel %d dir (%g,%g,%g)", foot, h, double(ta),
                double(tb), channel, double(s.dir.x), double(s.dir.y), double(s.dir.z));
  return text;
}

// The point-light segment (table with the guard) against the original integral, for every phase,
// extinction, light placement and section. Measured worst 5.2e-4 (HG g = −0.9, a section across
// the foot: the table's lookup error where the backward lobe puts k ln k into Ĝ at small k).
TEST(ScatteringLutSegment, MatchesDoublePrecisionQuadrature) {
  std::mt19937 rng(5);
  for (const NamedPhase& phase : allPhases()) {
    for (vec3 sigma : allExtinctions()) {
      const TynMedium m = makeMedium(phase.components, sigma);
      const LutTable table = buildTable(m);
      Tally tally;
      for (double foot : kFeet) {
        for (double h : kDistances) {
          for (int oriented = 0; oriented < 2; ++oriented) {
            if (oriented == 1 && std::sqrt(foot * foot + h * h) > 1e3 * h) continue;
            const Scene s = oriented == 1 ? orientedScene(foot, h, rng) : axisScene(foot, h);
            const TynLightRay r = tyn_light_ray(s.origin, s.dir, s.light);
            for (const auto& [ta, tb] : sections(foot, h, rng)) {
              const vec3 got = tyn_scattering_lut_segment(table, m, r, ta, tb);
              const vec3 table_only = tyn_scattering_lut_segment_guarded(table, m, r, ta, tb, -1.0f);
              ++tally.sections;
              if (got != table_only) ++tally.by_quadrature;
              for (int c = 0; c < 3; ++c) {
                const double exact = exactSegment(m, c, s, double(ta), double(tb));
                if (!(exact > kNegligible)) continue;
                const double error = std::fabs(double(got[c]) - exact) / exact;
                record(tally, error, sectionText(s, foot, h, ta, tb, c));
                EXPECT_LT(error, kSegmentBound) << phase.name << " σ " << describe(sigma) << " "
                                                << sectionText(s, foot, h, ta, tb, c) << " got " << got[c]
                                                << " table alone " << table_only[c] << " exact " << exact
                                                << " light (" << s.light.x << "," << s.light.y << "," << s.light.z
                                                << ") t_L " << r.t_light << " h " << r.h;
              }
            }
          }
        }
      }
      std::printf("segment %-15s σ %-14s: %4d values, max relative error %.2e, %3d%% of sections by quadrature  [%s]\n",
                  phase.name.c_str(), describe(sigma).c_str(), tally.count, tally.worst,
                  100 * tally.by_quadrature / std::max(tally.sections, 1), tally.where.c_str());
    }
  }
}

// The quadrature alone on every section (the spot's penumbra hands it arbitrary ones): the same
// bound. It must handle long sections in dense media (pieces limited by σ (t + d)), rays passing
// 1e-3 from a light 1e3 away, and channels extinguished at different rates.
TEST(ScatteringLutQuadrature, MatchesDoublePrecisionQuadrature) {
  std::mt19937 rng(9);
  const TynSpotCone no_cone = TynSpotCone{0.0f, 0.0f, 0.0f, 1.0f};
  for (const NamedPhase& phase : allPhases()) {
    for (vec3 sigma : allExtinctions()) {
      const TynMedium m = makeMedium(phase.components, sigma);
      Tally tally;
      for (double foot : kFeet) {
        for (double h : kDistances) {
          const Scene s = axisScene(foot, h);
          const TynLightRay r = tyn_light_ray(s.origin, s.dir, s.light);
          for (const auto& [ta, tb] : sections(foot, h, rng)) {
            const vec3 got = tyn_local_light_quadrature(m, r, no_cone, false, ta, tb);
            for (int c = 0; c < 3; ++c) {
              const double exact = exactSegment(m, c, s, double(ta), double(tb));
              if (!(exact > kNegligible)) continue;
              const double error = std::fabs(double(got[c]) - exact) / exact;
              record(tally, error, sectionText(s, foot, h, ta, tb, c));
              EXPECT_LT(error, kSegmentBound) << phase.name << " σ " << describe(sigma) << " "
                                              << sectionText(s, foot, h, ta, tb, c);
            }
          }
        }
      }
      std::printf("quadrature %-15s σ %-14s: max relative error %.2e  [%s]\n", phase.name.c_str(),
                  describe(sigma).c_str(), tally.worst, tally.where.c_str());
    }
  }
}

// ---- The guard ----

// A ray passing at h from a light 2 units ahead, and sections of length 1 before the foot
// ([0, 1]), after it ([3, 4]) and across it ([1.5, 2.5]). Before the foot the section subtends
// Δθ ≈ h ℓ / (s_a s_b) near θ = 0, where Ĝ ≈ Ĝ(0) − P(0) θ: F_a and F_b agree to ~Δθ and their
// difference carries the table's absolute error, so the table alone fails as h shrinks. After the
// foot Ĝ ∝ u ≈ h / s vanishes at θ = π and F_b / F_a ≈ s_a / s_b whatever h (no cancellation);
// across it Δθ ≈ π. The guard (quadrature where F_a − F_b < GUARD F_a) must keep every section
// within the bound; the table alone must be accurate after and across the foot. Printed: both
// errors per h, 1 − F_b/F_a, and the h below which the table alone exceeds 1e-3 before the foot.
TEST(ScatteringLutGuard, RaysPassingCloseToTheLight) {
  const TynMedium m = makeMedium({{TYN_PHASE_RAYLEIGH, 0.0f}, {TYN_PHASE_HENYEY_GREENSTEIN, 0.76f}}, vec3(0.1f));
  const LutTable table = buildTable(m);
  const std::pair<float, float> cases[3] = {{0.0f, 1.0f}, {3.0f, 4.0f}, {1.5f, 2.5f}};
  double crossing = 0.0;
  double guard_switch = 0.0;
  double before_foot_alone = 0.0;
  for (double h : {3.0, 1.0, 0.3, 0.1, 3e-2, 1e-2, 3e-3, 1e-3, 1e-4, 1e-5, 1e-6}) {
    const Scene s = axisScene(2.0, h);
    const TynLightRay r = tyn_light_ray(s.origin, s.dir, s.light);
    std::printf("guard h %-7g:", h);
    for (int k = 0; k < 3; ++k) {
      const auto [ta, tb] = cases[k];
      const double exact = exactSegment(m, 1, s, double(ta), double(tb));
      const vec3 guarded_value = tyn_scattering_lut_segment(table, m, r, ta, tb);
      const vec3 alone_value = tyn_scattering_lut_segment_guarded(table, m, r, ta, tb, -1.0f);
      const double guarded = std::fabs(double(guarded_value.y) - exact) / exact;
      const double alone = std::fabs(double(alone_value.y) - exact) / exact;
      const vec3 fa = tyn_scattering_lut_tail(table, m, r, tyn_light_point(r, ta));
      const vec3 fb = tyn_scattering_lut_tail(table, m, r, tyn_light_point(r, tb));
      std::printf("  [%g,%g] 1−F_b/F_a %.1e table %.1e guarded %.1e", double(ta), double(tb),
                  1.0 - double(fb.y) / double(fa.y), alone, guarded);
      EXPECT_LT(guarded, kSegmentBound) << "h " << h << " [" << ta << ", " << tb << "]";
      if (k == 0) {
        if (alone > 1e-3 && crossing == 0.0) crossing = h;
        if (guarded_value != alone_value && guard_switch == 0.0) guard_switch = h;
        before_foot_alone = alone;
      } else {
        EXPECT_LT(alone, kSegmentBound) << "h " << h << " [" << ta << ", " << tb << "]";
      }
    }
    std::printf("\n");
  }
  std::printf("guard: before the foot the table alone exceeds 1e-3 from h = %g down; the guard switches to "
              "quadrature from h = %g down\n", crossing, guard_switch);
  // Without the guard the section before the foot is badly wrong at the smallest h: the guard is
  // what holds it (this fails if the guard is removed or made ineffective).
  EXPECT_GT(before_foot_alone, 1e-2);
  EXPECT_GT(guard_switch, crossing);
}

// Cancellation without a small h: a backward lobe (g = −0.9) makes Ĝ(θ_a) ≈ Ĝ(θ_b) for a section
// in front of the light, because almost all of Ĝ comes from beyond θ_b. The table alone loses
// digits there; the guard catches it by the same test.
TEST(ScatteringLutGuard, BackwardLobeCancellation) {
  const TynMedium m = makeMedium({{TYN_PHASE_HENYEY_GREENSTEIN, -0.9f}}, vec3(0.0f));
  const LutTable table = buildTable(m);
  const Scene s = axisScene(10.0, 0.5);
  const TynLightRay r = tyn_light_ray(s.origin, s.dir, s.light);
  double worst_alone = 0.0;
  for (const auto& [ta, tb] : std::vector<std::pair<float, float>>{{0.0f, 2.0f}, {2.0f, 6.0f}, {6.0f, 8.0f}}) {
    const double exact = exactSegment(m, 0, s, double(ta), double(tb));
    const double guarded = std::fabs(double(tyn_scattering_lut_segment(table, m, r, ta, tb).x) - exact) / exact;
    const double alone =
        std::fabs(double(tyn_scattering_lut_segment_guarded(table, m, r, ta, tb, -1.0f).x) - exact) / exact;
    std::printf("backward lobe [%g, %g]: table alone %.2e, guarded %.2e\n", double(ta), double(tb), alone, guarded);
    EXPECT_LT(guarded, kSegmentBound);
    worst_alone = std::max(worst_alone, alone);
  }
  EXPECT_GT(worst_alone, kSegmentBound);
}

// ---- The spot cone ----

// A random unit vector, uniform over directions (rejection sampling in the unit ball).
vec3 randomUnit(std::mt19937& rng) {
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  vec3 v;
  do {
    v = vec3(u(rng), u(rng), u(rng));
  } while (length(v) > 1.0f || length(v) < 0.1f);
  return normalize(v);
}

// The cone intervals against a dense scan of the cone test (cos of the angle to the axis ≥ the
// cone's, in front of the light) on random rays, some nearly along the axis, some through the
// apex region, half-angles from 3° to 86°: no disagreement away from the surface.
TEST(ScatteringLutSpot, ConeIntervalMatchesBruteForce) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  int disagreements = 0;
  int checked = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const vec3 light = 5.0f * vec3(u(rng), u(rng), u(rng));
    const vec3 axis = randomUnit(rng);
    const float cos_half = std::cos(std::uniform_real_distribution<float>(0.05f, 1.5f)(rng));
    vec3 origin = 5.0f * vec3(u(rng), u(rng), u(rng));
    vec3 dir = randomUnit(rng);
    if (trial % 4 == 1) origin = light + 2.0f * axis + 0.3f * vec3(u(rng), u(rng), u(rng));
    if (trial % 4 == 2) dir = normalize(axis + 0.05f * randomUnit(rng));
    if (trial % 4 == 3) origin = light - 3.0f * dir + 1e-3f * randomUnit(rng);
    const TynLightRay r = tyn_light_ray(origin, dir, light);
    const TynSpotCone cone = tyn_spot_cone(r, dir, axis, cos_half, cos_half);
    const vec2 interval = tyn_spot_cone_interval(r, cone, cos_half, 0.0f, 20.0f);
    for (int k = 0; k <= 400; ++k) {
      const double t = 20.0 * k / 400.0;
      double offset[3];
      double d2 = 0.0;
      double along = 0.0;
      for (int i = 0; i < 3; ++i) {
        offset[i] = double(origin[i]) + t * double(dir[i]) - double(light[i]);
        d2 += offset[i] * offset[i];
        along += offset[i] * double(axis[i]);
      }
      const double cos_angle = along / std::sqrt(d2);
      if (std::fabs(cos_angle - double(cos_half)) < 1e-4) continue;  // on the surface: either
      const bool inside = cos_angle >= double(cos_half);
      const bool claimed = interval.y > interval.x && t >= double(interval.x) && t <= double(interval.y);
      ++checked;
      if (inside != claimed) ++disagreements;
    }
  }
  EXPECT_EQ(disagreements, 0) << "of " << checked;
  EXPECT_GT(checked, 1000000);
}

// The march computes a ray's cone intervals once (tyn_spot_ray) and clips them to each lit section
// (tyn_spot_ray_segment): the clipped intervals must be the ones tyn_spot_cone_interval finds for
// the section itself, bit for bit, empty where it is empty, so that hoisting changes no result.
TEST(ScatteringLutSpot, TheRaysIntervalsClippedAreEachSectionsOwn) {
  std::mt19937 rng(29);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::uniform_real_distribution<float> along(-5.0f, 30.0f);
  int nonEmpty = 0, sections = 0;
  for (float halfAngle : {0.1f, 0.5f, 1.2f}) {
    const float cos_outer = std::cos(halfAngle);
    const float cos_inner = std::cos(0.7f * halfAngle);
    for (int trial = 0; trial < 2000; ++trial) {
      const vec3 light = 3.0f * vec3(u(rng), u(rng), u(rng));
      const vec3 axis = randomUnit(rng);
      const vec3 origin = 4.0f * vec3(u(rng), u(rng), u(rng));
      const vec3 dir = trial % 4 == 0 ? normalize(light - origin + 0.05f * randomUnit(rng)) : randomUnit(rng);
      const TynLightRay r = tyn_light_ray(origin, dir, light);
      const TynSpotCone cone = tyn_spot_cone(r, dir, axis, cos_outer, cos_inner);
      const TynSpotRay spot = tyn_spot_ray(r, cone);
      for (int k = 0; k < 8; ++k) {
        float ta = std::max(along(rng), 0.0f);
        const float tb = k == 0 ? ta : ta + std::fabs(along(rng));
        const vec2 outer = tyn_spot_cone_interval(r, cone, cos_outer, ta, tb);
        const vec2 clippedOuter(std::max(ta, spot.outer.x), std::min(tb, spot.outer.y));
        ++sections;
        ASSERT_EQ(outer.y > outer.x, clippedOuter.y > clippedOuter.x) << "trial " << trial << " section " << k;
        if (!(outer.y > outer.x)) continue;
        ++nonEmpty;
        EXPECT_EQ(outer, clippedOuter) << "trial " << trial << " section " << k;
        const vec2 inner = tyn_spot_cone_interval(r, cone, cos_inner, outer.x, outer.y);
        const vec2 clippedInner(std::max(outer.x, spot.inner.x), std::min(outer.y, spot.inner.y));
        ASSERT_EQ(inner.y > inner.x, clippedInner.y > clippedInner.x) << "trial " << trial << " section " << k;
        if (inner.y > inner.x) {
          EXPECT_EQ(inner, clippedInner) << "trial " << trial << " section " << k;
        }
      }
    }
  }
  EXPECT_GT(nonEmpty, sections / 10);  // the sections do meet the cones
}

// Spot segments crossing the penumbra (camera near the cone's surface, looking in every direction
// and towards the light) against the original integral with the smoothstep falloff; plus the
// structural cases: a section inside the inner cone is the point light's, one outside is 0, and a
// hard-edged spot (equal cones) is the inner part alone.
TEST(ScatteringLutSpot, SegmentsCrossingThePenumbra) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const float cos_outer = std::cos(0.5f);
  const float cos_inner = std::cos(0.35f);
  for (const NamedPhase& phase : {allPhases()[1], allPhases()[5], allPhases()[7]}) {
    for (vec3 sigma : {vec3(0.0f), vec3(0.1f, 0.05f, 0.0f), vec3(2.0f)}) {
      const TynMedium m = makeMedium(phase.components, sigma);
      const LutTable table = buildTable(m);
      Tally tally;
      int penumbra = 0;
      for (int trial = 0; trial < 150; ++trial) {
        Scene s;
        s.spot = true;
        s.light = 3.0f * vec3(u(rng), u(rng), u(rng));
        s.axis = randomUnit(rng);
        s.cos_outer = cos_outer;
        s.cos_inner = cos_inner;
        const vec3 perp = normalize(cross(s.axis, randomUnit(rng)));
        const float dist = std::uniform_real_distribution<float>(0.5f, 6.0f)(rng);
        s.origin = s.light + dist * std::cos(0.42f) * s.axis + dist * std::sin(0.42f) * perp;
        s.dir = trial % 3 == 0 ? normalize(s.light - s.origin + 0.2f * randomUnit(rng)) : randomUnit(rng);
        const TynLightRay r = tyn_light_ray(s.origin, s.dir, s.light);
        const TynSpotCone cone = tyn_spot_cone(r, s.dir, s.axis, cos_outer, cos_inner);
        const float tb = std::uniform_real_distribution<float>(0.5f, 20.0f)(rng);
        const float ta = trial % 2 == 1 ? 0.3f * tb : 0.0f;
        const vec2 outer = tyn_spot_cone_interval(r, cone, cos_outer, ta, tb);
        const vec2 inner = tyn_spot_cone_interval(r, cone, cos_inner, ta, tb);
        if (outer.y > outer.x && !(inner.x <= outer.x && inner.y >= outer.y)) ++penumbra;
        const vec3 got = tyn_spot_segment(table, m, r, cone, ta, tb);
        for (int c = 0; c < 3; ++c) {
          const double exact = exactSegment(m, c, s, double(ta), double(tb),
                                            {double(outer.x), double(outer.y), double(inner.x), double(inner.y)});
          if (!(exact > kNegligible)) {
            EXPECT_LT(double(got[c]), 1e-25) << "outside the outer cone";
            continue;
          }
          const double error = std::fabs(double(got[c]) - exact) / exact;
          record(tally, error, sectionText(s, double(r.t_light), double(r.h), ta, tb, c));
          EXPECT_LT(error, kSegmentBound) << phase.name << " σ " << describe(sigma) << " trial " << trial;
        }
      }
      EXPECT_GT(penumbra, 50);  // the scenes do cross the penumbra
      std::printf("spot %-15s σ %-14s: %d values (%d sections in the penumbra), max relative error %.2e\n",
                  phase.name.c_str(), describe(sigma).c_str(), tally.count, penumbra, tally.worst);
    }
  }
  // Structural cases, on a ray along the axis of a spot behind the camera.
  const TynMedium m = makeMedium({{TYN_PHASE_HENYEY_GREENSTEIN, 0.5f}}, vec3(0.2f));
  const LutTable table = buildTable(m);
  const vec3 dir(1.0f, 0.0f, 0.0f);
  const TynLightRay r = tyn_light_ray(vec3(0.0f), dir, vec3(-1.0f, 0.1f, 0.0f));
  const TynSpotCone cone = tyn_spot_cone(r, dir, dir, cos_outer, cos_inner);
  const vec3 inside = tyn_spot_segment(table, m, r, cone, 1.0f, 5.0f);
  EXPECT_EQ(inside, tyn_scattering_lut_segment(table, m, r, 1.0f, 5.0f));
  const TynSpotCone backwards = tyn_spot_cone(r, dir, -dir, cos_outer, cos_inner);
  EXPECT_EQ(tyn_spot_segment(table, m, r, backwards, 0.0f, 50.0f), vec3(0.0f));
  const TynSpotCone hard = tyn_spot_cone(r, dir, dir, cos_inner, cos_inner);
  const vec2 hard_interval = tyn_spot_cone_interval(r, hard, cos_inner, 0.0f, 5.0f);
  EXPECT_NEAR(tyn_spot_segment(table, m, r, hard, 0.0f, 5.0f).x,
              tyn_scattering_lut_segment(table, m, r, hard_interval.x, hard_interval.y).x,
              1e-4f * tyn_spot_segment(table, m, r, hard, 0.0f, 5.0f).x);
}

}  // namespace
