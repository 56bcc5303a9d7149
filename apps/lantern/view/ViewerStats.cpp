// The viewer's frame-time statistics: intervals between presented frames and the parts of each.
#include "view/ViewerStats.h"

#include <algorithm>
#include <cstdio>

namespace lantern::cli {
namespace {

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

double percentile(std::vector<double> v, double p) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    return v[std::min(v.size() - 1, std::size_t(p * double(v.size() - 1) + 0.5))];
}

} // namespace

void ViewerStats::add(Clock::time_point sampled, const WindowFrame& frame) {
    ++m_presented;
    if (m_lastPresent != Clock::time_point{}) {
        const double ms =
            std::chrono::duration<double, std::milli>(sampled - m_lastPresent).count();
        m_intervals.push_back(ms);
        m_recentIntervals.push_back(ms);
    }
    m_lastPresent = sampled;
    m_cpuMs.push_back(frame.stats.cpuMs);
    m_waitMs.push_back(frame.stats.waitMs);
    m_presentMs.push_back(frame.presentMs);
    if (frame.stats.gpuMs >= 0) m_gpuMs.push_back(frame.stats.gpuMs);
}

std::optional<double> ViewerStats::recentMs() {
    const auto now = Clock::now();
    if (now - m_lastTitle < std::chrono::milliseconds(500) || m_recentIntervals.empty())
        return std::nullopt;
    m_lastTitle = now;
    const double ms = median(m_recentIntervals);
    m_recentIntervals.clear();
    return ms;
}

void ViewerStats::print(const WindowTarget& t) const {
    // The first frames compile pipelines; they are left out.
    const std::size_t skip = std::min<std::size_t>(10, m_intervals.size() / 4);
    auto tail = [&](const std::vector<double>& v) {
        return std::vector<double>(v.begin() + std::ptrdiff_t(std::min(skip, v.size())), v.end());
    };
    std::fprintf(
        stderr,
        "lantern: view: %d frames at %dx%d, %s, %u frames in flight, %u swapchain images; "
        "frame time median %.2f ms (p10 %.2f, p90 %.2f); per frame (median): planning and "
        "recording %.2f ms, waiting for the frame slot and image %.2f ms, presenting %.2f ms, "
        "GPU %.2f ms\n",
        m_presented, t.width(), t.height(), toString(t.presentMode()), t.framesInFlight(),
        t.imageCount(), median(tail(m_intervals)), percentile(tail(m_intervals), 0.1),
        percentile(tail(m_intervals), 0.9), median(tail(m_cpuMs)), median(tail(m_waitMs)),
        median(tail(m_presentMs)), median(tail(m_gpuMs)));
}

} // namespace lantern::cli
