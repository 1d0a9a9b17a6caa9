// SlotBuffer: the node slots' storage keeps every slot through growth on the heap, from the heap to
// a mapped block, and from mapped to larger mapped blocks (mremap), and in copies and moves.
#include <gtest/gtest.h>

#include <cstdint>
#include <utility>

#include "sonarmap/octree/slot_buffer.hpp"

namespace sonarmap {
namespace {

OcTreeNode numbered(std::size_t i) { return OcTreeNode{static_cast<float>(i) * 0.5F, static_cast<std::uint32_t>(i)}; }

void expectNumbered(const SlotBuffer& slots, std::size_t count) {
  ASSERT_GE(slots.size(), count);
  for (std::size_t i = 0; i < count; ++i) {
    ASSERT_EQ(slots[i].log_odds, static_cast<float>(i) * 0.5F) << i;
    ASSERT_EQ(slots[i].link, static_cast<std::uint32_t>(i)) << i;
  }
}

TEST(octreeSlotBuffer, GrowingKeepsEverySlotAcrossTheMappedThreshold) {
  SlotBuffer slots;
  std::size_t filled = 0;
  // 8 B a slot: 1 MiB (the first mapped block) is 131,072 slots; grow one slot at a time past
  // several doublings, so heap → heap, heap → mapped and mapped → mapped growth all happen.
  for (const std::size_t target : {std::size_t{10}, std::size_t{100000}, std::size_t{140000}, std::size_t{600000}}) {
    while (filled < target) {
      slots.resize(filled + 1);
      EXPECT_FALSE(slots[filled].exists());  // a new slot is unknown, with no children
      EXPECT_EQ(slots[filled].link, 0U);
      slots[filled] = numbered(filled);
      ++filled;
    }
    expectNumbered(slots, filled);
    EXPECT_GE(slots.capacity(), filled);
  }
  slots.reserve(3000000);  // a large reservation (mremap) keeps the contents as well
  EXPECT_EQ(slots.size(), filled);
  expectNumbered(slots, filled);
}

TEST(octreeSlotBuffer, CopiesAndMovesHoldTheSameSlots) {
  for (const std::size_t count : {std::size_t{5}, std::size_t{200000}}) {  // on the heap; mapped
    SlotBuffer slots;
    slots.resize(count);
    for (std::size_t i = 0; i < count; ++i) slots[i] = numbered(i);
    SlotBuffer copy(slots);
    expectNumbered(copy, count);
    copy[0].link = 99;
    EXPECT_EQ(slots[0].link, 0U);  // a copy, not a view
    SlotBuffer moved(std::move(copy));
    EXPECT_EQ(moved.size(), count);
    EXPECT_EQ(moved[0].link, 99U);
    SlotBuffer assigned;
    assigned = slots;
    expectNumbered(assigned, count);
    assigned.assign(2, OcTreeNode{});
    EXPECT_EQ(assigned.size(), 2U);
    EXPECT_FALSE(assigned[1].exists());
    assigned.resize(count);  // shrink-then-grow within the capacity gives unknown slots again
    EXPECT_FALSE(assigned[count - 1].exists());
    slots.release();
    EXPECT_EQ(slots.size(), 0U);
    EXPECT_EQ(slots.capacity(), 0U);
  }
}

}  // namespace
}  // namespace sonarmap
