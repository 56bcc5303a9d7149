// ViewerState: the animation range and choice of `lantern view`, and its keys.
#include "view/ViewerState.h"

#include <algorithm>

namespace lantern::cli {

double ViewerState::startTime() const {
    return animationRange(*scene).start;
}

double ViewerState::endTime() const {
    return animationRange(*scene).end;
}

void ViewerState::applyAnimationChoice() {
    if (animation < 0 || animation >= int(animations.size()))
        scene->animations = animations;
    else
        scene->animations = {animations[std::size_t(animation)]};
}

const std::vector<KeyHelp>& viewerKeys() {
    static const std::vector<KeyHelp> keys = {
        {"left drag", "orbit about the pivot (fly mode: look around)"},
        {"middle drag, shift + left drag", "pan"},
        {"right drag, ctrl + left drag, wheel", "zoom"},
        {"Tab", "fly mode on/off (W A S D move, Q E down/up, shift faster)"},
        {"F", "frame all"},
        {"C", "next scene camera (the panel picks any)"},
        {"Space", "play / pause the animation"},
        {"Left, Right", "step one frame back / forward (pauses)"},
        {"Home", "back to the animation's start"},
        {"1, 2, 3", "flat, gouraud, phong shading"},
        {"B", "specular term: Blinn / Phong"},
        {"P", "perspective / orthographic projection"},
        {"L", "local viewer on/off"},
        {"T", "two-sided lighting on/off"},
        {"Z", "wireframe overlay on/off"},
        {"N", "normals display on/off"},
        {"V", "quad view (top, front, side, perspective)"},
        {"H", "headlight: lights follow the camera / stay in the world"},
        {"F1", "this help"},
        {"F2", "side panel"},
        {"F12", "screenshot (EXR and PNG of the picture)"},
        {"Esc", "quit"},
    };
    return keys;
}

} // namespace lantern::cli
