#include "report.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include <nlohmann/json.hpp>

#include "error_metrics.h"
#include "pareto.h"
#include "profiles.h"
#include "render_job.h"
#include "tyndall_host/scene.h"

namespace tyndall::samples::bench {

namespace {

std::string format(const char* pattern, double value) {
  char text[64];
  std::snprintf(text, sizeof(text), pattern, value);
  return text;
}

std::string percent(double fraction) { return format("%.2f%%", 100.0 * fraction); }
std::string speedup(double ratio) { return ratio > 0.0 ? format("%.1f×", 1.0 / ratio) : "-"; }
std::string groupName(std::uint32_t w, std::uint32_t h, std::uint32_t map) {
  return std::to_string(w) + "x" + std::to_string(h) + "-" + std::to_string(map);
}

// CSV field: quoted when it holds a comma or a quote.
std::string csv(const std::string& text) {
  if (text.find_first_of(",\"") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string rowsCsv(const std::vector<Row>& rows) {
  std::string out =
      "scene,light,width,height,shadow_map,technique,parameters,technique_used,measured,note,total_ms,reference_ms,floor_ms,"
      "compute_floor_ms,compute_floor_note,composite,time_ratio_to_reference,time_ratio_to_floor,dispatches,barriers,"
      "device_memory_bytes,relative_rmse,relative_p99,relative_max,"
      "non_finite,temporal_change,temporal_ratio,marched_samples,fixed_up_pixel_fraction,pass_ms\n";
  for (const Row& r : rows) {
    std::string passes;
    for (const std::string& name : r.passOrder) {
      if (!r.passMilliseconds.contains(name)) continue;
      passes += (passes.empty() ? "" : ";") + name + "=" + format("%.6g", r.passMilliseconds.at(name));
    }
    out += csv(r.scene) + "," + r.light + "," + std::to_string(r.width) + "," + std::to_string(r.height) + "," +
           std::to_string(r.shadowMap) + "," + r.technique + "," + csv(r.parameters) + "," + r.techniqueUsed + "," +
           (r.measured ? "1" : "0") + "," + csv(r.note) + "," + format("%.6g", r.totalMilliseconds) + "," +
           format("%.6g", r.referenceMilliseconds) + "," + format("%.6g", r.floorMilliseconds) + "," +
           format("%.6g", r.computeFloorMilliseconds) + "," + csv(r.computeFloorNote) + "," + r.composite + "," +
           format("%.6g", r.timeRatioToReference) + "," + format("%.6g", r.timeRatioToFloor) + "," +
           std::to_string(r.dispatches) + "," + std::to_string(r.barriers) + "," + std::to_string(r.deviceMemoryBytes) + "," + format("%.6g", r.relativeRmse) + "," +
           format("%.6g", r.relativeP99) + "," + format("%.6g", r.relativeMax) + "," + std::to_string(r.nonFinite) +
           "," + format("%.6g", r.temporalChange) + "," + format("%.6g", r.temporalRatio) + "," +
           std::to_string(r.marchedSamples) + "," + format("%.6g", r.fixedUpPixelFraction) + "," + csv(passes) + "\n";
  }
  return out;
}

// The compute floor's time, or why it was not measured (rows from files written before it: a dash).
std::string computeFloorCell(const Row& r) {
  if (r.computeFloorMilliseconds > 0.0) return format("%.3f", r.computeFloorMilliseconds);
  return r.computeFloorNote.empty() ? "—" : "— (" + r.computeFloorNote + ")";
}

nlohmann::ordered_json rowJson(const Row& r) {
  nlohmann::ordered_json j;
  j["scene"] = r.scene;
  j["light"] = r.light;
  j["width"] = r.width;
  j["height"] = r.height;
  j["shadowMap"] = r.shadowMap;
  j["technique"] = r.technique;
  j["parameters"] = r.parameters;
  j["techniqueUsed"] = r.techniqueUsed;
  j["measured"] = r.measured;
  j["note"] = r.note;
  nlohmann::ordered_json passes = nlohmann::ordered_json::object();
  for (const std::string& name : r.passOrder) {
    if (r.passMilliseconds.contains(name)) passes[name] = r.passMilliseconds.at(name);
  }
  j["passMilliseconds"] = passes;
  j["totalMilliseconds"] = r.totalMilliseconds;
  j["referenceMilliseconds"] = r.referenceMilliseconds;
  j["floorMilliseconds"] = r.floorMilliseconds;
  j["computeFloorMilliseconds"] = r.computeFloorMilliseconds;
  j["computeFloorNote"] = r.computeFloorNote;
  j["composite"] = r.composite;
  j["timeRatioToReference"] = r.timeRatioToReference;
  j["timeRatioToFloor"] = r.timeRatioToFloor;
  j["dispatches"] = r.dispatches;
  j["barriers"] = r.barriers;
  j["deviceMemoryBytes"] = r.deviceMemoryBytes;
  j["relativeRmse"] = r.relativeRmse;
  j["relativeP99"] = r.relativeP99;
  j["relativeMax"] = r.relativeMax;
  j["nonFinite"] = r.nonFinite;
  j["temporalChange"] = r.temporalChange;
  j["temporalRatio"] = r.temporalRatio;
  j["marchedSamples"] = r.marchedSamples;
  j["fixedUpPixelFraction"] = r.fixedUpPixelFraction;
  return j;
}

std::string rowsMarkdown(const std::vector<Row>& rows) {
  std::string out =
      "| scene | size | map | technique | parameters | ms | speedup | composite | × floor | floor ms | compute floor ms | "
      "dispatches | barriers | relative RMSE | p99 | max | NaN/Inf | temporal | memory MiB |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const Row& r : rows) {
    out += "| " + r.scene + " | " + std::to_string(r.width) + "×" + std::to_string(r.height) + " | " +
           std::to_string(r.shadowMap) + "² | " + r.technique + " | `" + r.parameters + "`" +
           (r.measured && !r.note.empty() ? ": " + r.note : std::string()) + " | ";
    if (!r.measured) {
      out += r.note + " ||||||||||||||\n";
      continue;
    }
    out += format("%.3f", r.totalMilliseconds) + " | " + speedup(r.timeRatioToReference) + " | " + r.composite +
           " | " + format("%.2f", r.timeRatioToFloor) + " | " + format("%.3f", r.floorMilliseconds) + " | " +
           computeFloorCell(r) + " | " + std::to_string(r.dispatches) + " | " + std::to_string(r.barriers) + " | " +
           percent(r.relativeRmse) + " | " + percent(r.relativeP99) +
           " | " + percent(r.relativeMax) + " | " + std::to_string(r.nonFinite) + " | " +
           format("%.2f", r.temporalRatio) + " | " + format("%.1f", static_cast<double>(r.deviceMemoryBytes) / 1048576.0) +
           " |\n";
  }
  return out;
}

std::string summariesMarkdown(const std::vector<Summary>& summaries, const std::vector<std::size_t>& front) {
  const std::set<std::size_t> onFront(front.begin(), front.end());
  std::string out =
      "| technique | parameters | scenes | speedup | × floor | relative RMSE | worst (scene) | p99 | temporal | "
      "time spread | memory MiB | NaN/Inf | Pareto |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (std::size_t i = 0; i < summaries.size(); ++i) {
    const Summary& s = summaries[i];
    out += "| " + s.technique + " | `" + s.parameters + "` | " + std::to_string(s.scenes) + " | " +
           speedup(s.timeRatioToReference) + " | " + format("%.2f", s.timeRatioToFloor) + " | " +
           percent(s.relativeRmse) + " | " + percent(s.worstRelativeRmse) + " (" + s.worstScene + ") | " +
           percent(s.relativeP99) + " | " + format("%.2f", s.temporalRatio) + " | " + percent(s.timeSpread) + " | " +
           format("%.1f", static_cast<double>(s.deviceMemoryBytes) / 1048576.0) + " | " + std::to_string(s.nonFinite) +
           " | " + (onFront.contains(i) ? "yes" : "") + " |\n";
  }
  return out;
}

// One point per summary but the Reference's ((1, 0) by definition); `summaryOf[i]` is point i's
// summary.
std::vector<PlotPoint> plotPoints(const std::vector<Summary>& summaries, const std::vector<ProfileChoiceResult>& choice,
                                  std::vector<std::size_t>& summaryOf) {
  std::vector<PlotPoint> points;
  summaryOf.clear();
  for (std::size_t i = 0; i < summaries.size(); ++i) {
    const Summary& s = summaries[i];
    if (s.technique == to_string(Technique::Reference)) continue;
    PlotPoint p;
    p.label = s.configuration;
    p.series = s.technique;
    p.x = s.timeRatioToReference;
    p.y = s.relativeRmse;
    for (const ProfileChoiceResult& c : choice) {
      if (c.summary != i) continue;
      if (!p.marker.empty()) p.marker += '/';
      // The local lights' rows are marked as such; the directional ones (every sweep has them) plainly.
      p.marker += c.goal.name() + (c.lights == LightClass::Local ? " (local)" : "");
    }
    points.push_back(p);
    summaryOf.push_back(i);
  }
  return points;
}

// The summary indices of the points on the Pareto front (`summaryOf` as plotPoints fills it).
std::vector<std::size_t> frontSummaries(const std::vector<PlotPoint>& points, const std::vector<std::size_t>& summaryOf) {
  std::vector<std::size_t> out;
  for (std::size_t p : paretoFront(points)) out.push_back(summaryOf[p]);
  return out;
}

// Which of a profile's goals a median error, time ratio to the Reference and to the floor meet.
struct GoalsMet {
  bool error = false, speed = false, floor = true;
};
GoalsMet goalsMet(const ProfileGoal& goal, double relativeRmse, double timeRatioToReference, double timeRatioToFloor) {
  return {relativeRmse <= goal.maxRelativeRmse,
          timeRatioToReference > 0.0 && 1.0 / timeRatioToReference >= goal.minSpeedup,
          goal.maxTimeOverFloor <= 0.0 || timeRatioToFloor <= goal.maxTimeOverFloor};
}

// "≤ 2.00% met, ≥ 12× **missed**" (and Performance's floor goal), as the document's tables say it.
std::string goalsText(const ProfileGoal& goal, const GoalsMet& met) {
  const auto verdict = [](bool ok) { return ok ? "met" : "**missed**"; };
  std::string text = "≤ " + percent(goal.maxRelativeRmse) + " " + verdict(met.error) + ", ≥ " +
                     format("%.0f×", goal.minSpeedup) + " " + verdict(met.speed);
  if (goal.maxTimeOverFloor > 0.0) {
    text += ", ≤ " + format("%.0f×", goal.maxTimeOverFloor) + " floor " + verdict(met.floor);
  }
  return text;
}

// How the timed frames were scheduled, as the document's protocol sentence says it (nothing for
// files written before the bench recorded it).
std::string scheduleText(const std::string& schedule) {
  if (schedule == "interleaved") {
    return ", interleaved: every round renders one frame of the floor passes, the Reference and every "
           "configuration in turn (the first rotating), each frame alone on the device, so that the machine's "
           "other work slows them alike";
  }
  if (schedule == "sequential") return ", each configuration's frames in a row, each frame alone on the device";
  return "";
}

}  // namespace

std::string perLightMarkdown(const std::vector<Row>& rows) {
  std::size_t lights = 0;
  for (const Row& r : rows) {
    for (const auto& [pass, ms] : r.passMilliseconds) {
      if (const std::optional<std::size_t> light = passLight(pass)) lights = std::max(lights, *light + 1);
    }
  }
  if (lights == 0) return {};
  std::string out = "| scene | size | map | technique | parameters | ms |";
  std::string rule = "|---|---|---|---|---|---|";
  for (std::size_t i = 0; i < lights; ++i) {
    out += " light " + std::to_string(i) + " ms |";
    rule += "---|";
  }
  out += " shared ms |\n" + rule + "---|\n";
  for (const Row& r : rows) {
    if (!r.measured) continue;
    std::vector<double> perLight(lights, 0.0);
    double shared = 0.0;
    bool several = false;
    for (const auto& [pass, ms] : r.passMilliseconds) {
      if (const std::optional<std::size_t> light = passLight(pass)) {
        perLight[*light] += ms;
        several = true;
      } else {
        shared += ms;
      }
    }
    if (!several) continue;
    out += "| " + r.scene + " | " + std::to_string(r.width) + "×" + std::to_string(r.height) + " | " +
           std::to_string(r.shadowMap) + "² | " + r.technique + " | `" + r.parameters + "` | " +
           format("%.3f", r.totalMilliseconds) + " |";
    for (double ms : perLight) out += " " + format("%.3f", ms) + " |";
    out += " " + format("%.3f", shared) + " |\n";
  }
  return out;
}

std::optional<LightClass> lightClassOf(const Row& row) {
  if (row.light == "several") return std::nullopt;
  return row.light == "directional" ? LightClass::Directional : LightClass::Local;
}

std::vector<Summary> summarize(const std::vector<Row>& rows, std::uint32_t width, std::uint32_t height,
                               std::uint32_t shadowMap, std::optional<LightClass> lights) {
  std::vector<std::string> order;
  std::map<std::string, std::vector<const Row*>> byConfiguration;
  for (const Row& r : rows) {
    if (r.width != width || r.height != height || r.shadowMap != shadowMap || !r.measured) continue;
    if (lights && lightClassOf(r) != *lights) continue;
    if (!byConfiguration.contains(r.configuration)) order.push_back(r.configuration);
    byConfiguration[r.configuration].push_back(&r);
  }
  std::vector<Summary> out;
  for (const std::string& name : order) {
    const std::vector<const Row*>& group = byConfiguration[name];
    Summary s;
    s.configuration = name;
    s.technique = group.front()->technique;
    s.parameters = group.front()->parameters;
    s.scenes = group.size();
    std::vector<double> ratio, floorRatio, rmse, p99, temporal, ms;
    for (const Row* r : group) {
      ratio.push_back(r->timeRatioToReference);
      floorRatio.push_back(r->timeRatioToFloor);
      rmse.push_back(r->relativeRmse);
      p99.push_back(r->relativeP99);
      temporal.push_back(r->temporalRatio);
      ms.push_back(r->totalMilliseconds);
      if (r->relativeRmse >= s.worstRelativeRmse) {
        s.worstRelativeRmse = r->relativeRmse;
        s.worstScene = r->scene;
      }
      s.sceneRelativeRmse[r->scene] = r->relativeRmse;
      s.deviceMemoryBytes = std::max(s.deviceMemoryBytes, r->deviceMemoryBytes);
      s.nonFinite += r->nonFinite;
    }
    s.timeRatioToReference = median(ratio);
    s.timeRatioToFloor = median(floorRatio);
    s.relativeRmse = median(rmse);
    s.relativeP99 = median(p99);
    s.temporalRatio = median(temporal);
    s.milliseconds = median(ms);
    const auto [lo, hi] = std::minmax_element(ms.begin(), ms.end());
    s.timeSpread = s.milliseconds > 0.0 ? (*hi - *lo) / s.milliseconds : 0.0;
    out.push_back(s);
  }
  return out;
}

const std::vector<ProfileGoal>& profileGoals() {
  // The goals ("Goals the benchmark must show"): error bars and speedups over the Reference.
  static const std::vector<ProfileGoal> goals{
      {Profile::High, 0.02, 12.0, 0.0, 0.03},
      {Profile::Balanced, 0.04, 25.0, 0.0, 0.06},
      {Profile::Performance, 0.08, 50.0, 4.0, 0.16},
  };
  return goals;
}

std::string ProfileGoal::name() const {
  std::string n = to_string(profile);
  n[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(n[0])));
  return n;
}

const ProfileGoal* profileGoal(Profile profile) {
  const std::vector<ProfileGoal>& goals = profileGoals();
  auto it = std::find_if(goals.begin(), goals.end(), [&](const ProfileGoal& g) { return g.profile == profile; });
  return it != goals.end() ? &*it : nullptr;
}

std::map<Profile, std::string> profileTableConfigurations(LightClass lights, std::uint32_t outputHeight) {
  std::map<Profile, std::string> out;
  for (const ProfileGoal& goal : profileGoals()) {
    const ProfileChoice& row = profileChoice(goal.profile, lights);
    Configuration c;
    c.technique = row.technique;
    if (row.technique == Technique::Epipolar) c.epipolar = settingsAsRunAt(row.epipolar, outputHeight);
    if (row.technique == Technique::Prefiltered) c.prefiltered = settingsAsRunAt(row.prefiltered, outputHeight);
    out[goal.profile] = c.name();
  }
  return out;
}

Incumbents profileTableConfigurations(std::uint32_t outputHeight) {
  return {{LightClass::Directional, profileTableConfigurations(LightClass::Directional, outputHeight)},
          {LightClass::Local, profileTableConfigurations(LightClass::Local, outputHeight)}};
}

std::vector<ProfileChoiceResult> chooseProfiles(const std::vector<Summary>& summaries,
                                                const std::map<Profile, std::string>& incumbents) {
  std::vector<ProfileChoiceResult> out;
  for (const ProfileGoal& goal : profileGoals()) {
    ProfileChoiceResult c{goal, std::nullopt};
    const auto candidate = [](const Summary& s) {
      return s.technique != to_string(Technique::Reference) && s.nonFinite == 0 && s.timeRatioToReference > 0.0;
    };
    // The scenes on which some configuration meets the per-scene bar: there, each must.
    std::set<std::string> barScenes;
    for (const Summary& s : summaries) {
      if (!candidate(s)) continue;
      for (const auto& [scene, rmse] : s.sceneRelativeRmse) {
        if (goal.maxSceneRelativeRmse > 0.0 && rmse <= goal.maxSceneRelativeRmse) barScenes.insert(scene);
      }
    }
    // A configuration that did not run on such a scene (the prefiltered technique on a spot
    // light's) does not meet the bar there: a profile runs on every scene, and what would run in
    // its place was not measured as this profile.
    const auto meetsSceneBar = [&](const Summary& s) {
      for (const std::string& scene : barScenes) {
        auto it = s.sceneRelativeRmse.find(scene);
        if (it == s.sceneRelativeRmse.end() || it->second > goal.maxSceneRelativeRmse) return false;
      }
      return true;
    };
    // The most accurate; of equally accurate ones the faster.
    const auto moreAccurate = [&](std::size_t i, const std::optional<std::size_t>& than) {
      const Summary& s = summaries[i];
      return !than || s.relativeRmse < summaries[*than].relativeRmse ||
             (s.relativeRmse == summaries[*than].relativeRmse &&
              s.timeRatioToReference < summaries[*than].timeRatioToReference);
    };
    // The incumbent, if this run measured it as a candidate.
    std::optional<std::size_t> incumbent;
    if (auto it = incumbents.find(goal.profile); it != incumbents.end()) {
      for (std::size_t i = 0; i < summaries.size(); ++i) {
        if (summaries[i].configuration == it->second && candidate(summaries[i])) incumbent = i;
      }
    }
    if (incumbent) c.incumbent = summaries[*incumbent].configuration;
    // best: meets the speedup and the floor goal; speedOnly: the speedup goal, not the floor's;
    // each with the goals scaled by `margin` for every configuration but the incumbent.
    const auto pick = [&](double margin) {
      std::optional<std::size_t> best, speedOnly;
      bool incumbentBest = false, incumbentSpeedOnly = false;
      for (std::size_t i = 0; i < summaries.size(); ++i) {
        const Summary& s = summaries[i];
        if (!candidate(s) || !meetsSceneBar(s)) continue;
        const double scale = incumbent == i ? 1.0 : 1.0 + margin;
        if (1.0 / s.timeRatioToReference < goal.minSpeedup * scale) continue;
        if (moreAccurate(i, speedOnly)) speedOnly = i;
        incumbentSpeedOnly = incumbentSpeedOnly || incumbent == i;
        if (goal.maxTimeOverFloor > 0.0 && s.timeRatioToFloor * scale > goal.maxTimeOverFloor) continue;
        if (moreAccurate(i, best)) best = i;
        incumbentBest = incumbentBest || incumbent == i;
      }
      // The incumbent stays against a challenger that meets no more goals than it does unless the
      // challenger is clearly more accurate (kChallengerErrorMargin).
      const auto keepIncumbent = [&](std::optional<std::size_t> chosen, bool incumbentMeetsTheSame) {
        if (chosen && incumbentMeetsTheSame && *chosen != *incumbent &&
            summaries[*chosen].relativeRmse > (1.0 - kChallengerErrorMargin) * summaries[*incumbent].relativeRmse) {
          return incumbent;
        }
        return chosen;
      };
      // A floor goal no configuration meets does not trade the speedup goal's accuracy for speed
      // (on a CPU driver the floor pass is several times cheaper than any technique's per-pixel pass).
      return best ? keepIncumbent(best, incumbentBest) : keepIncumbent(speedOnly, incumbentSpeedOnly);
    };
    std::optional<std::size_t> fastest, fastestOfAll;
    for (std::size_t i = 0; i < summaries.size(); ++i) {
      const Summary& s = summaries[i];
      if (!candidate(s)) continue;
      if (!fastestOfAll || s.timeRatioToReference < summaries[*fastestOfAll].timeRatioToReference) fastestOfAll = i;
      if (meetsSceneBar(s) && (!fastest || s.timeRatioToReference < summaries[*fastest].timeRatioToReference)) {
        fastest = i;
      }
    }
    std::optional<std::size_t> chosen = incumbent ? pick(kChallengerSpeedMargin) : std::nullopt;
    if (!chosen) chosen = pick(0.0);
    c.summary = chosen ? chosen : fastest ? fastest : fastestOfAll;
    if (c.summary) {
      const Summary& s = summaries[*c.summary];
      const GoalsMet met = goalsMet(goal, s.relativeRmse, s.timeRatioToReference, s.timeRatioToFloor);
      c.errorMet = met.error;
      c.speedMet = met.speed;
      c.floorMet = met.floor;
    }
    out.push_back(c);
  }
  return out;
}

bool readResults(const std::string& path, std::vector<Row>& rows, ReportContext& context, std::string& error) {
  std::ifstream file(path);
  if (!file) {
    error = "cannot read " + path;
    return false;
  }
  try {
    const nlohmann::json all = nlohmann::json::parse(file);
    context.device = all.at("device").get<std::string>();
    context.commandLine = all.at("command").get<std::string>();
    // Older files lack these: the values they were measured with were tyndall-bench's defaults.
    const SweepOptions defaults;
    context.frames = all.value("frames", defaults.frames);
    context.warmUpFrames = all.value("warmUpFrames", defaults.warmUpFrames);
    context.orbitFrames = all.value("orbitFrames", defaults.orbitFrames);
    context.orbitDegreesPerFrame = all.value("orbitDegreesPerFrame", defaults.orbitDegreesPerFrame);
    context.schedule = all.value("schedule", std::string());
    rows.clear();
    for (const nlohmann::json& j : all.at("rows")) {
      Row r;
      r.scene = j.at("scene").get<std::string>();
      r.light = j.value("light", std::string());
      r.width = j.at("width").get<std::uint32_t>();
      r.height = j.at("height").get<std::uint32_t>();
      r.shadowMap = j.at("shadowMap").get<std::uint32_t>();
      r.technique = j.at("technique").get<std::string>();
      r.parameters = j.at("parameters").get<std::string>();
      r.configuration = configurationName(r.technique, r.parameters);
      r.techniqueUsed = j.at("techniqueUsed").get<std::string>();
      r.measured = j.at("measured").get<bool>();
      r.note = j.at("note").get<std::string>();
      for (const auto& [name, ms] : j.at("passMilliseconds").items()) {
        r.passOrder.push_back(name);
        r.passMilliseconds[name] = ms.get<double>();
      }
      r.totalMilliseconds = j.at("totalMilliseconds").get<double>();
      r.referenceMilliseconds = j.at("referenceMilliseconds").get<double>();
      r.floorMilliseconds = j.at("floorMilliseconds").get<double>();
      // Files written before the compute floor and the command counts have none: the defaults.
      const Row unset;
      r.computeFloorMilliseconds = j.value("computeFloorMilliseconds", unset.computeFloorMilliseconds);
      r.computeFloorNote = j.value("computeFloorNote", unset.computeFloorNote);
      r.composite = j.value("composite", unset.composite);
      r.dispatches = j.value("dispatches", unset.dispatches);
      r.barriers = j.value("barriers", unset.barriers);
      r.timeRatioToReference = j.at("timeRatioToReference").get<double>();
      r.timeRatioToFloor = j.at("timeRatioToFloor").get<double>();
      r.deviceMemoryBytes = j.at("deviceMemoryBytes").get<std::uint64_t>();
      r.relativeRmse = j.at("relativeRmse").get<double>();
      r.relativeP99 = j.at("relativeP99").get<double>();
      r.relativeMax = j.at("relativeMax").get<double>();
      r.nonFinite = j.at("nonFinite").get<std::size_t>();
      r.temporalChange = j.at("temporalChange").get<double>();
      r.temporalRatio = j.at("temporalRatio").get<double>();
      r.marchedSamples = j.at("marchedSamples").get<std::uint64_t>();
      r.fixedUpPixelFraction = j.at("fixedUpPixelFraction").get<double>();
      rows.push_back(r);
    }
    if (rows.empty()) {
      error = path + " has no rows";
      return false;
    }
    // Written before the rows recorded their light: the scene file's.
    std::map<std::string, std::string> sceneLights;
    for (Row& r : rows) {
      if (!r.light.empty()) continue;
      if (!sceneLights.contains(r.scene)) {
        const std::string scenePath = "samples/scenes/" + r.scene + ".json";
        host::SceneLoadResult loaded = host::loadScene(scenePath);
        if (!loaded.scene) {
          error = path + " does not say which light " + r.scene + " has, and " + scenePath + " does not load (" +
                  loaded.error + "; run from the repository root)";
          return false;
        }
        sceneLights[r.scene] = lightName(loaded.scene->light.type);
      }
      r.light = sceneLights.at(r.scene);
    }
    if (all.contains("chooseAt")) {
      context.chooseWidth = all["chooseAt"].at(0).get<std::uint32_t>();
      context.chooseHeight = all["chooseAt"].at(1).get<std::uint32_t>();
      context.chooseShadowMap = all["chooseAt"].at(2).get<std::uint32_t>();
    } else {
      context.chooseWidth = rows.front().width;  // the default: the first size and map swept
      context.chooseHeight = rows.front().height;
      context.chooseShadowMap = rows.front().shadowMap;
    }
  } catch (const nlohmann::json::exception& e) {
    error = path + ": " + e.what();
    return false;
  }
  return true;
}

bool writeReports(const std::vector<Row>& rows, const ReportContext& context, const std::string& directory,
                  std::string& error) {
  const std::filesystem::path dir(directory);
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (!writeFileWhole((dir / "results.csv").string(), rowsCsv(rows), error)) return false;
  nlohmann::ordered_json all;
  all["device"] = context.device;
  all["command"] = context.commandLine;
  all["frames"] = context.frames;
  all["warmUpFrames"] = context.warmUpFrames;
  if (!context.schedule.empty()) all["schedule"] = context.schedule;
  all["orbitFrames"] = context.orbitFrames;
  all["orbitDegreesPerFrame"] = context.orbitDegreesPerFrame;
  all["chooseAt"] = {context.chooseWidth, context.chooseHeight, context.chooseShadowMap};
  all["rows"] = nlohmann::ordered_json::array();
  for (const Row& r : rows) all["rows"].push_back(rowJson(r));
  if (!writeFileWhole((dir / "results.json").string(), all.dump(2) + "\n", error)) return false;
  if (!writeFileWhole((dir / "results.md").string(), rowsMarkdown(rows), error)) return false;

  // The kinds of light the rows have, in the table's order: a choice is made for each.
  std::vector<LightClass> classes;
  for (LightClass lights : {LightClass::Directional, LightClass::Local}) {
    if (std::any_of(rows.begin(), rows.end(), [&](const Row& r) { return r.measured && lightClassOf(r) == lights; })) {
      classes.push_back(lights);
    }
  }
  const Incumbents table = context.incumbents ? *context.incumbents : profileTableConfigurations(context.chooseHeight);
  // The choice per kind of light among that kind's summaries.
  struct ClassChoice {
    LightClass lights;
    std::vector<Summary> summaries;
    std::vector<ProfileChoiceResult> choice;
  };
  const auto chooseByClass = [&](std::uint32_t w, std::uint32_t h, std::uint32_t map) {
    std::vector<ClassChoice> out;
    for (LightClass lights : classes) {
      ClassChoice c{lights, summarize(rows, w, h, map, lights), {}};
      const auto incumbents = table.find(lights);
      c.choice = chooseProfiles(c.summaries, incumbents != table.end() ? incumbents->second
                                                                        : std::map<Profile, std::string>{});
      for (ProfileChoiceResult& r : c.choice) r.lights = lights;
      out.push_back(std::move(c));
    }
    return out;
  };
  // Markers on the plot of every scene: the profiles (and kinds of light) each point was chosen for.
  const auto markerChoice = [&](const std::vector<Summary>& summaries, const std::vector<ClassChoice>& byClass) {
    std::vector<ProfileChoiceResult> out;
    for (const ClassChoice& c : byClass) {
      for (ProfileChoiceResult r : c.choice) {
        if (!r.summary) continue;
        const std::string& name = c.summaries[*r.summary].configuration;
        r.summary.reset();
        for (std::size_t i = 0; i < summaries.size(); ++i) {
          if (summaries[i].configuration == name) r.summary = i;
        }
        if (r.summary) out.push_back(r);
      }
    }
    return out;
  };

  // Per group: the summaries and their plot.
  std::vector<std::tuple<std::uint32_t, std::uint32_t, std::uint32_t>> groups;
  for (const Row& r : rows) {
    const auto g = std::make_tuple(r.width, r.height, r.shadowMap);
    if (std::find(groups.begin(), groups.end(), g) == groups.end()) groups.push_back(g);
  }
  std::vector<ClassChoice> choice;
  std::string plotsText, summariesText;  // the plots go into tradeoffs.md, the tables into the measurements
  nlohmann::ordered_json plots = nlohmann::ordered_json::array();
  for (const auto& [w, h, map] : groups) {
    const std::vector<Summary> summaries = summarize(rows, w, h, map);
    const bool chooseHere = w == context.chooseWidth && h == context.chooseHeight && map == context.chooseShadowMap;
    std::vector<ClassChoice> groupChoice = chooseByClass(w, h, map);
    std::vector<std::size_t> summaryOf;
    const std::vector<PlotPoint> points = plotPoints(summaries, markerChoice(summaries, groupChoice), summaryOf);
    const std::string stem = "pareto-" + groupName(w, h, map);
    plots.push_back(plotJson(stem,
                             std::to_string(w) + "×" + std::to_string(h) + ", " + std::to_string(map) +
                                 "² shadow map: median over the scenes (" + context.device + ")",
                             points));
    const std::string groupTitle =
        "\n### " + std::to_string(w) + "×" + std::to_string(h) + ", " + std::to_string(map) + "² shadow map\n\n";
    plotsText += groupTitle + "![time against error](" + stem + ".svg)\n";
    summariesText += groupTitle + summariesMarkdown(summaries, frontSummaries(points, summaryOf));
    // Per kind of light too, when the sweep has both: the summaries each kind's rows are chosen
    // from, with that kind's Pareto front and plot (pareto-WxH-N-directional, -local).
    if (groupChoice.size() > 1) {
      for (const ClassChoice& c : groupChoice) {
        std::vector<std::size_t> classSummaryOf;
        const std::vector<PlotPoint> classPoints = plotPoints(c.summaries, c.choice, classSummaryOf);
        const std::string kind = c.lights == LightClass::Directional ? "Directional-light scenes" : "Spot- and point-light scenes";
        const std::string classStem = stem + "-" + to_string(c.lights);
        plots.push_back(plotJson(classStem,
                                 std::to_string(w) + "×" + std::to_string(h) + ", " + std::to_string(map) + "²: " +
                                     (c.lights == LightClass::Directional ? "directional lights" : "spot and point lights") +
                                     " (" + context.device + ")",
                                 classPoints));
        const std::string kindTitle =
            "\n#### " + kind + " (the `" + to_string(c.lights) + "` rows are chosen from these)\n\n";
        plotsText += kindTitle + "![time against error, " + to_string(c.lights) + "](" + classStem + ".svg)\n";
        summariesText += kindTitle + summariesMarkdown(c.summaries, frontSummaries(classPoints, classSummaryOf));
      }
    }
    if (chooseHere && !summaries.empty()) choice = std::move(groupChoice);
  }
  // The plots' data, drawn by scripts/plot-pareto.py (scripts/measure.sh tradeoffs runs it).
  if (!writeFileWhole((dir / "pareto.json").string(), nlohmann::ordered_json{{"plots", plots}}.dump(2) + "\n", error)) {
    return false;
  }
  if (choice.empty()) {
    error = "the sweep has no measured row at the size the profiles are chosen at (" +
            groupName(context.chooseWidth, context.chooseHeight, context.chooseShadowMap) + ")";
    return false;
  }

  // The configuration a profile runs as on its kind of light's scenes: the profile table's row
  // (plugin/src/profiles.cpp, the incumbent) where this run measured it, else this run's choice (a
  // sweep without the table's row); choice.json's asItRuns and the per-scene table below. On the run
  // docs/TRADEOFFS-H200.md shows the two are the same; on another device's or size's run the choice
  // may differ, and the profiles run the table.
  // Its medians over every scene are what the goals are stated for.
  // The kind's summaries are its configurations measured at the choice's size.
  const auto asItRuns = [&](const ClassChoice& byClass, Profile profile, const Summary& chosen) {
    const auto tableRows = table.find(byClass.lights);
    if (tableRows == table.end()) return chosen.configuration;
    const auto row = tableRows->second.find(profile);
    const bool measured = row != tableRows->second.end() &&
                          std::any_of(byClass.summaries.begin(), byClass.summaries.end(),
                                      [&](const Summary& s) { return s.configuration == row->second; });
    return measured ? row->second : chosen.configuration;
  };
  // The choice, machine-readable: tests compare it with the plugin's profile table, and with the
  // configuration each profile runs as (asItRuns).
  nlohmann::ordered_json choiceJson = nlohmann::ordered_json::array();
  std::string choiceTable =
      "| profile | lights | technique | parameters | scenes | speedup over the Reference | time / floor | relative RMSE | "
      "worst scene | goal |\n|---|---|---|---|---|---|---|---|---|---|\n";
  for (const ClassChoice& byClass : choice) {
    for (const ProfileChoiceResult& c : byClass.choice) {
      if (!c.summary) continue;
      const Summary& s = byClass.summaries[*c.summary];
      nlohmann::ordered_json j;
      j["profile"] = c.goal.name();
      j["lights"] = to_string(c.lights);
      j["technique"] = s.technique;
      j["parameters"] = s.parameters;
      j["scenes"] = s.scenes;
      j["speedup"] = s.timeRatioToReference > 0.0 ? 1.0 / s.timeRatioToReference : 0.0;
      j["timeRatioToFloor"] = s.timeRatioToFloor;
      j["relativeRmse"] = s.relativeRmse;
      j["errorGoalMet"] = c.errorMet;
      j["speedGoalMet"] = c.speedMet;
      j["floorGoalMet"] = c.floorMet;
      j["replaces"] = !c.incumbent.empty() && c.incumbent != s.configuration ? c.incumbent : std::string();
      j["asItRuns"] = asItRuns(byClass, c.goal.profile, s);
      choiceJson.push_back(j);
      const std::string goal =
          goalsText(c.goal, {c.errorMet, c.speedMet, c.floorMet}) +
          (c.incumbent.empty()                ? ""
           : c.incumbent == s.configuration ? "; the table's, kept"
                                            : "; replaces the table's `" + c.incumbent + "`");
      choiceTable += "| " + c.goal.name() + " | " + to_string(c.lights) + " | " + s.technique + " | `" + s.parameters +
                     "` | " + std::to_string(s.scenes) + " | " + speedup(s.timeRatioToReference) + " | " +
                     format("%.2f", s.timeRatioToFloor) + " | " + percent(s.relativeRmse) + " | " +
                     percent(s.worstRelativeRmse) + " (" + s.worstScene + ") | " + goal + " |\n";
    }
  }
  if (!writeFileWhole((dir / "choice.json").string(), choiceJson.dump(2) + "\n", error)) return false;

  std::string perScene =
      "| profile | scene | lights | parameters | ms | speedup | composite | × floor | dispatches | barriers | "
      "relative RMSE | p99 | temporal |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  std::string profileText =
      "| profile | scenes | speedup over the Reference | time / floor | relative RMSE | worst scene | time spread | goal |\n"
      "|---|---|---|---|---|---|---|---|\n";
  for (const ProfileGoal& goal : profileGoals()) {
    std::vector<double> ratio, floorRatio, rmse, ms;
    double worst = -1.0;
    std::string worstScene;
    for (const ClassChoice& byClass : choice) {
      for (const ProfileChoiceResult& c : byClass.choice) {
        if (c.goal.profile != goal.profile || !c.summary) continue;
        const std::string configuration = asItRuns(byClass, goal.profile, byClass.summaries[*c.summary]);
        for (const Row& r : rows) {
          if (r.configuration != configuration || !r.measured || lightClassOf(r) != byClass.lights ||
              r.width != context.chooseWidth || r.height != context.chooseHeight ||
              r.shadowMap != context.chooseShadowMap) {
            continue;
          }
          perScene += "| " + goal.name() + " | " + r.scene + " | " + to_string(byClass.lights) + " | `" + r.parameters +
                      "` | " + format("%.3f", r.totalMilliseconds) + " | " + speedup(r.timeRatioToReference) + " | " +
                      r.composite + " | " + format("%.2f", r.timeRatioToFloor) + " | " + std::to_string(r.dispatches) +
                      " | " + std::to_string(r.barriers) + " | " + percent(r.relativeRmse) + " | " +
                      percent(r.relativeP99) + " | " + format("%.2f", r.temporalRatio) + " |\n";
          ratio.push_back(r.timeRatioToReference);
          floorRatio.push_back(r.timeRatioToFloor);
          rmse.push_back(r.relativeRmse);
          ms.push_back(r.totalMilliseconds);
          if (r.relativeRmse > worst) {
            worst = r.relativeRmse;
            worstScene = r.scene;
          }
        }
      }
    }
    if (ms.empty()) continue;
    const double medianRatio = median(ratio), medianFloor = median(floorRatio), medianRmse = median(rmse);
    const double medianMs = median(ms);
    const auto [lo, hi] = std::minmax_element(ms.begin(), ms.end());
    const double spread = medianMs > 0.0 ? (*hi - *lo) / medianMs : 0.0;
    std::string goals = goalsText(goal, goalsMet(goal, medianRmse, medianRatio, medianFloor));
    // Performance's scene-independent cost (the issue's < 15%).
    if (goal.maxTimeOverFloor > 0.0) goals += std::string(", spread < 15% ") + (spread < 0.15 ? "met" : "**missed**");
    profileText += "| " + goal.name() + " | " + std::to_string(ms.size()) + " | " + speedup(medianRatio) + " | " +
                   format("%.2f", medianFloor) + " | " + percent(medianRmse) + " | " + percent(worst) + " (" +
                   worstScene + ") | " + percent(spread) + " | " + goals + " |\n";
  }

  const std::string chosenAt = std::to_string(context.chooseWidth) + "×" + std::to_string(context.chooseHeight) +
                               " with a " + std::to_string(context.chooseShadowMap) + "² shadow map";
  std::string doc;
  doc += "# Trade-offs\n\n";
  doc += "Generated by `scripts/measure.sh tradeoffs`, which ran\n\n```\n" + context.commandLine + "\n```\n\n";
  doc += "on **" + context.device + "**. Every configuration (a technique and its parameters) ran on every scene at "
         "every size after the Reference and the full-screen floor passes (one pass that reads depth and colour and "
         "writes colour: a fragment pass blending into the back buffer, `samples/bench/shaders/floor.frag`, and, where "
         "the back buffer has STORAGE usage, a compute pass writing it in place, `floor.comp`), in the same run. Times are the median GPU time "
         "(Tyndall's timestamps, first pass start to last pass end; frames timed without copying L_in to the AOV, which one more frame does for the errors) of " + std::to_string(context.frames) +
         " frames after " + std::to_string(context.warmUpFrames) + " warm-up frames" + scheduleText(context.schedule) +
         "; speedup is the Reference's "
         "time over the configuration's, `× floor` its time over the floor of the kind its composite ran (`composite`: "
         "`compute` or `fragment`, `Stats::composite`); `dispatches` and `barriers` are the compute dispatches and "
         "pipeline barriers Tyndall recorded in a frame (`Stats`). Errors are L_in against the "
         "Reference's (relative RMSE = RMSE / mean |reference|; p99 and max of |error| / mean |reference|). "
         "`temporal` is the mean frame-to-frame change of L_in over " + std::to_string(context.orbitFrames) +
         " frames of a camera orbit (" + format("%g", context.orbitDegreesPerFrame) +
         "° per frame about the target) over the Reference's own (1: as steady as the Reference). Memory is the "
         "context's device memory (`Stats::deviceMemoryBytes`) with only that configuration run. The prefiltered "
         "technique runs for directional lights only; its medians are over the directional-light scenes. On a CPU "
         "driver such as lavapipe the GPU time is CPU time: other work on the machine inflates it, unevenly " +
         std::string(context.schedule == "interleaved"
                         ? "over a long run; the interleaving spreads that over one scene's configurations alike, not "
                           "over scenes or runs, so compare times only within one quiet run"
                         : "over a long run, so compare only figures from one quiet run") +
         ", and a GPU's figures only with a GPU's.\n\n";
  // The per-scene bars as profileGoals() holds them, so that the text cannot drift from the choice.
  std::string bars;
  for (const ProfileGoal& goal : profileGoals()) {
    if (goal.maxSceneRelativeRmse <= 0.0) continue;
    bars += std::string(bars.empty() ? "" : ", ") + goal.name() + " " + format("%g%%", 100.0 * goal.maxSceneRelativeRmse);
  }
  doc += "## The choice\n\n";
  doc += "At " + chosenAt + ", per profile and per kind of light (`directional`: the directional-light scenes; "
         "`local`: the spot-light scenes, whose row point lights take too), over that kind's scenes: of the "
         "configurations that meet the bar the profile's tests hold it to on every scene (" + bars +
         " relative RMSE; a scene on which no configuration meets it does not count) and the profile's speed "
         "goal (median speedup over the Reference; Performance also its time over the floor), the one with the "
         "lowest median relative RMSE over the scenes — of those that meet the speedup goal if none meets the "
         "floor goal too, or the fastest if none is fast enough; then whether it meets the error goal. The "
         "configuration the profile table already holds (the incumbent) is held to the speed goals as they are; "
         "every other one must clear them by " + format("%.0f%%", 100.0 * kChallengerSpeedMargin) +
         " (speedup at least that much above the goal, time over the floor that much below), so that a "
         "configuration within a run's noise of a goal does not move the table (if neither the incumbent nor "
         "any other clears its goals so, the plain goals decide); and against an incumbent that meets the same "
         "goals, a challenger must be " + format("%.0f%%", 100.0 * kChallengerErrorMargin) +
         " more accurate (median relative RMSE), so that the table does not trade speed for a negligible gain. "
         "`plugin/src/profiles.cpp` holds this table; "
         "`TradeoffsDocument.AgreesWithTheProfileTable` checks that they agree. A row at reduced resolution "
         "keeps the L_in rows it has at the size it was chosen at (`EpipolarSettings::minimumRows`): a smaller "
         "output runs it at a finer resolution, whose error this size does not measure; the incumbents are "
         "the rows as they run at this size.\n\n";
  doc += choiceTable + "\n";
  doc += "Each profile as it runs (every scene with its kind of light's row of the profile table, "
         "`plugin/src/profiles.cpp`, or this run's choice where the run did not measure that row), against the "
         "issue's goals (stated at "
         "1920×1080 with a 2048² map, medians over the scenes; these figures are at " + chosenAt +
         " on the device above; time spread: (max − min) / median of the time over the scenes, Performance's "
         "goal < 15%):\n\n";
  doc += profileText + "\n";
  doc += "Each profile per scene, every configuration's medians and every measurement: [" + context.measurementsLink +
         "](" + context.measurementsLink + ").\n\n";
  doc += "## Time against error (median over the scenes)\n\nEach point a configuration (its time over the "
         "Reference's, its relative RMSE); the Pareto front a staircase, the profiles' picks circled.\n" + plotsText;
  if (!writeFileWhole((dir / "tradeoffs.md").string(), doc, error)) return false;

  std::string measurements;
  measurements += "# Trade-offs: the measurements\n\n";
  measurements += "Generated by `scripts/measure.sh tradeoffs` with the trade-off document that makes the choice "
                  "from them and describes the method; it ran\n\n```\n" + context.commandLine + "\n```\n\non **" +
                  context.device + "**.\n\n";
  measurements += "## Each profile per scene\n\nAt " + chosenAt + ", each scene with its kind of light's row as the "
                  "profile runs:\n\n" + perScene + "\n";
  measurements += "## Every configuration (median over the scenes)\n" + summariesText + "\n";
  if (const std::string perLight = perLightMarkdown(rows); !perLight.empty()) {
    measurements += "## Per light (scenes of several lights)\n\nEach light's passes (`lightI/…`, the light "
                    "sum of its L_in included), their medians summed, and the passes the lights share (the "
                    "composite); `ms` is the frame's median.\n\n" + perLight + "\n";
  }
  measurements += "## Every measurement\n\n" + rowsMarkdown(rows);
  return writeFileWhole((dir / "tradeoffs-measurements.md").string(), measurements, error);
}

}  // namespace tyndall::samples::bench
