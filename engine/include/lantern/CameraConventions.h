// CameraConventions.h: computer-vision cameras in Lantern. OpenCV intrinsics (fx, fy, cx, cy in
// pixels, an image of width x height) and poses in OpenCV's axes (world_to_camera: x right,
// y down, z forward) or glTF's (camera_to_world: x right, y up, looking down -z), converted
// exactly, in double precision, to Lantern's viewFromWorld and projection; the conversion back
// from any rendered camera; and the camera JSON file of `lantern render --camera FILE` and
// `--write-camera` (docs/cameras.md, "Computer-vision cameras").
//
// Pixel convention (OpenCV's): pixel (i, j) covers [i - 0.5, i + 0.5] x [j - 0.5, j + 0.5], so
// pixel centres sit at integer coordinates, (0, 0) is the centre of the top-left pixel, v grows
// downwards, and a principal point in the middle of the image is cx = (width - 1) / 2,
// cy = (height - 1) / 2. A point X in OpenCV camera axes lands at u = fx X.x / X.z + cx,
// v = fy X.y / X.z + cy.
#pragma once

#include <lantern/Camera.h>
#include <lantern/Export.h>
#include <lantern/Image.h>
#include <lantern/Result.h>

#include <glm/mat4x4.hpp>

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace lantern {

/// OpenCV's pinhole intrinsics K = [fx 0 cx; 0 fy cy; 0 0 1] for a width x height image (no
/// skew), with the near and far planes Lantern draws between. `orthographic` makes it an
/// orthographic camera in the same pixel convention: u = fx X.x + cx, v = fy X.y + cy (fx and
/// fy in pixels per world unit).
struct Intrinsics {
    double fx = 0.0, fy = 0.0;  ///< focal lengths in pixels (> 0)
    double cx = 0.0, cy = 0.0;  ///< principal point in pixels, pixel centres at integers
    int width = 0, height = 0;  ///< the image the intrinsics are for, in pixels
    /// Distance to the near plane along the view axis: > 0 for a pinhole; any value but `zfar`
    /// for orthographic. 0 (the default) for a pinhole, or a NaN for either, means automatic
    /// (docs/cameras.md: fitted to the scene's bounds when rendered).
    double znear = 0.0;
    double zfar = kInfinity;  ///< +infinity: none for a pinhole, automatic for orthographic
    bool orthographic = false;

    /// K as a row-major 3x3 array (the JSON file's "K").
    std::array<double, 9> matrix() const noexcept {
        return {fx, 0.0, cx, 0.0, fy, cy, 0.0, 0.0, 1.0};
    }
};

/// True when the near plane is left to Lantern (see Intrinsics::znear).
LANTERN_API bool automaticNear(const Intrinsics& intrinsics) noexcept;

/// Which axes a pose matrix is written in.
enum class PoseConvention {
    OpenCV,  ///< world_to_camera [R | t]: camera x right, y down, z forward (OpenCV, COLMAP)
    Gltf,    ///< camera_to_world: a glTF camera node's world matrix (x right, y up, looks down -z)
};
LANTERN_API const char* toString(PoseConvention convention) noexcept;  ///< "opencv", "gltf"
LANTERN_API std::optional<PoseConvention> parsePoseConvention(std::string_view text) noexcept;

/// Refuses (InvalidInput naming `object`) intrinsics that cannot render: fx or fy <= 0, any
/// non-finite value, a size outside 1..16384, a near plane <= 0 or a far plane <= near for a
/// pinhole, far == near for orthographic, and a projection beyond single precision
/// (checkProjection's limits). An automatic near passes.
LANTERN_API Result<void> checkIntrinsics(const Intrinsics& intrinsics, const std::string& object);

/// Refuses a pose that is not rigid: non-finite entries, a last row other than (0, 0, 0, 1), or
/// a 3x3 part that is not a rotation (R R^T differs from the identity by more than 1e-6, or
/// det R < 0: a mirror). `object` names the input ("world_to_camera", "--camera-to-world").
LANTERN_API Result<void> checkPose(const glm::dmat4& pose, const std::string& object);

/// Lantern's viewFromWorld (right-handed eye space looking down -Z, +Y up) from a pose:
///   OpenCV: diag(1, -1, -1, 1) * world_to_camera (exact: only signs change);
///   Gltf:   the rigid inverse of camera_to_world, [R^T | -R^T t].
/// The pose should pass checkPose.
LANTERN_API glm::dmat4 viewFromPose(const glm::dmat4& pose, PoseConvention convention);
/// The inverse of viewFromPose: the pose of a camera whose viewFromWorld is `viewFromWorld`.
LANTERN_API glm::dmat4 poseFromView(const glm::dmat4& viewFromWorld, PoseConvention convention);

/// The projection drawing exactly what the intrinsics see in their width x height image: a
/// Frustum whose planes pass through the outer edges of the border pixels
/// (left = -(cx + 0.5) n / fx, right = (width - 0.5 - cx) n / fx, top = (cy + 0.5) n / fy,
/// bottom = -(height - 0.5 - cy) n / fy), or the Orthographic box of the same edges; between
/// `znear` and `zfar`, which must not be automatic here (the renderer fills them in).
LANTERN_API Projection projectionFromIntrinsics(const Intrinsics& intrinsics);

/// The inverse: the intrinsics (near and far included) of a Vulkan clip-from-view matrix that
/// Lantern renders a width x height image with (perspective, frustum or orthographic, either
/// depth mode: `reversedDepth` says which). nullopt for a matrix of another form (skewed, or
/// singular).
LANTERN_API std::optional<Intrinsics> intrinsicsFromClip(const glm::dmat4& clipFromView,
                                                         int width, int height,
                                                         bool reversedDepth);

/// A camera in computer-vision terms: intrinsics and the pose as OpenCV's world_to_camera.
struct CameraModel {
    Intrinsics intrinsics;
    glm::dmat4 worldToCamera{1.0};  ///< OpenCV axes; viewFromPose(.., OpenCV) gives the view
};

/// The camera a rendered image was made with (its CameraMetadata and size); InvalidInput when
/// the image carries no camera.
LANTERN_API Result<CameraModel> cameraModelOf(const Image& image);

/// The camera JSON file beside an image: the same path with the extension ".json".
LANTERN_API std::filesystem::path cameraFilePath(const std::filesystem::path& imagePath);

/// Reads a camera JSON file: "width", "height", "K" (3x3, row-major: [[fx, 0, cx], [0, fy, cy],
/// [0, 0, 1]] or nine numbers), "world_to_camera" (4x4 row-major, OpenCV axes) or, with
/// "convention": "gltf", "camera_to_world" (4x4 row-major, glTF axes), optional "near" and
/// "far" (a number; null or "inf" for an infinite far plane) and "projection": "perspective"
/// (the default) or "orthographic". InvalidInput naming the file and the key for anything
/// missing, mistyped or out of range; IoError when it cannot be read.
LANTERN_API Result<CameraModel> readCameraFile(const std::filesystem::path& path);

/// The camera JSON text of `camera` (as writeCameraFile writes it), with `clipFromView` (the
/// Vulkan projection matrix the image was rendered with, in the depth mode `reversedDepth`
/// says) as "projection_matrix", for information: reading ignores it, "gltf" and "depth".
LANTERN_API std::string cameraJson(const CameraModel& camera, const glm::dmat4& clipFromView,
                                   bool reversedDepth = true);

/// Writes cameraJson() atomically, as images are written (temporary file beside it, fsync,
/// rename): complete or absent.
LANTERN_API Result<void> writeCameraFile(const std::filesystem::path& path,
                                         const CameraModel& camera,
                                         const glm::dmat4& clipFromView,
                                         bool reversedDepth = true);

/// Writes the camera JSON of a rendered image beside `imagePath` (cameraFilePath).
LANTERN_API Result<void> writeImageCamera(const std::filesystem::path& imagePath,
                                          const Image& image);

} // namespace lantern
