// Worker threads writing EXR/PNG frames from a bounded queue.
#include "io/EncodePool.h"
#include "io/image/ImageIo.h"

#include <lantern/CameraConventions.h>

#include <algorithm>
#include <chrono>

namespace lantern::io {

EncodePool::EncodePool(int threads, std::size_t capacity, ExrOptions exr)
    : m_exr(exr), m_capacity(std::max<std::size_t>(capacity, 1)) {
    m_exr.clampedCount = nullptr;
    for (int i = 0; i < std::max(threads, 1); ++i) m_threads.emplace_back([this] { work(); });
}

EncodePool::~EncodePool() {
    {
        std::lock_guard lock(m_mutex);
        m_closing = true;
    }
    m_changed.notify_all();
    for (std::thread& t : m_threads) t.join();
}

bool EncodePool::push(Job job) {
    std::unique_lock lock(m_mutex);
    m_changed.wait(lock, [&] { return m_queue.size() < m_capacity || m_error; });
    if (m_error) return false;
    m_queue.push_back(std::move(job));
    m_peak = std::max(m_peak, m_queue.size() + m_busy);
    lock.unlock();
    m_changed.notify_all();
    return true;
}

void EncodePool::work() {
    for (;;) {
        Job job;
        {
            std::unique_lock lock(m_mutex);
            m_changed.wait(lock, [&] { return !m_queue.empty() || m_closing; });
            if (m_queue.empty()) return;
            job = std::move(m_queue.front());
            m_queue.pop_front();
            ++m_busy;
        }
        m_changed.notify_all();
        const auto t0 = std::chrono::steady_clock::now();
        std::optional<Error> error;
        std::uint64_t clamped = 0;
        for (const std::string& path : job.paths) {
            ExrOptions options = m_exr;
            std::uint64_t c = 0;
            options.clampedCount = &c;
            if (auto r = job.writeCamera ? writeImageCamera(path, job.image) : Result<void>{};
                !r) {
                error = r.error();
                break;
            }
            if (auto r = io::writeImage(path, job.image, options); !r) {
                error = r.error();
                break;
            }
            clamped += c;
        }
        const double ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        {
            std::lock_guard lock(m_mutex);
            --m_busy;
            m_clamped += clamped;
            if (error) {
                if (!m_error) m_error = std::move(error);
                m_queue.clear();  // stop: what is not written yet is not started
            } else {
                m_done.push_back({job.frame, ms});
            }
        }
        m_changed.notify_all();
    }
}

void EncodePool::finish(const std::function<void()>& tick) {
    std::unique_lock lock(m_mutex);
    std::size_t seen = m_done.size();
    while (!(m_queue.empty() && m_busy == 0)) {
        m_changed.wait_for(lock, std::chrono::milliseconds(200));
        if (tick && m_done.size() != seen) {
            seen = m_done.size();
            lock.unlock();
            tick();
            lock.lock();
        }
    }
}

bool EncodePool::failed() const {
    std::lock_guard lock(m_mutex);
    return m_error.has_value();
}

std::optional<Error> EncodePool::firstError() const {
    std::lock_guard lock(m_mutex);
    return m_error;
}

std::vector<EncodePool::Done> EncodePool::done() const {
    std::lock_guard lock(m_mutex);
    return m_done;
}

std::size_t EncodePool::writtenCount() const {
    std::lock_guard lock(m_mutex);
    return m_done.size();
}

std::uint64_t EncodePool::clampedValues() const {
    std::lock_guard lock(m_mutex);
    return m_clamped;
}

std::size_t EncodePool::peakQueued() const {
    std::lock_guard lock(m_mutex);
    return m_peak;
}

} // namespace lantern::io
