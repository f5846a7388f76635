// The explicit step's team size chosen from its own wall time (time/thread_tuner.hpp), driven
// with made-up step times: on a quiet machine the grant wins, on a busy one a single thread, and
// the choice follows the machine when its load changes. That the team size changes no result is
// checked on the solver itself (ExplicitSteps.TheTeamSizeChangesNoResult).
#include "time/thread_tuner.hpp"

#include <gtest/gtest.h>

#include <functional>

namespace rumble::fem {
namespace {

/// Steps `seconds` of wall time with step times given per team size; returns the wall time
/// spent on each size's steps.
void step_for(ThreadTuner& tuner, double seconds, const std::function<double(unsigned)>& step) {
  for (double t = 0.0; t < seconds;) {
    const double s = step(tuner.threads());
    tuner.record(s);
    t += s;
  }
}

double share_on(const ThreadTuner& tuner, unsigned size) {
  double total = 0.0, on = 0.0;
  for (std::size_t i = 0; i < tuner.sizes().size(); ++i) {
    total += tuner.seconds_on()[i];
    if (tuner.sizes()[i] == size) on = tuner.seconds_on()[i];
  }
  return on / total;
}

// Step times [s]: a quiet machine halves the step on two threads; a busy one makes the team
// wait for a descheduled thread (10x, as measured).
double quiet(unsigned threads) {
  return threads == 2 ? 1e-4 : 2e-4;
}
double busy(unsigned threads) {
  return threads == 2 ? 2e-3 : 2e-4;
}

TEST(ThreadTuner, AQuietMachineStepsOnTheGrant) {
  ThreadTuner tuner(2);
  EXPECT_EQ(tuner.sizes(), (std::vector<unsigned>{2, 1}));
  step_for(tuner, 60.0, quiet);
  EXPECT_EQ(tuner.threads(), 2u);
  EXPECT_GT(share_on(tuner, 2), 0.99) << tuner.account();
}

TEST(ThreadTuner, ABusyMachineStepsOnOneThreadAndLosesLittleToTheTrials) {
  ThreadTuner tuner(2);
  step_for(tuner, 60.0, busy);
  EXPECT_EQ(tuner.threads(), 1u);
  // The trials on two threads: 0.05 s each, after holds of 1, 2, 4, 8, 16 and 32 s.
  EXPECT_GT(share_on(tuner, 1), 0.98) << tuner.account();
}

TEST(ThreadTuner, LongStepsLoseLittleToTheTrials) {
  // A 1.0e6-DOF mesh's steps on a quiet machine: 12 ms on two threads, 20 ms on one. Over a
  // short run (13 s: rounds of trials at 0, 1, 3 and 7 s) the trials on one thread stay a few
  // percent of the stepping time (at least 16 steps a trial: 8 %).
  ThreadTuner tuner(2);
  step_for(tuner, 13.0, [](unsigned n) { return n == 2 ? 12e-3 : 20e-3; });
  EXPECT_EQ(tuner.threads(), 2u);
  EXPECT_GT(share_on(tuner, 2), 0.95) << tuner.account();
}

TEST(ThreadTuner, TheChoiceFollowsTheMachine) {
  ThreadTuner tuner(2);
  step_for(tuner, 10.0, quiet);
  EXPECT_EQ(tuner.threads(), 2u);
  step_for(tuner, 40.0, busy);  // within the longest hold (32 s) of the load's start
  EXPECT_EQ(tuner.threads(), 1u);
  step_for(tuner, 40.0, quiet);
  EXPECT_EQ(tuner.threads(), 2u);
}

TEST(ThreadTuner, ManyCoresTryHalvingsAndOneThreadHasNothingToChoose) {
  ThreadTuner eight(8);
  EXPECT_EQ(eight.sizes(), (std::vector<unsigned>{8, 4, 2, 1}));
  // Four cores taken by others: four threads are fastest.
  step_for(eight, 30.0, [](unsigned n) { return n > 4 ? 5e-3 : 1e-3 / n; });
  EXPECT_EQ(eight.threads(), 4u);
  ThreadTuner one(1);
  step_for(one, 1.0, busy);
  EXPECT_EQ(one.threads(), 1u);
  EXPECT_EQ(one.account(), "1 thread 100 % of the stepping time");
  ThreadTuner none(0);
  EXPECT_EQ(none.threads(), 1u) << "a grant of 0 is one thread";
}

TEST(ThreadTuner, AnOddStepDoesNotDecideATrial) {
  // One step of a trial on two threads descheduled for a whole time slice (4 ms) among 500
  // quick ones: the mean of the trial stays below one thread's.
  ThreadTuner tuner(2);
  int step = 0;
  step_for(tuner, 2.0, [&](unsigned n) { return n == 2 ? (++step == 7 ? 4e-3 : 1e-4) : 2e-4; });
  EXPECT_EQ(tuner.threads(), 2u);
}

}  // namespace
}  // namespace rumble::fem
