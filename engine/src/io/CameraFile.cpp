// The camera JSON file (`lantern render --camera FILE`, `--write-camera`): read with every key
// checked and named in errors, written atomically as images are. Format: docs/cameras.md.
#include <lantern/CameraConventions.h>

#include <lantern/Version.h>

#include "io/AtomicFile.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>

namespace lantern {
namespace {

using nlohmann::json;

// A camera file is a few hundred bytes; anything much larger is not one.
constexpr std::uintmax_t kMaxCameraFileBytes = 1 << 20;

const std::set<std::string> kKeys = {"width",  "height", "K",          "convention",
                                     "world_to_camera", "camera_to_world", "near", "far",
                                     "projection", "gltf", "depth", "projection_matrix",
                                     "writer"};

// Errors name the file and the key.
struct Reader {
    std::string file;
    const json& doc;

    Error bad(const std::string& key, const std::string& what) const {
        return makeError(ErrorCode::InvalidInput, what, key, file);
    }

    Result<double> number(const json& v, const std::string& key) const {
        if (!v.is_number()) return bad(key, "must be a number, got " + std::string(v.type_name()));
        const double d = v.get<double>();
        if (!std::isfinite(d)) return bad(key, "must be a finite number");
        return d;
    }

    Result<int> size(const std::string& key) const {
        if (!doc.contains(key)) return bad(key, "is missing (the image size in pixels)");
        const json& v = doc[key];
        if (!v.is_number_integer() && !v.is_number_unsigned())
            return bad(key, "must be a whole number of pixels, got " + v.dump());
        const auto n = v.get<std::int64_t>();
        if (n < 1 || n > 16384) return bad(key, "must be 1 to 16384 pixels, got " + v.dump());
        return int(n);
    }

    // A row-major rows x cols matrix: nested rows ([[...], ...]) or rows*cols numbers.
    Result<std::vector<double>> matrix(const json& v, const std::string& key, int rows,
                                       int cols) const {
        const std::string shape = std::to_string(rows) + "x" + std::to_string(cols);
        std::vector<double> out;
        if (!v.is_array()) return bad(key, "must be a " + shape + " matrix (an array of rows)");
        if (v.size() == std::size_t(rows * cols) && !v[0].is_array()) {
            for (std::size_t i = 0; i < v.size(); ++i) {
                auto d = number(v[i], key + "[" + std::to_string(i) + "]");
                if (!d) return std::move(d).error();
                out.push_back(*d);
            }
            return out;
        }
        if (v.size() != std::size_t(rows))
            return bad(key, "must be a " + shape + " matrix: " + std::to_string(rows) +
                                " rows of " + std::to_string(cols) + " numbers, got " +
                                std::to_string(v.size()) + " rows");
        for (int r = 0; r < rows; ++r) {
            const json& row = v[std::size_t(r)];
            const std::string rowKey = key + "[" + std::to_string(r) + "]";
            if (!row.is_array() || row.size() != std::size_t(cols))
                return bad(rowKey, "must be a row of " + std::to_string(cols) + " numbers");
            for (int c = 0; c < cols; ++c) {
                auto d = number(row[std::size_t(c)], rowKey + "[" + std::to_string(c) + "]");
                if (!d) return std::move(d).error();
                out.push_back(*d);
            }
        }
        return out;
    }

    Result<Intrinsics> intrinsics() const;
    Result<glm::dmat4> viewFrom(const std::string& key, PoseConvention convention) const;
    Result<glm::dmat4> view(PoseConvention convention) const;
};

Result<Intrinsics> Reader::intrinsics() const {
    Intrinsics k;
    auto w = size("width");
    if (!w) return std::move(w).error();
    auto h = size("height");
    if (!h) return std::move(h).error();
    k.width = *w, k.height = *h;
    if (!doc.contains("K")) return bad("K", "is missing (the 3x3 intrinsic matrix, row-major)");
    auto m = matrix(doc["K"], "K", 3, 3);
    if (!m) return std::move(m).error();
    const auto& v = *m;
    if (v[1] != 0.0)
        return bad("K", "has a skew K[0][1] = " + std::to_string(v[1]) + ": Lantern draws "
                        "rectangular pixels only (skew must be 0)");
    if (v[3] != 0.0 || v[6] != 0.0 || v[7] != 0.0 || v[8] != 1.0)
        return bad("K", "must have the form [[fx, 0, cx], [0, fy, cy], [0, 0, 1]]");
    k.fx = v[0], k.cx = v[2], k.fy = v[4], k.cy = v[5];
    if (doc.contains("projection")) {
        const json& p = doc["projection"];
        if (p != "perspective" && p != "orthographic")
            return bad("projection", "must be \"perspective\" or \"orthographic\", got " +
                                         p.dump());
        k.orthographic = p == "orthographic";
    }
    if (doc.contains("near")) {
        auto n = number(doc["near"], "near");
        if (!n) return std::move(n).error();
        k.znear = *n;
        if (!k.orthographic && !(k.znear > 0.0)) return bad("near", "must be > 0");
    } else {
        k.znear = std::nan("");  // automatic
    }
    if (doc.contains("far")) {
        const json& f = doc["far"];
        if (f.is_null() || f == "inf") {
            k.zfar = kInfinity;
        } else {
            auto n = number(f, "far");
            if (!n) return std::move(n).error();
            k.zfar = *n;
        }
    }
    if (!(k.fx > 0.0) || !(k.fy > 0.0))
        return bad("K", "the focal lengths fx = K[0][0] and fy = K[1][1] must be > 0");
    // What is left to refuse is the depth range (or a view volume beyond single precision).
    auto ok = checkIntrinsics(k, "near/far");
    if (!ok) return bad(ok.error().object, ok.error().message);
    return k;
}

// Lantern's viewFromWorld from the matrix under `key`, in the file's convention.
Result<glm::dmat4> Reader::viewFrom(const std::string& key, PoseConvention convention) const {
    auto m = matrix(doc[key], key, 4, 4);
    if (!m) return std::move(m).error();
    glm::dmat4 pose(0.0);
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) pose[c][r] = (*m)[std::size_t(r * 4 + c)];
    if (auto ok = checkPose(pose, key); !ok) return bad(key, ok.error().message);
    // The rigid inverse is viewFromPose's glTF branch; the OpenCV branch flips y and z.
    const bool worldToCamera = key == "world_to_camera";
    if (convention == PoseConvention::Gltf)
        return worldToCamera ? pose : viewFromPose(pose, PoseConvention::Gltf);
    if (!worldToCamera) pose = viewFromPose(pose, PoseConvention::Gltf);
    return viewFromPose(pose, PoseConvention::OpenCV);
}

Result<glm::dmat4> Reader::view(PoseConvention convention) const {
    const bool w2c = doc.contains("world_to_camera"), c2w = doc.contains("camera_to_world");
    if (!w2c && !c2w)
        return bad("world_to_camera",
                   "is missing (the 4x4 pose, row-major; or give camera_to_world)");
    auto v = viewFrom(w2c ? "world_to_camera" : "camera_to_world", convention);
    if (!v || !(w2c && c2w)) return v;
    // Both given (a written file has both): they must describe the same camera.
    auto other = viewFrom("camera_to_world", convention);
    if (!other) return std::move(other).error();
    double worst = 0.0, scale = 1.0;
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) {
            worst = std::max(worst, std::abs((*v)[c][r] - (*other)[c][r]));
            scale = std::max(scale, std::abs((*v)[c][r]));
        }
    if (worst > 1e-9 * scale)
        return bad("camera_to_world", "is not the inverse of world_to_camera (give one of them)");
    return v;
}

} // namespace

Result<CameraModel> readCameraFile(const std::filesystem::path& path) {
    const std::string file = path.string();
    std::error_code ec;
    // A folder, device or pipe is refused before it is opened (a pipe would block).
    if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
        return makeError(ErrorCode::InvalidInput, "is not a regular file", {}, file);
    const auto bytes = std::filesystem::file_size(path, ec);
    if (ec) return makeError(ErrorCode::IoError, "cannot read the camera file: " + ec.message(), {}, file);
    if (bytes > kMaxCameraFileBytes)
        return makeError(ErrorCode::InvalidInput,
                         "is " + std::to_string(bytes) + " bytes: not a camera file (at most 1 MiB)",
                         {}, file);
    std::ifstream in(path, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    if (!in) return makeError(ErrorCode::IoError, "cannot read the camera file", {}, file);
    json doc;
    try {
        doc = json::parse(text.str());
    } catch (const json::exception& e) {
        return makeError(ErrorCode::InvalidInput, std::string("is not valid JSON: ") + e.what(), {},
                         file);
    }
    if (!doc.is_object())
        return makeError(ErrorCode::InvalidInput, "must hold a JSON object", {}, file);
    const Reader reader{file, doc};
    for (const auto& item : doc.items())
        if (!kKeys.count(item.key()))
            return reader.bad(item.key(), "is not a camera key (width, height, K, convention, "
                                          "world_to_camera, camera_to_world, near, far, "
                                          "projection)");
    PoseConvention convention = PoseConvention::OpenCV;
    if (doc.contains("convention")) {
        const json& c = doc["convention"];
        const auto parsed = c.is_string() ? parsePoseConvention(c.get<std::string>()) : std::nullopt;
        if (!parsed)
            return reader.bad("convention", "must be \"opencv\" or \"gltf\", got " + c.dump());
        convention = *parsed;
    }
    auto k = reader.intrinsics();
    if (!k) return std::move(k).error();
    auto v = reader.view(convention);
    if (!v) return std::move(v).error();
    return CameraModel{*k, poseFromView(*v, PoseConvention::OpenCV)};
}

namespace {

json rows(const glm::dmat4& m) {
    json out = json::array();
    for (int r = 0; r < 4; ++r) out.push_back({m[0][r], m[1][r], m[2][r], m[3][r]});
    return out;
}

} // namespace

std::string cameraJson(const CameraModel& camera, const glm::dmat4& clipFromView,
                       bool reversedDepth) {
    const Intrinsics& k = camera.intrinsics;
    const glm::dmat4 view = viewFromPose(camera.worldToCamera, PoseConvention::OpenCV);
    const glm::dmat4 cameraToWorld = poseFromView(view, PoseConvention::Gltf);
    json doc = json::object();
    doc["width"] = k.width;
    doc["height"] = k.height;
    doc["K"] = {{k.fx, 0.0, k.cx}, {0.0, k.fy, k.cy}, {0.0, 0.0, 1.0}};
    doc["convention"] = "opencv";
    doc["world_to_camera"] = rows(camera.worldToCamera);
    // OpenCV's camera_to_world is glTF's with the camera's y and z columns negated.
    doc["camera_to_world"] = rows(poseFromView(camera.worldToCamera, PoseConvention::Gltf));
    doc["gltf"] = {{"world_to_camera", rows(view)}, {"camera_to_world", rows(cameraToWorld)}};
    doc["projection"] = k.orthographic ? "orthographic" : "perspective";
    doc["near"] = k.znear;
    doc["far"] = std::isinf(k.zfar) ? json(nullptr) : json(k.zfar);
    doc["depth"] = reversedDepth ? "reversed" : "standard";
    doc["writer"] = std::string("lantern ") + versionString();
    doc["projection_matrix"] = rows(clipFromView);
    return doc.dump(2) + "\n";
}

namespace {

// A file already at `path` is replaced only when Lantern wrote it (its "writer" says so): a
// user's own JSON beside an image, or a link, is never overwritten.
Result<void> checkReplaceable(const std::filesystem::path& path) {
    std::error_code ec;
    const auto status = std::filesystem::symlink_status(path, ec);
    if (ec || status.type() == std::filesystem::file_type::not_found) return {};
    auto refuse = [&] {
        return makeError(ErrorCode::IoError,
                         "exists and is not a camera file Lantern wrote: not replaced (move it, "
                         "or choose another output name)",
                         {}, path.string());
    };
    if (status.type() != std::filesystem::file_type::regular) return refuse();
    const auto bytes = std::filesystem::file_size(path, ec);
    if (ec || bytes > kMaxCameraFileBytes) return refuse();
    std::ifstream in(path, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    const json doc = json::parse(text.str(), nullptr, false);
    if (!doc.is_object() || !doc.contains("writer") || !doc["writer"].is_string() ||
        doc["writer"].get<std::string>().rfind("lantern", 0) != 0)
        return refuse();
    return {};
}

} // namespace

Result<void> writeCameraFile(const std::filesystem::path& path, const CameraModel& camera,
                             const glm::dmat4& clipFromView, bool reversedDepth) {
    const std::string text = cameraJson(camera, clipFromView, reversedDepth);
    io::AtomicFile file(path);
    LANTERN_TRY(file.checkWritable());
    LANTERN_TRY(checkReplaceable(path));
    LANTERN_TRY(file.writeAll(text.data(), text.size()));
    return file.commit();
}

Result<void> writeImageCamera(const std::filesystem::path& imagePath, const Image& image) {
    auto camera = cameraModelOf(image);
    if (!camera) {
        Error e = std::move(camera).error();
        e.file = imagePath.string();
        return e;
    }
    return writeCameraFile(cameraFilePath(imagePath), *camera, image.camera->clipFromView,
                           image.camera->reversedDepth);
}

std::filesystem::path cameraFilePath(const std::filesystem::path& imagePath) {
    std::filesystem::path p = imagePath;
    return p.replace_extension(".json");
}

} // namespace lantern
