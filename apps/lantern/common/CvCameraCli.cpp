// The computer-vision camera options: camera JSON files, OpenCV intrinsics and poses.
#include "common/CvCameraCli.h"

#include "common/CliSupport.h"

#include <climits>
#include <filesystem>

namespace lantern::cli {

bool isCameraIndex(const std::string& text) {
    if (text.empty()) return false;
    for (char c : text)
        if (c < '0' || c > '9') return false;
    return true;
}

int cameraIndex(const std::string& text) {
    long long n = 0;
    for (char c : text) {
        n = n * 10 + (c - '0');
        if (n > INT_MAX) return INT_MAX;
    }
    return int(n);
}

Result<void> applyCameraFile(const std::string& path, CameraSpec& spec) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec))
        return makeError(ErrorCode::InvalidInput,
                         "\"" + path + "\" is neither a scene camera index (a whole number) nor a "
                         "camera file that exists",
                         "--camera");
    auto camera = readCameraFile(path);
    if (!camera) return std::move(camera).error();
    spec.source = CameraSpec::Source::GlDefault;  // every part is replaced
    spec.viewFromWorld = viewFromPose(camera->worldToCamera, PoseConvention::OpenCV);
    spec.intrinsics = camera->intrinsics;
    return {};
}

Result<void> applyIntrinsics(const std::string& text, int width, int height, CameraSpec& spec) {
    const std::size_t count = std::count(text.begin(), text.end(), ',') + 1;
    auto v = parseNumbers(text, count == 6 ? 6 : 4, "--intrinsics",
                          {false, false, false, false, false, true});
    if (!v) return std::move(v).error();
    Intrinsics k;
    k.fx = (*v)[0], k.fy = (*v)[1], k.cx = (*v)[2], k.cy = (*v)[3];
    k.width = width, k.height = height;
    if (count == 6) k.znear = (*v)[4], k.zfar = (*v)[5];
    if (count == 6 && !(k.znear > 0.0))
        return makeError(ErrorCode::InvalidInput, "near must be > 0", "--intrinsics");
    LANTERN_TRY(checkIntrinsics(k, "--intrinsics"));
    spec.intrinsics = k;
    return {};
}

Result<void> applyPose(const std::string& text, PoseConvention convention,
                       const std::string& option, CameraSpec& spec) {
    auto v = parseNumbers(text, 16, option);
    if (!v) return std::move(v).error();
    glm::dmat4 pose(0.0);
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) pose[c][r] = (*v)[std::size_t(r * 4 + c)];
    LANTERN_TRY(checkPose(pose, option));
    spec.viewFromWorld = viewFromPose(pose, convention);
    return {};
}

Result<void> takeCameraSize(const CameraSpec& spec, bool widthGiven, bool heightGiven,
                            int& width, int& height) {
    if (!spec.intrinsics) return {};
    const Intrinsics& k = *spec.intrinsics;
    for (auto [given, value, wanted, option] :
         {std::tuple{widthGiven, width, k.width, "--width"},
          std::tuple{heightGiven, height, k.height, "--height"}})
        if (given && value != wanted)
            return makeError(ErrorCode::InvalidInput,
                             std::to_string(value) + " differs from the camera file's " +
                                 std::to_string(wanted) + " (leave it out, or give the same)",
                             option);
    width = k.width;
    height = k.height;
    return {};
}

} // namespace lantern::cli
