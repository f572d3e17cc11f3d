// Layout is computed once into a list of primitives (lines, the front staircase, markers, texts) in
// output coordinates; the SVG writer and the rasteriser only draw that list, so the two outputs
// cannot drift apart.
#include "plot.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <tuple>
#include <utility>
#include <variant>

namespace tyndall::samples::bench {

namespace {

// A hand-made 5x7 bitmap font for printable ASCII 32..126 (drawn for this plot, no source). Seven
// rows per glyph, top row first, bit 4 the leftmost column; `drop` moves a glyph down that many
// rows so that g j p q y , ; _ reach below the baseline: a line of text is 9 rows tall.
struct Glyph {
  std::array<std::uint8_t, 7> rows;
  std::uint8_t drop;
};
constexpr std::array<Glyph, 95> kFont = {{
    {{0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00}, 0},  // space
    {{0x04, 0x04, 0x04, 0x04, 0x04, 0x00, 0x04}, 0},  // !
    {{0x0A, 0x0A, 0x0A, 0x00, 0x00, 0x00, 0x00}, 0},  // "
    {{0x0A, 0x0A, 0x1F, 0x0A, 0x1F, 0x0A, 0x0A}, 0},  // #
    {{0x04, 0x0F, 0x14, 0x0E, 0x05, 0x1E, 0x04}, 0},  // $
    {{0x18, 0x19, 0x02, 0x04, 0x08, 0x13, 0x03}, 0},  // %
    {{0x0C, 0x12, 0x14, 0x08, 0x15, 0x12, 0x0D}, 0},  // &
    {{0x04, 0x04, 0x08, 0x00, 0x00, 0x00, 0x00}, 0},  // '
    {{0x02, 0x04, 0x08, 0x08, 0x08, 0x04, 0x02}, 0},  // (
    {{0x08, 0x04, 0x02, 0x02, 0x02, 0x04, 0x08}, 0},  // )
    {{0x00, 0x04, 0x15, 0x0E, 0x15, 0x04, 0x00}, 0},  // *
    {{0x00, 0x04, 0x04, 0x1F, 0x04, 0x04, 0x00}, 0},  // +
    {{0x00, 0x00, 0x00, 0x0C, 0x0C, 0x04, 0x08}, 2},  // ,
    {{0x00, 0x00, 0x00, 0x0E, 0x00, 0x00, 0x00}, 0},  // -
    {{0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C}, 0},  // .
    {{0x00, 0x01, 0x02, 0x04, 0x08, 0x10, 0x00}, 0},  // /
    {{0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E}, 0},  // 0
    {{0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E}, 0},  // 1
    {{0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F}, 0},  // 2
    {{0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E}, 0},  // 3
    {{0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02}, 0},  // 4
    {{0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E}, 0},  // 5
    {{0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E}, 0},  // 6
    {{0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08}, 0},  // 7
    {{0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E}, 0},  // 8
    {{0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C}, 0},  // 9
    {{0x00, 0x0C, 0x0C, 0x00, 0x0C, 0x0C, 0x00}, 0},  // :
    {{0x00, 0x0C, 0x0C, 0x00, 0x0C, 0x0C, 0x08}, 1},  // ;
    {{0x02, 0x04, 0x08, 0x10, 0x08, 0x04, 0x02}, 0},  // <
    {{0x00, 0x00, 0x1F, 0x00, 0x1F, 0x00, 0x00}, 0},  // =
    {{0x08, 0x04, 0x02, 0x01, 0x02, 0x04, 0x08}, 0},  // >
    {{0x0E, 0x11, 0x01, 0x02, 0x04, 0x00, 0x04}, 0},  // ?
    {{0x0E, 0x11, 0x01, 0x0D, 0x15, 0x15, 0x0E}, 0},  // @
    {{0x0E, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11}, 0},  // A
    {{0x1E, 0x11, 0x11, 0x1E, 0x11, 0x11, 0x1E}, 0},  // B
    {{0x0E, 0x11, 0x10, 0x10, 0x10, 0x11, 0x0E}, 0},  // C
    {{0x1C, 0x12, 0x11, 0x11, 0x11, 0x12, 0x1C}, 0},  // D
    {{0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x1F}, 0},  // E
    {{0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x10}, 0},  // F
    {{0x0E, 0x11, 0x10, 0x17, 0x11, 0x11, 0x0F}, 0},  // G
    {{0x11, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11}, 0},  // H
    {{0x0E, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E}, 0},  // I
    {{0x07, 0x02, 0x02, 0x02, 0x02, 0x12, 0x0C}, 0},  // J
    {{0x11, 0x12, 0x14, 0x18, 0x14, 0x12, 0x11}, 0},  // K
    {{0x10, 0x10, 0x10, 0x10, 0x10, 0x10, 0x1F}, 0},  // L
    {{0x11, 0x1B, 0x15, 0x15, 0x11, 0x11, 0x11}, 0},  // M
    {{0x11, 0x11, 0x19, 0x15, 0x13, 0x11, 0x11}, 0},  // N
    {{0x0E, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}, 0},  // O
    {{0x1E, 0x11, 0x11, 0x1E, 0x10, 0x10, 0x10}, 0},  // P
    {{0x0E, 0x11, 0x11, 0x11, 0x15, 0x12, 0x0D}, 0},  // Q
    {{0x1E, 0x11, 0x11, 0x1E, 0x14, 0x12, 0x11}, 0},  // R
    {{0x0F, 0x10, 0x10, 0x0E, 0x01, 0x01, 0x1E}, 0},  // S
    {{0x1F, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04}, 0},  // T
    {{0x11, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}, 0},  // U
    {{0x11, 0x11, 0x11, 0x11, 0x11, 0x0A, 0x04}, 0},  // V
    {{0x11, 0x11, 0x11, 0x15, 0x15, 0x15, 0x0A}, 0},  // W
    {{0x11, 0x11, 0x0A, 0x04, 0x0A, 0x11, 0x11}, 0},  // X
    {{0x11, 0x11, 0x0A, 0x04, 0x04, 0x04, 0x04}, 0},  // Y
    {{0x1F, 0x01, 0x02, 0x04, 0x08, 0x10, 0x1F}, 0},  // Z
    {{0x0E, 0x08, 0x08, 0x08, 0x08, 0x08, 0x0E}, 0},  // [
    {{0x00, 0x10, 0x08, 0x04, 0x02, 0x01, 0x00}, 0},  // backslash
    {{0x0E, 0x02, 0x02, 0x02, 0x02, 0x02, 0x0E}, 0},  // ]
    {{0x04, 0x0A, 0x11, 0x00, 0x00, 0x00, 0x00}, 0},  // ^
    {{0x00, 0x00, 0x00, 0x00, 0x00, 0x1F, 0x00}, 2},  // _
    {{0x08, 0x04, 0x02, 0x00, 0x00, 0x00, 0x00}, 0},  // `
    {{0x00, 0x00, 0x0E, 0x01, 0x0F, 0x11, 0x0F}, 0},  // a
    {{0x10, 0x10, 0x16, 0x19, 0x11, 0x11, 0x1E}, 0},  // b
    {{0x00, 0x00, 0x0E, 0x10, 0x10, 0x11, 0x0E}, 0},  // c
    {{0x01, 0x01, 0x0D, 0x13, 0x11, 0x11, 0x0F}, 0},  // d
    {{0x00, 0x00, 0x0E, 0x11, 0x1F, 0x10, 0x0E}, 0},  // e
    {{0x06, 0x09, 0x08, 0x1C, 0x08, 0x08, 0x08}, 0},  // f
    {{0x0F, 0x11, 0x11, 0x11, 0x0F, 0x01, 0x0E}, 2},  // g
    {{0x10, 0x10, 0x16, 0x19, 0x11, 0x11, 0x11}, 0},  // h
    {{0x04, 0x00, 0x0C, 0x04, 0x04, 0x04, 0x0E}, 0},  // i
    {{0x02, 0x00, 0x06, 0x02, 0x02, 0x02, 0x02}, 2},  // j
    {{0x10, 0x10, 0x12, 0x14, 0x18, 0x14, 0x12}, 0},  // k
    {{0x0C, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E}, 0},  // l
    {{0x00, 0x00, 0x1A, 0x15, 0x15, 0x11, 0x11}, 0},  // m
    {{0x00, 0x00, 0x16, 0x19, 0x11, 0x11, 0x11}, 0},  // n
    {{0x00, 0x00, 0x0E, 0x11, 0x11, 0x11, 0x0E}, 0},  // o
    {{0x1E, 0x11, 0x11, 0x11, 0x1E, 0x10, 0x10}, 2},  // p
    {{0x0F, 0x11, 0x11, 0x11, 0x0F, 0x01, 0x01}, 2},  // q
    {{0x00, 0x00, 0x16, 0x19, 0x10, 0x10, 0x10}, 0},  // r
    {{0x00, 0x00, 0x0F, 0x10, 0x0E, 0x01, 0x1E}, 0},  // s
    {{0x08, 0x08, 0x1C, 0x08, 0x08, 0x09, 0x06}, 0},  // t
    {{0x00, 0x00, 0x11, 0x11, 0x11, 0x13, 0x0D}, 0},  // u
    {{0x00, 0x00, 0x11, 0x11, 0x11, 0x0A, 0x04}, 0},  // v
    {{0x00, 0x00, 0x11, 0x11, 0x15, 0x15, 0x0A}, 0},  // w
    {{0x00, 0x00, 0x11, 0x0A, 0x04, 0x0A, 0x11}, 0},  // x
    {{0x11, 0x11, 0x11, 0x11, 0x0F, 0x01, 0x0E}, 2},  // y
    {{0x00, 0x00, 0x1F, 0x02, 0x04, 0x08, 0x1F}, 0},  // z
    {{0x02, 0x04, 0x04, 0x08, 0x04, 0x04, 0x02}, 0},  // {
    {{0x04, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04}, 0},  // |
    {{0x08, 0x04, 0x04, 0x02, 0x04, 0x04, 0x08}, 0},  // }
    {{0x00, 0x00, 0x08, 0x15, 0x02, 0x00, 0x00}, 0},  // ~
}};
constexpr int kGlyphAdvance = 6;  // 5 columns and a blank one

// Okabe & Ito (2008), "Color Universal Design": told apart with the common colour-vision
// deficiencies. Their yellow is left out (too faint on white), and their black, which is the ink.
constexpr std::array<Rgb8, 6> kPalette = {
    {{0, 114, 178}, {213, 94, 0}, {0, 158, 115}, {204, 121, 167}, {230, 159, 0}, {86, 180, 233}}};
constexpr Rgb8 kInk{0, 0, 0};
constexpr Rgb8 kNoteInk{96, 96, 96};
constexpr Rgb8 kMajorGrid{208, 208, 208};
constexpr Rgb8 kMinorGrid{234, 234, 234};

// ---- Text and numbers ----

// Widths count code points (a UTF-8 continuation byte adds nothing), and cuts keep them whole.
bool isContinuation(char c) { return (static_cast<unsigned char>(c) & 0xC0u) == 0x80u; }

std::size_t codePoints(const std::string& s) {
  return static_cast<std::size_t>(std::count_if(s.begin(), s.end(), [](char c) { return !isContinuation(c); }));
}

// How many characters of width `charWidth` fit in `room`.
std::size_t fitting(double room, double charWidth) {
  return room > 0.0 ? static_cast<std::size_t>(std::floor(room / charWidth)) : 0;
}

std::string truncated(const std::string& s, std::size_t maxPoints) {
  if (codePoints(s) <= maxPoints) return s;
  if (maxPoints < 4) return std::string(maxPoints, '.');
  std::size_t cut = 0;
  for (std::size_t kept = 0; cut < s.size(); ++cut) {
    if (!isContinuation(s[cut]) && kept++ == maxPoints - 3) break;
  }
  return s.substr(0, cut) + "...";
}

// Lines of at most maxPoints, broken at spaces; a word too long for a line is cut.
std::vector<std::string> wrapped(const std::string& s, std::size_t maxPoints) {
  std::vector<std::string> lines(1);
  std::size_t begin = 0;
  while (begin < s.size()) {
    std::size_t end = s.find(' ', begin);
    if (end == std::string::npos) end = s.size();
    const std::string word = s.substr(begin, end - begin);
    begin = end + 1;
    if (word.empty()) continue;
    if (!lines.back().empty() && codePoints(lines.back()) + 1 + codePoints(word) > maxPoints) lines.emplace_back();
    std::string& line = lines.back();
    line = truncated(line + (line.empty() ? "" : " ") + word, maxPoints);
  }
  return lines;
}

// snprintf follows LC_NUMERIC and the outputs must not: a ',' can only be a decimal separator here.
// Non-finite values never reach this (the layout keeps every coordinate finite); 0 if they did, so
// no "nan" can appear in the SVG.
std::string localeFree(std::string s) {
  std::replace(s.begin(), s.end(), ',', '.');
  return s;
}

// %g with short exponents: "1e-05" -> "1e-5", "1e+06" -> "1e6".
std::string number(double v, int significant) {
  char text[48];
  std::snprintf(text, sizeof text, "%.*g", significant, std::isfinite(v) ? v : 0.0);
  std::string s = localeFree(text);
  const std::size_t e = s.find('e');
  if (e == std::string::npos) return s;
  std::size_t digits = e + 1;
  const bool negative = digits < s.size() && s[digits] == '-';
  if (digits < s.size() && (s[digits] == '-' || s[digits] == '+')) ++digits;
  while (digits + 1 < s.size() && s[digits] == '0') ++digits;
  return s.substr(0, e) + (negative ? "e-" : "e") + s.substr(digits);
}

std::string coordinate(double v) {
  char text[48];
  std::snprintf(text, sizeof text, "%.2f", std::isfinite(v) ? v : 0.0);
  return localeFree(text);
}

// ---- Axes ----

struct Axis {
  bool log = false;
  double lo = 0.0;    // range in axis space: log10 of the value on a log axis
  double hi = 1.0;
  double from = 0.0;  // output coordinates of lo and hi
  double to = 1.0;

  // Values a log axis cannot show (<= 0), and NaN, go to the minimum; the rest is clamped to the
  // range, which holds every drawable point already, so nothing can leave the plot area.
  double place(double v) const {
    const double t = log ? (v > 0.0 ? std::log10(v) : lo) : v;
    return placeAxis(t >= lo ? std::min(t, hi) : lo);
  }
  double placeAxis(double t) const { return from + (t - lo) / (hi - lo) * (to - from); }
};

void setRange(Axis& axis, const std::vector<double>& values) {
  const double defaultLo = axis.log ? -3.0 : 0.0;  // nothing to show: 1e-3..1, or 0..1
  const double defaultHi = axis.log ? 0.0 : 1.0;
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  for (double v : values) {
    if (axis.log && !(v > 0.0)) continue;
    const double t = axis.log ? std::log10(v) : v;
    lo = std::min(lo, t);
    hi = std::max(hi, t);
  }
  if (lo > hi) std::tie(lo, hi) = std::pair(defaultLo, defaultHi);
  // At least a decade on a log axis, so that two 1-2-5 ticks are always inside; a tenth of the
  // magnitude on a linear one (1 around zero), so that equal values get a readable range.
  const double magnitude = std::max(std::abs(lo), std::abs(hi));
  const double minSpan = axis.log ? 1.0 : (magnitude > 1e-100 ? 0.1 * magnitude : 1.0);
  if (hi - lo < minSpan) {
    const double centre = 0.5 * (lo + hi);
    lo = centre - 0.5 * minSpan;
    hi = centre + 0.5 * minSpan;
  }
  const double margin = 0.05 * (hi - lo);
  lo -= margin;
  hi += margin;
  const bool usable = std::isfinite(lo) && std::isfinite(hi) && hi > lo;  // not so with |values| near DBL_MAX
  axis.lo = usable ? lo : defaultLo;
  axis.hi = usable ? hi : defaultHi;
}

struct Tick {
  double t = 0.0;     // axis space
  int level = 0;      // 0: decade or linear step, 1: 2 and 5 x 10^k, 2: other minor ticks (never labelled)
  long index = 0;     // k of 10^k or of k x step
  std::string label;  // empty when not labelled
};

// Log axis: 1..9 x 10^k. Linear: multiples of the smallest 1-2-5 step at least `minSpacing` apart.
// Labels (of length extent(label) along the axis) must keep `gap` apart: every stride-th decade or
// step, with the smallest stride that allows it, then the 2s and 5s, all or none so that labels
// stay evenly spread (one by one only where fewer than two labels would be left).
template <typename Extent>
std::vector<Tick> makeTicks(const Axis& axis, double minSpacing, double gap, Extent extent) {
  constexpr std::size_t kMaxTicks = 4096;  // only reached on absurd ranges; keeps the loops bounded
  std::vector<Tick> ticks;
  if (axis.log) {
    for (double k = std::floor(axis.lo); k <= std::ceil(axis.hi) && ticks.size() < kMaxTicks; k += 1.0) {
      for (int m = 1; m <= 9; ++m) {
        const double v = m * std::pow(10.0, k);
        const double t = std::log10(v);
        if (t < axis.lo || t > axis.hi) continue;
        ticks.push_back({t, m == 1 ? 0 : (m == 2 || m == 5) ? 1 : 2, static_cast<long>(k), number(v, 6)});
      }
    }
  } else {
    const double raw = (axis.hi - axis.lo) * minSpacing / std::max(std::abs(axis.to - axis.from), 1.0);
    const double decade = std::pow(10.0, std::floor(std::log10(raw)));
    double step = 10.0 * decade;
    for (double m : {1.0, 2.0, 5.0}) {
      if (m * decade >= raw) {
        step = m * decade;
        break;
      }
    }
    for (double k = std::ceil(axis.lo / step); k * step <= axis.hi && ticks.size() < kMaxTicks; k += 1.0) {
      const double v = k * step + 0.0;  // + 0.0 turns -0 into 0
      ticks.push_back({v, 0, static_cast<long>(k), number(v, 6)});
    }
  }
  // Ticks come sorted along the axis, so neighbours in a chosen set are the only possible overlaps.
  const auto fits = [&](const std::vector<bool>& chosen) {
    double previous = 0.0;
    double previousHalf = -1.0;
    for (std::size_t i = 0; i < ticks.size(); ++i) {
      if (!chosen[i]) continue;
      const double centre = axis.placeAxis(ticks[i].t);
      const double half = 0.5 * extent(ticks[i].label);
      if (previousHalf >= 0.0 && std::abs(centre - previous) < half + previousHalf + gap) return false;
      previous = centre;
      previousHalf = half;
    }
    return true;
  };
  std::vector<bool> labelled(ticks.size(), false);
  long stride = 1;
  for (;; ++stride) {
    std::vector<bool> chosen(ticks.size(), false);
    for (std::size_t i = 0; i < ticks.size(); ++i) {
      chosen[i] = ticks[i].level == 0 && (ticks[i].index % stride + stride) % stride == 0;
    }
    if (fits(chosen) || stride > static_cast<long>(ticks.size())) {
      labelled = chosen;
      break;
    }
  }
  if (stride == 1) {
    std::vector<bool> chosen = labelled;
    for (std::size_t i = 0; i < ticks.size(); ++i) chosen[i] = chosen[i] || ticks[i].level == 1;
    if (fits(chosen)) {
      labelled = chosen;
    } else if (std::count(labelled.begin(), labelled.end(), true) < 2) {
      for (std::size_t i = 0; i < ticks.size(); ++i) {
        if (ticks[i].level != 1) continue;
        labelled[i] = true;
        labelled[i] = fits(labelled);
      }
    }
  }
  // Where not every decade has room for a label, minor ticks would only be clutter, and the
  // unlabelled decades stay, as short ticks, only while they are few.
  std::vector<Tick> kept;
  for (std::size_t i = 0; i < ticks.size(); ++i) {
    if (!labelled[i]) ticks[i].label.clear();
    if (stride == 1 || labelled[i]) {
      kept.push_back(ticks[i]);
    } else if (ticks[i].level == 0 && stride <= 3) {
      kept.push_back(ticks[i]);
      kept.back().level = 2;
    }
  }
  return kept;
}

// ---- The display list ----

struct LineItem {
  double x0, y0, x1, y1, width;
  Rgb8 colour;
};
struct FrontItem {  // the Pareto staircase
  std::vector<std::array<double, 2>> vertices;
  double width;
};
enum class Shape { Circle, Square, Triangle, Diamond };
struct MarkerItem {
  double x, y, radius;
  Shape shape;
  Rgb8 fill;
  bool outlined;   // highlighted presets
  bool dataPoint;  // false for the legend's symbols
  std::string tooltip;
};
enum class Anchor { Start, Middle, End };
struct TextItem {
  double x, y;  // y is the middle of the capitals
  std::string text;
  Anchor anchor = Anchor::Start;
  Rgb8 colour = kInk;
  bool title = false;
  bool vertical = false;  // reads bottom to top
  bool halo = false;      // a background-coloured outline, for annotations over grid lines and points
};
using Item = std::variant<LineItem, FrontItem, MarkerItem, TextItem>;

// One output's text metrics and base length: the SVG's in px of a 13 px monospace font, the
// raster's in pixels of the bitmap font at its scale.
struct Metrics {
  double charWidth, lineHeight;
  double titleCharWidth, titleLineHeight;
  double unit;  // gaps, ticks, markers and strokes are multiples of it
};

struct Plot {
  Axis x, y;
  std::vector<Item> items;
};

bool drawable(const PlotPoint& p) { return std::isfinite(p.x) && std::isfinite(p.y); }

Plot layOut(const std::vector<PlotPoint>& points, const PlotSpec& spec, double width, double height,
            const Metrics& m) {
  const double u = m.unit;
  const double pad = 8.0 * u;
  const double gap = 4.0 * u;
  const double tick = 4.0 * u;
  const double radius = 3.5 * u;
  const double bigRadius = 5.5 * u;
  const double lh = m.lineHeight;
  const double cw = m.charWidth;
  Plot plot;
  std::vector<Item>& items = plot.items;

  std::vector<std::string> seriesNames;
  std::vector<std::size_t> seriesOf(points.size());
  std::vector<double> xs;
  std::vector<double> ys;
  std::size_t nonFinite = 0;
  std::size_t clamped = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const PlotPoint& p = points[i];
    seriesOf[i] = static_cast<std::size_t>(std::find(seriesNames.begin(), seriesNames.end(), p.series) -
                                           seriesNames.begin());
    if (seriesOf[i] == seriesNames.size()) seriesNames.push_back(p.series);
    if (!drawable(p)) {
      ++nonFinite;
      continue;
    }
    xs.push_back(p.x);
    ys.push_back(p.y);
    if ((spec.logX && !(p.x > 0.0)) || (spec.logY && !(p.y > 0.0))) ++clamped;
  }
  const std::vector<std::size_t> front = paretoFront(points);
  std::vector<std::size_t> rank(points.size(), 0);  // 1-based position on the front, 0 off it
  for (std::size_t k = 0; k < front.size(); ++k) rank[front[k]] = k + 1;
  plot.x.log = spec.logX;
  plot.y.log = spec.logY;
  setRange(plot.x, xs);
  setRange(plot.y, ys);

  // Rows from the top: title, plot area, x tick labels, x label.
  const std::string title = truncated(spec.title, fitting(width - 2.0 * pad, m.titleCharWidth));
  const double top = pad + (title.empty() ? 0.5 * lh : m.titleLineHeight + gap);
  const double bottom = std::max(height - pad - 2.0 * lh - 2.0 * gap - tick, top + 1.0);
  plot.y.from = bottom;
  plot.y.to = top;
  const std::vector<Tick> yTicks = makeTicks(plot.y, 3.0 * lh, 0.2 * lh, [&](const std::string&) { return lh; });

  // Columns from the left: y label, y tick labels, plot area, legend panel. The panel is as wide
  // as its longest line, at most 38% of the width (longer lines are cut with "...").
  double yLabelsWidth = 0.0;
  for (const Tick& t : yTicks) yLabelsWidth = std::max(yLabelsWidth, static_cast<double>(codePoints(t.label)) * cw);
  const double left = pad + lh + gap + yLabelsWidth + gap + tick;
  std::vector<std::string> notes;
  if (nonFinite > 0) notes.push_back(std::to_string(nonFinite) + " non-finite, not drawn");
  if (clamped > 0) notes.push_back(std::to_string(clamped) + " at axis minimum (value <= 0)");
  const std::size_t numberWidth = std::to_string(front.size()).size() + 1;  // the number and a space
  const double swatch = 3.0 * cw;  // the legend's symbol column
  std::size_t widest = front.empty() ? 0 : codePoints("Pareto front");
  for (const std::string& s : seriesNames) widest = std::max(widest, codePoints(s));
  for (std::size_t i : front) widest = std::max(widest, numberWidth + codePoints(points[i].label));
  double panel = swatch + static_cast<double>(widest) * cw;
  for (const std::string& s : notes) panel = std::max(panel, static_cast<double>(codePoints(s)) * cw);
  panel = std::min(panel, 0.38 * width);
  const double right = std::max(width - pad - panel - 3.0 * gap, left + 1.0);
  const double legendX = right + 3.0 * gap;
  const std::size_t legendChars = fitting(panel - swatch, cw);
  plot.x.from = left;
  plot.x.to = right;
  const std::vector<Tick> xTicks = makeTicks(plot.x, 8.0 * cw, 1.5 * cw, [&](const std::string& s) {
    return static_cast<double>(codePoints(s)) * cw;
  });

  const auto line = [&](double x0, double y0, double x1, double y1, double w, Rgb8 c) {
    items.emplace_back(LineItem{x0, y0, x1, y1, w, c});
  };
  const auto text = [&](double x, double y, std::string s, Anchor anchor) -> TextItem& {
    return std::get<TextItem>(items.emplace_back(TextItem{x, y, std::move(s), anchor}));
  };

  // Grid, then the front (under the points and the frame), frame, ticks and labels.
  for (const Tick& t : xTicks) {
    const double px = plot.x.placeAxis(t.t);
    if (t.level < 2) line(px, top, px, bottom, 1.0, t.level == 0 ? kMajorGrid : kMinorGrid);
  }
  for (const Tick& t : yTicks) {
    const double py = plot.y.placeAxis(t.t);
    if (t.level < 2) line(left, py, right, py, 1.0, t.level == 0 ? kMajorGrid : kMinorGrid);
  }
  // From each front point right to the next one's time, then down to its error: the boundary of
  // what the sweep attains.
  FrontItem staircase{{}, 1.5 * u};
  for (std::size_t k = 0; k < front.size(); ++k) {
    const double px = plot.x.place(points[front[k]].x);
    const double py = plot.y.place(points[front[k]].y);
    if (k > 0) staircase.vertices.push_back({px, staircase.vertices.back()[1]});
    staircase.vertices.push_back({px, py});
  }
  if (staircase.vertices.size() >= 2) items.emplace_back(std::move(staircase));
  line(left, top, right, top, u, kInk);
  line(left, bottom, right, bottom, u, kInk);
  line(left, top, left, bottom, u, kInk);
  line(right, top, right, bottom, u, kInk);
  for (const Tick& t : xTicks) {
    const double px = plot.x.placeAxis(t.t);
    line(px, bottom, px, bottom + (t.level == 2 ? 0.5 : 1.0) * tick, u, kInk);
    if (!t.label.empty()) text(px, bottom + tick + gap + 0.5 * lh, t.label, Anchor::Middle);
  }
  for (const Tick& t : yTicks) {
    const double py = plot.y.placeAxis(t.t);
    line(left - (t.level == 2 ? 0.5 : 1.0) * tick, py, left, py, u, kInk);
    if (!t.label.empty()) text(left - tick - gap, py, t.label, Anchor::End);
  }
  text(0.5 * (left + right), bottom + tick + 2.0 * gap + 1.5 * lh,
       truncated(spec.xLabel, fitting(right - left, cw)), Anchor::Middle);
  text(pad + 0.5 * lh, 0.5 * (top + bottom), truncated(spec.yLabel, fitting(bottom - top, cw)), Anchor::Middle)
      .vertical = true;
  if (!title.empty()) {
    // Centred over the plot area where it fits, else over the image.
    const double half = 0.5 * static_cast<double>(codePoints(title)) * m.titleCharWidth;
    double cx = std::clamp(0.5 * (left + right), pad + half, std::max(width - pad - half, pad + half));
    if (cx + half > width) cx = 0.5 * width;
    text(cx, pad + 0.5 * m.titleLineHeight, title, Anchor::Middle).title = true;
  }

  // Plain points first, then the front, then the highlighted ones: what is named is never hidden.
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (drawable(points[i])) order.push_back(i);
  }
  const auto layer = [&](std::size_t i) { return !points[i].marker.empty() ? 2 : rank[i] > 0 ? 1 : 0; };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return layer(a) < layer(b); });
  const auto shapeOf = [](std::size_t series) { return static_cast<Shape>(series % 4); };
  for (std::size_t i : order) {
    const PlotPoint& p = points[i];
    const bool highlighted = !p.marker.empty();
    items.emplace_back(MarkerItem{plot.x.place(p.x), plot.y.place(p.y), highlighted ? bigRadius : radius,
                                  shapeOf(seriesOf[i]), seriesColour(seriesOf[i]), highlighted, true,
                                  p.label + " [" + p.series + "]: time " + number(p.x, 4) + "x, relative RMSE " +
                                      number(p.y, 4)});
  }
  // Front points carry their number in the legend's list; highlighted ones their marker text.
  // Up and to the right of the point, or to its left where that would leave the plot area.
  for (std::size_t i : order) {
    const PlotPoint& p = points[i];
    if (rank[i] == 0 && p.marker.empty()) continue;
    std::string note = rank[i] > 0 ? std::to_string(rank[i]) : "";
    if (!p.marker.empty()) note += (note.empty() ? "" : " ") + p.marker;
    const double r = p.marker.empty() ? radius : bigRadius;
    const double px = plot.x.place(p.x);
    const double py = plot.y.place(p.y);
    const bool toLeft = px + r + static_cast<double>(codePoints(note)) * cw > right;
    text(toLeft ? px - r : px + r, py - r - 0.25 * lh, note, toLeft ? Anchor::End : Anchor::Start).halo = true;
  }

  // Legend: series, the front and its points by number, notes.
  const double rowStep = std::max(1.2 * lh, 2.0 * bigRadius + u);
  double y = top + 0.5 * lh;
  for (std::size_t s = 0; s < seriesNames.size(); ++s) {
    items.emplace_back(MarkerItem{legendX + 0.4 * swatch, y, radius, shapeOf(s), seriesColour(s), false, false, ""});
    text(legendX + swatch, y, truncated(seriesNames[s].empty() ? "(no series)" : seriesNames[s], legendChars),
         Anchor::Start);
    y += rowStep;
  }
  if (!front.empty()) {
    y += 0.5 * lh;
    line(legendX, y, legendX + swatch - gap, y, 1.5 * u, kFrontColour);
    text(legendX + swatch, y, "Pareto front", Anchor::Start);
    y += rowStep;
    // Numbered, right-aligned; long labels wrap under their first word. Below the list, a line stays
    // free for "... n more" and the notes keep theirs.
    const double last = height - pad - static_cast<double>(notes.size() + 1) * lh - (notes.empty() ? 0.0 : 0.5 * lh);
    const std::size_t labelChars = std::max<std::size_t>(legendChars, numberWidth + 1) - numberWidth;
    for (std::size_t k = 0; k < front.size(); ++k) {
      const std::vector<std::string> lines = wrapped(points[front[k]].label, labelChars);
      const double room = last + (k + 1 == front.size() ? lh : 0.0);  // the last entry may use that line
      if (y + (static_cast<double>(lines.size()) - 0.5) * lh > room) {
        text(legendX + swatch, y, "... " + std::to_string(front.size() - k) + " more", Anchor::Start);
        y += lh;
        break;
      }
      const std::string n = std::to_string(k + 1);
      for (std::size_t l = 0; l < lines.size(); ++l) {
        const std::string prefix = l == 0 ? std::string(numberWidth - 1 - n.size(), ' ') + n + " "
                                          : std::string(numberWidth, ' ');
        text(legendX + swatch, y, prefix + lines[l], Anchor::Start);
        y += lh;
      }
      y += 0.2 * lh;  // sets wrapped entries apart
    }
  }
  y += 0.5 * lh;
  for (const std::string& note : notes) {
    text(legendX, y, truncated(note, fitting(panel, cw)), Anchor::Start).colour = kNoteInk;
    y += lh;
  }
  return plot;
}

// ---- SVG ----

std::string hex(Rgb8 c) {
  char text[8];
  std::snprintf(text, sizeof text, "#%02x%02x%02x", c.r, c.g, c.b);
  return text;
}

// XML 1.0 text: the five special characters as entities, control characters (not allowed even as
// references) as '?'.
std::string escaped(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: {
        const auto byte = static_cast<unsigned char>(c);
        out += (byte < 0x20 && c != '\t' && c != '\n' && c != '\r') || byte == 0x7F ? '?' : c;
      }
    }
  }
  return out;
}

std::string svgMarker(const MarkerItem& mk, double unit) {
  const double r = mk.radius;
  std::string attributes = std::string(" class=\"") + (mk.dataPoint ? "point" : "legend") + "\" fill=\"" +
                           hex(mk.fill) + "\"";
  if (mk.outlined) attributes += " stroke=\"" + hex(kInk) + "\" stroke-width=\"" + coordinate(1.5 * unit) + "\"";
  std::string element;
  const auto polygon = [&](std::initializer_list<std::array<double, 2>> corners) {
    std::string list;
    for (const auto& c : corners) {
      list += (list.empty() ? "" : " ") + coordinate(mk.x + c[0] * r) + "," + coordinate(mk.y + c[1] * r);
    }
    return "<polygon points=\"" + list + "\"";
  };
  switch (mk.shape) {
    case Shape::Circle:
      element = "<circle cx=\"" + coordinate(mk.x) + "\" cy=\"" + coordinate(mk.y) + "\" r=\"" + coordinate(r) + "\"";
      break;
    case Shape::Square:
      element = "<rect x=\"" + coordinate(mk.x - 0.85 * r) + "\" y=\"" + coordinate(mk.y - 0.85 * r) +
                "\" width=\"" + coordinate(1.7 * r) + "\" height=\"" + coordinate(1.7 * r) + "\"";
      break;
    case Shape::Triangle: element = polygon({{0.0, -1.2}, {1.08, 0.6}, {-1.08, 0.6}}); break;
    case Shape::Diamond: element = polygon({{0.0, -1.25}, {1.25, 0.0}, {0.0, 1.25}, {-1.25, 0.0}}); break;
  }
  const std::string name = element.substr(1, element.find(' ') - 1);
  if (mk.tooltip.empty()) return element + attributes + "/>\n";
  return element + attributes + "><title>" + escaped(mk.tooltip) + "</title></" + name + ">\n";
}

// The same triangle and diamond as the SVG's, and the same square.
bool insideShape(Shape shape, double dx, double dy, double r) {
  switch (shape) {
    case Shape::Circle: return dx * dx + dy * dy <= r * r;
    case Shape::Square: return std::max(std::abs(dx), std::abs(dy)) <= 0.85 * r;
    case Shape::Triangle: return dy <= 0.6 * r && std::abs(dx) <= 0.6 * (dy + 1.2 * r);
    case Shape::Diamond: return std::abs(dx) + std::abs(dy) <= 1.25 * r;
  }
  return false;
}

// ---- Raster ----

struct Canvas {
  std::uint32_t width;
  std::uint32_t height;
  std::vector<std::uint8_t>& rgba8;

  // Pixels [x0, x1) x [y0, y1), clipped to the image.
  void fill(long x0, long y0, long x1, long y1, Rgb8 c) {
    for (long y = std::max(y0, 0L); y < std::min(y1, static_cast<long>(height)); ++y) {
      for (long x = std::max(x0, 0L); x < std::min(x1, static_cast<long>(width)); ++x) {
        std::uint8_t* p = &rgba8[(static_cast<std::size_t>(y) * width + static_cast<std::size_t>(x)) * 4];
        p[0] = c.r;
        p[1] = c.g;
        p[2] = c.b;
      }
    }
  }
};

// The pixel holding coordinate v, bounded so that far-off coordinates cannot overflow a long.
long pixel(double v) { return static_cast<long>(std::clamp(std::floor(v), -1e6, 1e6)); }

// Square stamps of the stroke width every pixel along the line.
void drawLine(Canvas& canvas, double x0, double y0, double x1, double y1, double width, Rgb8 c) {
  const long w = std::max(1L, std::lround(width));
  const double half = 0.5 * static_cast<double>(w);
  const long steps = pixel(std::max(std::abs(x1 - x0), std::abs(y1 - y0))) + 1;
  for (long i = 0; i <= steps; ++i) {
    const double f = static_cast<double>(i) / static_cast<double>(steps);
    const long x = pixel(x0 + f * (x1 - x0) - half + 0.5);
    const long y = pixel(y0 + f * (y1 - y0) - half + 0.5);
    canvas.fill(x, y, x + w, y + w, c);
  }
}

void drawMarker(Canvas& canvas, const MarkerItem& mk, double r, Rgb8 c) {
  for (long y = pixel(mk.y - 1.5 * r); y <= pixel(mk.y + 1.5 * r); ++y) {
    for (long x = pixel(mk.x - 1.5 * r); x <= pixel(mk.x + 1.5 * r); ++x) {
      const double dx = static_cast<double>(x) + 0.5 - mk.x;
      const double dy = static_cast<double>(y) + 0.5 - mk.y;
      if (insideShape(mk.shape, dx, dy, r)) canvas.fill(x, y, x + 1, y + 1, c);
    }
  }
}

void drawText(Canvas& canvas, const TextItem& t, long scale, Rgb8 c, long offsetX, long offsetY) {
  const long length = static_cast<long>(codePoints(t.text)) * kGlyphAdvance * scale - scale;
  const double start = t.anchor == Anchor::Start ? 0.0 : t.anchor == Anchor::Middle ? -0.5 : -1.0;
  const double capHalf = 3.5 * static_cast<double>(scale);
  // Along the text from (alongX, alongY), across it from the top of the capitals.
  const long baseX = t.vertical ? pixel(t.x - capHalf + 0.5) : pixel(t.x + start * static_cast<double>(length) + 0.5);
  const long baseY = t.vertical ? pixel(t.y - start * static_cast<double>(length) + 0.5) : pixel(t.y - capHalf + 0.5);
  long index = 0;
  for (char ch : t.text) {
    if (isContinuation(ch)) continue;
    const auto code = static_cast<unsigned char>(ch);
    const Glyph& glyph = kFont[code >= 32 && code <= 126 ? code - 32 : '?' - 32];
    for (long row = 0; row < 7; ++row) {
      for (long column = 0; column < 5; ++column) {
        if ((glyph.rows[static_cast<std::size_t>(row)] & (0x10 >> column)) == 0) continue;
        const long along = (index * kGlyphAdvance + column) * scale;
        const long across = (row + glyph.drop) * scale;
        const long x = t.vertical ? baseX + across : baseX + along;
        const long y = t.vertical ? baseY - along - scale : baseY + across;
        canvas.fill(x + offsetX, y + offsetY, x + offsetX + scale, y + offsetY + scale, c);
      }
    }
    ++index;
  }
}

long rasterScale(std::uint32_t width, std::uint32_t height) {
  return std::max(1L, static_cast<long>(std::min(width / 600, height / 400)));
}

// The bitmap font is ASCII: typography common in titles and labels ("1920×1080", "2048² shadow
// map", "µs", dashes) is spelled out in it, other code points become '?'.
std::string asciiText(const std::string& s) {
  static constexpr std::array<std::pair<std::uint32_t, const char*>, 14> kSpelled = {{
      {0xD7, "x"}, {0xB2, "^2"}, {0xB3, "^3"}, {0xB5, "u"}, {0x3BC, "u"}, {0xB7, "."}, {0xA0, " "},  // × ² ³ µ μ ·
      {0xB0, "deg"}, {0x2013, "-"}, {0x2014, "-"}, {0x2212, "-"}, {0x2264, "<="}, {0x2265, ">="}, {0x2248, "~"}}};
  std::string out;
  for (std::size_t i = 0; i < s.size();) {
    const auto lead = static_cast<unsigned char>(s[i]);
    const std::size_t length = lead < 0x80 ? 1 : lead >= 0xF0 ? 4 : lead >= 0xE0 ? 3 : lead >= 0xC0 ? 2 : 0;
    std::uint32_t code = lead & (length == 4 ? 0x07u : length == 3 ? 0x0Fu : 0x1Fu);
    std::size_t j = 1;
    for (; j < length && i + j < s.size() && isContinuation(s[i + j]); ++j) {
      code = (code << 6) | (static_cast<unsigned char>(s[i + j]) & 0x3Fu);
    }
    if (length == 1) out += s[i];
    i += j;
    if (length == 1) continue;
    const auto* found = std::find_if(kSpelled.begin(), kSpelled.end(), [&](const auto& e) { return e.first == code; });
    out += j == length && found != kSpelled.end() ? found->second : "?";  // else a stray or cut sequence
  }
  return out;
}

// The raster's layout: its metrics at its scale (6 columns a glyph; 9 rows of glyph and 2 of
// leading a line; the title one scale step larger), and every text in ASCII.
Plot layOutRaster(const std::vector<PlotPoint>& points, const PlotSpec& spec, std::uint32_t width,
                  std::uint32_t height) {
  const auto s = static_cast<double>(rasterScale(width, height));
  std::vector<PlotPoint> ascii = points;
  for (PlotPoint& p : ascii) {
    for (std::string* text : {&p.label, &p.series, &p.marker}) *text = asciiText(*text);
  }
  PlotSpec asciiSpec = spec;
  for (std::string* text : {&asciiSpec.title, &asciiSpec.xLabel, &asciiSpec.yLabel}) *text = asciiText(*text);
  return layOut(ascii, asciiSpec, width, height, {6.0 * s, 11.0 * s, 6.0 * (s + 1.0), 11.0 * (s + 1.0), s});
}

// 13 px monospace: glyphs 0.6 em wide (DejaVu Sans Mono, Menlo, Consolas); the title 16 px bold.
constexpr Metrics kSvgMetrics{7.8, 16.0, 9.6, 20.0, 1.25};

}  // namespace

Rgb8 seriesColour(std::size_t series) { return kPalette[series % kPalette.size()]; }

std::vector<std::size_t> paretoFront(const std::vector<PlotPoint>& points) {
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (drawable(points[i])) order.push_back(i);
  }
  // By x, then y, then index: each point that is strictly below everything before it is on the
  // front, which leaves out equal-x and equal-y losers and all but the first of exact duplicates.
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return std::tie(points[a].x, points[a].y, a) < std::tie(points[b].x, points[b].y, b);
  });
  std::vector<std::size_t> front;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i : order) {
    if (points[i].y < best) {
      front.push_back(i);
      best = points[i].y;
    }
  }
  return front;
}

std::string plotSvg(const std::vector<PlotPoint>& points, const PlotSpec& spec) {
  const Metrics& m = kSvgMetrics;
  const Plot plot = layOut(points, spec, kSvgWidth, kSvgHeight, m);
  const std::string w = std::to_string(kSvgWidth);
  const std::string h = std::to_string(kSvgHeight);
  std::string out = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + w + "\" height=\"" + h +
                    "\" viewBox=\"0 0 " + w + " " + h +
                    "\" font-family=\"DejaVu Sans Mono, Menlo, Consolas, monospace\" font-size=\"13\""
                    " xml:space=\"preserve\">\n";
  out += "<rect width=\"" + w + "\" height=\"" + h + "\" fill=\"" + hex(kPlotBackground) + "\"/>\n";
  for (const Item& item : plot.items) {
    if (const auto* l = std::get_if<LineItem>(&item)) {
      out += "<line x1=\"" + coordinate(l->x0) + "\" y1=\"" + coordinate(l->y0) + "\" x2=\"" + coordinate(l->x1) +
             "\" y2=\"" + coordinate(l->y1) + "\" stroke=\"" + hex(l->colour) + "\" stroke-width=\"" +
             coordinate(l->width) + "\" shape-rendering=\"crispEdges\"/>\n";
    } else if (const auto* f = std::get_if<FrontItem>(&item)) {
      std::string list;
      for (const auto& v : f->vertices) list += (list.empty() ? "" : " ") + coordinate(v[0]) + "," + coordinate(v[1]);
      out += "<polyline class=\"front\" points=\"" + list + "\" fill=\"none\" stroke=\"" + hex(kFrontColour) +
             "\" stroke-width=\"" + coordinate(f->width) + "\"/>\n";
    } else if (const auto* mk = std::get_if<MarkerItem>(&item)) {
      out += svgMarker(*mk, m.unit);
    } else if (const auto* t = std::get_if<TextItem>(&item)) {
      const char* anchor = t->anchor == Anchor::Start ? "start" : t->anchor == Anchor::Middle ? "middle" : "end";
      out += "<text x=\"" + coordinate(t->x) + "\" y=\"" + coordinate(t->y) + "\" dy=\"0.35em\" text-anchor=\"" +
             anchor + "\" fill=\"" + hex(t->colour) + "\"";
      if (t->title) out += " font-size=\"16\" font-weight=\"bold\"";
      if (t->vertical) out += " transform=\"rotate(-90 " + coordinate(t->x) + " " + coordinate(t->y) + ")\"";
      if (t->halo) out += " stroke=\"" + hex(kPlotBackground) + "\" stroke-width=\"3\" paint-order=\"stroke\"";
      out += ">" + escaped(t->text) + "</text>\n";
    }
  }
  return out + "</svg>\n";
}

void plotRgba8(const std::vector<PlotPoint>& points, const PlotSpec& spec, std::uint32_t width, std::uint32_t height,
               std::vector<std::uint8_t>& rgba8) {
  static_assert(kPlotBackground == Rgb8{255, 255, 255}, "the assign below fills the background");
  rgba8.assign(static_cast<std::size_t>(width) * height * 4, 255);  // opaque everywhere
  if (rgba8.empty()) return;
  const long scale = rasterScale(width, height);
  const Plot plot = layOutRaster(points, spec, width, height);
  Canvas canvas{width, height, rgba8};
  for (const Item& item : plot.items) {
    if (const auto* l = std::get_if<LineItem>(&item)) {
      drawLine(canvas, l->x0, l->y0, l->x1, l->y1, l->width, l->colour);
    } else if (const auto* f = std::get_if<FrontItem>(&item)) {
      for (std::size_t i = 1; i < f->vertices.size(); ++i) {
        const auto& a = f->vertices[i - 1];
        const auto& b = f->vertices[i];
        drawLine(canvas, a[0], a[1], b[0], b[1], f->width, kFrontColour);
      }
    } else if (const auto* mk = std::get_if<MarkerItem>(&item)) {
      if (mk->outlined) drawMarker(canvas, *mk, mk->radius + 1.5 * static_cast<double>(scale), kInk);
      drawMarker(canvas, *mk, mk->radius, mk->fill);
    } else if (const auto* t = std::get_if<TextItem>(&item)) {
      const long s = t->title ? scale + 1 : scale;
      if (t->halo) {
        const long r = (scale + 1) / 2;
        for (long dy = -r; dy <= r; dy += r) {
          for (long dx = -r; dx <= r; dx += r) drawText(canvas, *t, s, kPlotBackground, dx, dy);
        }
      }
      drawText(canvas, *t, s, t->colour, 0, 0);
    }
  }
}

PixelPosition rasterPosition(const std::vector<PlotPoint>& points, const PlotSpec& spec, std::uint32_t width,
                             std::uint32_t height, double x, double y) {
  const Plot plot = layOutRaster(points, spec, width, height);
  return {plot.x.place(x), plot.y.place(y)};
}

}  // namespace tyndall::samples::bench
