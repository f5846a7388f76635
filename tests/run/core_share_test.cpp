// CoreShare (run/core_share.hpp): how the soil's threads follow what the coupler does. A coupler
// that advances one participant at a time leaves the soil every core; one that advances two at
// once starts with one core for the track, and gives the soil every core back after its window
// when the two never overlapped or the track's advance is small beside the soil's; the steps
// before the window (one-off work) do not count.
#include "run/core_share.hpp"

#include <gtest/gtest.h>

namespace rumble {
namespace {

/// Feeds steps of `track` and `soil` seconds each (overlapping or not) until a grant changes or
/// `steps` have gone; returns the new grant (0: none).
unsigned feed(CoreShare& share, double track, double soil, bool overlapped, int steps) {
  double t = 0.0, s = 0.0;
  for (int k = 0; k < steps; ++k) {
    t += track;
    s += soil;
    if (const unsigned g = share.after_step(t, s, overlapped)) return g;
  }
  return 0;
}

constexpr int kEnough = CoreShare::kSkipSteps + CoreShare::kWindowSteps;

TEST(CoreShare, OneAtATimeGivesTheSoilEveryCoreFromTheStart) {
  CoreShare share(4, false);
  EXPECT_EQ(share.first_grant(), 4u);
  EXPECT_EQ(feed(share, 1e-3, 1e-3, false, 100), 0u);
}

TEST(CoreShare, TwoAtOnceAndAlikeKeepOneCoreForTheTrack) {
  CoreShare share(2, true);
  EXPECT_EQ(share.first_grant(), 1u);
  EXPECT_EQ(feed(share, 1e-3, 1.2e-3, true, 100), 0u);
}

TEST(CoreShare, ACheapTrackBesideTheSoilGivesItEveryCore) {
  CoreShare share(2, true);
  EXPECT_EQ(feed(share, 1e-4, 1e-3, true, kEnough - 1), 0u);  // not before the window's end
  CoreShare again(2, true);
  EXPECT_EQ(feed(again, 1e-4, 1e-3, true, kEnough), 2u);
  EXPECT_EQ(again.reason(), "the track's advance took 10 % of the soil's");
  // 1 / (2 cores) of the soil's is the bound: on 8 cores a track at 10 % keeps its core.
  CoreShare eight(8, true);
  EXPECT_EQ(eight.first_grant(), 7u);
  EXPECT_EQ(feed(eight, 1e-4, 1e-3, true, 100), 0u);
}

TEST(CoreShare, NoOverlapGivesTheSoilEveryCore) {
  CoreShare share(2, true);
  EXPECT_EQ(feed(share, 1e-3, 1e-3, false, kEnough), 2u);
  EXPECT_EQ(share.reason(), "the coupler advanced the track and the soil one after the other");
}

TEST(CoreShare, TheFirstStepsDoNotCount) {
  // A first step whose track advance is long (its factorization) does not hide a cheap track.
  CoreShare share(2, true);
  double t = 1.0, s = 1e-3;
  unsigned grant = share.after_step(t, s, true);
  for (int k = 1; k < kEnough && grant == 0; ++k) {
    t += 1e-4;
    s += 1e-3;
    grant = share.after_step(t, s, true);
  }
  EXPECT_EQ(grant, 2u);
}

TEST(CoreShare, OneCoreHasNothingToShare) {
  CoreShare share(1, true);
  EXPECT_EQ(share.first_grant(), 1u);
  EXPECT_EQ(feed(share, 1e-4, 1e-3, false, 100), 0u);
}

}  // namespace
}  // namespace rumble
