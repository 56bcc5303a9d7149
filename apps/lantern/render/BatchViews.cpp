// The views of a batch (--views, Batch.h): orbits and turntables around the up axis, the named
// views of automatic framing, and pose files. Orbits and named views frame each scene's
// bounding sphere (CameraSpec::Framing), so every view of a scene is at the same distance.
#include "render/Batch.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <sstream>
#include <sys/stat.h>

namespace lantern::cli {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kMaxRingViews = 3600;

// "orbit7" for view 7 of orbit:12: the index zero-padded to the width of the largest, so the
// names sort in the order of the views.
std::string ringName(const std::string& kind, int i, int count) {
    std::string index = std::to_string(i);
    const std::size_t width = std::to_string(count - 1).size();
    return kind + std::string(width - index.size(), '0') + index;
}

// N views around the up axis (+Y) at `elevation` (radians), the first at `azimuth` (radians
// from the front, +Z, towards +X), each looking at the centre of the scene's bounds.
std::vector<BatchView> ring(const std::string& kind, int count, double elevation,
                            double azimuth) {
    std::vector<BatchView> views;
    for (int i = 0; i < count; ++i) {
        const double a = azimuth + 2.0 * kPi * i / count;
        const glm::dvec3 from(std::cos(elevation) * std::sin(a), std::sin(elevation),
                              std::cos(elevation) * std::cos(a));
        CameraSpec spec;
        spec.source = CameraSpec::Source::Framing;
        spec.framingDirection = -from;
        views.push_back({ringName(kind, i, count), spec});
    }
    return views;
}

Result<int> ringCount(const std::string& item, std::size_t colon) {
    const std::string n = item.substr(colon + 1);
    char* end = nullptr;
    const long count = std::strtol(n.c_str(), &end, 10);
    if (n.empty() || *end != '\0' || count < 1 || count > kMaxRingViews)
        return makeError(ErrorCode::Usage,
                         "\"" + item + "\": the number of views must be 1 to " +
                             std::to_string(kMaxRingViews),
                         "--views");
    return int(count);
}

Result<glm::dvec3> vec3(const nlohmann::json& j, const std::string& object) {
    if (!j.is_array() || j.size() != 3)
        return makeError(ErrorCode::InvalidInput, "must be an array of 3 numbers", object);
    glm::dvec3 v;
    for (int i = 0; i < 3; ++i) {
        if (!j[std::size_t(i)].is_number() || !std::isfinite(j[std::size_t(i)].get<double>()))
            return makeError(ErrorCode::InvalidInput, "must be an array of 3 finite numbers",
                             object);
        v[i] = j[std::size_t(i)].get<double>();
    }
    return v;
}

// camera_to_world (glTF's camera axes: looking down -Z, +Y up), 16 numbers row-major, as a
// lookAt. The rotation must be orthonormal: a lookAt keeps no scale or shear.
Result<LookAt> lookAtFromMatrix(const nlohmann::json& j, const std::string& object) {
    if (!j.is_array() || j.size() != 16)
        return makeError(ErrorCode::InvalidInput, "must be 16 numbers (a 4x4 matrix, row-major)",
                         object);
    double m[4][4];
    for (std::size_t i = 0; i < 16; ++i) {
        if (!j[i].is_number() || !std::isfinite(j[i].get<double>()))
            return makeError(ErrorCode::InvalidInput, "must hold finite numbers", object);
        m[i / 4][i % 4] = j[i].get<double>();
    }
    const glm::dvec3 x(m[0][0], m[1][0], m[2][0]), y(m[0][1], m[1][1], m[2][1]),
        z(m[0][2], m[1][2], m[2][2]), t(m[0][3], m[1][3], m[2][3]);
    const double tol = 1e-4;
    const bool orthonormal = std::abs(glm::length(x) - 1) < tol && std::abs(glm::length(y) - 1) < tol &&
                             std::abs(glm::length(z) - 1) < tol && std::abs(glm::dot(x, y)) < tol &&
                             std::abs(glm::dot(y, z)) < tol && std::abs(glm::dot(x, z)) < tol &&
                             std::abs(glm::dot(glm::cross(x, y), z) - 1) < tol;
    if (!orthonormal || m[3][0] != 0 || m[3][1] != 0 || m[3][2] != 0 || m[3][3] != 1)
        return makeError(ErrorCode::InvalidInput,
                         "must be a rigid transform (an orthonormal right-handed rotation, a "
                         "translation, last row 0 0 0 1)",
                         object);
    return LookAt{t, t - z, y};
}

Result<BatchView> poseView(const nlohmann::json& p, std::size_t i) {
    const std::string object = "[" + std::to_string(i) + "]";
    if (!p.is_object()) return makeError(ErrorCode::InvalidInput, "must be an object", object);
    BatchView view;
    view.name = "pose" + std::to_string(i);
    if (p.contains("name")) {
        if (!p["name"].is_string() || p["name"].get<std::string>().empty())
            return makeError(ErrorCode::InvalidInput, "must be a non-empty string", object + ".name");
        view.name = p["name"].get<std::string>();
    }
    if (view.name.find_first_of("/{}") != std::string::npos || view.name == "." || view.name == "..")
        return makeError(ErrorCode::InvalidInput, "may not contain /, { or }, nor be . or ..",
                         object + ".name");
    CameraSpec spec;
    spec.source = CameraSpec::Source::Framing;
    if (p.contains("look_at") == p.contains("camera_to_world"))
        return makeError(ErrorCode::InvalidInput, "needs either look_at or camera_to_world", object);
    if (p.contains("look_at")) {
        const nlohmann::json& la = p["look_at"];
        const std::string o = object + ".look_at";
        if (!la.is_object()) return makeError(ErrorCode::InvalidInput, "must be an object", o);
        auto eye = vec3(la.value("eye", nlohmann::json()), o + ".eye");
        auto center = vec3(la.value("center", nlohmann::json()), o + ".center");
        auto up = la.contains("up") ? vec3(la["up"], o + ".up") : Result<glm::dvec3>(glm::dvec3(0, 1, 0));
        for (auto* r : {&eye, &center, &up})
            if (!*r) return std::move(*r).error();
        spec.lookAt = LookAt{*eye, *center, *up};
    } else {
        auto la = lookAtFromMatrix(p["camera_to_world"], object + ".camera_to_world");
        if (!la) return std::move(la).error();
        spec.lookAt = *la;
    }
    LANTERN_TRY(checkLookAt(*spec.lookAt, object));
    const double yfov = p.value("yfov_deg", 45.0), znear = p.value("near", 0.01);
    const double zfar = p.contains("far") && p["far"].is_null() ? kInfinity : p.value("far", kInfinity);
    spec.projection = Projection::makePerspective(yfov * kPi / 180.0, 0.0, znear, zfar);
    LANTERN_TRY(checkProjection(*spec.projection, object));
    view.camera = spec;
    return view;
}

} // namespace

Result<std::vector<BatchView>> readPoseFile(const std::string& path, std::uint64_t maxBytes) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode))
        return makeError(ErrorCode::IoError, "cannot read the pose file (not a regular file)",
                         "--views", path);
    if (std::uint64_t(st.st_size) > maxBytes)
        return makeError(ErrorCode::InvalidInput, "the pose file is larger than --max-size",
                         "--views", path);
    std::ifstream in(path, std::ios::binary);
    nlohmann::json doc = nlohmann::json::parse(in, nullptr, false);
    if (doc.is_discarded())
        return makeError(ErrorCode::InvalidInput, "not valid JSON", "--views", path);
    if (!doc.is_array() || doc.empty())
        return makeError(ErrorCode::InvalidInput, "must be a non-empty JSON array of poses",
                         "--views", path);
    std::vector<BatchView> views;
    for (std::size_t i = 0; i < doc.size(); ++i) {
        try {
            auto v = poseView(doc[i], i);
            if (!v) {
                Error e = std::move(v).error();
                e.file = path;
                return e;
            }
            views.push_back(std::move(*v));
        } catch (const nlohmann::json::exception&) {
            // value() throws when a key holds the wrong type ("near": "x").
            return makeError(ErrorCode::InvalidInput,
                             "yfov_deg, near and far must be numbers (far may be null: infinite)",
                             "[" + std::to_string(i) + "]", path);
        }
    }
    return views;
}

Result<std::vector<BatchView>> parseViews(const std::string& text, std::uint64_t maxBytes) {
    if (text.empty()) return std::vector<BatchView>{{"default", std::nullopt}};
    std::vector<BatchView> views;
    std::stringstream items(text);
    std::string item;
    while (std::getline(items, item, ',')) {
        const std::size_t colon = item.find(':');
        const std::string kind = item.substr(0, colon);
        if (colon != std::string::npos && (kind == "orbit" || kind == "turntable")) {
            auto count = ringCount(item, colon);
            if (!count) return std::move(count).error();
            // orbit: the three-quarter view's elevation (30 degrees) and first azimuth (45);
            // turntable: level with the centre, starting from the front.
            const auto more = kind == "orbit" ? ring(kind, *count, kPi / 6.0, kPi / 4.0)
                                              : ring(kind, *count, 0.0, 0.0);
            views.insert(views.end(), more.begin(), more.end());
        } else if (auto named = parseViewDirection(item)) {
            views.push_back({item, CameraSpec::framed(*named)});
        } else if (item.size() > 5 && item.substr(item.size() - 5) == ".json") {
            auto poses = readPoseFile(item, maxBytes);
            if (!poses) return std::move(poses).error();
            views.insert(views.end(), poses->begin(), poses->end());
        } else {
            return makeError(ErrorCode::Usage,
                             "unknown view \"" + item +
                                 "\" (orbit:N, turntable:N, three-quarter, front, back, left, "
                                 "right, top, bottom, iso, or a .json pose file)",
                             "--views");
        }
    }
    if (views.empty()) return makeError(ErrorCode::Usage, "no view given", "--views");
    return views;
}

} // namespace lantern::cli
