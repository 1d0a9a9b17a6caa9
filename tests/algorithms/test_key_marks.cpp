// KeyMarks (private to the algorithms layer): marking with the DDA's stepped axis gives the same
// set as inserting every key, in the dense and the sparse kinds, across brick borders both ways.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "algorithms/key_marks.hpp"
#include "sonarmap/raycast/dda.hpp"

namespace sonarmap {
namespace {

using Marks = KeyMarks<16>;
using Bricks = std::vector<std::pair<Key16, std::uint64_t>>;

Bricks bricksOf(Marks& marks) {
  Bricks out;
  marks.forEachBrick([&](const Key16& corner, std::uint64_t bits) { out.emplace_back(corner, bits); });
  return out;
}

// Face-step walks from random starts (each a run of keys as a DDA gives them), with the axis of
// every step; steps go both ways so walks cross brick borders upwards and downwards.
struct Walk {
  std::vector<Key16> keys;
  std::vector<int> axes;  // -1 for the first key of a walk
};

Walk randomWalks(unsigned seed, const Key16& lo, int walks, int steps) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> axis_of(0, 2), sign(0, 1), start(2, 29);
  Walk walk;
  for (int w = 0; w < walks; ++w) {
    Key16 key{{static_cast<std::uint16_t>(lo[0] + start(rng)), static_cast<std::uint16_t>(lo[1] + start(rng)),
               static_cast<std::uint16_t>(lo[2] + start(rng))}};
    walk.keys.push_back(key);
    walk.axes.push_back(-1);
    for (int s = 0; s < steps; ++s) {
      const int axis = axis_of(rng);
      const int next = key[axis] + (sign(rng) != 0 ? 1 : -1);
      if (next < lo[axis] || next > lo[axis] + 31) continue;  // stay in the box
      key[axis] = static_cast<std::uint16_t>(next);
      walk.keys.push_back(key);
      walk.axes.push_back(axis);
    }
  }
  return walk;
}

void markWalk(Marks& marks, const Walk& walk, bool with_axes) {
  marks.marking([&](auto mark) {
    for (std::size_t i = 0; i < walk.keys.size(); ++i) {
      const Key16& key = walk.keys[i];
      if (!with_axes || i % 7 == 3) {  // some keys through the general path, as clipped rays do
        mark(key);
        continue;
      }
      switch (walk.axes[i]) {
        case 0: mark(key, SteppedAxis<0>{}); break;
        case 1: mark(key, SteppedAxis<1>{}); break;
        case 2: mark(key, SteppedAxis<2>{}); break;
        default: mark(key, SteppedAxis<-1>{}); break;
      }
    }
  });
}

class algorithmsKeyMarks : public ::testing::TestWithParam<bool> {};  // dense?

TEST_P(algorithmsKeyMarks, SteppedMarkingEqualsInsertingEveryKey) {
  const bool dense = GetParam();
  const Key16 lo{{32761, 32770, 32701}};  // not multiples of 4: bricks start below lo
  const Key16 hi{{static_cast<std::uint16_t>(lo[0] + 31), static_cast<std::uint16_t>(lo[1] + 31),
                  static_cast<std::uint16_t>(lo[2] + 31)}};
  const std::size_t limit = dense ? Marks::kMaxDenseVoxels : 64;
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const Walk walk = randomWalks(seed, lo, 30, 200);
    Marks stepped, inserted;
    stepped.reset(lo, hi, limit);
    inserted.reset(lo, hi, limit);
    ASSERT_EQ(stepped.dense(), dense);
    markWalk(stepped, walk, true);
    for (const Key16& key : walk.keys) inserted.insert(key);
    const Bricks expected = bricksOf(inserted);
    ASSERT_FALSE(expected.empty());
    EXPECT_EQ(bricksOf(stepped), expected) << "seed " << seed;
  }
}

INSTANTIATE_TEST_SUITE_P(Kinds, algorithmsKeyMarks, ::testing::Values(true, false),
                         [](const auto& info) { return info.param ? "Dense" : "Sparse"; });

}  // namespace
}  // namespace sonarmap
