#include "settings_text.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cstdio>
#include <initializer_list>
#include <type_traits>

namespace tyndall::samples {

namespace {

// One EpipolarSettings field: its key and a pointer to the member, of one of three types.
struct EpipolarField {
  const char* key;
  std::uint32_t EpipolarSettings::*uintMember = nullptr;
  float EpipolarSettings::*floatMember = nullptr;
  bool EpipolarSettings::*boolMember = nullptr;
};

// In EpipolarSettings' order; describe() writes them in this order.
const std::array<EpipolarField, 16> kEpipolarFields{{
    {"slices", &EpipolarSettings::slices},
    {"samples", &EpipolarSettings::samplesPerSlice},
    {"improved-placement", nullptr, nullptr, &EpipolarSettings::improvedSamplePlacement},
    {"initial-step", &EpipolarSettings::initialSampleStep},
    {"refinement", nullptr, &EpipolarSettings::refinementThreshold},
    {"intensity-refinement", nullptr, &EpipolarSettings::intensityRefinementThreshold},
    {"density", nullptr, &EpipolarSettings::epipoleDensity},
    {"tree", nullptr, nullptr, &EpipolarSettings::minMaxTree},
    {"max-tree-step", &EpipolarSettings::maxTreeStep},
    {"bilateral", nullptr, &EpipolarSettings::bilateralDepthThreshold},
    {"fixup-weight", nullptr, &EpipolarSettings::fixupWeightThreshold},
    {"slice-contrast", nullptr, &EpipolarSettings::sliceContrastThreshold},
    {"epipole-radius", nullptr, &EpipolarSettings::epipoleFixupRadius},
    {"epipole-fraction", nullptr, &EpipolarSettings::epipoleFixupHeightFraction},
    {"fixup-steps", &EpipolarSettings::fixupSteps},
    {"colored-step", &EpipolarSettings::coloredStep},
}};

constexpr std::array<const char*, 6> kBasisNames{"moments4_64", "moments4_128", "moments6_64",
                                                 "moments6_96", "moments6_192", "fourier32"};
constexpr std::array<const char*, 3> kRectificationNames{"automatic", "non-linear", "projective"};
constexpr std::array<const char*, 3> kSpacingNames{"mean-theta", "reference-ray", "fastest-ray"};
constexpr std::array<const char*, 3> kPrefixSumNames{"row-parallel", "thread-per-row", "workgroup-scan"};

// ScatteringResolution by name ("full", "half", "quarter": the library's to_string).
bool pickResolution(const std::string& value, ScatteringResolution& out) {
  for (ScatteringResolution r : {ScatteringResolution::Full, ScatteringResolution::Half, ScatteringResolution::Quarter}) {
    if (value == to_string(r)) {
      out = r;
      return true;
    }
  }
  return false;
}

// The shortest text that reads back as the same float ("0.15", not "0.150000006").
std::string floatText(float value) {
  std::array<char, 32> text{};
  const auto [end, ec] = std::to_chars(text.data(), text.data() + text.size(), value);
  return ec == std::errc() ? std::string(text.data(), end) : std::string("?");
}

template <typename Enum, std::size_t N>
bool pickName(const std::string& value, const std::array<const char*, N>& names, Enum& field) {
  for (std::size_t i = 0; i < N; ++i) {
    if (value == names[i]) {
      field = static_cast<Enum>(i);
      return true;
    }
  }
  return false;
}

template <typename Enum, std::size_t N>
const char* nameOf(Enum value, const std::array<const char*, N>& names) {
  const auto index = static_cast<std::size_t>(value);
  return index < N ? names[index] : "?";
}

// Calls item(key, value) for each KEY=VALUE of `text`; stops at the first that returns false.
template <typename Item>
bool forEachItem(const std::string& text, Item item) {
  std::size_t begin = 0;
  while (begin <= text.size()) {
    const std::size_t end = std::min(text.find(',', begin), text.size());
    const std::string entry = text.substr(begin, end - begin);
    const std::size_t eq = entry.find('=');
    if (!item(entry.substr(0, eq), eq == std::string::npos ? std::string() : entry.substr(eq + 1))) return false;
    begin = end + 1;
  }
  return true;
}

void append(std::string& out, const std::string& key, const std::string& value) {
  if (!out.empty()) out += ',';
  out += key + '=' + value;
}

}  // namespace

const char* const kEpipolarKeys =
    "slices, samples, improved-placement (0|1), initial-step, refinement, intensity-refinement, density, tree (0|1), "
    "max-tree-step, bilateral, fixup-weight, slice-contrast, epipole-radius, epipole-fraction, fixup-steps, colored-step, "
    "resolution (full|half|quarter), min-rows";
const char* const kPrefilteredKeys =
    "basis (moments4_64|moments4_128|moments6_64|moments6_96|moments6_192|fourier32), "
    "rectification (automatic|non-linear|projective), rows, columns, filtered (0|1), "
    "spacing (mean-theta|reference-ray|fastest-ray), taps, prefix-sums (row-parallel|thread-per-row|workgroup-scan), "
    "beta (adaptive|a number in [0, 1]), epipole-block, short-rays, depth-bounds (0|1), segments (0|1), trim (0|1), "
    "texel-walk, resolution (full|half|quarter), min-rows";

bool parseUint(const std::string& text, std::uint32_t minimum, std::uint32_t maximum, std::uint32_t& out) {
  std::uint32_t value = 0;
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc() || ptr != end || value < minimum || value > maximum) return false;
  out = value;
  return true;
}

bool parseFloat(const std::string& text, float& out) {
  float value = 0.0f;
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc() || ptr != end) return false;
  out = value;
  return true;
}

bool parseEpipolarSettings(const std::string& text, EpipolarSettings& out, std::string& error) {
  EpipolarSettings s;
  const bool ok = forEachItem(text, [&](const std::string& key, const std::string& value) {
    if (key == "resolution") {
      const bool parsed = pickResolution(value, s.resolution);
      if (!parsed) error = "--epipolar: bad value for resolution (got '" + value + "')";
      return parsed;
    }
    if (key == "min-rows") {
      const bool parsed = parseUint(value, 0, 1u << 30, s.minimumRows);
      if (!parsed) error = "--epipolar: bad value for min-rows (got '" + value + "')";
      return parsed;
    }
    const auto field = std::find_if(kEpipolarFields.begin(), kEpipolarFields.end(),
                                    [&](const EpipolarField& f) { return key == f.key; });
    if (field == kEpipolarFields.end()) {
      error = "--epipolar: unknown key '" + key + "' (keys: " + kEpipolarKeys + ")";
      return false;
    }
    std::uint32_t u = 0;
    bool parsed = false;
    if (field->uintMember != nullptr) {
      parsed = parseUint(value, 0, 1u << 30, s.*field->uintMember);
    } else if (field->floatMember != nullptr) {
      parsed = parseFloat(value, s.*field->floatMember);
    } else if (parseUint(value, 0, 1, u)) {
      s.*field->boolMember = u != 0;
      parsed = true;
    }
    if (!parsed) error = "--epipolar: bad value for " + key + " (got '" + value + "')";
    return parsed;
  });
  if (ok) out = s;
  return ok;
}

bool parsePrefilteredSettings(const std::string& text, PrefilteredSettings& out, std::string& error) {
  PrefilteredSettings s;
  const bool ok = forEachItem(text, [&](const std::string& key, const std::string& value) {
    std::uint32_t u = 0;
    bool parsed = false;
    if (key == "basis") {
      parsed = pickName(value, kBasisNames, s.basis);
    } else if (key == "rectification") {
      parsed = pickName(value, kRectificationNames, s.rectification);
    } else if (key == "rows") {
      parsed = parseUint(value, 0, 1u << 30, s.rows);
    } else if (key == "columns") {
      parsed = parseUint(value, 0, 1u << 30, s.columns);
    } else if (key == "filtered") {
      parsed = parseUint(value, 0, 1, u);
      s.filteredResampling = u != 0;
    } else if (key == "spacing") {
      parsed = pickName(value, kSpacingNames, s.spacing);
    } else if (key == "taps") {
      parsed = parseUint(value, 0, 1u << 30, s.rayWeightTaps);
    } else if (key == "prefix-sums") {
      parsed = pickName(value, kPrefixSumNames, s.prefixSums);
    } else if (key == "beta") {
      s.adaptiveOverestimation = value == "adaptive";
      parsed = s.adaptiveOverestimation || parseFloat(value, s.overestimation);
    } else if (key == "epipole-block") {
      parsed = parseUint(value, 0, 1u << 30, s.epipoleBlockPixels);
    } else if (key == "short-rays") {
      parsed = parseUint(value, 0, 1u << 30, s.shortRayColumns);
    } else if (key == "texel-walk") {
      parsed = parseUint(value, 0, 1u << 30, s.texelWalkSteps);
    } else if (key == "depth-bounds") {
      parsed = parseUint(value, 0, 1, u);
      s.depthBounds = u != 0;
    } else if (key == "segments") {
      parsed = parseUint(value, 0, 1, u);
      s.segmentedReconstruction = u != 0;
    } else if (key == "resolution") {
      parsed = pickResolution(value, s.resolution);
    } else if (key == "min-rows") {
      parsed = parseUint(value, 0, 1u << 30, s.minimumRows);
    } else if (key == "trim") {
      parsed = parseUint(value, 0, 1, u);
      s.trimmedSegments = u != 0;
    } else {
      error = "--prefiltered: unknown key '" + key + "' (keys: " + kPrefilteredKeys + ")";
      return false;
    }
    if (!parsed) error = "--prefiltered: bad value for " + key + " (got '" + value + "')";
    return parsed;
  });
  if (ok) out = s;
  return ok;
}

std::string describe(const EpipolarSettings& settings) {
  const EpipolarSettings defaults;
  std::string out;
  for (const EpipolarField& field : kEpipolarFields) {
    if (field.uintMember != nullptr) {
      if (settings.*field.uintMember != defaults.*field.uintMember) {
        append(out, field.key, std::to_string(settings.*field.uintMember));
      }
    } else if (field.floatMember != nullptr) {
      if (settings.*field.floatMember != defaults.*field.floatMember) {
        append(out, field.key, floatText(settings.*field.floatMember));
      }
    } else if (settings.*field.boolMember != defaults.*field.boolMember) {
      append(out, field.key, settings.*field.boolMember ? "1" : "0");
    }
  }
  if (settings.resolution != defaults.resolution) append(out, "resolution", to_string(settings.resolution));
  if (settings.minimumRows != defaults.minimumRows) append(out, "min-rows", std::to_string(settings.minimumRows));
  return out.empty() ? "defaults" : out;
}

std::string describe(const PrefilteredSettings& s) {
  const PrefilteredSettings d;
  std::string out;
  if (s.basis != d.basis) append(out, "basis", nameOf(s.basis, kBasisNames));
  if (s.rectification != d.rectification) append(out, "rectification", nameOf(s.rectification, kRectificationNames));
  if (s.rows != d.rows) append(out, "rows", std::to_string(s.rows));
  if (s.columns != d.columns) append(out, "columns", std::to_string(s.columns));
  if (s.filteredResampling != d.filteredResampling) append(out, "filtered", s.filteredResampling ? "1" : "0");
  if (s.spacing != d.spacing) append(out, "spacing", nameOf(s.spacing, kSpacingNames));
  if (s.rayWeightTaps != d.rayWeightTaps) append(out, "taps", std::to_string(s.rayWeightTaps));
  if (s.prefixSums != d.prefixSums) append(out, "prefix-sums", nameOf(s.prefixSums, kPrefixSumNames));
  if (s.adaptiveOverestimation) {
    append(out, "beta", "adaptive");
  } else if (s.overestimation != d.overestimation || d.adaptiveOverestimation) {
    append(out, "beta", floatText(s.overestimation));
  }
  if (s.epipoleBlockPixels != d.epipoleBlockPixels) append(out, "epipole-block", std::to_string(s.epipoleBlockPixels));
  if (s.shortRayColumns != d.shortRayColumns) append(out, "short-rays", std::to_string(s.shortRayColumns));
  if (s.depthBounds != d.depthBounds) append(out, "depth-bounds", s.depthBounds ? "1" : "0");
  if (s.segmentedReconstruction != d.segmentedReconstruction) {
    append(out, "segments", s.segmentedReconstruction ? "1" : "0");
  }
  if (s.trimmedSegments != d.trimmedSegments) append(out, "trim", s.trimmedSegments ? "1" : "0");
  if (s.texelWalkSteps != d.texelWalkSteps) append(out, "texel-walk", std::to_string(s.texelWalkSteps));
  if (s.resolution != d.resolution) append(out, "resolution", to_string(s.resolution));
  if (s.minimumRows != d.minimumRows) append(out, "min-rows", std::to_string(s.minimumRows));
  return out.empty() ? "defaults" : out;
}

}  // namespace tyndall::samples
