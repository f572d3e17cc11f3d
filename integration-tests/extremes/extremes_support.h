// The extremes suite's check, shared by its cases: every profile against the Reference.
#pragma once

#include <string>

#include "test_support.h"

namespace tyndall::test {

/// Renders `scene` with the Reference and then with High, Balanced, Performance and Auto (all
/// through one shared context per output size), and asserts for each: no NaN/Inf in L_in and T,
/// T within 10⁻⁵ relative RMSE of the Reference's, and L_in within twice the profile's budget (High
/// 2%, Balanced 4%, Performance 8% relative RMSE; Auto: the profile it ran) — or exactly zero
/// where the Reference's is. Prints one "[ extremes ]" line per profile (scripts/extremes-report.sh
/// reads them), then checks that validation saw nothing.
void expectEveryProfileWithinTwiceItsBudget(const host::Scene& scene, samples::RenderOptions options,
                                            const std::string& caseName);

}  // namespace tyndall::test
