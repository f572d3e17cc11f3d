// The 1D min/max trees of shaders/epipolar/min_max_tree.h, compiled as C++ from the shader source:
// layout arithmetic, the build against brute force, the leaf rule and the integral against double
// precision, the accelerated march against the plain march (the tree must not change the answer),
// the footprint guarantee and the lit-set agreement against a texel-exact 2D walk of the shadow
// map (the Reference's shadow test), and the step counts the tree saves.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "epipolar/light_color_sums.h"
#include "epipolar/min_max_tree.h"

namespace {

using namespace tyndall::gpu;

// ---- Test data: one slice's cells, samples and tree row ----

struct Slice {
  int sample_count = 0;
  std::vector<float> samples;  // d_k, the plain march's depth for cell k
  std::vector<vec2> cells;     // conservative (min, max) of cell k
  std::vector<vec2> row;       // the tree, levels 0..highest at tyn_min_max_level_offset
};

// Builds the row with the header's layout and merge; level 0 from the cells' bounds.
void buildTree(Slice& s) {
  const int n = s.sample_count;
  const int top = tyn_min_max_highest_level(n);
  s.row.assign(static_cast<size_t>(tyn_min_max_row_length(n, top)), vec2(-1.0f));
  for (int i = 0; i < tyn_min_max_level_nodes(n, 0); ++i) {
    s.row[static_cast<size_t>(tyn_min_max_level_offset(n, 0) + i)] =
        tyn_min_max_merge(s.cells[static_cast<size_t>(2 * i)], s.cells[static_cast<size_t>(2 * i + 1)]);
  }
  for (int level = 1; level <= top; ++level) {
    const int below = tyn_min_max_level_offset(n, level - 1);
    for (int i = 0; i < tyn_min_max_level_nodes(n, level); ++i) {
      s.row[static_cast<size_t>(tyn_min_max_level_offset(n, level) + i)] =
          tyn_min_max_merge(s.row[static_cast<size_t>(below + 2 * i)],
                            s.row[static_cast<size_t>(below + 2 * i + 1)]);
    }
  }
}

// The accessor the march templates read; counts reads outside the slice or above `max_level`.
struct SliceAccess {
  const Slice* slice;
  int max_level;
  mutable int bad_reads = 0;

  vec2 fetch(int level, int index) const {
    if (level < 0 || level > max_level || index < 0 ||
        index >= tyn_min_max_level_nodes(slice->sample_count, level)) {
      ++bad_reads;
      return vec2(0.0f, 1.0f);
    }
    return slice->row[static_cast<size_t>(tyn_min_max_level_offset(slice->sample_count, level) + index)];
  }
  float sample(int k) const {
    if (k < 0 || k >= slice->sample_count) {
      ++bad_reads;
      return 1.0f;
    }
    return slice->samples[static_cast<size_t>(k)];
  }
  vec3 color_mean(float, float) const { return vec3(1.0f); }
};

enum class Profile { Smooth, Noisy, ClearRuns, Steps, Constant };
const Profile kProfiles[] = {Profile::Smooth, Profile::Noisy, Profile::ClearRuns, Profile::Steps,
                             Profile::Constant};
const char* profileName(Profile p) {
  switch (p) {
    case Profile::Smooth: return "smooth";
    case Profile::Noisy: return "noisy";
    case Profile::ClearRuns: return "clear-runs";
    case Profile::Steps: return "steps";
    default: return "constant";
  }
}

float uniform(std::mt19937& rng, float lo, float hi) {
  return std::uniform_real_distribution<float>(lo, hi)(rng);
}
int uniformInt(std::mt19937& rng, int lo, int hi) {
  return std::uniform_int_distribution<int>(lo, hi)(rng);
}

// A 1D depth profile of L samples; the cells' bounds are either the sample itself or, like a
// 2×2 footprint, the min/max over the sample and its neighbours.
Slice makeProfile(Profile kind, int n, std::mt19937& rng) {
  Slice s;
  s.sample_count = n;
  s.samples.resize(static_cast<size_t>(n));
  const float f1 = uniform(rng, 1.0f, 4.0f), f2 = uniform(rng, 5.0f, 20.0f);
  const float p1 = uniform(rng, 0.0f, 6.3f), p2 = uniform(rng, 0.0f, 6.3f);
  const float constant = uniformInt(rng, 0, 3) == 0 ? 1.0f : uniform(rng, 0.2f, 0.8f);
  float run_value = 0.5f;
  int run_left = 0;
  for (int k = 0; k < n; ++k) {
    const float x = static_cast<float>(k) / static_cast<float>(n);
    const float smooth = 0.5f + 0.3f * std::sin(6.2831853f * f1 * x + p1) +
                         0.1f * std::sin(6.2831853f * f2 * x + p2);
    float d = smooth;
    switch (kind) {
      case Profile::Smooth: break;
      case Profile::Noisy: d = uniform(rng, 0.05f, 0.95f); break;
      case Profile::ClearRuns:
      case Profile::Steps:
        if (run_left == 0) {
          run_left = uniformInt(rng, 1, std::max(1, n / 8));
          run_value = uniformInt(rng, 0, 2) == 0 ? 1.0f : uniform(rng, 0.1f, 0.9f);
        }
        --run_left;
        d = kind == Profile::Steps ? run_value : (run_value == 1.0f ? 1.0f : smooth);
        break;
      case Profile::Constant: d = constant; break;
    }
    s.samples[static_cast<size_t>(k)] = d;
  }
  const bool wide = uniformInt(rng, 0, 1) == 1;
  s.cells.resize(static_cast<size_t>(n));
  for (int k = 0; k < n; ++k) {
    float lo = s.samples[static_cast<size_t>(k)], hi = lo;
    if (wide) {
      for (int j = std::max(0, k - 1); j <= std::min(n - 1, k + 1); ++j) {
        lo = std::min(lo, s.samples[static_cast<size_t>(j)]);
        hi = std::max(hi, s.samples[static_cast<size_t>(j)]);
      }
    }
    s.cells[static_cast<size_t>(k)] = vec2(lo, hi);
  }
  buildTree(s);
  return s;
}

// A random view ray over the slice: partial, full, empty and overhanging intervals; depths that
// cross the profile or miss it; increasing and (rarely) decreasing distances; σ_t with zeros.
TynMinMaxRay randomRay(int n, std::mt19937& rng) {
  const float len = static_cast<float>(n);
  float u0 = 0.0f, u1 = len;
  switch (uniformInt(rng, 0, 9)) {
    case 0: break;
    case 1: u1 = uniform(rng, 0.0f, len); break;
    case 2: u0 = uniform(rng, -8.0f, 8.0f); u1 = uniform(rng, len - 8.0f, len + 8.0f); break;
    case 3: u0 = static_cast<float>(uniformInt(rng, 0, n)); u1 = u0; break;
    default:
      u0 = uniform(rng, 0.0f, len);
      u1 = std::min(len, u0 + uniform(rng, 0.0f, len));
  }
  const float z0 = uniform(rng, -0.2f, 1.3f);
  const float z1 = uniformInt(rng, 0, 9) == 0 ? z0 : uniform(rng, -0.2f, 1.3f);
  const float t0 = uniform(rng, 0.0f, 50.0f);
  const float t1 = uniformInt(rng, 0, 9) == 0 ? uniform(rng, 0.0f, t0) : t0 + uniform(rng, 0.0f, 300.0f);
  vec3 sigma;
  for (int c = 0; c < 3; ++c) sigma[c] = uniformInt(rng, 0, 3) == 0 ? 0.0f : uniform(rng, 0.0f, 0.05f);
  return tyn_min_max_ray(u0, u1, z0, z1, t0, t1, sigma);
}

// ---- Double-precision oracles ----

using Intervals = std::vector<std::pair<double, double>>;

double depthAt(const TynMinMaxRay& r, double u) {
  return double(r.depth_begin) + (u - double(r.u_begin)) * double(r.depth_slope);
}
double distanceAt(const TynMinMaxRay& r, double u) {
  return double(r.t_begin) + (u - double(r.u_begin)) * double(r.t_slope);
}

// ∫_a^b e^{−σt} dt = e^{−σa} (1 − e^{−σ(b−a)}) / σ, via expm1.
double exactIntegral(double a, double b, double sigma) {
  if (sigma == 0.0) return b - a;
  return std::exp(-sigma * a) * -std::expm1(-sigma * (b - a)) / sigma;
}

double integrate(const TynMinMaxRay& r, const Intervals& lit, int channel) {
  double sum = 0.0;
  for (const auto& [a, b] : lit) {
    const double ta = std::max(0.0, distanceAt(r, a)), tb = std::max(0.0, distanceAt(r, b));
    sum += exactIntegral(std::min(ta, tb), std::max(ta, tb), double(r.sigma_t[channel]));
  }
  return sum;
}

// Where on [a, b] z(u) ≤ threshold (below = true) or z(u) > threshold (below = false), in double.
std::pair<double, double> whereDepth(const TynMinMaxRay& r, double a, double b, double threshold,
                                     bool below) {
  const double za = depthAt(r, a), zb = depthAt(r, b);
  const bool a_in = below ? za <= threshold : za > threshold;
  const bool b_in = below ? zb <= threshold : zb > threshold;
  if (a_in && b_in) return {a, b};
  if (!a_in && !b_in) return {b, b};
  const double u = a + (b - a) * (threshold - za) / (zb - za);
  return a_in ? std::make_pair(a, u) : std::make_pair(u, b);
}

// The plain march's lit set, in double, from the same samples: lit where z ≤ d_k, all of a cell
// with d_k ≥ 1.
Intervals plainLitSetDouble(const Slice& s, const TynMinMaxRay& r) {
  const double end = s.sample_count;
  const double a = std::clamp(double(r.u_begin), 0.0, end);
  const double b = std::clamp(double(r.u_end), a, end);
  Intervals lit;
  for (int k = 0; k < s.sample_count; ++k) {
    const double ca = std::max(a, double(k)), cb = std::min(b, double(k + 1));
    if (cb <= ca) continue;
    const double d = s.samples[static_cast<size_t>(k)];
    const auto part = d >= 1.0 ? std::make_pair(ca, cb) : whereDepth(r, ca, cb, d, true);
    if (part.second > part.first) lit.push_back(part);
  }
  return lit;
}

// The lit set of the header's leaf rule, cell by cell (what the plain march integrates).
Intervals plainLitSetFloat(const Slice& s, const TynMinMaxRay& r) {
  const float end = static_cast<float>(s.sample_count);
  const float a = std::clamp(r.u_begin, 0.0f, end);
  const float b = std::clamp(r.u_end, a, end);
  Intervals lit;
  for (int k = 0; k < s.sample_count; ++k) {
    const float ca = std::max(a, static_cast<float>(k)), cb = std::min(b, static_cast<float>(k + 1));
    if (cb <= ca) continue;
    const vec2 part = tyn_min_max_lit_part(ca, cb, tyn_min_max_depth_at(r, ca),
                                           tyn_min_max_depth_at(r, cb), s.samples[static_cast<size_t>(k)]);
    if (part.y > part.x) lit.emplace_back(part.x, part.y);
  }
  return lit;
}

double measure(const Intervals& set) {
  double sum = 0.0;
  for (const auto& [a, b] : set) sum += b - a;
  return sum;
}

double overlap(const Intervals& set, double a, double b) {
  double sum = 0.0;
  for (const auto& [x, y] : set) sum += std::max(0.0, std::min(y, b) - std::max(x, a));
  return sum;
}

double relativeDifference(float x, float y) {
  const double scale = std::max(std::abs(double(x)), std::abs(double(y)));
  return scale == 0.0 ? 0.0 : std::abs(double(x) - double(y)) / scale;
}

// ---- Layout ----

TEST(MinMaxTreeLayout, LevelsFillOneRowOfLMinusOneTexels) {
  for (int n = 2; n <= TYN_MIN_MAX_MAX_SAMPLES; n *= 2) {
    const int top = tyn_min_max_highest_level(n);
    EXPECT_EQ(1 << (top + 1), n);
    EXPECT_EQ(tyn_min_max_level_nodes(n, top), 1) << n;
    EXPECT_EQ(tyn_min_max_level_offset(n, 0), 0);
    EXPECT_EQ(tyn_min_max_node_span(-1), 1);
    int column = 0;
    for (int level = 0; level <= top; ++level) {
      EXPECT_EQ(tyn_min_max_level_offset(n, level), column) << n << " level " << level;
      EXPECT_EQ(tyn_min_max_level_nodes(n, level) * tyn_min_max_node_span(level), n);
      EXPECT_EQ(tyn_min_max_node_span(level), 2 << level);
      column += tyn_min_max_level_nodes(n, level);
      EXPECT_EQ(tyn_min_max_row_length(n, level), column);
      EXPECT_EQ(tyn_min_max_level_for_max_step(tyn_min_max_node_span(level)), level);
    }
    EXPECT_EQ(column, n - 1);
    EXPECT_EQ(tyn_min_max_row_length(n, top), n - 1);
    EXPECT_LE(tyn_min_max_row_length(n, top), TYN_MIN_MAX_MAX_SAMPLES);
  }
  EXPECT_EQ(tyn_min_max_row_length(4096, 5), 2048 + 1024 + 512 + 256 + 128 + 64);
  EXPECT_EQ(tyn_min_max_row_length(4096, -1), 0);
}

// ---- Build ----

TEST(MinMaxTreeBuild, NodesAreTheMinAndMaxOfTheirCells) {
  std::mt19937 rng(11);
  int checked = 0;
  for (Profile kind : kProfiles) {
    for (int n : {2, 8, 64, 1024}) {
      const Slice s = makeProfile(kind, n, rng);
      for (int level = 0; level <= tyn_min_max_highest_level(n); ++level) {
        const int span = tyn_min_max_node_span(level);
        for (int i = 0; i < tyn_min_max_level_nodes(n, level); ++i) {
          float lo = 2.0f, hi = -2.0f;
          for (int k = i * span; k < (i + 1) * span; ++k) {
            lo = std::min(lo, s.cells[static_cast<size_t>(k)].x);
            hi = std::max(hi, s.cells[static_cast<size_t>(k)].y);
          }
          const vec2 node = s.row[static_cast<size_t>(tyn_min_max_level_offset(n, level) + i)];
          ASSERT_EQ(node.x, lo) << profileName(kind) << " L " << n << " level " << level << " node " << i;
          ASSERT_EQ(node.y, hi) << profileName(kind) << " L " << n << " level " << level << " node " << i;
          ++checked;
        }
      }
    }
  }
  EXPECT_GT(checked, 5000);
  EXPECT_EQ(tyn_min_max_footprint_bounds(vec4(0.4f, 0.2f, 1.0f, 0.7f)), vec2(0.2f, 1.0f));
  EXPECT_EQ(tyn_min_max_merge(vec2(0.3f, 0.5f), vec2(0.1f, 0.4f)), vec2(0.1f, 0.5f));
}

// ---- Leaf rule, ray and integral against double precision ----

TEST(MinMaxLeafRule, LitPartSolvesTheLinearShadowTest) {
  // Exact cases: clear texels light even z > 1; z = d is lit (≤); both directions of crossing.
  EXPECT_EQ(tyn_min_max_lit_part(2.0f, 3.0f, 1.5f, 1.7f, 1.0f), vec2(2.0f, 3.0f));
  EXPECT_EQ(tyn_min_max_lit_part(2.0f, 3.0f, 0.5f, 0.5f, 0.5f), vec2(2.0f, 3.0f));
  const vec2 none = tyn_min_max_lit_part(2.0f, 3.0f, 0.6f, 0.8f, 0.5f);
  EXPECT_LE(none.y, none.x);
  EXPECT_EQ(tyn_min_max_lit_part(2.0f, 3.0f, 0.2f, 0.6f, 0.4f), vec2(2.0f, 2.5f));
  EXPECT_EQ(tyn_min_max_lit_part(2.0f, 3.0f, 0.6f, 0.2f, 0.4f), vec2(2.5f, 3.0f));
  EXPECT_EQ(tyn_min_max_classify(0.2f, 0.3f, vec2(0.3f, 0.9f)), TYN_MIN_MAX_LIT);
  EXPECT_EQ(tyn_min_max_classify(0.95f, 0.91f, vec2(0.3f, 0.9f)), TYN_MIN_MAX_SHADOWED);
  EXPECT_EQ(tyn_min_max_classify(0.95f, 0.91f, vec2(0.3f, 1.0f)), TYN_MIN_MAX_MIXED);
  EXPECT_EQ(tyn_min_max_classify(5.0f, 7.0f, vec2(1.0f, 1.0f)), TYN_MIN_MAX_LIT);

  std::mt19937 rng(5);
  double worst = 0.0;  // in units of the tolerance
  for (int i = 0; i < 100000; ++i) {
    const float a = uniform(rng, 0.0f, 4000.0f), b = a + uniform(rng, 0.01f, 1.0f);
    const float za = uniform(rng, 0.0f, 1.0f), zb = uniform(rng, 0.0f, 1.0f);
    const float d = uniform(rng, 0.0f, 1.0f);
    if (std::abs(zb - za) < 1e-3f) continue;  // the crossing is ill-conditioned there
    const vec2 part = tyn_min_max_lit_part(a, b, za, zb, d);
    // Double: z(u) = za + (u − a)(zb − za)/(b − a) ≤ d.
    const double zs = (double(zb) - za) / (double(b) - a);
    double lo = a, hi = b;
    const double cross = a + (double(d) - za) / zs;
    if (zs > 0.0) hi = std::min(hi, cross); else lo = std::max(lo, cross);
    const double exact_len = std::max(0.0, hi - lo);
    const double len = std::max(0.0, double(part.y) - part.x);
    // Float positions near u = 4000 are 2.4e-4 apart, and the crossing fraction carries the
    // depths' rounding (1e-7) over |zb − za| ≥ 1e-3: a few ulps of b plus 2e-4 of the section.
    const double ulp = std::nextafter(b, 2.0f * b) - b;
    const double tolerance = 4.0 * ulp + 2e-4 * (double(b) - a);
    worst = std::max(worst, std::abs(len - exact_len) / tolerance);
    if (exact_len > 0.0 && len > 0.0) {
      EXPECT_NEAR(part.x, lo, tolerance);
      EXPECT_NEAR(part.y, hi, tolerance);
    }
  }
  EXPECT_LE(worst, 1.0);
  std::printf("[ MinMax ] leaf rule: worst lit-length error %.2f of the tolerance (4 ulp(u) + 2e-4 of the section)\n", worst);
}

TEST(MinMaxLeafRule, RayAndIntegralMatchDoublePrecision) {
  std::mt19937 rng(9);
  for (int i = 0; i < 2000; ++i) {
    const float u0 = uniform(rng, 0.0f, 4000.0f), u1 = u0 + uniform(rng, 0.5f, 96.0f);
    const float z0 = uniform(rng, 0.0f, 1.0f), z1 = uniform(rng, 0.0f, 1.0f);
    const float t0 = uniform(rng, 0.0f, 100.0f), t1 = t0 + uniform(rng, 0.0f, 100.0f);
    const float sigma = uniformInt(rng, 0, 4) == 0 ? 0.0f : uniform(rng, 0.0f, 0.2f);
    const TynMinMaxRay r = tyn_min_max_ray(u0, u1, z0, z1, t0, t1, vec3(sigma));
    EXPECT_NEAR(tyn_min_max_depth_at(r, u1), z1, 2e-6);
    EXPECT_NEAR(tyn_min_max_distance_at(r, u1), t1, 2e-5 * t1 + 1e-6);
    const float ua = uniform(rng, u0, u1), ub = uniform(rng, ua, u1);
    const double exact = exactIntegral(distanceAt(r, ua), distanceAt(r, ub), sigma);
    EXPECT_NEAR(tyn_min_max_directional_integral(r, ua, ub).x, exact, 2e-5 * exact + 1e-7);
  }
  const TynMinMaxRay empty = tyn_min_max_ray(3.0f, 3.0f, 0.5f, 0.9f, 1.0f, 2.0f, vec3(0.1f));
  EXPECT_EQ(empty.depth_slope, 0.0f);
  EXPECT_EQ(empty.t_slope, 0.0f);
}

// ---- The tree changes the cost, never the answer ----

TEST(MinMaxMarch, TreeEqualsPlainMarchForEveryMaxStep) {
  std::mt19937 rng(2013);
  double worst_tree = 0.0, worst_double = 0.0;
  long rays = 0, bad_reads = 0;
  for (Profile kind : kProfiles) {
    long plain_steps = 0, tree_steps = 0, kind_rays = 0;
    for (int n : {64, 512, 4096}) {
      const int profiles = n == 4096 ? 3 : 10;
      const int rays_per_profile = n == 4096 ? 60 : 60;
      for (int p = 0; p < profiles; ++p) {
        const Slice s = makeProfile(kind, n, rng);
        for (int i = 0; i < rays_per_profile; ++i) {
          const TynMinMaxRay r = randomRay(n, rng);
          const SliceAccess plain_access{&s, -1};
          const TynMinMaxMarch plain = tyn_min_max_march_plain(plain_access, n, r, 0);
          bad_reads += plain_access.bad_reads;

          // The plain march against the same lit set integrated in double.
          const Intervals lit = plainLitSetDouble(s, r);
          for (int c = 0; c < 3; ++c) {
            const Intervals whole = {{std::clamp(double(r.u_begin), 0.0, double(n)),
                                      std::clamp(double(r.u_end), std::clamp(double(r.u_begin), 0.0, double(n)), double(n))}};
            const double full = integrate(r, whole, c);
            const double err = std::abs(double(plain.lit_integral[c]) - integrate(r, lit, c));
            worst_double = std::max(worst_double, full > 0.0 ? err / full : err);
            // Float resolves a crossing to about an ulp of u (2.4e-4 near u = 4096), which a ray
            // nearly along the light (|dt/du| in the thousands, u range ≪ 1) turns into distance.
            const double position_ulp = std::nextafter(float(n), 2.0f * float(n)) - float(n);
            ASSERT_LE(err, 1e-4 * full + 4.0 * position_ulp * std::abs(double(r.t_slope)) + 1e-9)
                << profileName(kind) << " L " << n << " ray " << i << " channel " << c;
          }

          const int highest = tyn_min_max_highest_level(n);
          for (int top = -1; top <= highest + 1; ++top) {
            const SliceAccess access{&s, std::min(top, highest)};
            const TynMinMaxMarch tree = tyn_min_max_march_tree(access, n, top, r, 0);
            bad_reads += access.bad_reads;
            for (int c = 0; c < 3; ++c) {
              const double rel = relativeDifference(tree.lit_integral[c], plain.lit_integral[c]);
              worst_tree = std::max(worst_tree, rel);
              ASSERT_LE(rel, 1e-6) << profileName(kind) << " L " << n << " top level " << top
                                   << " ray " << i << ": tree " << tree.lit_integral[c]
                                   << " plain " << plain.lit_integral[c];
            }
            if (top == -1) {
              EXPECT_EQ(tree.steps, plain.steps);  // no tree: the plain march
            }
            EXPECT_LE(tree.steps, 2 * n + highest + 2);
            if (top == highest) tree_steps += tree.steps;
          }
          plain_steps += plain.steps;
          ++kind_rays;
          ++rays;
        }
      }
    }
    std::printf("[ MinMax ] %-10s mean steps per ray: plain %.1f, full tree %.1f\n", profileName(kind),
                double(plain_steps) / double(kind_rays), double(tree_steps) / double(kind_rays));
  }
  EXPECT_EQ(bad_reads, 0);
  EXPECT_GE(rays, 4000);
  std::printf("[ MinMax ] %ld rays x every max step: worst tree/plain relative difference %.2e; "
              "worst plain vs double %.2e of the unshadowed integral\n", rays, worst_tree, worst_double);
}

// The tree texture's RG16 UNORM round trip as Vulkan defines it: the nearest code, and code / 65535.
vec2 throughUnorm16(vec2 v) {
  auto trip = [](float x) { return float(std::lround(std::clamp(double(x), 0.0, 1.0) * 65535.0)) / 65535.0f; };
  return vec2(trip(v.x), trip(v.y));
}

TEST(MinMaxStorage, StoredNodesStillBoundTheirDepthsAndMarchTheSame) {
  // Every depth, as stored and read back, lies within the node's stored bounds; a clear node stays 1.
  std::mt19937 rng(16);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<float> depths = {0.0f, 1.0f, 1.5f, std::nextafter(1.0f, 0.0f), 1.0f / 65535.0f, 0.5f};
  for (int code = 0; code <= 65535; code += 97) depths.push_back(float(code) / 65535.0f);
  for (int i = 0; i < 100000; ++i) depths.push_back(unit(rng));
  for (float d : depths) {
    const vec2 stored = throughUnorm16(tyn_min_max_stored_bounds(vec2(d)));
    ASSERT_LE(stored.x, std::min(d, 1.0f)) << d;
    ASSERT_GE(stored.y, std::min(d, 1.0f)) << d;
    if (d >= 1.0f) {
      ASSERT_EQ(stored, vec2(1.0f)) << d;
    } else {
      ASSERT_LT(stored.x, 1.0f) << d;  // else the node would light points beyond it
    }
  }
  // The accelerated march over a stored tree equals the plain march (which reads the map's depths).
  long rays = 0;
  for (Profile kind : kProfiles) {
    for (int n : {64, 512}) {
      for (int p = 0; p < 5; ++p) {
        Slice s = makeProfile(kind, n, rng);
        for (vec2& node : s.row) node = throughUnorm16(tyn_min_max_stored_bounds(node));
        for (int i = 0; i < 40; ++i, ++rays) {
          const TynMinMaxRay r = randomRay(n, rng);
          const TynMinMaxMarch plain = tyn_min_max_march_plain(SliceAccess{&s, -1}, n, r, 0);
          const int highest = tyn_min_max_highest_level(n);
          const TynMinMaxMarch tree = tyn_min_max_march_tree(SliceAccess{&s, highest}, n, highest, r, 0);
          for (int c = 0; c < 3; ++c) {
            ASSERT_LE(relativeDifference(tree.lit_integral[c], plain.lit_integral[c]), 1e-6)
                << profileName(kind) << " L " << n << " ray " << i;
          }
        }
      }
    }
  }
  EXPECT_GE(rays, 600);
}

// The whole-ray shadow test the refinement runs before the march (a sample it accepts is set to
// zero and never marched): whenever it says "shadowed", both marches give exactly zero, for every
// maximum step; and it does say so for most rays whose plain march is zero.
TEST(MinMaxShadowTest, ShadowedRaysMarchToExactlyZero) {
  std::mt19937 rng(2026);
  long accepted = 0, zero_rays = 0, rays = 0, bad_reads = 0;
  for (Profile kind : kProfiles) {
    for (int n : {64, 512, 4096}) {
      for (int p = 0; p < (n == 4096 ? 3 : 10); ++p) {
        const Slice s = makeProfile(kind, n, rng);
        for (int i = 0; i < 60; ++i) {
          TynMinMaxRay r = randomRay(n, rng);
          // Half the rays lifted above the profile's range, where a shadowed verdict is possible.
          if (i % 2 == 0) r.depth_begin = std::max(r.depth_begin, uniform(rng, 0.85f, 0.99f));
          const SliceAccess plain_access{&s, -1};
          const bool plain_zero = tyn_min_max_march_plain(plain_access, n, r, 0).lit_integral == vec3(0.0f);
          const int highest = tyn_min_max_highest_level(n);
          for (int top = 0; top <= highest; ++top) {
            const SliceAccess access{&s, top};
            const bool shadowed = tyn_min_max_ray_shadowed(access, n, top, r);
            bad_reads += access.bad_reads;
            if (!shadowed) continue;
            ++accepted;
            ASSERT_TRUE(plain_zero) << profileName(kind) << " L " << n << " top " << top << " ray " << i;
            ASSERT_EQ(tyn_min_max_march_tree(access, n, top, r, 0).lit_integral, vec3(0.0f))
                << profileName(kind) << " L " << n << " top " << top << " ray " << i;
          }
          if (plain_zero) zero_rays += highest + 1;
          rays += highest + 1;
        }
      }
    }
  }
  std::printf("[ MinMax ] whole-ray shadow test: %ld of %ld (ray, max step) pairs march to zero, %ld of them "
              "found without marching\n", zero_rays, rays, accepted);
  EXPECT_EQ(bad_reads, 0);
  EXPECT_GT(zero_rays, rays / 20);
  EXPECT_GE(double(accepted), 0.5 * double(zero_rays));
}

// A tilted occluder (depth rising along the slice by much more than the gap under it) over a ray
// just below it: no single bound over the ray's span shows it shadowed (the occluder's far end is
// deeper than the ray's near end), the walk down the tree does; lifting the ray's far end to the
// occluder lights a sliver, and the test then says no.
TEST(MinMaxShadowTest, DescendsUnderATiltedOccluder) {
  const int n = 512;
  Slice s;
  s.sample_count = n;
  for (int k = 0; k < n; ++k) s.samples.push_back(0.2f + 0.6f * (float(k) + 0.5f) / float(n));
  for (int k = 0; k < n; ++k) {
    const float lo = s.samples[static_cast<size_t>(std::max(k - 1, 0))];
    const float hi = s.samples[static_cast<size_t>(std::min(k + 1, n - 1))];
    s.cells.push_back(vec2(lo, hi));
  }
  buildTree(s);
  const SliceAccess access{&s, tyn_min_max_highest_level(n)};
  // 0.02 deeper than the occluder everywhere: z from 0.22 to 0.82.
  const TynMinMaxRay under = tyn_min_max_ray(0.0f, float(n), 0.22f, 0.82f, 0.0f, 100.0f, vec3(0.01f));
  const vec2 whole = access.fetch(tyn_min_max_highest_level(n), 0);
  ASSERT_GT(whole.y, 0.22f);  // one bound over the span cannot decide
  EXPECT_TRUE(tyn_min_max_ray_shadowed(access, n, tyn_min_max_highest_level(n), under));
  EXPECT_EQ(tyn_min_max_march_tree(access, n, tyn_min_max_highest_level(n), under, 0).lit_integral, vec3(0.0f));
  const TynMinMaxRay grazing = tyn_min_max_ray(0.0f, float(n), 0.22f, 0.78f, 0.0f, 100.0f, vec3(0.01f));
  EXPECT_FALSE(tyn_min_max_ray_shadowed(access, n, tyn_min_max_highest_level(n), grazing));
  EXPECT_GT(tyn_min_max_march_tree(access, n, tyn_min_max_highest_level(n), grazing, 0).lit_integral.x, 0.0f);
  EXPECT_EQ(access.bad_reads, 0);
}

// A light-colour texture along the slice (coloured shafts): a channel-varying colour in [0, 1]
// (fast in red: 0.37 rad a cell, about a colour texel of 8 cells), taken per cell at its centre and
// summed in float as slice_setup.comp does (runs of consecutive cells, then the runs'
// offsets), read through light_color_sums.h's mean.
dvec3 colorDouble(double u) { return dvec3(0.6 + 0.4 * std::sin(0.37 * u), 0.5 + 0.5 * std::cos(0.11 * u), 0.25); }

struct ColorSums {
  std::vector<vec3> sums;  // S_k
  vec3 sum(int k) const { return sums[static_cast<size_t>(k)]; }
};

ColorSums buildColorSums(int n, bool white, int run = 16) {
  ColorSums s;
  s.sums.resize(static_cast<size_t>(n));
  vec3 offset(0.0f);
  for (int first = 0; first < n; first += run) {
    vec3 sum(0.0f);
    for (int k = first; k < std::min(first + run, n); ++k) {
      sum += white ? vec3(1.0f) : vec3(colorDouble(k + 0.5));
      s.sums[static_cast<size_t>(k)] = sum;
    }
    for (int k = first; k < std::min(first + run, n); ++k) s.sums[static_cast<size_t>(k)] += offset;
    offset += sum;
  }
  return s;
}

struct ColoredAccess : SliceAccess {
  const ColorSums* colors;
  vec3 color_mean(float a, float b) const { return tyn_color_sums_mean(*colors, slice->sample_count, a, b); }
};

// ∫_a^b c(u) du of the cells' colours, in double.
double colorIntegralDouble(double a, double b, int channel) {
  double sum = 0.0;
  for (int k = int(std::floor(a)); double(k) < b; ++k) {
    sum += colorDouble(k + 0.5)[channel] * std::max(0.0, std::min(b, double(k + 1)) - std::max(a, double(k)));
  }
  return sum;
}

// The plain march's lit parts merged where they touch inside one chunk of `chunk` cells: the
// sections a coloured march integrates (tyn_min_max_add_colored).
Intervals coloredSectionsDouble(const Slice& s, const TynMinMaxRay& r, int chunk) {
  Intervals sections;
  for (const auto& part : plainLitSetDouble(s, r)) {
    const bool chunkStart = std::fmod(part.first, double(chunk)) == 0.0;
    if (!sections.empty() && sections.back().second == part.first && !chunkStart) {
      sections.back().second = part.second;
    } else {
      sections.push_back(part);
    }
  }
  return sections;
}

// The sums and their mean: S_k against double, a mean inside one cell is that cell's colour, and
// means over random sections against double.
TEST(LightColorSums, MeansMatchDouble) {
  EXPECT_EQ(tyn_color_sums_width(2048), 2048);
  EXPECT_EQ(tyn_color_sums_rows(2048), 1);
  EXPECT_EQ(tyn_color_sums_width(8192), 4096);
  EXPECT_EQ(tyn_color_sums_rows(8192), 2);
  EXPECT_EQ(tyn_color_sums_texel(8192, 3, 5000), ivec2(5000 - 4096, 7));
  std::mt19937 rng(7);
  for (int n : {64, 2048}) {
    const ColorSums sums = buildColorSums(n, false);
    double worst = 0.0;
    for (int i = 0; i < 20000; ++i) {
      float a = uniform(rng, 0.0f, float(n));
      float b = i % 3 == 0 ? std::min(float(n), a + uniform(rng, 0.0f, 1.5f)) : uniform(rng, a, float(n));
      if (i % 7 == 0) a = std::floor(a);  // sections starting on a cell edge
      if (!(b > a)) continue;
      const vec3 mean = tyn_color_sums_mean(sums, n, a, b);
      for (int c = 0; c < 3; ++c) {
        const double expected = colorIntegralDouble(a, b, c) / (double(b) - double(a));
        const double err = std::abs(double(mean[c]) - expected);
        worst = std::max(worst, err);
        // One float ulp of S at n (the sums' rounding, light_color_sums.h) over the section's length
        // (at least the part of a cell it spans), and a few ulps of the colour.
        const double ulp = std::nextafter(float(n), 2.0f * float(n)) - float(n);
        ASSERT_LE(err, 4.0 * ulp / std::max(double(b) - double(a), 1.0) + 1e-6)
            << "n " << n << " [" << a << ", " << b << "] channel " << c;
      }
    }
    // Inside one cell: exactly that cell's colour as summed (S_k − S_{k−1}).
    for (int k : {0, 1, n / 2, n - 1}) {
      const vec3 mean = tyn_color_sums_mean(sums, n, float(k) + 0.25f, float(k) + 0.5f);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(mean[c], colorDouble(k + 0.5)[c], 4e-4) << k;
    }
    std::printf("[ ColorSums ] L %d: worst mean vs double %.2e\n", n, worst);
  }
}

// Coloured marches, with chunks of one cell (yusov2013's fine step), eight and 32 (the default):
// the tree (which then only skips shadowed nodes whole) still equals the plain march, both equal
// Σ mean colour · ∫ over each section in double, and a white light gives the uncoloured march's
// result.
TEST(MinMaxMarch, ColoredTreeEqualsColoredPlainAndDouble) {
  std::mt19937 rng(48);
  for (int chunk : {1, 8, 32}) {
    double worst_tree = 0.0, worst_double = 0.0, worst_white = 0.0;
    long plain_steps = 0, tree_steps = 0, uncolored_tree_steps = 0, cell_tree_steps = 0;
    for (Profile kind : kProfiles) {
      for (int n : {64, 512}) {
        const ColorSums sums = buildColorSums(n, false);
        const ColorSums white_sums = buildColorSums(n, true);
        for (int p = 0; p < 6; ++p) {
          const Slice s = makeProfile(kind, n, rng);
          for (int i = 0; i < 40; ++i) {
            const TynMinMaxRay r = randomRay(n, rng);
            const ColoredAccess colored{{&s, tyn_min_max_highest_level(n)}, &sums};
            const ColoredAccess white{{&s, tyn_min_max_highest_level(n)}, &white_sums};
            const TynMinMaxMarch plain = tyn_min_max_march_plain(colored, n, r, chunk);
            const TynMinMaxMarch tree = tyn_min_max_march_tree(colored, n, tyn_min_max_highest_level(n), r, chunk);
            // Every maximum step: a lit node is walked chunk by chunk from whichever level found it.
            for (int top = -1; top <= tyn_min_max_highest_level(n) + 1; ++top) {
              const ColoredAccess capped{{&s, std::min(top, tyn_min_max_highest_level(n))}, &sums};
              const TynMinMaxMarch step_tree = tyn_min_max_march_tree(capped, n, top, r, chunk);
              for (int c = 0; c < 3; ++c) {
                const double rel = relativeDifference(step_tree.lit_integral[c], plain.lit_integral[c]);
                worst_tree = std::max(worst_tree, rel);
                ASSERT_LE(rel, 1e-6) << profileName(kind) << " L " << n << " top level " << top << " ray " << i
                                     << " chunk " << chunk;
              }
            }
            const TynMinMaxMarch white_colored = tyn_min_max_march_plain(white, n, r, chunk);
            const TynMinMaxMarch uncolored = tyn_min_max_march_tree(white, n, tyn_min_max_highest_level(n), r, 0);
            plain_steps += plain.steps;
            tree_steps += tree.steps;
            uncolored_tree_steps += uncolored.steps;
            cell_tree_steps += tyn_min_max_march_tree(colored, n, tyn_min_max_highest_level(n), r, 1).steps;
            for (int c = 0; c < 3; ++c) {
              worst_tree = std::max(worst_tree, relativeDifference(tree.lit_integral[c], plain.lit_integral[c]));
              ASSERT_LE(relativeDifference(tree.lit_integral[c], plain.lit_integral[c]), 1e-6)
                  << profileName(kind) << " L " << n << " ray " << i << " chunk " << chunk;
              // Σ mean colour · ∫ over each section, in double.
              double expected = 0.0, full = 0.0;
              for (const auto& [a, b] : coloredSectionsDouble(s, r, chunk)) {
                expected += colorIntegralDouble(a, b, c) / (b - a) * integrate(r, {{a, b}}, c);
              }
              const double a = std::clamp(double(r.u_begin), 0.0, double(n));
              full = integrate(r, {{a, std::clamp(double(r.u_end), a, double(n))}}, c);
              const double err = std::abs(double(plain.lit_integral[c]) - expected);
              worst_double = std::max(worst_double, full > 0.0 ? err / full : err);
              const double position_ulp = std::nextafter(float(n), 2.0f * float(n)) - float(n);
              ASSERT_LE(err, 2e-4 * full + 4.0 * position_ulp * std::abs(double(r.t_slope)) + 1e-9)
                  << profileName(kind) << " L " << n << " ray " << i << " channel " << c << " chunk " << chunk;
              const double white_difference =
                  relativeDifference(white_colored.lit_integral[c], uncolored.lit_integral[c]);
              worst_white = std::max(worst_white, white_difference);
              ASSERT_LE(white_difference, 1e-4) << profileName(kind) << " L " << n << " ray " << i;
            }
          }
        }
      }
    }
    // Shadowed nodes are still skipped whole and lit ones walked chunk by chunk: the coloured tree
    // costs more than the uncoloured one and less than the plain march, and longer chunks cost
    // less than single cells.
    EXPECT_GT(tree_steps, uncolored_tree_steps);
    EXPECT_LT(tree_steps, plain_steps);
    if (chunk > 1) {
      EXPECT_LT(tree_steps, cell_tree_steps);
    }
    std::printf("[ MinMax ] coloured, chunk %d: worst tree/plain %.2e, plain vs double %.2e of the unshadowed "
                "integral, white vs uncoloured %.2e; steps plain %ld, coloured tree %ld (cell by cell %ld), "
                "uncoloured tree %ld\n",
                chunk, worst_tree, worst_double, worst_white, plain_steps, tree_steps, cell_tree_steps,
                uncolored_tree_steps);
  }
}

// What a chunk costs in accuracy: against the exact coloured integral Σ_k c_k ∫_cell e^{−σt} dt
// (double), a chunk of h scene units (chunk cells × |dt/du|) is off by at most
// max|c − c̄| · ∫ |w − w̄| ≤ (max c − min c) · σh e^{σh} · W over the chunk (w = e^{−σt}, W = ∫ w:
// |w − w̄| ≤ w_max − w_min ≤ w_max σh and W ≥ h w_min = h w_max e^{−σh}); so the whole ray is off by
// at most σ h e^{σh} of its unshadowed integral, with c ∈ [0, 1]. Fully lit rays at several optical
// depths per chunk; the error must stay within that bound and shrink with the chunk; the chunk
// tyn_min_max_colored_chunk picks keeps σh within TYN_MIN_MAX_COLORED_OPTICAL_DEPTH.
TEST(MinMaxMarch, ColoredChunkErrorWithinItsBound) {
  const int n = 512;
  Slice s;
  s.sample_count = n;
  s.samples.assign(n, 1.0f);
  s.cells.assign(n, vec2(1.0f));
  buildTree(s);
  const ColorSums sums = buildColorSums(n, false);
  const ColoredAccess access{{&s, tyn_min_max_highest_level(n)}, &sums};
  const vec3 sigma(0.05f, 0.2f, 0.0f);
  const double sigma_max = 0.2;  // σ's largest channel, which tyn_min_max_colored_chunk caps
  for (float t_per_cell : {0.01f, 0.1f, 1.0f}) {
    const TynMinMaxRay r = tyn_min_max_ray(0.0f, float(n), 0.0f, 0.0f, 2.0f, 2.0f + t_per_cell * float(n), sigma);
    // Per channel: the exact coloured integral and the unshadowed one, in double.
    dvec3 exact(0.0), full(0.0);
    for (int c = 0; c < 3; ++c) {
      for (int k = 0; k < n; ++k) exact[c] += colorDouble(k + 0.5)[c] * integrate(r, {{double(k), double(k + 1)}}, c);
      full[c] = integrate(r, {{0.0, double(n)}}, c);
    }
    double previous = 0.0;
    for (int chunk : {1, 4, 32, 256}) {
      const TynMinMaxMarch m = tyn_min_max_march_tree(access, n, tyn_min_max_highest_level(n), r, chunk);
      double worst = 0.0;
      for (int c = 0; c < 3; ++c) {
        const double sh = double(sigma[c]) * chunk * t_per_cell;
        const double err = std::abs(double(m.lit_integral[c]) - exact[c]) / full[c];
        worst = std::max(worst, err);
        EXPECT_LE(err, sh * std::exp(sh) + 1e-5) << "dt/du " << t_per_cell << " chunk " << chunk << " channel " << c;
      }
      std::printf("[ MinMax ] coloured chunk error, dt/du %.2f, chunk %3d: %.2e of the unshadowed integral\n",
                  t_per_cell, chunk, worst);
      // The ray's own chunk for this largest chunk: within the optical-depth cap, so within its bound.
      const int own = tyn_min_max_colored_chunk(r, chunk);
      const double tau = sigma_max * own * t_per_cell;
      EXPECT_LE(own, chunk);
      EXPECT_TRUE(own == 1 || tau <= TYN_MIN_MAX_COLORED_OPTICAL_DEPTH + 1e-6) << own;
      EXPECT_TRUE(own == chunk || 2.0 * tau > TYN_MIN_MAX_COLORED_OPTICAL_DEPTH) << "not the largest: " << own;
      const TynMinMaxMarch capped = tyn_min_max_march_tree(access, n, tyn_min_max_highest_level(n), r, own);
      const double bound_tau = std::max(tau, sigma_max * t_per_cell);  // one cell's, when the cap hits 1
      for (int c = 0; c < 3; ++c) {
        EXPECT_LE(std::abs(double(capped.lit_integral[c]) - exact[c]) / full[c],
                  bound_tau * std::exp(bound_tau) + 1e-5);
      }
      if (chunk > 4) {
        EXPECT_GT(worst, previous * 0.5) << "error should not vanish as chunks grow";
      }
      previous = worst;
    }
  }
}

// Fully lit or fully shadowed stretches cost one node; the maximum step caps the stride.
TEST(MinMaxMarch, StepCountsFarBelowTheSampleCount) {
  const int n = 4096;
  const int highest = tyn_min_max_highest_level(n);
  Slice s;
  s.sample_count = n;
  s.samples.assign(n, 0.6f);
  s.cells.assign(n, vec2(0.6f));
  buildTree(s);
  const vec3 sigma(0.01f, 0.02f, 0.0f);

  // Every max step, a ray in front of everything: exactly L / 2^(top+1) steps, one per node.
  const TynMinMaxRay lit = tyn_min_max_ray(0.0f, float(n), 0.1f, 0.5f, 0.0f, 100.0f, sigma);
  const TynMinMaxRay shadowed = tyn_min_max_ray(0.0f, float(n), 0.7f, 0.9f, 0.0f, 100.0f, sigma);
  for (int top = 0; top <= highest; ++top) {
    const SliceAccess access{&s, top};
    EXPECT_EQ(tyn_min_max_march_tree(access, n, top, lit, 0).steps, n / tyn_min_max_node_span(top));
    EXPECT_EQ(tyn_min_max_march_tree(access, n, top, shadowed, 0).steps, n / tyn_min_max_node_span(top));
  }
  const SliceAccess full{&s, highest};
  EXPECT_EQ(tyn_min_max_march_tree(full, n, highest, lit, 0).steps, 1);
  EXPECT_EQ(tyn_min_max_march_plain(full, n, lit, 0).steps, n);
  EXPECT_EQ(tyn_min_max_march_tree(full, n, highest, shadowed, 0).lit_integral, vec3(0.0f));

  // A ray crossing the constant occluder depth once: one root-to-leaf path down and one up.
  const TynMinMaxRay crossing = tyn_min_max_ray(0.0f, float(n), 0.2f, 0.9f, 0.0f, 100.0f, sigma);
  const int crossing_steps = tyn_min_max_march_tree(full, n, highest, crossing, 0).steps;
  EXPECT_LE(crossing_steps, 2 * (highest + 2));
  // Starting mid-slice at an odd position: the march climbs back up in log L steps.
  const TynMinMaxRay offset = tyn_min_max_ray(1234.5f, 4000.25f, 0.1f, 0.5f, 3.0f, 90.0f, sigma);
  const int offset_steps = tyn_min_max_march_tree(full, n, highest, offset, 0).steps;
  EXPECT_LE(offset_steps, 2 * (highest + 2));

  // Half shadowed, half lit: the root is mixed, its two children decide.
  for (int k = 0; k < n / 2; ++k) {
    s.samples[static_cast<size_t>(k)] = 0.3f;
    s.cells[static_cast<size_t>(k)] = vec2(0.3f);
  }
  buildTree(s);
  const TynMinMaxRay flat = tyn_min_max_ray(0.0f, float(n), 0.5f, 0.5f, 0.0f, 100.0f, sigma);
  const TynMinMaxMarch halves = tyn_min_max_march_tree(full, n, highest, flat, 0);
  EXPECT_EQ(halves.steps, 3);
  EXPECT_NEAR(halves.lit_integral.z, 50.0f, 1e-4f);  // σ = 0: the lit half's length 100 / 2
  EXPECT_EQ(full.bad_reads, 0);
  std::printf("[ MinMax ] L 4096: lit/shadowed ray 1 step (plain 4096), single crossing %d, "
              "mid-slice start %d, half/half 3\n", crossing_steps, offset_steps);
}

// ---- Against the texel-exact 2D walk of the shadow map ----

struct ShadowMap {
  int n = 0;
  std::vector<float> depth;
  // Depth at a texel; 1 (clear, lit) outside the map, like a directional map's outside.
  float shadow_texel(ivec2 t) const {
    if (t.x < 0 || t.y < 0 || t.x >= n || t.y >= n) return 1.0f;
    return depth[static_cast<size_t>(t.y * n + t.x)];
  }
};

enum class MapKind { Boxes, Noise, Smooth };
const MapKind kMapKinds[] = {MapKind::Boxes, MapKind::Noise, MapKind::Smooth};
const char* mapName(MapKind k) {
  return k == MapKind::Boxes ? "boxes" : (k == MapKind::Noise ? "noise" : "smooth");
}

ShadowMap makeMap(MapKind kind, int n, std::mt19937& rng) {
  ShadowMap m;
  m.n = n;
  m.depth.assign(static_cast<size_t>(n * n), 1.0f);
  if (kind == MapKind::Boxes) {
    for (int b = uniformInt(rng, 1, 8); b > 0; --b) {
      const int x0 = uniformInt(rng, 0, n - 1), y0 = uniformInt(rng, 0, n - 1);
      const int x1 = std::min(n, x0 + uniformInt(rng, 1, n / 2)), y1 = std::min(n, y0 + uniformInt(rng, 1, n / 2));
      const float d = uniform(rng, 0.1f, 0.9f);
      for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) m.depth[static_cast<size_t>(y * n + x)] = std::min(m.depth[static_cast<size_t>(y * n + x)], d);
    }
  } else {
    const float fx = uniform(rng, 0.05f, 0.4f), fy = uniform(rng, 0.05f, 0.4f), ph = uniform(rng, 0.0f, 6.3f);
    for (int y = 0; y < n; ++y) {
      for (int x = 0; x < n; ++x) {
        float d = 0.5f + 0.35f * std::sin(fx * float(x) + ph) * std::cos(fy * float(y));
        if (kind == MapKind::Noise) d = uniformInt(rng, 0, 9) == 0 ? 1.0f : uniform(rng, 0.05f, 0.95f);
        m.depth[static_cast<size_t>(y * n + x)] = d;
      }
    }
  }
  return m;
}

// A slice line: random origin around the map, random direction, step of max-norm `max_norm`.
std::pair<vec2, vec2> randomLine(int n, float max_norm, std::mt19937& rng) {
  const float angle = uniform(rng, 0.0f, 6.2831853f);
  vec2 dir(std::cos(angle), std::sin(angle));
  dir /= std::max(std::abs(dir.x), std::abs(dir.y));
  const vec2 origin(uniform(rng, -4.0f, float(n) + 4.0f), uniform(rng, -4.0f, float(n) + 4.0f));
  return {origin, dir * max_norm};
}

Slice sliceFromMap(const ShadowMap& m, vec2 origin, vec2 step, int count) {
  Slice s;
  s.sample_count = count;
  for (int k = 0; k < count; ++k) {
    s.samples.push_back(tyn_min_max_cell_sample(m, origin, step, k));
    s.cells.push_back(tyn_min_max_cell_bounds(m, origin, step, k));
  }
  buildTree(s);
  return s;
}

// The texel-exact walk (what common/texel_walk.glsl does): the line p(u) = origin + u·step cut at
// every texel edge and every integer u (so that each piece lies in one cell), in double.
struct Piece {
  double a, b;
  ivec2 texel;
  float depth;
};

std::vector<Piece> walk2D(const ShadowMap& m, vec2 origin, vec2 step, double a, double b) {
  std::vector<double> cuts = {a, b};
  for (double k = std::ceil(a); k < b; k += 1.0) cuts.push_back(k);
  for (int axis = 0; axis < 2; ++axis) {
    const double o = origin[axis], s = step[axis];
    if (s == 0.0) continue;
    const double xa = o + a * s, xb = o + b * s;
    for (double e = std::ceil(std::min(xa, xb)); e <= std::max(xa, xb); e += 1.0) {
      const double u = (e - o) / s;
      if (u > a && u < b) cuts.push_back(u);
    }
  }
  std::sort(cuts.begin(), cuts.end());
  std::vector<Piece> pieces;
  for (size_t i = 0; i + 1 < cuts.size(); ++i) {
    if (cuts[i + 1] <= cuts[i]) continue;
    const double mid = 0.5 * (cuts[i] + cuts[i + 1]);
    const ivec2 t(int(std::floor(double(origin.x) + mid * double(step.x))),
                  int(std::floor(double(origin.y) + mid * double(step.y))));
    pieces.push_back({cuts[i], cuts[i + 1], t, m.shadow_texel(t)});
  }
  return pieces;
}

// IMPORTANT: slivers shorter than this (in samples) are below float's resolution of the cell
// centre p(k + ½) and are not counted as texels the segment touches.
constexpr double kSliver = 1e-4;

// Checks that every texel the line crosses in each cell and each node lies within the cell's
// 2×2 block and the node's bounds; returns the number of violations.
int footprintViolations(const ShadowMap& m, vec2 origin, vec2 step, const Slice& s, int* checked) {
  int violations = 0;
  const int n = s.sample_count;
  for (int k = 0; k < n; ++k) {
    const ivec2 block = tyn_min_max_footprint_origin(tyn_min_max_cell_center(origin, step, k));
    const vec2 cell = s.cells[static_cast<size_t>(k)];
    const float d = s.samples[static_cast<size_t>(k)];
    if (d < cell.x || d > cell.y) ++violations;
    for (const Piece& p : walk2D(m, origin, step, k, k + 1)) {
      if (p.b - p.a < kSliver) continue;
      ++*checked;
      const ivec2 rel = p.texel - block;
      if (rel.x < 0 || rel.x > 1 || rel.y < 0 || rel.y > 1) ++violations;
      if (p.depth < cell.x || p.depth > cell.y) ++violations;
    }
  }
  for (int level = 0; level <= tyn_min_max_highest_level(n); ++level) {
    const int span = tyn_min_max_node_span(level);
    for (int i = 0; i < tyn_min_max_level_nodes(n, level); ++i) {
      const vec2 node = s.row[static_cast<size_t>(tyn_min_max_level_offset(n, level) + i)];
      for (const Piece& p : walk2D(m, origin, step, i * span, (i + 1) * span)) {
        if (p.b - p.a >= kSliver && (p.depth < node.x || p.depth > node.y)) ++violations;
      }
    }
  }
  return violations;
}

TEST(MinMaxConservative, FootprintCoversEveryTexelTheLineCrosses) {
  std::mt19937 rng(77);
  int checked = 0, violations = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const MapKind kind = kMapKinds[trial % 3];
    const ShadowMap m = makeMap(kind, 32, rng);
    // Max-norm exactly 1 (the recommended step), or shorter, or axis-aligned and diagonal.
    float max_norm = trial % 2 == 0 ? 1.0f : uniform(rng, 0.25f, 1.0f);
    auto [origin, step] = randomLine(32, max_norm, rng);
    if (trial % 10 == 1) step = vec2(0.0f, trial % 20 == 1 ? 1.0f : -1.0f);
    if (trial % 10 == 3) step = vec2(trial % 20 == 3 ? 1.0f : -1.0f, 1.0f);
    const Slice s = sliceFromMap(m, origin, step, 64);
    // The shader's level-0 builder reads the map; it must equal the merged cells.
    for (int i = 0; i < tyn_min_max_level_nodes(64, 0); ++i) {
      ASSERT_EQ(tyn_min_max_level0_node(m, origin, step, i), s.row[static_cast<size_t>(i)]);
    }
    violations += footprintViolations(m, origin, step, s, &checked);
  }
  EXPECT_EQ(violations, 0);
  EXPECT_GT(checked, 20000);
}

// The guarantee needs max(|step.x|, |step.y|) ≤ 1 texel: a longer step skips texels.
TEST(MinMaxConservative, FootprintGuaranteeNeedsAStepOfAtMostOneTexel) {
  std::mt19937 rng(78);
  int checked = 0, violations = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const ShadowMap m = makeMap(MapKind::Noise, 32, rng);
    const auto [origin, step] = randomLine(32, 1.6f, rng);
    violations += footprintViolations(m, origin, step, sliceFromMap(m, origin, step, 32), &checked);
  }
  EXPECT_GT(violations, 0);
}

// Where the tree decides, the texel-exact walk agrees (always); where a cell is mixed, the plain
// march's one-sample leaf rule can disagree with it: measured here.
TEST(MinMaxConservative, LineMarchAgreesWithTheTexelExactWalk) {
  // Depths within this of a texel's are ties that float evaluation of z may break either way.
  constexpr double kDepthTie = 1e-5;
  std::mt19937 rng(2011);
  const int n = 64;
  const int highest = tyn_min_max_highest_level(n);
  double worst_tree = 0.0;
  long decisions = 0;
  int decision_errors = 0, confinement_errors = 0;
  for (MapKind kind : kMapKinds) {
    double total = 0.0, false_lit = 0.0, false_shadow = 0.0, mixed_cells = 0.0, lit2d = 0.0;
    double sum_difference = 0.0, sum_full = 0.0;
    std::vector<double> ray_differences;  // per ray of ≥ 8 samples, relative to its unshadowed integral
    for (int trial = 0; trial < 60; ++trial) {
      const ShadowMap m = makeMap(kind, 32, rng);
      const auto [origin, step] = randomLine(32, trial % 2 == 0 ? 1.0f : uniform(rng, 0.3f, 1.0f), rng);
      const Slice s = sliceFromMap(m, origin, step, n);
      for (int i = 0; i < 40; ++i) {
        // Rays whose depth crosses the occluders' range, so that there is something to decide.
        TynMinMaxRay r = randomRay(n, rng);
        const double a = std::clamp(double(r.u_begin), 0.0, double(n));
        const double b = std::clamp(double(r.u_end), a, double(n));
        if (b <= a) continue;
        const Intervals lit1d = plainLitSetFloat(s, r);
        const std::vector<Piece> pieces = walk2D(m, origin, step, a, b);

        // The plain march integrates exactly the leaf rule's lit set (σ = 0, t = u: its length).
        TynMinMaxRay length_ray = r;
        length_ray.t_begin = std::max(r.u_begin, 0.0f);
        length_ray.t_slope = 1.0f;
        length_ray.sigma_t = vec3(0.0f);
        const SliceAccess access{&s, highest};
        EXPECT_NEAR(tyn_min_max_march_plain(access, n, length_ray, 0).lit_integral.x, measure(lit1d), 1e-4);

        // Disagreement per piece: 1D lit where the walk is strictly shadowed, and vice versa.
        std::vector<double> cell_disagreement(static_cast<size_t>(n), 0.0);
        Intervals lit_walk;
        for (const Piece& p : pieces) {
          const auto strictly_lit = p.depth >= 1.0f ? std::make_pair(p.a, p.b)
                                                    : whereDepth(r, p.a, p.b, p.depth - kDepthTie, true);
          const auto strictly_shadowed = p.depth >= 1.0f ? std::make_pair(p.b, p.b)
                                                         : whereDepth(r, p.a, p.b, p.depth + kDepthTie, false);
          const double fl = overlap(lit1d, strictly_shadowed.first, strictly_shadowed.second);
          const double fs = std::max(0.0, strictly_lit.second - strictly_lit.first) -
                            overlap(lit1d, strictly_lit.first, strictly_lit.second);
          false_lit += fl;
          false_shadow += fs;
          cell_disagreement[static_cast<size_t>(std::floor(0.5 * (p.a + p.b)))] += fl + fs;
          const auto walk_lit = p.depth >= 1.0f ? std::make_pair(p.a, p.b) : whereDepth(r, p.a, p.b, p.depth, true);
          if (walk_lit.second > walk_lit.first) lit_walk.push_back(walk_lit);
        }
        total += b - a;
        lit2d += measure(lit_walk);
        const double full = integrate(r, {{a, b}}, 0);
        const double difference = std::abs(integrate(r, lit1d, 0) - integrate(r, lit_walk, 0));
        sum_difference += difference;
        sum_full += full;
        if (full > 0.0 && b - a >= 8.0) ray_differences.push_back(difference / full);

        // Disagreement only in cells the footprint bounds leave mixed.
        for (int k = int(std::floor(a)); k < n && k < b; ++k) {
          const float ca = std::max(float(a), float(k)), cb = std::min(float(b), float(k + 1));
          const int c = tyn_min_max_classify(tyn_min_max_depth_at(r, ca), tyn_min_max_depth_at(r, cb),
                                             s.cells[static_cast<size_t>(k)]);
          if (c == TYN_MIN_MAX_MIXED) {
            mixed_cells += double(cb) - double(ca);
          } else if (cell_disagreement[static_cast<size_t>(k)] > kSliver) {
            ++confinement_errors;
          }
        }

        // Every decided tree node agrees with the walk over its section.
        for (int level = 0; level <= highest; ++level) {
          const int span = tyn_min_max_node_span(level);
          for (int node = 0; node < tyn_min_max_level_nodes(n, level); ++node) {
            const float sa = std::max(float(a), float(node * span));
            const float sb = std::min(float(b), float((node + 1) * span));
            if (sb <= sa) continue;
            const int c = tyn_min_max_classify(tyn_min_max_depth_at(r, sa), tyn_min_max_depth_at(r, sb),
                                               access.fetch(level, node));
            if (c == TYN_MIN_MAX_MIXED) continue;
            ++decisions;
            double against = 0.0;
            for (const Piece& p : walk2D(m, origin, step, sa, sb)) {
              if (p.depth >= 1.0f) {
                if (c == TYN_MIN_MAX_SHADOWED) against += p.b - p.a;
                continue;
              }
              const auto x = c == TYN_MIN_MAX_LIT ? whereDepth(r, p.a, p.b, p.depth + kDepthTie, false)
                                                  : whereDepth(r, p.a, p.b, p.depth - kDepthTie, true);
              against += std::max(0.0, x.second - x.first);
            }
            if (against > kSliver) ++decision_errors;
          }
        }

        // And on these realistic slices too, the tree equals the plain march at every max step.
        const TynMinMaxMarch plain = tyn_min_max_march_plain(access, n, r, 0);
        for (int top = -1; top <= highest; ++top) {
          const TynMinMaxMarch tree = tyn_min_max_march_tree(access, n, top, r, 0);
          for (int c = 0; c < 3; ++c) {
            worst_tree = std::max(worst_tree, relativeDifference(tree.lit_integral[c], plain.lit_integral[c]));
          }
        }
        EXPECT_EQ(access.bad_reads, 0);
      }
    }
    const double fl = false_lit / total, fs = false_shadow / total;
    std::sort(ray_differences.begin(), ray_differences.end());
    const double p99 = ray_differences[ray_differences.size() * 99 / 100];
    std::printf("[ MinMax ] %-6s vs texel-exact walk: %.0f samples marched, walk lit %.1f%%, mixed cells "
                "%.1f%%; 1D lit where walk shadowed %.3f%%, 1D shadowed where walk lit %.3f%% "
                "(agreement %.3f%%); lit integral |1D - walk|: %.3f%% of the unshadowed in all, "
                "99th percentile per ray %.2f%%\n",
                mapName(kind), total, 100.0 * lit2d / total, 100.0 * mixed_cells / total, 100.0 * fl,
                100.0 * fs, 100.0 * (1.0 - fl - fs), 100.0 * sum_difference / sum_full, 100.0 * p99);
    // Documented tolerance: the leaf rule's disagreement stays below 1.5% of the marched length
    // each way even on per-texel noise (measured: see the printout), and is 0 where decided.
    EXPECT_LT(fl, 0.015) << mapName(kind);
    EXPECT_LT(fs, 0.015) << mapName(kind);
  }
  EXPECT_EQ(decision_errors, 0);
  EXPECT_EQ(confinement_errors, 0);
  EXPECT_GT(decisions, 10000);
  EXPECT_LE(worst_tree, 1e-6);
  std::printf("[ MinMax ] %ld tree decisions checked against the walk: %d wrong\n", decisions, decision_errors);
}

}  // namespace
