// `lantern farm` on a real Slurm: each test installs (if needed) and starts a private
// single-node cluster from Debian's packages with scripts/slurm-single-node.sh (its own
// configuration, state and munge key under /tmp), and stops it by PID in TearDown. A watchdog
// started with the cluster stops it too if this process dies without tearing down.
#include "FarmTestSupport.h"

#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <regex>
#include <unistd.h>

namespace {

using lantern::test::ProcessResult;
using lantern::test::runLantern;
using lantern::test::runProcess;
using lantern::test::testOutputDir;
using namespace lantern::test::farm;
namespace fs = std::filesystem;

class SlurmCluster : public ::testing::Test {
protected:
    void SetUp() override {
        if (!lantern::test::sharedRenderer())
            GTEST_SKIP() << "no Vulkan device for the tasks to render on: "
                         << lantern::test::noDeviceReason();
        const auto install = script({"install"});
        if (install.exitCode != 0)
            GTEST_SKIP() << "the Slurm packages (slurm-wlm slurmctld slurmd slurm-client munge) "
                            "are not installed "
                            "and cannot be installed here:\n"
                         << install.err;
        if (::geteuid() != 0)
            GTEST_SKIP() << "a single-node Slurm needs root (slurmd starts each job as its owner); "
                            "run as root";
        // What else the cluster needs from the machine (the loopback network, two free TCP
        // ports), checked before starting it: a machine without them skips, naming what.
        const auto probe = script({"probe"});
        if (probe.exitCode != 0)
            GTEST_SKIP() << "this machine cannot run a private single-node Slurm: " << probe.err;
        m_dir = "/tmp/lantern-farm-test-" + std::to_string(::getpid());
        const auto start = script({"start", "--watch", std::to_string(::getpid())});
        m_started = true; // stop even after a failed start: it cleans up whatever did start
        ASSERT_EQ(start.exitCode, 0) << "the cluster did not start:\n" << start.err;
        for (const char* daemon : {"munged", "slurmctld", "slurmd"}) {
            const std::string pid =
                fileBytes(fs::path(m_dir) / "run" / (std::string(daemon) + ".pid"));
            ASSERT_FALSE(pid.empty()) << daemon << " wrote no PID file";
            m_pids.push_back(std::stoi(pid));
        }
    }

    void TearDown() override {
        if (!m_started) return;
        const auto stop =
            script({"stop"}, {"LANTERN_SLURM_SAVE_LOGS=" + (lantern::test::binaryDir() / "tests" /
                                                            "output" / "slurm-logs" / testName())
                                                               .string()});
        EXPECT_EQ(stop.exitCode, 0) << stop.err;
        for (int pid : m_pids)
            EXPECT_FALSE(alive(pid)) << "PID " << pid << " still running after stop";
        EXPECT_FALSE(fs::exists(m_dir)) << m_dir << " left behind";
    }

    // The environment that points Slurm's clients (and so `lantern farm`) at this cluster.
    std::vector<std::string> env() const { return {"SLURM_CONF=" + m_dir + "/etc/slurm.conf"}; }

    ProcessResult script(const std::vector<std::string>& args,
                         std::vector<std::string> extraEnv = {}) const {
        std::vector<std::string> full = {
            (lantern::test::sourceDir() / "scripts" / "slurm-single-node.sh").string()};
        full.insert(full.end(), args.begin(), args.end());
        if (!m_dir.empty()) extraEnv.push_back("LANTERN_SLURM_DIR=" + m_dir);
        return runProcess(full, extraEnv, 600.0);
    }

    ProcessResult farm(std::vector<std::string> args) const {
        args.insert(args.begin(), "farm");
        return runLantern(args, env());
    }

    ProcessResult slurm(const std::vector<std::string>& args) const {
        return runProcess(args, env(), 60.0);
    }

    // `farm submit` of the sample's frames 0-10 in 4 tasks (11 frames: shards of 3, 3, 3, 2).
    std::vector<std::string> submitArgs(const fs::path& out) const {
        std::vector<std::string> args = {
            "submit",  "--scheduler", "slurm", "builtin:spheres-animated", "--frames", "0-10",
            "--tasks", "4",           "-o",    (out / "f_##.exr").string()};
        const auto options = sampleRenderOptions();
        args.insert(args.end(), options.begin(), options.end());
        return args;
    }

private:
    static bool alive(int pid) {
        // A daemon that exited may linger a moment as a zombie of PID 1: that is not running.
        std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
        std::string line;
        if (!std::getline(stat, line)) return false;
        const auto close = line.rfind(')');
        return close != std::string::npos && close + 2 < line.size() && line[close + 2] != 'Z';
    }
    static std::string testName() {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        return std::string(info->test_suite_name()) + "." + info->name();
    }

    std::string m_dir;
    bool m_started = false;
    std::vector<int> m_pids;
};

TEST_F(SlurmCluster, JobArrayRendersTheSameBytesAsOneMachine) {
    const auto dir = testOutputDir();
    // The controller's first batch job starts about 3 s after it does: render the reference now.
    renderReference(dir / "single", "0-10");
    const auto r = farm(concat(submitArgs(dir / "farm"), {"--wait"}));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(std::regex_match(r.out, std::regex("[0-9]+\n"))) << "not a job id: " << r.out;
    const std::string id = r.out.substr(0, r.out.size() - 1);
    EXPECT_NE(r.err.find("4/4 tasks done (0 running, 0 pending), 11/11 frames present"),
              std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("4 COMPLETED"), std::string::npos) << r.err;
    expectSameFrames(dir / "single", dir / "farm");
    // The script stays beside the frames, with one log per task.
    EXPECT_NE(fileBytes(dir / "farm" / "f.sbatch").find("#SBATCH --array=0-3\n"),
              std::string::npos);
    EXPECT_EQ(
        filesEndingWith(dir / "farm" / "f-logs", ".out"),
        (std::vector<std::string>{id + "_0.out", id + "_1.out", id + "_2.out", id + "_3.out"}));
    EXPECT_NE(fileBytes(dir / "farm" / "f.farm").find("\"id\": \"" + id + "\""), std::string::npos)
        << "the record names the job";
    const auto check = farm({"check", (dir / "farm" / "f_##.exr").string()});
    EXPECT_EQ(check.exitCode, 0) << check.out;
}

TEST_F(SlurmCluster, CancelledTaskLosesOnlyItsFramesAndResumeRendersThem) {
    const auto dir = testOutputDir();
    const std::string pattern = (dir / "farm" / "f_##.exr").string();
    // Held, so task 1 can be cancelled before it runs while the others go on.
    const auto submitted = farm(concat(submitArgs(dir / "farm"), {"--hold"}));
    ASSERT_EQ(submitted.exitCode, 0) << submitted.err;
    const std::string id = submitted.out.substr(0, submitted.out.find('\n'));
    // Its frames are not missing yet, only not rendered: resume refuses to render them twice.
    const auto early = farm({"submit", "--resume", "-o", pattern});
    EXPECT_EQ(early.exitCode, 1) << early.err;
    EXPECT_NE(early.err.find("4 task(s) of this sequence are still pending or running"),
              std::string::npos)
        << early.err;
    ASSERT_EQ(slurm({"scancel", id + "_1"}).exitCode, 0);
    ASSERT_EQ(slurm({"scontrol", "release", id}).exitCode, 0);
    renderReference(dir / "single", "0-10");
    // A task cancelled while pending leaves the queue at once on Slurm 22.05 (then every task
    // left completed: rc 0); other versions may list it as CANCELLED (rc 1).
    const auto waited = script({"wait", id, "300"});
    ASSERT_TRUE(waited.exitCode == 0 || waited.out.find("1 CANCELLED") != std::string::npos)
        << waited.out << waited.err;

    // Task 1 of 4 had frames 1, 5 and 9; a frame of task 2 is then damaged.
    const std::string damaged = lantern::expandFramePattern(pattern, 2);
    const std::string kept = fileBytes(damaged).substr(0, 200);
    std::ofstream(damaged, std::ios::binary | std::ios::trunc) << kept;
    auto check = farm({"check", pattern, "--frames", "0-10"});
    EXPECT_EQ(check.exitCode, 1) << check.out;
    EXPECT_NE(check.out.find("frames 0-10: 7 of 11 present; missing 1-2,5,9\n"), std::string::npos)
        << check.out;
    for (int frame : {1, 5, 9})
        EXPECT_NE(check.out.find(lantern::expandFramePattern(pattern, frame) + ": missing\n"),
                  std::string::npos)
            << check.out;
    EXPECT_NE(check.out.find(damaged + ": unreadable"), std::string::npos) << check.out;

    const auto resumed = farm({"submit", "--resume", "-o", pattern, "--wait"});
    ASSERT_EQ(resumed.exitCode, 0) << resumed.err;
    EXPECT_NE(resumed.err.find("frames 1-2,5,9"), std::string::npos) << resumed.err;
    EXPECT_NE(resumed.err.find("4/4 tasks done"), std::string::npos) << resumed.err;
    EXPECT_NE(fileBytes(dir / "farm" / "f.resume-1.sbatch").find("--frame-list 1-2,5,9"),
              std::string::npos);
    check = farm({"check", pattern});
    EXPECT_EQ(check.exitCode, 0) << check.out;
    expectSameFrames(dir / "single", dir / "farm");
    // Nothing left to do: a second resume submits nothing.
    const auto again = farm({"submit", "--resume", "-o", pattern});
    EXPECT_EQ(again.exitCode, 0) << again.err;
    EXPECT_EQ(again.out, "");
    EXPECT_NE(again.err.find("nothing to resume"), std::string::npos) << again.err;
}

} // namespace
