// EncodePool.h: encodes and writes finished frames on worker threads. The queue is bounded, so
// the renderer waits when encoders fall behind and memory stays flat however long the
// sequence; the first write error stops the pool and is reported.
#pragma once

#include <lantern/Image.h>
#include <lantern/FileOptions.h>
#include <lantern/Image.h>
#include <lantern/Result.h>

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace lantern::io {

class EncodePool {
public:
    struct Job {
        int frame = 0;
        Image image;
        std::vector<std::string> paths;
        /// Write the image's camera JSON beside each path (cameraFilePath), before the image,
        /// so that a finished image always has its camera.
        bool writeCamera = false;
    };
    struct Done {
        int frame = 0;
        double encodeMs = 0.0;
    };

    /// `threads` workers; at most `capacity` jobs wait in the queue.
    EncodePool(int threads, std::size_t capacity, ExrOptions exr);
    ~EncodePool();  ///< finishes the queued jobs and joins the workers
    EncodePool(const EncodePool&) = delete;
    EncodePool& operator=(const EncodePool&) = delete;

    /// Queues a job, waiting while the queue is full. False (job dropped) once a job failed.
    bool push(Job job);
    /// Waits until every queued job is written, calling `tick` about every 200 ms and after
    /// each frame written.
    void finish(const std::function<void()>& tick = {});
    bool failed() const;
    std::optional<Error> firstError() const;
    std::vector<Done> done() const;
    std::size_t writtenCount() const;
    std::uint64_t clampedValues() const;
    std::size_t peakQueued() const;

private:
    void work();

    ExrOptions m_exr;
    mutable std::mutex m_mutex;
    std::condition_variable m_changed;
    std::deque<Job> m_queue;
    std::size_t m_capacity;
    std::size_t m_busy = 0;
    bool m_closing = false;
    std::optional<Error> m_error;
    std::vector<Done> m_done;
    std::uint64_t m_clamped = 0;
    std::size_t m_peak = 0;
    std::vector<std::thread> m_threads;
};

} // namespace lantern::io
