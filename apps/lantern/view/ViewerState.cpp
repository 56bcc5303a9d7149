// ViewerState: the animation range and choice of `lantern view`, the camera changes its keys
// and panel ask for (take-over, scene cameras, frame all, headlight), and its keys' help.
#include "view/ViewerState.h"

#include "common/CliSupport.h"

#include <algorithm>
#include <cstdio>

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

double ViewerState::perspectiveAspect(int width, int height) const {
    const int w = std::max(width, 1), h = std::max(height, 1);
    if (!quad) return double(w) / double(h);
    const int vw = std::max(w - w / 2, 1), vh = std::max(h - h / 2, 1);
    return double(vw) / double(vh);
}

void ViewerState::ensureFree(double aspect) {
    if (camera.isFree()) return;
    auto placement = resolveCameraPlacement(*scene, camera.base(), aspect, root, time);
    if (!placement) {
        report(placement.error());
        return;
    }
    camera.takeOver(*placement);
}

void ViewerState::applyRequests(double aspect) {
    if (cameraPicked) {
        cameraPicked = false;
        CameraSpec spec = camera.base();
        spec.source =
            sceneCamera < 0 ? CameraSpec::Source::Automatic : CameraSpec::Source::SceneCamera;
        spec.sceneCamera = sceneCamera;
        spec.lookAt.reset();
        spec.projection.reset();
        if (auto p = resolveCameraPlacement(*scene, spec, aspect, root, time)) {
            camera.setBase(spec);
            fly = false;
        } else {
            report(p.error());
            sceneCamera = -1;
        }
    }
    if (viewRequested) {
        ensureFree(aspect);
        if (camera.isFree()) camera.lookFrom(*viewRequested, aspect);
        viewRequested.reset();
        frameAllRequested = false;
    }
    if (frameAllRequested) {
        frameAllRequested = false;
        ensureFree(aspect);
        if (camera.isFree()) camera.frameAll(aspect);
    }
    if (!camera.isFree()) fly = false;
}

void ViewerState::updateHeadlight(double aspect) {
    RenderOptions& o = options;
    if (!headlight) {
        o.lightsViewFromWorld.reset();
        return;
    }
    if (o.lightsViewFromWorld) return;
    auto placement = resolveCameraPlacement(*scene, camera.spec(aspect), aspect, root, time);
    if (placement)
        o.lightsViewFromWorld = placement->viewFromWorld;
    else
        report(placement.error());
}

RenderOptions ViewerState::frameOptions(int width, int height) const {
    RenderOptions o = options;
    o.width = std::max(width, 1);
    o.height = std::max(height, 1);
    o.root = root;
    const CameraSpec spec = camera.spec(perspectiveAspect(width, height));
    o.camera = spec;
    o.views.clear();
    if (quad) o.views = quadLayout(o.width, o.height, spec);
    return o;
}

std::string ViewerState::statusText() const {
    const RenderOptions& o = options;
    std::string s = std::string(toString(o.shading.value_or(ShadingMode::Phong))) + ", " +
                    toString(o.specular.value_or(SpecularModel::Blinn)) +
                    (camera.orthographic() ? ", ortho" : "") + (fly ? ", fly" : "") +
                    (quad ? ", quad" : "") + (headlight ? ", headlight" : "");
    char t[64];
    std::snprintf(t, sizeof t, ", t=%.2f s%s", time, playing ? "" : " (paused)");
    return s + t;
}

const std::vector<KeyHelp>& viewerKeys() {
    static const std::vector<KeyHelp> keys = {
        {"left drag", "orbit about the pivot (fly mode: look around)"},
        {"middle drag, shift + left drag", "pan"},
        {"right drag, ctrl + left drag, wheel", "zoom"},
        {"Tab", "fly mode on/off (W A S D move, Q E down/up, shift faster)"},
        {"F", "frame all"},
        {"keypad 1, 3, 7 (Ctrl: the opposite side), 9, 0",
         "view from the front, right, top (back, left, bottom), the isometric corner, the "
         "automatic three-quarter view (as --view), framing all"},
        {"C", "next scene camera (the panel picks any)"},
        {"Space", "play / pause the animation"},
        {"Left, Right", "step one frame back / forward (pauses)"},
        {"Home", "back to the animation's start"},
        {"1, 2, 3", "flat, gouraud, phong shading"},
        {"B", "specular term: Blinn / Phong"},
        {"P", "perspective / orthographic projection"},
        {"L", "local viewer on/off"},
        {"T", "two-sided lighting on/off"},
        {"O", "transparency: sorted, exact, weighted"},
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
