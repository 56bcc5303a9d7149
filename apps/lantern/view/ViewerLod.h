// ViewerLod.h: the viewer's level of detail (RenderOptions::lodError) while the camera moves.
// While it moves, the bound in pixels grows by half after each frame slower than the budget
// and shrinks by a third after each frame faster than half of it (from 0.5 pixel up to 16),
// so that orbiting a scene too large for the device stays interactive; once the camera has
// stood still for a fifth of a second (one frame without a move at least), the frame is drawn
// at the bound the command line asked for (0, the default: the exact picture), and stays so
// until the camera moves again.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>
#include <optional>
#include <string>

namespace lantern::cli {

class ViewerLod {
public:
    using Clock = std::chrono::steady_clock;
    static constexpr double kBudgetMs = 100.0;  ///< ten frames a second
    static constexpr double kSettleSeconds = 0.2;

    /// The bound for the frame about to be drawn: `camera` is the camera as the command line
    /// says it (a change is a move), `requested` the command line's bound, `lastFrameMs` how
    /// long the previous frame took.
    double bound(const std::string& camera, double requested, double lastFrameMs, Clock::time_point now) {
        record(lastFrameMs, now);
        if (camera != m_camera) {
            const bool first = m_camera.empty();
            m_camera = camera;
            if (!first) m_movedAt = now;
        }
        const bool moving = m_movedAt && now - *m_movedAt < std::chrono::duration<double>(kSettleSeconds);
        if (!moving) {
            if (m_movedAt) m_settling = *m_movedAt;  // this frame is the settled one
            m_movedAt.reset();
            m_lastBound = requested;
            return requested;
        }
        if (lastFrameMs > kBudgetMs)
            m_moving = std::clamp(std::max(m_moving, 0.5) * 1.5, 0.5, 16.0);
        else if (lastFrameMs < 0.5 * kBudgetMs)
            m_moving = m_moving * 2.0 / 3.0 < 0.5 ? 0.0 : m_moving * 2.0 / 3.0;
        m_lastBound = std::max(m_moving, requested);
        m_largest = std::max(m_largest, m_lastBound);
        m_wasMoving = true;
        return m_lastBound;
    }
    bool moving() const { return m_movedAt.has_value(); }

    /// --stats: the frames drawn while the camera moved, and how long after its last move the
    /// settled (exact) picture was done.
    void print() const {
        if (m_movingMs.empty()) return;
        std::vector<double> ms = m_movingMs;
        std::sort(ms.begin(), ms.end());
        std::fprintf(stderr,
                     "level of detail while moving: %zu frames, median %.2f ms (%.1f fps), bound up "
                     "to %.2f px; the last settled picture done %.0f ms after the camera stopped\n",
                     ms.size(), ms[ms.size() / 2], 1000.0 / ms[ms.size() / 2], m_largest, m_settledAfterMs);
    }

private:
    // The previous frame took `lastFrameMs`, ending now: a moving frame, or the settled one.
    void record(double lastFrameMs, Clock::time_point now) {
        if (m_wasMoving) m_movingMs.push_back(lastFrameMs);
        m_wasMoving = false;
        if (m_settling) {
            m_settledAfterMs = std::chrono::duration<double, std::milli>(now - *m_settling).count();
            m_settling.reset();
        }
    }

    std::string m_camera;
    std::optional<Clock::time_point> m_settling;  // the last move, until the settled frame is done
    bool m_wasMoving = false;
    std::vector<double> m_movingMs;
    double m_lastBound = 0.0, m_largest = 0.0, m_settledAfterMs = 0.0;
    std::optional<Clock::time_point> m_movedAt;
    double m_moving = 0.0;  ///< the bound while moving, kept between moves
};

} // namespace lantern::cli
