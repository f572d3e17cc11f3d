// The text form of the techniques' parameters: `KEY=VALUE[,KEY=VALUE…]` over the defaults, as
// tyndall-render's --epipolar / --prefiltered take them, tyndall-bench names its configurations and
// docs/TRADEOFFS*.md write the profile table. describe() writes the fields that differ from the
// defaults in a fixed order, so that parse(describe(s)) == s and equal settings read the same.
#pragma once

#include <cstdint>
#include <string>

#include "tyndall/tuning.h"

namespace tyndall::samples {

/// A decimal integer in [minimum, maximum], nothing else.
bool parseUint(const std::string& text, std::uint32_t minimum, std::uint32_t maximum, std::uint32_t& out);
/// A decimal number (std::from_chars), nothing else.
bool parseFloat(const std::string& text, float& out);

/// Ranges are the plugin's to check (a frame with an invalid value fails and names the field);
/// these check the syntax, the keys and the names of enumerations.
bool parseEpipolarSettings(const std::string& text, EpipolarSettings& out, std::string& error);
bool parsePrefilteredSettings(const std::string& text, PrefilteredSettings& out, std::string& error);

/// "defaults" when nothing differs.
std::string describe(const EpipolarSettings& settings);
std::string describe(const PrefilteredSettings& settings);

/// The keys, for usage texts.
extern const char* const kEpipolarKeys;
extern const char* const kPrefilteredKeys;

}  // namespace tyndall::samples
