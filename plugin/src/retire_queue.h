// Resources a frame stopped using while earlier frames may still be in flight with them: a
// technique that changes its textures' sizes or formats between frames (a profile switch, a new
// shadow-map size) hands the old ones to a RetireQueue, which destroys each once the last frame
// that could read it has completed. The techniques record into the host's command buffers and
// never wait on a fence, so the frame index is the only clock they have.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

namespace tyndall {

/// Whether frame `lastFrame` has completed while frame `frameIndex` is being recorded, with
/// `framesInFlight` frames in flight (frame f has, once frame f + framesInFlight is): what it used
/// may then be destroyed.
inline bool frameCompleted(std::uint64_t lastFrame, std::uint64_t frameIndex, std::uint32_t framesInFlight) {
  return lastFrame + framesInFlight <= frameIndex;
}

template <class Resource>
class RetireQueue {
 public:
  /// `resource` is no longer used from frame `frameIndex` (the one being recorded) on; the frame
  /// before it is the last that may read it.
  void retire(std::uint64_t frameIndex, Resource resource) {
    entries_.push_back({frameIndex == 0 ? 0 : frameIndex - 1, std::move(resource)});
  }

  /// Destroys, oldest first, every entry whose last frame has completed — except the `keep` most
  /// recently retired ones, kept as spares for take().
  template <class Destroy>
  void release(std::uint64_t frameIndex, std::uint32_t framesInFlight, Destroy&& destroy, std::size_t keep = 0) {
    std::size_t excess = entries_.size() > keep ? entries_.size() - keep : 0;
    for (auto it = entries_.begin(); excess > 0 && it != entries_.end();) {
      if (frameCompleted(it->lastFrame, frameIndex, framesInFlight)) {
        destroy(it->resource);
        it = entries_.erase(it);
        --excess;
      } else {
        ++it;
      }
    }
  }

  /// Removes and returns the oldest entry `fits` accepts, to serve again. The caller's frame must
  /// be ordered after the frames still in flight with it (the barriers every frame starts with
  /// do that for the techniques, as for a resource kept from frame to frame).
  template <class Fits>
  std::optional<Resource> take(Fits&& fits) {
    for (auto it = entries_.begin(); it != entries_.end(); ++it) {
      if (!fits(std::as_const(it->resource))) continue;
      Resource resource = std::move(it->resource);
      entries_.erase(it);
      return resource;
    }
    return std::nullopt;
  }

  /// Destroys every entry now (the device is idle: the context is being destroyed).
  template <class Destroy>
  void destroyAll(Destroy&& destroy) {
    for (Entry& entry : entries_) destroy(entry.resource);
    entries_.clear();
  }

  std::size_t size() const { return entries_.size(); }

 private:
  struct Entry {
    std::uint64_t lastFrame = 0;
    Resource resource;
  };
  std::vector<Entry> entries_;  // oldest first
};

}  // namespace tyndall
