// The profile table: which technique and parameters each quality profile uses, per kind of light.
// Data, not code paths (FidelityFX's quality-mode tables); docs/TRADEOFFS-H200.md justifies each row
// by measurement on a GPU (scripts/measure-gpu.sh) and TradeoffsDocument.AgreesWithTheProfileTable
// keeps the two equal.
#pragma once

#include "tyndall/tuning.h"

namespace tyndall {

/// The lights a row of the table is chosen for. A spot light's shafts fill a cone, not the screen,
/// and its epipolar slices cover only the wedge that can see the cone (epipolar/slice_arc.h), so
/// the same accuracy costs it different parameters than a directional light; the sweep chooses a
/// row for each over the scenes of that kind. Point lights take the local row: their scenes are
/// measured with the spot scenes (point-lamp in the GPU sweep; the point scenes of thin occluders
/// in the tests, whose bars that row meets).
enum class LightClass : std::uint8_t { Directional, Local };

constexpr LightClass lightClassOf(LightType type) {
  return type == LightType::Directional ? LightClass::Directional : LightClass::Local;
}

/// "directional", "local": the names the choice tables of docs/TRADEOFFS*.md use.
const char* to_string(LightClass lights);

struct ProfileChoice {
  Profile profile;
  LightClass lights;
  Technique technique;
  /// Why, in one line, for the stats.
  const char* note;
  /// Parameters when the technique is Epipolar.
  EpipolarSettings epipolar;
  /// Parameters when the technique is Prefiltered.
  PrefilteredSettings prefiltered{};
};

/// The resolution L_in runs at for an output of `outputHeight` rows when `asked` comes with a
/// floor of `minimumRows` (EpipolarSettings::minimumRows): `asked`, or the next finer one while
/// its target would have fewer rows (Full always runs).
constexpr ScatteringResolution resolutionForRows(ScatteringResolution asked, std::uint32_t minimumRows,
                                                 std::uint32_t outputHeight) {
  ScatteringResolution r = asked;
  while (r != ScatteringResolution::Full) {
    const auto stride = static_cast<std::uint32_t>(r);
    if ((outputHeight + stride - 1) / stride >= minimumRows) break;
    r = r == ScatteringResolution::Quarter ? ScatteringResolution::Half : ScatteringResolution::Full;
  }
  return r;
}

/// Technique settings as they run for an output of `outputHeight` rows: the resolution the floor
/// leaves (resolutionForRows), the floor itself dropped, so that they name what a sweep measures.
template <class Settings>
constexpr Settings settingsAsRunAt(Settings settings, std::uint32_t outputHeight) {
  settings.resolution = resolutionForRows(settings.resolution, settings.minimumRows, outputHeight);
  settings.minimumRows = 0;
  return settings;
}

/// The row for a profile and a kind of light (the context resolves Auto to High, Balanced or
/// Performance first).
const ProfileChoice& profileChoice(Profile profile, LightClass lights);

}  // namespace tyndall
