// resolveCameraPlacement(): the camera a render would use, for hosts that move it themselves.
#include <lantern/Renderer.h>

#include "frame/Frame.h"

#include <cmath>

namespace lantern {

Result<CameraPlacement> resolveCameraPlacement(const Scene& scene, const CameraSpec& spec,
                                               double aspect, int root, double time) {
    if (root < -1 || root >= int(scene.roots.size()))
        return makeError(ErrorCode::InvalidInput,
                         "scene " + std::to_string(root) + " does not exist", "root");
    if (!(aspect > 0.0) || !std::isfinite(aspect) || !std::isfinite(time))
        return makeError(ErrorCode::InvalidInput, "aspect must be > 0 and time finite", "aspect");
    const Pose pose = evaluatePose(scene, root < 0 ? scene.defaultRoot : root, time);
    auto rc = frame::resolveCamera(scene, pose, spec, aspect, DepthMode::ReversedZ, "camera");
    if (!rc) return std::move(rc).error();
    return CameraPlacement{rc->viewFromWorld, rc->projection, rc->description};
}

} // namespace lantern
