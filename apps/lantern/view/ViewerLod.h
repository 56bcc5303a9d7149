// ViewerLod.h: the viewer's level of detail (RenderOptions::lodError) while the camera moves.
// While it moves, the bound in pixels grows by half after each frame slower than the budget
// and shrinks by a third after each frame faster than half of it (from 0.5 pixel up to 16),
// so that orbiting a scene too large for the device stays interactive; once the camera has
// stood still for a quarter of a second, the frame is drawn at the bound the command line
// asked for (0, the default: the exact picture), and stays so until the camera moves again.
#pragma once

#include <algorithm>
#include <chrono>
#include <optional>
#include <string>

namespace lantern::cli {

class ViewerLod {
public:
    using Clock = std::chrono::steady_clock;
    static constexpr double kBudgetMs = 100.0;  ///< ten frames a second
    static constexpr double kSettleSeconds = 0.25;

    /// The bound for the frame about to be drawn: `camera` is the camera as the command line
    /// says it (a change is a move), `requested` the command line's bound, `lastFrameMs` how
    /// long the previous frame took.
    double bound(const std::string& camera, double requested, double lastFrameMs, Clock::time_point now) {
        if (camera != m_camera) {
            const bool first = m_camera.empty();
            m_camera = camera;
            if (!first) m_movedAt = now;
        }
        const bool moving = m_movedAt && now - *m_movedAt < std::chrono::duration<double>(kSettleSeconds);
        if (!moving) {
            m_movedAt.reset();
            m_moving = std::max(m_moving, requested);
            return requested;
        }
        if (lastFrameMs > kBudgetMs)
            m_moving = std::clamp(std::max(m_moving, 0.5) * 1.5, 0.5, 16.0);
        else if (lastFrameMs < 0.5 * kBudgetMs)
            m_moving = m_moving * 2.0 / 3.0 < 0.5 ? 0.0 : m_moving * 2.0 / 3.0;
        return std::max(m_moving, requested);
    }
    bool moving() const { return m_movedAt.has_value(); }

private:
    std::string m_camera;
    std::optional<Clock::time_point> m_movedAt;
    double m_moving = 0.0;  ///< the bound while moving, kept between moves
};

} // namespace lantern::cli
