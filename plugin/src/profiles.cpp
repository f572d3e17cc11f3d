#include "profiles.h"

#include <array>

namespace tyndall {

namespace {

// Only the brute-force reference exists so far: every profile maps to it, and says so.
constexpr std::array<ProfileChoice, 5> kProfileTable{{
    {Profile::Reference, Technique::Reference, "profile table: Reference -> brute force"},
    {Profile::High, Technique::Reference,
     "profile table: High -> Reference (epipolar technique not implemented yet)"},
    {Profile::Balanced, Technique::Reference,
     "profile table: Balanced -> Reference (epipolar technique not implemented yet)"},
    {Profile::Performance, Technique::Reference,
     "profile table: Performance -> Reference (prefiltered technique not implemented yet)"},
    {Profile::Auto, Technique::Reference,
     "profile table: Auto -> Reference (the only technique; no budget choice to make)"},
}};

}  // namespace

const ProfileChoice& profileChoice(Profile profile) {
  for (const ProfileChoice& choice : kProfileTable) {
    if (choice.profile == profile) return choice;
  }
  return kProfileTable[0];
}

}  // namespace tyndall
