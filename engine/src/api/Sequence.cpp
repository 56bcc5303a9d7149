// Renderer::renderSequence: writing sequences, above the renderer: frames double buffered
// through the device's frame slots and encoded in parallel by an EncodePool (io/).
#include "api/RendererImpl.h"
#include "render/AovPlanes.h"
#include "render/Cryptomatte.h"
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
    if (s.frameList.empty() &&
        (s.frames.first < 0 || s.frames.last < s.frames.first ||
         std::int64_t(s.frames.last) - s.frames.first + 1 > kMaxSequenceFrames))
        return makeError(ErrorCode::InvalidInput,
                         "frames " + std::to_string(s.frames.first) + "-" +
                             std::to_string(s.frames.last) + " are not a range A-B with 0 <= A <= B "
                             "of at most " + std::to_string(kMaxSequenceFrames) + " frames",
                         "--frames");
    if (s.encoderThreads < 0 || s.encoderThreads > kMaxEncoderThreads)
        return makeError(ErrorCode::InvalidInput,
                         std::to_string(s.encoderThreads) + " encoder threads: use 0 (one per core) "
                         "to " + std::to_string(kMaxEncoderThreads),
                         "--encoder-threads");
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

// A process killed mid-write (SIGKILL) leaves a temporary file; clear those of dead writers.
void removeStaleTemporaries(const SequenceOptions& seq) {
    std::set<std::filesystem::path> folders;
    for (const std::string& out : seq.outputs) folders.insert(std::filesystem::path(out).parent_path());
    for (const auto& folder : folders) io::removeStaleTemporariesIn(folder);
}

int encoderThreads(const SequenceOptions& seq) {
    const int cores = int(std::max(1u, std::thread::hardware_concurrency()));
    return seq.encoderThreads > 0 ? seq.encoderThreads : cores;
}

// One renderSequence call: frames double buffered through the device's frame slots, collected
// oldest first and handed to the encoders, with progress reported as frames are written.
class SequenceRun {
public:
    // A waiting frame is a full float image; `threads` of them bound the queue's memory.
    SequenceRun(gpu::Device& device, const SequenceOptions& seq, std::size_t total, int threads)
        : m_device(device), m_seq(seq), m_total(total),
          m_pool(threads, std::size_t(threads), seq.exr) {}

    // Submits every frame, stopping early when asked to, when a frame fails or when an encoder
    // failed.
    void renderFrames(const Scene& scene, const std::shared_ptr<gpu::SceneBuffers>& buffers,
                      const RenderOptions& options, const std::vector<int>& frames) {
        m_scene = &scene;
        m_buffers = &buffers;
        m_options = &options;
        for (int frame : frames) {
            if (m_seq.shouldStop && m_seq.shouldStop()) {
                m_report.stopped = true;
                break;
            }
            if (m_pool.failed()) break;
            // Double buffering: the next slot is reused only after its previous frame is
            // collected, so frame k+1 is recorded and rendering while frame k is read back and
            // encoded.
            if (m_device.busy(m_device.nextSlot())) {
                if (auto r = collectOldest(true); !r) {
                    m_failure = r.error();
                    break;
                }
                reportProgress();
            }
            if (auto r = submitFrame(scene, buffers, options, frame); !r) {
                m_failure = r.error();
                break;
            }
            // Cryptomatte's id render is a second, synchronous frame on the same slots: the
            // frame is collected (and its layers made) before the next is submitted. Encoding
            // still runs beside the rendering.
            if (options.aovs.anyCryptomatte()) {
                if (auto r = collectOldest(true); !r) {
                    m_failure = r.error();
                    break;
                }
                reportProgress();
            }
        }
    }

    // Frames still in flight: finish them (unless stopping or failing, then only wait for the
    // GPU), so every slot is free when this returns; then the encoders finish.
    void drain() {
        while (!m_inFlight.empty()) {
            const bool keep = !m_report.stopped && !m_failure && !m_pool.failed();
            if (auto r = collectOldest(keep); !r && !m_failure) m_failure = r.error();
            reportProgress();
        }
        m_pool.finish([this] { reportProgress(); });
        reportProgress();
    }

    // The report, or the first error (a frame's before an encoder's).
    Result<SequenceReport> finish() {
        m_report.wallSeconds = msBetween(m_start, Clock::now()) / 1000.0;
        m_report.cpuSeconds = processCpuSeconds() - m_cpuStart;
        for (const auto& d : m_pool.done()) {
            m_report.framesWritten.push_back(d.frame);
            m_report.encodeMs.push_back(d.encodeMs);
        }
        m_report.clampedValues = m_pool.clampedValues();
        m_report.peakQueuedFrames = m_pool.peakQueued();
        if (m_failure) return *m_failure;
        if (auto e = m_pool.firstError()) return *e;
        return std::move(m_report);
    }

private:
    struct InFlight {
        std::uint32_t slot;
        int frame;
        double time;
        double submitMs;
        frame::Frame model;
    };

    Result<void> submitFrame(const Scene& scene, const std::shared_ptr<gpu::SceneBuffers>& buffers,
                             const RenderOptions& options, int frame) {
        const auto t0 = Clock::now();
        const double time = double(frame) / m_seq.fps;
        auto planned = render::planFrame(scene, options, time);
        if (!planned) return std::move(planned).error();
        auto slot = m_device.submit(planned->list, buffers);
        if (!slot) return std::move(slot).error();
        m_inFlight.push_back(
            {*slot, frame, time, msBetween(t0, Clock::now()), std::move(planned->frame)});
        return {};
    }

    // Waits for the oldest frame in flight, reads it back and hands it to the encoders.
    Result<void> collectOldest(bool encode) {
        InFlight f = std::move(m_inFlight.front());
        m_inFlight.pop_front();
        const auto t0 = Clock::now();
        auto result = m_device.collect(f.slot);
        if (!result) return std::move(result).error();
        m_report.renderMs.push_back(f.submitMs + msBetween(t0, Clock::now()));
        m_report.gpuMs.push_back(result->gpuMs);
        if (!encode) return {};
        if (result->nonFinite > 0) {
            // The later frames are dropped (collected, not written): the probe that names the
            // object renders on their slots.
            for (; !m_inFlight.empty(); m_inFlight.pop_front()) (void)m_device.collect(m_inFlight.front().slot);
            return render::nonFiniteFrame(m_device, *m_buffers, *m_scene, *m_options, f.time, *result,
                                          f.frame);
        }
        render::resolveAovPlanes(*m_scene, f.model, m_options->aovs, *result);
        Image image = std::move(result->image);
        attachMetadata(image, f.model, m_device.info(), f.time);
        image.metadata.emplace_back("lantern:frame", std::to_string(f.frame));
        image.framesPerSecond = m_seq.fps;
        if (m_options->aovs.anyCryptomatte()) {
            auto layers = render::renderCryptomatte(m_device, *m_buffers, *m_scene, *m_options, f.time);
            if (!layers) {
                Error e = std::move(layers).error();
                e.message = "frame " + std::to_string(f.frame) + ": " + e.message;
                return e;
            }
            image.cryptomatte = std::move(*layers);
        }
        io::EncodePool::Job job;
        job.frame = f.frame;
        job.image = std::move(image);
        job.writeCamera = m_seq.writeCamera;
        for (const std::string& out : m_seq.outputs)
            job.paths.push_back(expandFramePattern(out, f.frame));
        m_pool.push(std::move(job)); // false after a write error: reported below
        return {};
    }

    void reportProgress() {
        if (!m_seq.progress) return;
        const std::size_t written = m_pool.writtenCount();
        if (written == m_reported) return;
        m_reported = written;
        SequenceProgress p;
        p.written = int(written);
        p.total = int(m_total);
        const auto done = m_pool.done();
        p.lastFrame = done.empty() ? -1 : done.back().frame;
        p.elapsedSeconds = msBetween(m_start, Clock::now()) / 1000.0;
        p.framesPerSecond = p.elapsedSeconds > 0 ? p.written / p.elapsedSeconds : 0.0;
        p.secondsLeft = p.framesPerSecond > 0 ? (p.total - p.written) / p.framesPerSecond : 0.0;
        m_seq.progress(p);
    }

    gpu::Device& m_device;
    const SequenceOptions& m_seq;
    std::size_t m_total;
    SequenceReport m_report;
    io::EncodePool m_pool;
    const Clock::time_point m_start = Clock::now();
    const double m_cpuStart = processCpuSeconds();
    std::deque<InFlight> m_inFlight;
    std::optional<Error> m_failure;
    std::size_t m_reported = 0;
    // What renderFrames was given, for naming the object of a non-finite frame.
    const Scene* m_scene = nullptr;
    const std::shared_ptr<gpu::SceneBuffers>* m_buffers = nullptr;
    const RenderOptions* m_options = nullptr;
};

} // namespace

Result<SequenceReport> Renderer::renderSequence(const PreparedScene& prepared,
                                                const RenderOptions& options,
                                                const SequenceOptions& seq) {
    if (!prepared) return makeError(ErrorCode::Usage, "renderSequence() needs a prepared scene");
    gpu::Device& device = *m_impl->device;
    LANTERN_TRY(render::checkOptions(device, options));
    const std::vector<int> frames = sequenceFrames(seq);
    LANTERN_TRY(checkSequence(seq, frames));
    LANTERN_TRY(render::checkCryptomatte(options.aovs));
    if (seq.writeCamera && options.views.size() > 1)
        return makeError(ErrorCode::Usage,
                         "a camera file describes one view: it cannot be written for " +
                             std::to_string(options.views.size()) + " views",
                         "--write-camera");
    removeStaleTemporaries(seq);
    SequenceRun run(device, seq, frames.size(), encoderThreads(seq));
    run.renderFrames(prepared.scene(), prepared.m_gpu, options, frames);
    run.drain();
    return run.finish();
}

} // namespace lantern
