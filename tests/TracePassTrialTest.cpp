// TracePass::Auto's trial (TracePassTrial): the two sides alternate, each side's first draw (a
// compile) is not counted, the medians of three decide with the compute pass's margin, a time
// that cannot be is not counted, and a decision stands.

#include "hfx/effects/tracer/TracePassTrial.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace hfx::test {
namespace {

/// Runs draws as ExactTracer does (next, began, record) with each side's times in the order given,
/// until the trial decides or a side's list runs out; returns the draws made.
int runTrial(TracePassTrial& trial, const std::vector<double>& inDraw, const std::vector<double>& compute) {
    size_t i = 0, c = 0;
    int draws = 0;
    while (!trial.decided()) {
        const TracePass pass = trial.next();
        std::vector<double> const& times = pass == TracePass::Compute ? compute : inDraw;
        size_t& at = pass == TracePass::Compute ? c : i;
        if (at == times.size()) break;
        trial.began(pass);
        trial.record(pass, times[at++]);
        ++draws;
    }
    return draws;
}

TEST(TracePassTrial, TheSidesAlternateFromTheComputePassAndTheFirstDrawOfEachIsNotCounted) {
    TracePassTrial trial;
    EXPECT_EQ(trial.next(), TracePass::Compute);
    EXPECT_FALSE(trial.started());
    // Times begun ahead of their results (a GPU's timestamps come back frames later) still alternate.
    trial.began(TracePass::Compute);
    EXPECT_EQ(trial.next(), TracePass::InDraw);
    trial.began(TracePass::InDraw);
    EXPECT_EQ(trial.next(), TracePass::Compute);
    EXPECT_TRUE(trial.started());
    // The first of each side (a compile: 500 ms) is left out; kCounted more each decide, not one fewer.
    trial.record(TracePass::Compute, 500.0);
    trial.record(TracePass::InDraw, 500.0);
    for (int k = 0; k < TracePassTrial::kCounted; ++k) {
        EXPECT_FALSE(trial.decided()) << k;
        trial.began(TracePass::Compute);
        trial.record(TracePass::Compute, 1.0);
        EXPECT_FALSE(trial.decided()) << k;
        trial.began(TracePass::InDraw);
        trial.record(TracePass::InDraw, 2.0);
    }
    ASSERT_TRUE(trial.decided());
    const TracePassTrialReport r = trial.report();
    EXPECT_EQ(r.chosen, TracePass::Compute);
    EXPECT_EQ(r.computeDraws, TracePassTrial::kCounted);
    EXPECT_EQ(r.inDrawDraws, TracePassTrial::kCounted);
    EXPECT_DOUBLE_EQ(r.computeMs, 1.0); // the compile's 500 ms would make neither median
    EXPECT_DOUBLE_EQ(r.inDrawMs, 2.0);
}

TEST(TracePassTrial, TheMediansDecideAndTheComputePassMustSaveItsMargin) {
    // One slow draw on either side (a neighbour's burst) moves no median of three.
    {
        TracePassTrial trial;
        EXPECT_EQ(runTrial(trial, {9.0, 2.0, 2.0, 40.0}, {9.0, 1.0, 30.0, 1.0}), 2 * (1 + TracePassTrial::kCounted));
        EXPECT_EQ(trial.report().chosen, TracePass::Compute);
        EXPECT_DOUBLE_EQ(trial.report().computeMs, 1.0);
        EXPECT_DOUBLE_EQ(trial.report().inDrawMs, 2.0);
    }
    {
        TracePassTrial trial;
        runTrial(trial, {9.0, 1.0, 1.0, 1.0}, {9.0, 2.0, 2.0, 2.0});
        EXPECT_EQ(trial.report().chosen, TracePass::InDraw);
    }
    // Within the margin the draw keeps the walks: no buffers, one pass.
    const double margin = TracePassTrial::kComputeMargin;
    {
        TracePassTrial trial;
        runTrial(trial, {9.0, 1.0, 1.0, 1.0}, {9.0, margin + 0.01, margin + 0.01, margin + 0.01});
        EXPECT_EQ(trial.report().chosen, TracePass::InDraw);
    }
    {
        TracePassTrial trial;
        runTrial(trial, {9.0, 1.0, 1.0, 1.0}, {9.0, margin - 0.01, margin - 0.01, margin - 0.01});
        EXPECT_EQ(trial.report().chosen, TracePass::Compute);
    }
}

TEST(TracePassTrial, ATimeThatCannotBeIsNotCountedAndADecisionStands) {
    TracePassTrial trial;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    // A wrapped timestamp (below 0) or NaN: the side times another draw.
    trial.began(TracePass::Compute);
    trial.record(TracePass::Compute, nan);
    EXPECT_EQ(trial.next(), TracePass::Compute);
    EXPECT_FALSE(trial.started());
    trial.began(TracePass::Compute);
    trial.record(TracePass::Compute, -3.0);
    EXPECT_EQ(trial.next(), TracePass::Compute);
    EXPECT_EQ(runTrial(trial, {9.0, 3.0, 3.0, 3.0}, {9.0, nan, 1.0, 1.0, 1.0}), 2 * (1 + TracePassTrial::kCounted) + 1);
    ASSERT_TRUE(trial.decided());
    EXPECT_EQ(trial.report().chosen, TracePass::Compute);
    EXPECT_EQ(trial.report().computeDraws, TracePassTrial::kCounted);
    // Decided: every draw takes it, and later times change nothing.
    for (int k = 0; k < 10; ++k) {
        EXPECT_EQ(trial.next(), TracePass::Compute);
        trial.began(TracePass::InDraw);
        trial.record(TracePass::InDraw, 0.001);
    }
    EXPECT_EQ(trial.report().chosen, TracePass::Compute);
    EXPECT_EQ(trial.report().inDrawDraws, TracePassTrial::kCounted);
}

TEST(TracePassTrial, PassesHaveNames) {
    EXPECT_STREQ(tracePassName(TracePass::Auto), "auto");
    EXPECT_STREQ(tracePassName(TracePass::InDraw), "in the draw");
    EXPECT_STREQ(tracePassName(TracePass::Compute), "compute pass");
}

} // namespace
} // namespace hfx::test
