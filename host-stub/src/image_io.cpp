// PNG (stb_image_write, stb_image) and EXR (OpenEXR) files. Writers go through `path + ".tmp"` and a rename,
// so a reader never sees a half-written file and a failed write leaves no file behind.
#include <filesystem>
#include <system_error>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>

// The one translation unit that compiles stb_image_write and stb_image (PNG only).
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#include <stb/stb_image.h>

#include "tyndall_host/renderer.h"

namespace tyndall::host {

namespace {

// Moves the finished temporary file over `path`; removes it if that fails.
bool commitTemporary(const std::string& temporary, const std::string& path, std::string& error) {
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  if (ec) {
    std::filesystem::remove(temporary, ec);
    error = "cannot rename " + temporary + " to " + path + ": " + ec.message();
    return false;
  }
  return true;
}

void removeQuietly(const std::string& path) {
  std::error_code ignored;
  std::filesystem::remove(path, ignored);
}

}  // namespace

bool readPng(const std::string& path, std::uint32_t& width, std::uint32_t& height, std::vector<std::uint8_t>& rgba8,
             std::string& error) {
  int w = 0, h = 0, channels = 0;
  stbi_uc* pixels = stbi_load(path.c_str(), &w, &h, &channels, 4);
  if (pixels == nullptr) {
    error = "readPng(" + path + "): " + (stbi_failure_reason() != nullptr ? stbi_failure_reason() : "unreadable");
    return false;
  }
  width = static_cast<std::uint32_t>(w);
  height = static_cast<std::uint32_t>(h);
  rgba8.assign(pixels, pixels + static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 4);
  stbi_image_free(pixels);
  return true;
}

bool writePng(const std::string& path, std::uint32_t width, std::uint32_t height,
              const std::vector<std::uint8_t>& rgba8, std::string& error) {
  if (width == 0 || height == 0 || rgba8.size() != static_cast<std::size_t>(width) * height * 4) {
    error = "writePng(" + path + "): expected " + std::to_string(width) + "x" + std::to_string(height) +
            " RGBA8 pixels, got " + std::to_string(rgba8.size()) + " bytes";
    return false;
  }
  if (width > 0x7fffffffu / 4 || height > 0x7fffffffu) {
    error = "writePng(" + path + "): image too large";
    return false;
  }
  const std::string temporary = path + ".tmp";
  const int ok = stbi_write_png(temporary.c_str(), static_cast<int>(width), static_cast<int>(height), 4,
                                rgba8.data(), static_cast<int>(width * 4));
  if (ok == 0) {
    removeQuietly(temporary);
    error = "writePng: cannot write " + temporary;
    return false;
  }
  return commitTemporary(temporary, path, error);
}

bool writeExr(const std::string& path, const ImageRgba32f& image, std::string& error) {
  const std::size_t pixelCount = static_cast<std::size_t>(image.width) * image.height;
  if (image.width == 0 || image.height == 0 || image.pixels.size() != pixelCount * 4 ||
      image.width > 0x7fffffffu || image.height > 0x7fffffffu) {
    error = "writeExr(" + path + "): image is empty or its pixel count does not match width x height";
    return false;
  }
  const std::string temporary = path + ".tmp";
  try {
    const auto width = static_cast<int>(image.width);
    const auto height = static_cast<int>(image.height);
    Imf::Header header(width, height);  // data window (0,0)-(w-1,h-1), INCREASING_Y: row 0 on top
    header.channels().insert("R", Imf::Channel(Imf::FLOAT));
    header.channels().insert("G", Imf::Channel(Imf::FLOAT));
    header.channels().insert("B", Imf::Channel(Imf::FLOAT));
    // OpenEXR's Slice takes a mutable pointer for both directions; an output file only reads it.
    char* base = reinterpret_cast<char*>(const_cast<float*>(image.pixels.data()));
    const std::size_t xStride = 4 * sizeof(float);
    const std::size_t yStride = xStride * image.width;
    Imf::FrameBuffer frameBuffer;
    frameBuffer.insert("R", Imf::Slice(Imf::FLOAT, base + 0 * sizeof(float), xStride, yStride));
    frameBuffer.insert("G", Imf::Slice(Imf::FLOAT, base + 1 * sizeof(float), xStride, yStride));
    frameBuffer.insert("B", Imf::Slice(Imf::FLOAT, base + 2 * sizeof(float), xStride, yStride));
    {
      Imf::OutputFile file(temporary.c_str(), header);  // closed (flushed) at the end of this scope
      file.setFrameBuffer(frameBuffer);
      file.writePixels(height);
    }
  } catch (const std::exception& e) {
    removeQuietly(temporary);
    error = "writeExr(" + path + "): " + e.what();
    return false;
  }
  return commitTemporary(temporary, path, error);
}

bool readExr(const std::string& path, ImageRgba32f& out, std::string& error) {
  try {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i window = file.header().dataWindow();
    const long width = static_cast<long>(window.max.x) - window.min.x + 1;
    const long height = static_cast<long>(window.max.y) - window.min.y + 1;
    if (width <= 0 || height <= 0) {
      error = "readExr(" + path + "): empty data window";
      return false;
    }
    const Imf::ChannelList& channels = file.header().channels();
    for (const char* name : {"R", "G", "B"}) {
      if (channels.findChannel(name) == nullptr) {
        error = "readExr(" + path + "): no " + name + " channel (expects an RGB image)";
        return false;
      }
    }
    out.width = static_cast<std::uint32_t>(width);
    out.height = static_cast<std::uint32_t>(height);
    out.pixels.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4, 0.0f);

    // Slices are addressed in data-window coordinates: shift the base so (min.x, min.y) is pixel 0.
    const std::ptrdiff_t xStride = 4 * sizeof(float);
    const std::ptrdiff_t yStride = xStride * width;
    char* const origin = reinterpret_cast<char*>(out.pixels.data()) -
                         static_cast<std::ptrdiff_t>(window.min.x) * xStride -
                         static_cast<std::ptrdiff_t>(window.min.y) * yStride;
    Imf::FrameBuffer frameBuffer;
    const char* names[4] = {"R", "G", "B", "A"};
    for (std::ptrdiff_t c = 0; c < 4; ++c) {
      // A missing alpha channel reads as opaque.
      frameBuffer.insert(names[c], Imf::Slice(Imf::FLOAT, origin + c * static_cast<std::ptrdiff_t>(sizeof(float)),
                                               static_cast<std::size_t>(xStride),
                                               static_cast<std::size_t>(yStride), 1, 1, c == 3 ? 1.0 : 0.0));
    }
    file.setFrameBuffer(frameBuffer);
    file.readPixels(window.min.y, window.max.y);
  } catch (const std::exception& e) {
    error = "readExr(" + path + "): " + e.what();
    return false;
  }
  return true;
}

}  // namespace tyndall::host
