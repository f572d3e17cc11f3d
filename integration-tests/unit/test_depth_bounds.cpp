// The row depth bounds of the prefiltered technique (shaders/prefiltered/depth_bounds.h, compiled
// as C++ from the shader's source): outward 16-bit rounding, the verdict of a whole ray against
// brute force over the row's occluder depths in double precision, and the texels a lookup covers
// against the bilinear footprint of the prefix-sum lookup it stands beside.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "prefiltered/depth_bounds.h"
#include "prefiltered/rectification.h"

// The tree the searches read (tyn_depth_bounds_node is the includer's: the shader reads its
// image, this test its own vector laid out the same way); rows_columns.x picks the row.
namespace {
std::vector<std::vector<tyndall::gpu::vec2>> gTreeRows;
}  // namespace

namespace tyndall::gpu {
vec2 tyn_depth_bounds_node(ivec3 rows_columns, uint level, int index) {
  const auto& row = gTreeRows.at(static_cast<std::size_t>(rows_columns.x));
  return row.at(static_cast<std::size_t>(tyn_depth_bounds_level_offset(rows_columns.z, level) + index));
}
}  // namespace tyndall::gpu

namespace {

using namespace tyndall::gpu;

// What a UNORM16 channel returns for a stored float (Vulkan: round to nearest).
float throughUnorm16(float x) { return std::round(std::clamp(x, 0.0f, 1.0f) * 65535.0f) / 65535.0f; }

TEST(DepthBounds, QuantizationRoundsOutwardsToStoredValues) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<float> values{0.0f, 1.0f, 0.5f, 1.0f / 65535.0f, 1.0f - 1.0f / 65535.0f};
  for (int i = 0; i < 100000; ++i) values.push_back(unit(rng));
  for (int k = 1; k < 65535; k += 97) values.push_back(static_cast<float>(k) / 65535.0f);  // on a step
  for (float x : values) {
    const vec2 q = tyn_depth_bounds_quantize(vec2(x, x));
    ASSERT_LE(static_cast<double>(q.x), static_cast<double>(x)) << x;
    ASSERT_GE(static_cast<double>(q.y), static_cast<double>(x)) << x;
    // Exactly what the channel stores, and no more than two steps apart.
    ASSERT_EQ(throughUnorm16(q.x), q.x) << x;
    ASSERT_EQ(throughUnorm16(q.y), q.y) << x;
    ASSERT_LE(q.y - q.x, 2.0f / 65535.0f + 1e-7f) << x;
  }
}

// Rows of random texels, each with one or two occluder depths (some rows all near, all far, or
// clear); for rays ending anywhere along the row at random depths the verdict must agree with
// every depth the ray's texels hold, and must be given whenever the depths leave no doubt by more
// than the rounding.
TEST(DepthBounds, VerdictMatchesEveryOccluderOfTheRay) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  constexpr int kColumns = 64;
  int verdicts[3] = {0, 0, 0};
  for (int row = 0; row < 400; ++row) {
    const int kind = row % 4;  // 0: mixed, 1: all in [0, 0.4], 2: all in [0.6, 1], 3: clear (1)
    std::vector<std::vector<double>> depths(kColumns);
    for (auto& texel : depths) {
      const int count = 1 + static_cast<int>(unit(rng) * 2.0);
      for (int i = 0; i < count; ++i) {
        const double d = kind == 0 ? unit(rng) : kind == 1 ? 0.4 * unit(rng) : kind == 2 ? 0.6 + 0.4 * unit(rng) : 1.0;
        texel.push_back(d);
      }
    }
    // As the passes build them: each texel's range rounded outwards, then the running merge.
    std::vector<vec2> prefix(kColumns);
    vec2 running = tyn_depth_bounds_empty();
    for (int c = 0; c < kColumns; ++c) {
      vec2 texel = tyn_depth_bounds_empty();
      for (double d : depths[c]) texel = tyn_depth_bounds_merge(texel, vec2(static_cast<float>(d)));
      running = tyn_depth_bounds_merge(running, tyn_depth_bounds_quantize(texel));
      prefix[c] = running;
    }
    for (int ray = 0; ray < 50; ++ray) {
      const int end = static_cast<int>(unit(rng) * kColumns);
      const float depthRay = static_cast<float>(unit(rng));
      double lo = 1.0;
      double hi = 0.0;
      for (int c = 0; c <= end; ++c) {
        for (double d : depths[c]) {
          lo = std::min(lo, d);
          hi = std::max(hi, d);
        }
      }
      const float verdict = tyn_depth_bounds_verdict(prefix[end], depthRay);
      if (verdict == 0.0f) {
        ASSERT_LT(hi, depthRay) << "a ray in shadow has an occluder behind it";
        ++verdicts[0];
      } else if (verdict == 1.0f) {
        ASSERT_GE(lo, depthRay) << "a lit ray has an occluder in front of it";
        ++verdicts[1];
      } else {
        ASSERT_EQ(verdict, -1.0f);
        // Doubt only within the rounding of the bounds.
        const double step = 2.0 / 65535.0;
        ASSERT_FALSE(hi < depthRay - step) << "every occluder in front, yet no verdict";
        ASSERT_FALSE(lo >= depthRay + step) << "no occluder in front, yet no verdict";
        ++verdicts[2];
      }
    }
  }
  // Each outcome occurred often enough for the checks above to mean something.
  for (int count : verdicts) EXPECT_GT(count, 1000);
}

// The bilinear lookup of the prefix sums at tyn_prefix_lookup_u(u) reads columns i0 and i0 + 1
// (clamped) and rows j0, j0 + 1 (wrapped or clamped); the bounds must be read at the later column,
// whose prefix holds both, and at both rows.
TEST(DepthBounds, TexelsCoverTheBilinearLookup) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int columns : {16, 1024, 4096}) {
    for (int rows : {16, 1000}) {
      for (bool wrap : {false, true}) {
        for (int i = 0; i < 2000; ++i) {
          const float u = unit(rng);
          const float v = unit(rng);
          const ivec3 t = tyn_depth_bounds_texels(u, v, columns, rows, wrap);
          const float x = tyn_prefix_lookup_u(u, static_cast<float>(columns)) * static_cast<float>(columns) - 0.5f;
          const int i0 = static_cast<int>(std::floor(x));
          const int i1 = std::clamp(i0 + 1, 0, columns - 1);
          ASSERT_EQ(t.x, std::max(std::clamp(i0, 0, columns - 1), i1)) << u;
          ASSERT_LE(static_cast<float>(t.x) / static_cast<float>(columns), u) << "the column starts after the ray's end";
          const int j0 = static_cast<int>(std::floor(v * static_cast<float>(rows) - 0.5f));
          const auto place = [&](int j) { return wrap ? (j % rows + rows) % rows : std::clamp(j, 0, rows - 1); };
          ASSERT_EQ(t.y, place(j0)) << v;
          ASSERT_EQ(t.z, place(j0 + 1)) << v;
        }
      }
    }
  }
}

// The min/max tree as the prefix-sum pass builds it (level l node j merges level l − 1 nodes 2j,
// 2j + 1), laid out by tyn_depth_bounds_level_offset; the runs found from both ends of random
// ranges must be what a linear scan of the texels finds, for any column count (powers of two or
// not) and rows of runs of every length.
TEST(DepthBounds, TreeSearchesFindTheRunsALinearScanFinds) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int columns : {1, 2, 3, 5, 16, 17, 100, 1024, 2048, 4096}) {
    const uint levels = tyn_depth_bounds_levels(columns);
    ASSERT_EQ(tyn_depth_bounds_level_nodes(columns, levels - 1u), 1);
    ASSERT_LE(tyn_depth_bounds_tree_width(columns), 2 * columns + static_cast<int>(levels));
    ASSERT_LE(levels, TYN_DEPTH_BOUNDS_MAX_LEVELS);
    for (int trial = 0; trial < 40; ++trial) {
      // Runs of depths below or above 0.5 (some texels straddling it), of random lengths.
      std::vector<vec2> texels(static_cast<std::size_t>(columns));
      const float runScale = static_cast<float>(1 + trial % 8) * static_cast<float>(columns) / 8.0f;
      int c = 0;
      while (c < columns) {
        const int length = 1 + static_cast<int>(unit(rng) * runScale);
        const float kind = unit(rng);
        for (int i = c; i < std::min(columns, c + length); ++i) {
          const float a = kind < 0.45f ? 0.5f * unit(rng) : kind < 0.9f ? 0.5f + 0.5f * unit(rng) : unit(rng);
          const float b = kind < 0.9f ? a : unit(rng);
          texels[static_cast<std::size_t>(i)] = vec2(std::min(a, b), std::max(a, b));
        }
        c += length;
      }
      std::vector<vec2> tree(texels);
      for (uint l = 1u; l < levels; ++l) {
        const int below = tyn_depth_bounds_level_offset(columns, l - 1u);
        const int nodesBelow = tyn_depth_bounds_level_nodes(columns, l - 1u);
        ASSERT_EQ(static_cast<int>(tree.size()), tyn_depth_bounds_level_offset(columns, l));
        for (int j = 0; j < tyn_depth_bounds_level_nodes(columns, l); ++j) {
          const vec2 right = 2 * j + 1 < nodesBelow ? tree[static_cast<std::size_t>(below + 2 * j + 1)]
                                                    : tyn_depth_bounds_empty();
          tree.push_back(tyn_depth_bounds_merge(tree[static_cast<std::size_t>(below + 2 * j)], right));
        }
      }
      ASSERT_EQ(static_cast<int>(tree.size()), tyn_depth_bounds_tree_width(columns));
      gTreeRows.assign(1, tree);
      const float depthRay = 0.5f;
      const auto side = [&](int i) { return tyn_depth_bounds_verdict(texels[static_cast<std::size_t>(i)], depthRay); };
      for (int query = 0; query < 50; ++query) {
        int first = static_cast<int>(unit(rng) * static_cast<float>(columns));
        int last = static_cast<int>(unit(rng) * static_cast<float>(columns));
        first = std::min(first, columns - 1);
        last = std::min(last, columns - 1);
        if (first > last) std::swap(first, last);
        for (float s : {0.0f, 1.0f}) {
          int end = first;
          while (end <= last && side(end) == s) ++end;
          int begin = last;
          while (begin >= first && side(begin) == s) --begin;
          const ivec3 rc(0, 0, columns);
          ASSERT_EQ(tyn_depth_bounds_run_end(rc, first, last, depthRay, s), end)
              << columns << " [" << first << ", " << last << "] side " << s;
          ASSERT_EQ(tyn_depth_bounds_run_begin(rc, first, last, depthRay, s), begin)
              << columns << " [" << first << ", " << last << "] side " << s;
        }
      }
    }
  }
}

// The texel walk's visibility of one texel (tyn_two_depth_visibility): the weight of its two depths
// at or beyond the ray's depth, as stored (16-bit UNORM, rectify.glsl), against the same count in
// double precision; where the two depths alone decide it, the same answer as the texel's verdict.
TEST(DepthBounds, TwoDepthVisibilityIsTheWeightNotInFront) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto stored = [](double x) { return static_cast<float>(std::round(x * 65535.0) / 65535.0); };
  int partial = 0;
  for (int i = 0; i < 20000; ++i) {
    const vec3 texel(stored(unit(rng)), stored(unit(rng)), stored(unit(rng)));
    // Rays at random depths, at either stored depth exactly (an occluder at the ray's own depth
    // does not shadow it: tyn_depth_bounds_verdict's convention) and just in front of them.
    const float rays[] = {static_cast<float>(unit(rng)), texel.x, texel.y, std::nextafter(texel.x, 0.0f),
                          std::nextafter(texel.y, 0.0f)};
    for (float depthRay : rays) {
      const double w2 = texel.z;
      const double expected = (1.0 - w2) * (double(texel.x) >= depthRay ? 1.0 : 0.0) +
                              w2 * (double(texel.y) >= depthRay ? 1.0 : 0.0);
      const float visibility = tyn_two_depth_visibility(texel, depthRay);
      ASSERT_NEAR(visibility, expected, 1e-6);
      const float verdict = tyn_depth_bounds_verdict(vec2(std::min(texel.x, texel.y), std::max(texel.x, texel.y)), depthRay);
      if (verdict >= 0.0f) {
        ASSERT_EQ(visibility, verdict);
      } else {
        ++partial;
      }
    }
  }
  EXPECT_GT(partial, 10000) << "too few rays between the two depths to test the weights";
  // One depth (nearest resampling stores (z, 1, 0)): lit exactly when z is not in front.
  EXPECT_EQ(tyn_two_depth_visibility(vec3(0.5f, 1.0f, 0.0f), 0.5f), 1.0f);
  EXPECT_EQ(tyn_two_depth_visibility(vec3(0.5f, 1.0f, 0.0f), 0.6f), 0.0f);
}

}  // namespace
