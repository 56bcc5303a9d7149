// ViewerStats.h: the viewer's frame times: the recent median the window title shows, and the
// summary --stats prints when the viewer exits.
#pragma once

#include <chrono>
#include <lantern/Window.h>
#include <optional>
#include <vector>

namespace lantern::cli {

class ViewerStats {
public:
    using Clock = std::chrono::steady_clock;

    /// Counts a presented frame whose input was sampled at `sampled`.
    void add(Clock::time_point sampled, const WindowFrame& frame);
    int presented() const { return m_presented; }
    /// The median frame time (ms) of the frames since the last answer, at most every 0.5 s;
    /// nothing between (or when no frame came).
    std::optional<double> recentMs();
    /// One line on stderr: frames, size, present mode, the frame-time median and spread and
    /// the median of each part of a frame. The first frames (pipeline compiles) are left out.
    void print(const WindowTarget& target) const;

private:
    int m_presented = 0;
    Clock::time_point m_lastPresent{}, m_lastTitle{};
    std::vector<double> m_intervals, m_cpuMs, m_waitMs, m_presentMs, m_gpuMs, m_recentIntervals;
};

} // namespace lantern::cli
