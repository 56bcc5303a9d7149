// animationRange and loopTime (lantern/Scene.h): the span a host plays and the clock wrapped
// into it, as the viewer and the GLFW example use them.
#include <lantern/Scene.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace {

using namespace lantern;

Animation keysAt(std::vector<double> times) {
    AnimationSampler s;
    s.times = times;
    s.values.assign(times.size(), glm::dvec4(0.0));
    Animation a;
    a.samplers = {s};
    a.channels = {{0, AnimationPath::Translation, 0}};
    return a;
}

TEST(AnimationRange, SpansTheKeysOfOneOrAllAnimations) {
    Scene s;
    EXPECT_EQ(animationRange(s).start, 0.0);
    EXPECT_EQ(animationRange(s).end, 0.0);
    s.animations = {keysAt({0.5, 1.0, 2.0}), keysAt({1.0, 3.0})};
    struct Row {
        int animation;
        double start, end;
        const char* why;
    };
    const Row rows[] = {
        {-1, 0.5, 3.0, "all animations: the earliest and the latest key"},
        {0, 0.5, 2.0, "the first alone"},
        {1, 1.0, 3.0, "the second alone"},
        {2, 0.0, 0.0, "an index out of range: empty"},
    };
    for (const Row& r : rows) {
        const TimeRange range = animationRange(s, r.animation);
        EXPECT_EQ(range.start, r.start) << r.why;
        EXPECT_EQ(range.end, r.end) << r.why;
        EXPECT_EQ(range.duration(), r.end - r.start) << r.why;
    }
}

TEST(AnimationRange, LoopTimeWrapsAClockIntoTheRange) {
    const TimeRange range{1.0, 3.0};
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    struct Row {
        double time, expected;
        TimeRange range;
        const char* why;
    };
    const Row rows[] = {
        {1.5, 1.5, range, "inside: unchanged"},
        {3.0, 1.0, range, "the end is the start of the next loop"},
        {4.5, 2.5, range, "after the end: wrapped"},
        {0.5, 2.5, range, "before the start: wrapped backwards"},
        {-7.0, 1.0, range, "far before: still in [start, end)"},
        {nan, 1.0, range, "NaN: the start"},
        {inf, 1.0, range, "infinity: the start"},
        {5.0, 2.0, TimeRange{2.0, 2.0}, "an empty range: its start"},
    };
    for (const Row& r : rows) {
        const double t = loopTime(r.time, r.range);
        EXPECT_DOUBLE_EQ(t, r.expected) << r.why;
        EXPECT_GE(t, r.range.start) << r.why;
    }
}

} // namespace
