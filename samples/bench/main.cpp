// tyndall-bench: the speed–accuracy sweep behind docs/TRADEOFFS.md (scripts/measure.sh tradeoffs runs it).
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "report.h"
#include "settings_text.h"
#include "sweep.h"

namespace {

using namespace tyndall::samples;
using namespace tyndall::samples::bench;

const char* const kUsage =
    "usage: tyndall-bench [--scenes NAME|FILE.json,...] [--sizes WxH,...] [--shadow-maps N,...]\n"
    "         [--grid default|full|quick|none] [--config TECHNIQUE[:KEY=VALUE,...]]... [--frames N] [--warm-up N]\n"
    "         [--orbit-frames N] [--orbit-degrees D] [--choose-at WxH/N] [--out DIR] [--sequential] [--validation]\n"
    "         [--no-storage-back-buffer] [--measurements-link PATH]\n"
    "       tyndall-bench --from RESULTS.json [--choose-at WxH/N] [--out DIR] [--measurements-link PATH]\n"
    "  --scenes: names in samples/scenes/ or scene files (default: the directional pillars,fence,forest,\n"
    "            window-room,gltf-pergola, the spot spot-lamp,stained-glass,spot-fan,spot-fan-up,spot-fan-narrow,\n"
    "            spot-fan-close,spot-grille,spot-lattice,spot-foliage,spot-street,gltf-pergola-lamp, the point\n"
    "            point-lamp,point-fan,point-cage,point-street and street-dusk's several lights: a profile\n"
    "            row is chosen over every scene of its kind of light)\n"
    "  --sizes / --shadow-maps: output sizes and shadow-map sizes (default 640x360 / 2048)\n"
    "  --grid: the built-in configurations (default: default; full: more); --config adds one: epipolar:KEY=VALUE,...\n"
    "          or prefiltered:KEY=VALUE,... in tyndall-render's --epipolar / --prefiltered syntax\n"
    "  --frames: timed frames per configuration, median reported (default 20); --warm-up: untimed (3)\n"
    "  --sequential: each configuration's frames in a row, one context alive at a time (default: interleaved,\n"
    "                one frame of every configuration, the Reference and the floor passes per round)\n"
    "  --orbit-frames / --orbit-degrees: the orbit for temporal stability (6 frames, 0.25 degrees each)\n"
    "  --choose-at: the size and shadow map the profiles are chosen at (default: the first of each)\n"
    "  --out: the output directory (default out/bench): results.csv/.json/.md, pareto.json (the plots'\n"
    "         data: scripts/plot-pareto.py DIR/pareto.json DIR draws pareto-*.svg/.png), choice.json, tradeoffs.md\n"
    "         (the choice) and tradeoffs-measurements.md (its tables)\n"
    "  --measurements-link: the path tradeoffs.md links the tables at (default tradeoffs-measurements.md)\n"
    "  --validation: Vulkan validation on; any message fails the run\n"
    "  --no-storage-back-buffer: back buffers without STORAGE usage: Tyndall composites with a fragment pass\n"
    "         and the compute floor is not measured\n"
    "  --from: write the reports again from an earlier run's results.json, measuring nothing\n";

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> out;
  std::size_t begin = 0;
  while (begin <= text.size()) {
    const std::size_t end = std::min(text.find(',', begin), text.size());
    if (end > begin) out.push_back(text.substr(begin, end - begin));
    begin = end + 1;
  }
  return out;
}

bool parseSize(const std::string& text, std::uint32_t& w, std::uint32_t& h) {
  const std::size_t x = text.find('x');
  return x != std::string::npos && parseUint(text.substr(0, x), 1, 16384, w) &&
         parseUint(text.substr(x + 1), 1, 16384, h);
}

bool parseChooseAt(const std::string& text, ReportContext& context) {
  const std::size_t slash = text.find('/');
  return slash != std::string::npos && parseSize(text.substr(0, slash), context.chooseWidth, context.chooseHeight) &&
         parseUint(text.substr(slash + 1), 16, 16384, context.chooseShadowMap);
}

int fail(const std::string& message) {
  std::fprintf(stderr, "tyndall-bench: %s\n", message.c_str());
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  SweepOptions options;
  ReportContext context;
  std::string grid = "default";
  std::vector<Configuration> extra;
  std::string out = "out/bench";
  std::string chooseAt;
  std::string from;
  std::vector<std::string> scenes{
      "pillars", "fence", "forest", "window-room", "gltf-pergola",  // directional
      "spot-lamp", "stained-glass", "spot-fan", "spot-fan-up", "spot-fan-narrow", "spot-fan-close", "spot-grille",
      "spot-lattice", "spot-foliage", "spot-street", "gltf-pergola-lamp",  // spot
      "point-lamp", "point-fan", "point-cage", "point-street",  // point
      "street-dusk"};  // several lights: in the tables over every scene, in no kind's choice
  context.commandLine = "tyndall-bench";
  for (int i = 1; i < argc; ++i) context.commandLine += std::string(" ") + argv[i];

  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      std::fputs(kUsage, stdout);
      return 0;
    }
    if (arg == "--validation") {
      options.validation = true;
      continue;
    }
    if (arg == "--sequential") {
      options.interleaved = false;
      continue;
    }
    if (arg == "--no-storage-back-buffer") {
      options.storageBackBuffer = false;
      continue;
    }
    if (i + 1 >= argc) return fail(arg + " needs a value (--help)");
    const std::string value = argv[++i];
    std::string error;
    if (arg == "--scenes") {
      scenes = split(value);
    } else if (arg == "--sizes") {
      options.sizes.clear();
      for (const std::string& size : split(value)) {
        std::uint32_t w = 0, h = 0;
        if (!parseSize(size, w, h)) return fail("--sizes takes WxH,... (got '" + size + "')");
        options.sizes.emplace_back(w, h);
      }
    } else if (arg == "--shadow-maps") {
      options.shadowMaps.clear();
      for (const std::string& size : split(value)) {
        std::uint32_t n = 0;
        if (!parseUint(size, 16, 16384, n) || (n & (n - 1)) != 0) {
          return fail("--shadow-maps takes powers of two in [16, 16384] (got '" + size + "')");
        }
        options.shadowMaps.push_back(n);
      }
    } else if (arg == "--grid") {
      grid = value;
    } else if (arg == "--config") {
      Configuration c;
      if (!parseConfiguration(value, c, error)) return fail(error);
      extra.push_back(c);
    } else if (arg == "--frames" || arg == "--warm-up" || arg == "--orbit-frames") {
      std::uint32_t& target = arg == "--frames" ? options.frames : arg == "--warm-up" ? options.warmUpFrames : options.orbitFrames;
      if (!parseUint(value, arg == "--frames" ? 1 : 0, 100000, target)) return fail(arg + " takes a count (got '" + value + "')");
    } else if (arg == "--orbit-degrees") {
      float degrees = 0.0f;
      if (!parseFloat(value, degrees)) return fail("--orbit-degrees takes a number (got '" + value + "')");
      options.orbitDegreesPerFrame = degrees;
    } else if (arg == "--choose-at") {
      chooseAt = value;
    } else if (arg == "--out") {
      out = value;
    } else if (arg == "--from") {
      from = value;
    } else if (arg == "--measurements-link") {
      context.measurementsLink = value;
    } else {
      return fail("unknown option " + arg + " (--help)");
    }
  }
  if (options.sizes.empty() || options.shadowMaps.empty() || scenes.empty()) {
    return fail("--scenes, --sizes and --shadow-maps need at least one value each");
  }
  std::string error;
  if (!from.empty()) {
    std::vector<Row> rows;
    if (!readResults(from, rows, context, error)) return fail(error);
    if (!chooseAt.empty() && !parseChooseAt(chooseAt, context)) return fail("--choose-at takes WxH/N (got '" + chooseAt + "')");
    if (!writeReports(rows, context, out, error)) return fail(error);
    std::fprintf(stderr, "tyndall-bench: wrote the reports of %s into %s\n", from.c_str(), out.c_str());
    return 0;
  }
  if (!builtInGrid(grid, options.configurations, error)) return fail(error);
  for (const Configuration& c : extra) {
    const bool known = std::any_of(options.configurations.begin(), options.configurations.end(),
                                   [&](const Configuration& o) { return o.name() == c.name(); });
    if (!known) options.configurations.push_back(c);
  }
  for (const std::string& scene : scenes) {
    const bool isFile = scene.size() > 5 && scene.substr(scene.size() - 5) == ".json";
    options.scenes.push_back(isFile ? scene : "samples/scenes/" + scene + ".json");
    if (!std::filesystem::exists(options.scenes.back())) {
      return fail("no scene " + options.scenes.back() + " (run from the repository root, or give a file)");
    }
  }
  context.chooseWidth = options.sizes.front().first;
  context.chooseHeight = options.sizes.front().second;
  context.chooseShadowMap = options.shadowMaps.front();
  if (!chooseAt.empty() && !parseChooseAt(chooseAt, context)) return fail("--choose-at takes WxH/N (got '" + chooseAt + "')");
  context.frames = options.frames;
  context.warmUpFrames = options.warmUpFrames;
  context.schedule = options.interleaved ? "interleaved" : "sequential";
  context.orbitFrames = options.orbitFrames;
  context.orbitDegreesPerFrame = options.orbitDegreesPerFrame;
  options.progress = [](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); };
  options.groupDone = [&](const std::vector<Row>& rows) {
    std::string reportError;
    if (!writeReports(rows, context, out, reportError)) {
      std::fprintf(stderr, "tyndall-bench: (reports so far) %s\n", reportError.c_str());
    }
  };

  std::vector<Row> rows;
  const bool ok = runSweep(options, rows, context.device, error);
  if (!rows.empty()) {
    std::string reportError;
    if (!writeReports(rows, context, out, reportError)) {
      std::fprintf(stderr, "tyndall-bench: %s\n", reportError.c_str());
      return 1;
    }
    std::fprintf(stderr, "tyndall-bench: wrote %s/{results.csv,results.json,results.md,pareto.json,tradeoffs.md,tradeoffs-measurements.md,choice.json}\n",
                 out.c_str());
  }
  if (!ok) {
    std::fprintf(stderr, "tyndall-bench: %s\n", error.c_str());
    return 1;
  }
  return 0;
}
