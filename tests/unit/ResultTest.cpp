// Result<T> and LANTERN_ASSERT: a misused Result aborts with file, line and condition in every
// build type (this suite runs in RelWithDebInfo, where assert() is compiled out).
#include <lantern/Result.h>

#include <gtest/gtest.h>

namespace {

using namespace lantern;

Result<int> failing() { return makeError(ErrorCode::InvalidInput, "no", "object", "file.gltf"); }

TEST(Result, ValueAndErrorReadBack) {
    Result<int> ok = 7;
    ASSERT_TRUE(ok);
    EXPECT_EQ(*ok, 7);
    const Result<int> bad = failing();
    ASSERT_FALSE(bad);
    EXPECT_EQ(bad.error().describe(), "file.gltf: object: no");
}

TEST(ResultDeathTest, ValueOfAFailedResultAbortsInEveryBuildType) {
    EXPECT_DEATH((void)failing().value(), "Result.h:[0-9]+: assertion failed: has_value\\(\\)");
}

TEST(ResultDeathTest, ErrorOfASuccessfulResultAborts) {
    EXPECT_DEATH((void)Result<int>(3).error(), "assertion failed: !has_value\\(\\)");
    EXPECT_DEATH((void)Result<void>().error(), "assertion failed: m_failed");
}

TEST(ResultDeathTest, LanternAssertNamesFileLineAndCondition) {
    const int frames = 0;
    EXPECT_DEATH(LANTERN_ASSERT(frames > 0, "a sequence needs frames"),
                 "ResultTest.cpp:[0-9]+: assertion failed: frames > 0 \\(a sequence needs frames\\)");
}

} // namespace
