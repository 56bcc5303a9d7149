// Soak: a 2000-frame sequence with the process's resident memory sampled every 100 frames;
// after the first few hundred frames (pipelines compiled, buffers at their size) memory must
// not grow. The series is printed so it can be reported.
#include "TestSupport.h"

#include <lantern/Sequence.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <thread>
#include <unistd.h>

namespace {

using namespace lantern;

double residentMiB() {
    std::ifstream statm("/proc/self/statm");
    long pages = 0, resident = 0;
    statm >> pages >> resident;
    return double(resident) * double(sysconf(_SC_PAGESIZE)) / 1048576.0;
}

class Soak : public test::GpuTest {};

TEST_F(Soak, TwoThousandFramesKeepMemoryFlat) {
    auto scene = builtinScene("spheres-animated");
    ASSERT_TRUE(scene);
    auto prepared = renderer().prepare(std::make_shared<const Scene>(std::move(*scene)));
    ASSERT_TRUE(prepared);
    RenderOptions o;
    o.width = 64;
    o.height = 48;
    SequenceOptions s;
    s.frames = {0, 1999};
    s.fps = 30;
    const auto dir = test::testOutputDir();
    s.outputs = {(dir / "f_####.exr").string()};
    std::vector<std::pair<int, double>> samples;
    int next = 100;
    s.progress = [&](const SequenceProgress& p) {
        if (p.written >= next) {
            samples.emplace_back(p.written, residentMiB());
            next += 100;
        }
    };
    auto r = renderer().renderSequence(*prepared, o, s);
    std::filesystem::remove_all(dir);  // 2000 small files: not worth keeping
    ASSERT_TRUE(r) << r.error().describe();
    ASSERT_EQ(r->framesWritten.size(), 2000u);
    ASSERT_GE(samples.size(), 19u);
    std::string series;
    for (const auto& [frame, mib] : samples) series += std::to_string(frame) + ":" + std::to_string(mib).substr(0, 6) + " ";
    std::printf("resident MiB by frames written: %s\n", series.c_str());
    // From frame 500 on, memory stays within 4 MiB of its level there. Progress arrives in
    // steps of a few frames, so the baseline is the first sample at or after frame 500.
    double base = -1, peak = 0;
    for (const auto& [frame, mib] : samples) {
        if (frame < 500) continue;
        if (base < 0) base = mib;
        peak = std::max(peak, mib);
    }
    ASSERT_GE(base, 0.0);
    // Under AddressSanitizer freed blocks wait in its quarantine (256 MiB by default) before
    // reuse, so resident memory creeps up and drops back in steps of a few MiB with no leak
    // (LeakSanitizer checks leaks in that build); the plain build holds the 4 MiB line.
    constexpr double kToleranceMiB = test::kAddressSanitizer ? 16.0 : 4.0;
    // A leak grows with the frames, so the level at the end (the least of the last three
    // samples) is held to the line; a passing peak (a thread's arena while the parallel
    // suite loads the machine: 128.4 MiB once against 126.5 before and after) only to 4x it.
    const std::size_t n = samples.size();
    const double end = std::min({samples[n - 1].second, samples[n - 2].second, samples[n - 3].second});
    EXPECT_LT(end - base, kToleranceMiB) << series;
    EXPECT_LT(peak - base, 4.0 * kToleranceMiB) << series;
    EXPECT_LE(r->peakQueuedFrames, 2u * std::max(1u, std::thread::hardware_concurrency()));
}

} // namespace
