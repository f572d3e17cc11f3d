// tyndall-compare MEASURED.exr REFERENCE.exr [--error-png FILE.png]: the project's error metrics of
// one L_in image against another (e.g. `tyndall-render --aov-scattering` of a profile against the
// Reference's), printed as one JSON object; optionally a picture of where the error is (grey level
// = |error| / mean |reference| of the pixel's largest channel, white at 50% and above; NaN/Inf red).
// Exit status 1 with a one-line reason when a file cannot be read or the sizes differ.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "error_metrics.h"

int main(int argc, char** argv) {
  using namespace tyndall;
  const bool errorPng = argc == 5 && std::string(argv[3]) == "--error-png";
  if (argc != 3 && !errorPng) {
    std::fputs("usage: tyndall-compare MEASURED.exr REFERENCE.exr [--error-png FILE.png]\n", stderr);
    return 2;
  }
  host::ImageRgba32f measured;
  host::ImageRgba32f reference;
  std::string error;
  if (!host::readExr(argv[1], measured, error) || !host::readExr(argv[2], reference, error)) {
    std::fprintf(stderr, "tyndall-compare: %s\n", error.c_str());
    return 1;
  }
  if (measured.width != reference.width || measured.height != reference.height) {
    std::fprintf(stderr, "tyndall-compare: sizes differ (%ux%u and %ux%u)\n", measured.width, measured.height,
                 reference.width, reference.height);
    return 1;
  }
  const samples::ErrorStats s = samples::compareRgb(measured, reference);
  nlohmann::ordered_json json;
  json["relativeRmse"] = s.relativeRmse;
  json["relativeP99"] = s.relativeP99;
  json["relativeMax"] = s.relativeMax;
  json["nonFinite"] = s.nonFinite;
  json["meanReference"] = s.meanReference;
  json["values"] = s.samples;
  std::puts(json.dump().c_str());
  if (errorPng) {
    const double scale = s.meanReference > 0.0 ? s.meanReference : 1.0;
    std::vector<std::uint8_t> rgba(measured.pixels.size());
    for (std::size_t i = 0; i < rgba.size() / 4; ++i) {
      double worst = 0.0;
      bool finite = true;
      for (std::size_t c = 0; c < 3; ++c) {
        const double m = measured.pixels[i * 4 + c];
        finite = finite && std::isfinite(m);
        worst = std::max(worst, std::abs(m - double(reference.pixels[i * 4 + c])) / scale);
      }
      const auto grey = static_cast<std::uint8_t>(std::lround(std::min(worst / 0.5, 1.0) * 255.0));
      rgba[i * 4 + 0] = finite ? grey : 255;
      rgba[i * 4 + 1] = finite ? grey : 0;
      rgba[i * 4 + 2] = finite ? grey : 0;
      rgba[i * 4 + 3] = 255;
    }
    if (!host::writePng(argv[4], measured.width, measured.height, rgba, error)) {
      std::fprintf(stderr, "tyndall-compare: %s\n", error.c_str());
      return 1;
    }
  }
  return 0;
}
