// Renderer::renderSequence: writing sequences, above the renderer: frames double buffered
// through the device's frame slots and encoded in parallel by an EncodePool (io/).
#include "api/RendererImpl.h"
#include "render/FrameRender.h"

#include "io/AtomicFile.h"
#include "io/EncodePool.h"

#include <chrono>
#include <cmath>
#include <deque>
#include <filesystem>
#include <set>
#include <sys/resource.h>
#include <thread>

namespace lantern {
namespace {

using Clock = std::chrono::steady_clock;

double msBetween(Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
}

double processCpuSeconds() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
           double(u.ru_utime.tv_usec + u.ru_stime.tv_usec) * 1e-6;
}

Result<void> checkSequence(const SequenceOptions& s, const std::vector<int>& frames) {
    if (!(s.fps > 0.0) || !std::isfinite(s.fps))
        return makeError(ErrorCode::InvalidInput, "frames per second must be a positive number", "--fps");
    if (s.outputs.empty()) return makeError(ErrorCode::Usage, "a sequence needs an output", "--output");
    for (const std::string& out : s.outputs) {
        const std::string ext = std::filesystem::path(out).extension().string();
        if (ext != ".exr" && ext != ".png")
            return makeError(ErrorCode::InvalidInput,
                             "unknown image type \"" + ext + "\" (use .exr or .png)", "--output", out);
        if (frames.size() > 1 && !hasFramePattern(out))
            return makeError(ErrorCode::InvalidInput,
                             "several frames need '#' in the output name for the frame number "
                             "(e.g. out/frame_####.exr)",
                             "--output", out);
    }
    // Refuse an unwritable destination before rendering anything.
    if (!frames.empty())
        for (const std::string& out : s.outputs) {
            io::AtomicFile probe(expandFramePattern(out, frames.front()));
            LANTERN_TRY(probe.checkWritable());
        }
    return {};
}

} // namespace

Result<SequenceReport> Renderer::renderSequence(const PreparedScene& prepared, const RenderOptions& options,
                                                const SequenceOptions& seq) {
    if (!prepared) return makeError(ErrorCode::Usage, "renderSequence() needs a prepared scene");
    gpu::Device& device = *m_impl->device;
    LANTERN_TRY(render::checkOptions(device, options));
    const std::vector<int> frames = sequenceFrames(seq);
    LANTERN_TRY(checkSequence(seq, frames));
    // A process killed mid-write (SIGKILL) leaves a temporary file; clear those of dead writers.
    std::set<std::filesystem::path> folders;
    for (const std::string& out : seq.outputs) folders.insert(std::filesystem::path(out).parent_path());
    for (const auto& folder : folders) io::removeStaleTemporariesIn(folder);

    SequenceReport report;
    const int cores = int(std::max(1u, std::thread::hardware_concurrency()));
    const int threads = seq.encoderThreads > 0 ? seq.encoderThreads : cores;
    // A waiting frame is a full float image; `threads` of them bound the queue's memory.
    io::EncodePool pool(threads, std::size_t(threads), seq.exr);

    const auto start = Clock::now();
    const double cpuStart = processCpuSeconds();
    struct InFlight {
        std::uint32_t slot;
        int frame;
        double time;
        double submitMs;
        frame::Frame model;
    };
    std::deque<InFlight> inFlight;
    std::optional<Error> failure;
    std::size_t reported = 0;
    auto reportProgress = [&] {
        if (!seq.progress) return;
        const std::size_t written = pool.writtenCount();
        if (written == reported) return;
        reported = written;
        SequenceProgress p;
        p.written = int(written);
        p.total = int(frames.size());
        const auto done = pool.done();
        p.lastFrame = done.empty() ? -1 : done.back().frame;
        p.elapsedSeconds = msBetween(start, Clock::now()) / 1000.0;
        p.framesPerSecond = p.elapsedSeconds > 0 ? p.written / p.elapsedSeconds : 0.0;
        p.secondsLeft = p.framesPerSecond > 0 ? (p.total - p.written) / p.framesPerSecond : 0.0;
        seq.progress(p);
    };
    // Waits for the oldest frame in flight, reads it back and hands it to the encoders.
    auto collectOldest = [&](bool encode) -> Result<void> {
        InFlight f = std::move(inFlight.front());
        inFlight.pop_front();
        const auto t0 = Clock::now();
        auto result = device.collect(f.slot);
        if (!result) return std::move(result).error();
        report.renderMs.push_back(f.submitMs + msBetween(t0, Clock::now()));
        report.gpuMs.push_back(result->gpuMs);
        if (!encode) return {};
        Image image = std::move(result->image);
        attachMetadata(image, f.model, device.info(), f.time);
        image.metadata.emplace_back("lantern:frame", std::to_string(f.frame));
        image.framesPerSecond = seq.fps;
        io::EncodePool::Job job;
        job.frame = f.frame;
        job.image = std::move(image);
        for (const std::string& out : seq.outputs) job.paths.push_back(expandFramePattern(out, f.frame));
        pool.push(std::move(job));  // false after a write error: reported below
        return {};
    };

    for (int frame : frames) {
        if (seq.shouldStop && seq.shouldStop()) {
            report.stopped = true;
            break;
        }
        if (pool.failed()) break;
        // Double buffering: the next slot is reused only after its previous frame is collected,
        // so frame k+1 is recorded and rendering while frame k is read back and encoded.
        if (device.busy(device.nextSlot())) {
            if (auto r = collectOldest(true); !r) {
                failure = r.error();
                break;
            }
            reportProgress();
        }
        const auto t0 = Clock::now();
        const double time = double(frame) / seq.fps;
        auto planned = render::planFrame(prepared.scene(), options, time);
        if (!planned) {
            failure = planned.error();
            break;
        }
        auto slot = device.submit(planned->list, prepared.m_gpu);
        if (!slot) {
            failure = slot.error();
            break;
        }
        inFlight.push_back(
            {*slot, frame, time, msBetween(t0, Clock::now()), std::move(planned->frame)});
    }
    // Frames still in flight: finish them (unless stopping or failing, then only wait for the
    // GPU), so every slot is free when this returns.
    while (!inFlight.empty()) {
        const bool keep = !report.stopped && !failure && !pool.failed();
        if (auto r = collectOldest(keep); !r && !failure) failure = r.error();
        reportProgress();
    }
    pool.finish(reportProgress);
    reportProgress();

    report.wallSeconds = msBetween(start, Clock::now()) / 1000.0;
    report.cpuSeconds = processCpuSeconds() - cpuStart;
    for (const auto& d : pool.done()) {
        report.framesWritten.push_back(d.frame);
        report.encodeMs.push_back(d.encodeMs);
    }
    report.clampedValues = pool.clampedValues();
    report.peakQueuedFrames = pool.peakQueued();
    if (failure) return *failure;
    if (auto e = pool.firstError()) return *e;
    return report;
}

} // namespace lantern
