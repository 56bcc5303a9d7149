// CvCameraCli.h: the computer-vision camera options of `lantern render` and `lantern view`:
// --camera FILE (a camera JSON file; an integer stays a scene camera index), --intrinsics,
// --world-to-camera, --camera-to-world (docs/cameras.md, "Computer-vision cameras").
#pragma once

#include <lantern/Lantern.h>

#include <string>

namespace lantern::cli {

/// True when a --camera value is a scene camera index (digits only) rather than a file path.
bool isCameraIndex(const std::string& text);
/// The scene camera index of a --camera value that isCameraIndex (INT_MAX when too large, which
/// the renderer then refuses as a camera that does not exist).
int cameraIndex(const std::string& text);

/// --camera FILE: the file's intrinsics and pose into `spec` (errors name the file and key; a
/// value that names no file says it is neither an index nor a file).
Result<void> applyCameraFile(const std::string& path, CameraSpec& spec);

/// --intrinsics FX,FY,CX,CY[,NEAR,FAR] (pixels, OpenCV's convention; FAR may be inf) for a
/// width x height image into `spec`.
Result<void> applyIntrinsics(const std::string& text, int width, int height, CameraSpec& spec);

/// --world-to-camera (OpenCV axes) or --camera-to-world (glTF axes): 16 numbers, row-major.
Result<void> applyPose(const std::string& text, PoseConvention convention,
                       const std::string& option, CameraSpec& spec);

/// The image size of a camera file's intrinsics against --width/--height: the file's size when
/// they were not given, InvalidInput naming --width or --height when one differs.
Result<void> takeCameraSize(const CameraSpec& spec, bool widthGiven, bool heightGiven,
                            int& width, int& height);

} // namespace lantern::cli
