// RetireQueue (plugin/src/retire_queue.h): a resource a frame stopped using is destroyed exactly
// when the last frame that could read it has completed, spares are kept and served again, and
// nothing is destroyed twice or leaked.
#include <cstdint>
#include <optional>
#include <vector>

#include <gtest/gtest.h>

#include "retire_queue.h"

namespace tyndall {
namespace {

struct Texture {
  int id = 0;
  int width = 0;
};

TEST(RetireQueue, DestroysOnceTheLastFrameUsingItHasCompleted) {
  // Two frames in flight: recording frame f means frame f − 2 has completed.
  constexpr std::uint32_t kInFlight = 2;
  RetireQueue<Texture> queue;
  std::vector<int> destroyed;
  auto destroy = [&](Texture& t) { destroyed.push_back(t.id); };
  queue.retire(5, {1, 64});  // frame 4 was the last to read it
  queue.release(5, kInFlight, destroy);
  EXPECT_TRUE(destroyed.empty());
  EXPECT_EQ(queue.size(), 1u);
  queue.release(6, kInFlight, destroy);  // frame 4 completed
  EXPECT_EQ(destroyed, std::vector<int>{1});
  EXPECT_EQ(queue.size(), 0u);
  queue.release(7, kInFlight, destroy);
  EXPECT_EQ(destroyed, std::vector<int>{1});
}

TEST(RetireQueue, FrameZeroRetiresWithoutUnderflow) {
  RetireQueue<Texture> queue;
  std::vector<int> destroyed;
  auto destroy = [&](Texture& t) { destroyed.push_back(t.id); };
  queue.retire(0, {7, 8});
  queue.release(1, 3, destroy);
  EXPECT_TRUE(destroyed.empty());
  queue.release(3, 3, destroy);
  EXPECT_EQ(destroyed, std::vector<int>{7});
}

TEST(RetireQueue, KeepsTheMostRecentSparesAndServesThemAgain) {
  RetireQueue<Texture> queue;
  std::vector<int> destroyed;
  auto destroy = [&](Texture& t) { destroyed.push_back(t.id); };
  queue.retire(10, {1, 64});
  queue.retire(11, {2, 128});
  queue.retire(12, {3, 256});
  // Long after: all completed, but the two most recent stay as spares; the oldest goes.
  queue.release(100, 2, destroy, 2);
  EXPECT_EQ(destroyed, std::vector<int>{1});
  ASSERT_EQ(queue.size(), 2u);

  std::optional<Texture> spare = queue.take([](const Texture& t) { return t.width == 256; });
  ASSERT_TRUE(spare.has_value());
  EXPECT_EQ(spare->id, 3);
  EXPECT_EQ(queue.size(), 1u);
  EXPECT_FALSE(queue.take([](const Texture& t) { return t.width == 512; }).has_value());
  EXPECT_EQ(queue.size(), 1u);

  queue.destroyAll(destroy);
  EXPECT_EQ(destroyed, (std::vector<int>{1, 2}));
  EXPECT_EQ(queue.size(), 0u);
}

TEST(RetireQueue, AnEntryStillInFlightIsSkippedNotBlocking) {
  // keep = 0: a completed entry behind one still in flight is destroyed; the pending one waits.
  RetireQueue<Texture> queue;
  std::vector<int> destroyed;
  auto destroy = [&](Texture& t) { destroyed.push_back(t.id); };
  queue.retire(20, {1, 1});
  queue.retire(10, {2, 2});  // out of order, to see the walk pass over a pending entry
  queue.release(13, 2, destroy);
  EXPECT_EQ(destroyed, std::vector<int>{2});
  EXPECT_EQ(queue.size(), 1u);
  queue.release(21, 2, destroy);
  EXPECT_EQ(destroyed, (std::vector<int>{2, 1}));
}

}  // namespace
}  // namespace tyndall
