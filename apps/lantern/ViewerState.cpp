// ViewerState: the animation range and choice of `lantern view`.
#include "ViewerState.h"

#include <algorithm>

namespace lantern::cli {

double ViewerState::startTime() const {
    double t = 0.0;
    bool any = false;
    for (const Animation& a : scene->animations) {
        t = any ? std::min(t, a.startTime()) : a.startTime();
        any = true;
    }
    return t;
}

double ViewerState::endTime() const {
    double t = startTime();
    for (const Animation& a : scene->animations) t = std::max(t, a.endTime());
    return t;
}

void ViewerState::applyAnimationChoice() {
    if (animation < 0 || animation >= int(animations.size()))
        scene->animations = animations;
    else
        scene->animations = {animations[std::size_t(animation)]};
}

} // namespace lantern::cli
