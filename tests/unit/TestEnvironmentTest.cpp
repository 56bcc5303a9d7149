// The test suite's checks for what a plain machine may lack: each names what is missing, so a
// test that needs it skips with a reason a user can act on. The refusals are faked with
// stand-in programs on $PATH, as a chroot or a container would answer.
#include "TestSupport.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sys/stat.h>

namespace {

using namespace lantern::test;

// $PATH with a stand-in `unshare` (a shell script running `body`) in `dir` first.
std::vector<std::string> fakeUnshare(const std::filesystem::path& dir, const std::string& body) {
    const auto path = dir / "unshare";
    std::ofstream(path) << "#!/bin/sh\n" << body << "\n";
    ::chmod(path.c_str(), 0755);
    const char* old = std::getenv("PATH");
    return {"PATH=" + dir.string() + ":" + (old ? old : "/usr/bin:/bin")};
}

TEST(TestEnvironment, AMissingProgramIsNamedWithItsPackage) {
    const std::string reason = missingProgram("lantern-no-such-tool", "lantern-tools");
    EXPECT_EQ(reason, "lantern-no-such-tool is not installed (Debian package lantern-tools)");
    EXPECT_EQ(missingProgram("sh", "dash"), "");
}

TEST(TestEnvironment, ARefusedUserNamespaceIsNamed) {
    const auto dir = testOutputDir();
    // What util-linux's unshare prints in a chroot or under Docker's default profile.
    const std::string reason = missingUserNamespaceMount(
        fakeUnshare(dir, "echo 'unshare: unshare failed: Operation not permitted' >&2; exit 1"));
    EXPECT_NE(reason.find("no unprivileged user namespace"), std::string::npos) << reason;
    EXPECT_NE(reason.find("unshare failed: Operation not permitted"), std::string::npos) << reason;
}

TEST(TestEnvironment, ARefusedMountIsNamed) {
    const auto dir = testOutputDir();
    const std::string reason = missingUserNamespaceMount(
        fakeUnshare(dir, "echo 'mount: /tmp: permission denied.' >&2; exit 77"));
    EXPECT_NE(reason.find("no tmpfs can be mounted"), std::string::npos) << reason;
    EXPECT_NE(reason.find("permission denied"), std::string::npos) << reason;
}

TEST(TestEnvironment, AnAllowedUserNamespaceIsNoReason) {
    EXPECT_EQ(missingUserNamespaceMount(fakeUnshare(testOutputDir(), "exit 0")), "");
}

} // namespace
