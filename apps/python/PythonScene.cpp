// The Python module's C++ side: scenes whose lights the host edits, render options from
// keyword arguments, the renderer that keeps its device and uploads between calls, and
// pictures handed to NumPy without a copy.
#define GLM_ENABLE_EXPERIMENTAL
#include "PythonScene.h"

#include <glm/gtx/quaternion.hpp>
#include <pybind11/stl.h>

#include <algorithm>
#include <atomic>
#include <cmath>

namespace lantern::python {
namespace {

glm::dvec3 vec3(const std::vector<double>& v, const char* keyword) {
    if (v.size() != 3)
        throw py::value_error(std::string(keyword) + ": expected 3 numbers, got " +
                              std::to_string(v.size()));
    return {v[0], v[1], v[2]};
}

void check(const Result<void>& r) {
    if (!r) raise(r.error());
}

// The camera keywords: look_at, perspective, ortho and the scene's camera N.
void applyCamera(const RenderArgs& a, RenderOptions& o) {
    if (a.camera) {
        o.camera.source = CameraSpec::Source::SceneCamera;
        o.camera.sceneCamera = *a.camera;
    }
    if (a.lookAt) {
        if (a.lookAt->size() != 3)
            throw py::value_error("look_at: expected (eye, target, up)");
        LookAt la{vec3((*a.lookAt)[0], "look_at eye"), vec3((*a.lookAt)[1], "look_at target"),
                  vec3((*a.lookAt)[2], "look_at up")};
        check(checkLookAt(la, "look_at"));
        o.camera.lookAt = la;
    }
    if (a.perspective && a.ortho) throw py::value_error("give perspective or ortho, not both");
    if (a.perspective) {
        const auto& p = *a.perspective;
        if (p.size() != 3 && p.size() != 4)
            throw py::value_error("perspective: expected (fovy_deg, near, far) or (fovy_deg, "
                                  "aspect, near, far)");
        const double aspect = p.size() == 4 ? p[1] : 0.0; // 0: the image's aspect
        o.camera.projection = Projection::makePerspective(p[0] * 3.14159265358979323846 / 180.0, aspect,
                                                          p[p.size() - 2], p.back());
        check(checkProjection(*o.camera.projection, "perspective"));
    }
    if (a.ortho) {
        const auto& p = *a.ortho;
        if (p.size() != 6) throw py::value_error("ortho: expected (l, r, b, t, n, f)");
        o.camera.projection = Projection::makeOrtho(p[0], p[1], p[2], p[3], p[4], p[5]);
        check(checkProjection(*o.camera.projection, "ortho"));
    }
}

// A 4x4 row-major pose from nested sequences (a NumPy array works), checked to be rigid.
glm::dmat4 poseMatrix(const std::vector<std::vector<double>>& rows, const char* keyword) {
    glm::dmat4 m(0.0);
    if (rows.size() != 4) throw py::value_error(std::string(keyword) + ": expected a 4x4 matrix");
    for (int r = 0; r < 4; ++r) {
        if (rows[std::size_t(r)].size() != 4)
            throw py::value_error(std::string(keyword) + ": expected a 4x4 matrix");
        for (int c = 0; c < 4; ++c) m[c][r] = rows[std::size_t(r)][std::size_t(c)];
    }
    check(checkPose(m, keyword));
    return m;
}

// intrinsics=(fx, fy, cx, cy) or a 3x3 K = [[fx, 0, cx], [0, fy, cy], [0, 0, 1]].
Intrinsics intrinsicsOf(const RenderArgs& a) {
    Intrinsics k;
    k.width = a.width, k.height = a.height;
    std::vector<double> v;
    try {
        const auto rows = a.intrinsics.cast<std::vector<std::vector<double>>>();
        if (rows.size() != 3 || rows[0].size() != 3 || rows[1].size() != 3 || rows[2].size() != 3)
            throw py::value_error("intrinsics: expected (fx, fy, cx, cy) or a 3x3 K");
        if (rows[0][1] != 0.0 || rows[1][0] != 0.0 || rows[2][0] != 0.0 || rows[2][1] != 0.0 ||
            rows[2][2] != 1.0)
            throw py::value_error("intrinsics: K must be [[fx, 0, cx], [0, fy, cy], [0, 0, 1]] "
                                  "(no skew)");
        v = {rows[0][0], rows[1][1], rows[0][2], rows[1][2]};
    } catch (const py::cast_error&) {
        v = a.intrinsics.cast<std::vector<double>>();
    }
    if (v.size() != 4) throw py::value_error("intrinsics: expected (fx, fy, cx, cy) or a 3x3 K");
    k.fx = v[0], k.fy = v[1], k.cx = v[2], k.cy = v[3];
    if (a.znear) k.znear = *a.znear;
    if (a.zfar) k.zfar = *a.zfar;
    check(checkIntrinsics(k, "intrinsics"));
    return k;
}

// The computer-vision keywords: intrinsics, world_to_camera, camera_to_world, a camera file.
void applyCvCamera(const RenderArgs& a, RenderOptions& o) {
    if (a.worldToCamera && a.cameraToWorld)
        throw py::value_error("give world_to_camera or camera_to_world, not both");
    if ((a.worldToCamera || a.cameraToWorld) && a.lookAt)
        throw py::value_error("a pose places the camera: leave out look_at");
    if (!a.intrinsics.is_none() && (a.perspective || a.ortho))
        throw py::value_error("intrinsics are the projection: leave out perspective and ortho");
    if ((a.znear || a.zfar) && a.intrinsics.is_none())
        throw py::value_error("near and far go with intrinsics");
    if (a.cameraFile) {
        if (a.lookAt || a.perspective || a.ortho || !a.intrinsics.is_none() || a.worldToCamera ||
            a.cameraToWorld)
            throw py::value_error("a camera file sets the whole camera: leave out the other "
                                  "camera keywords");
        auto camera = readCameraFile(*a.cameraFile);
        if (!camera) raise(camera.error());
        if (camera->intrinsics.width != a.width || camera->intrinsics.height != a.height)
            throw py::value_error("camera: the file is for a " +
                                  std::to_string(camera->intrinsics.width) + "x" +
                                  std::to_string(camera->intrinsics.height) +
                                  " image; pass that width and height");
        o.camera = CameraSpec::fromPose(camera->intrinsics, camera->worldToCamera);
        return;
    }
    if (!a.intrinsics.is_none()) o.camera.intrinsics = intrinsicsOf(a);
    if (a.worldToCamera)
        o.camera.viewFromWorld =
            viewFromPose(poseMatrix(*a.worldToCamera, "world_to_camera"), PoseConvention::OpenCV);
    if (a.cameraToWorld)
        o.camera.viewFromWorld =
            viewFromPose(poseMatrix(*a.cameraToWorld, "camera_to_world"), PoseConvention::Gltf);
}

std::atomic<std::uint64_t> g_nextRendererId{1};

} // namespace

void raise(const Error& error) {
    const std::string text = std::string(errorCodeName(error.code)) + ": " + error.describe();
    if (error.code == ErrorCode::InvalidInput || error.code == ErrorCode::Usage)
        throw py::value_error(text);
    if (error.code == ErrorCode::IoError) {
        // A file that cannot be read or written: Python's OSError, as open() raises.
        PyErr_SetString(PyExc_OSError, text.c_str());
        throw py::error_already_set();
    }
    throw LanternException(text);
}

void PyScene::addLight(const std::string& type, std::optional<std::vector<double>> position,
                       std::optional<std::vector<double>> direction, std::vector<double> color,
                       std::vector<double> ambient, std::vector<double> attenuation,
                       double spotCutoffDeg, double spotExponent, const std::string& name) {
    Light light;
    light.name = name;
    if (type == "directional")
        light.type = LightType::Directional;
    else if (type == "point")
        light.type = LightType::Point;
    else if (type == "spot")
        light.type = LightType::Spot;
    else
        throw py::value_error("light type \"" + type + "\": directional, point or spot");
    light.diffuse = light.specular = vec3(color, "color");
    light.ambient = vec3(ambient, "ambient");
    light.attenuation = vec3(attenuation, "attenuation");
    light.spotCutoffDeg = light.type == LightType::Spot ? spotCutoffDeg : 180.0;
    light.spotExponent = spotExponent;
    Node node;
    node.name = name.empty() ? type + " light" : name;
    node.light = int(scene->lights.size());
    if (light.type != LightType::Directional) {
        if (!position) throw py::value_error("a " + type + " light needs position=(x, y, z)");
        node.translation = vec3(*position, "position");
    }
    if (light.type != LightType::Point) {
        if (!direction) throw py::value_error("a " + type + " light needs direction=(x, y, z)");
        const glm::dvec3 d = vec3(*direction, "direction");
        if (!(glm::length(d) > 0.0)) throw py::value_error("direction: must not be zero");
        // A glTF light shines down its node's -Z.
        node.rotation = glm::rotation(glm::dvec3(0.0, 0.0, -1.0), glm::normalize(d));
    }
    scene->lights.push_back(light);
    scene->nodes.push_back(node);
    if (scene->roots.empty()) scene->roots.push_back({});
    for (SceneRoot& root : scene->roots)
        root.nodes.push_back(int(scene->nodes.size()) - 1);
    if (auto r = scene->validate(); !r) {
        scene->lights.pop_back();
        scene->nodes.pop_back();
        for (SceneRoot& root : scene->roots)
            root.nodes.pop_back();
        raise(r.error());
    }
    ++generation;
}

void PyScene::clearLights() {
    for (Node& n : scene->nodes)
        n.light = -1;
    scene->lights.clear();
    ++generation;
}

py::list PyScene::lights() const {
    py::list out;
    for (const Light& l : scene->lights) {
        py::dict d;
        d["name"] = l.name;
        d["type"] = l.type == LightType::Directional ? "directional"
                    : l.type == LightType::Point     ? "point"
                                                     : "spot";
        d["color"] = py::make_tuple(l.diffuse.x, l.diffuse.y, l.diffuse.z);
        d["ambient"] = py::make_tuple(l.ambient.x, l.ambient.y, l.ambient.z);
        out.append(d);
    }
    return out;
}

RenderOptions renderOptions(const RenderArgs& a) {
    RenderOptions o;
    o.width = a.width;
    o.height = a.height;
    if (a.shading) {
        o.shading = parseShadingMode(*a.shading);
        if (!o.shading) throw py::value_error("shading \"" + *a.shading + "\": flat, gouraud or phong");
    }
    if (a.specular) {
        o.specular = parseSpecularModel(*a.specular);
        if (!o.specular) throw py::value_error("specular \"" + *a.specular + "\": blinn or phong");
    }
    o.msaa = a.msaa;
    if (!(a.pointSize >= 1.0 && a.pointSize <= 255.0))
        throw py::value_error("point_size " + std::to_string(a.pointSize) + ": in [1, 255]");
    if (!(a.lineWidth >= 1.0 && a.lineWidth <= 255.0))
        throw py::value_error("line_width " + std::to_string(a.lineWidth) + ": in [1, 255]");
    o.pointSize = a.pointSize;
    o.lineWidth = a.lineWidth;
    if (a.background) {
        // As --background: R,G,B is opaque; R,G,B,A is premultiplied here.
        const auto& b = *a.background;
        if (b.size() != 3 && b.size() != 4)
            throw py::value_error("background: expected (r, g, b) or (r, g, b, a), linear");
        const double alpha = b.size() == 4 ? b[3] : 1.0;
        if (!(alpha >= 0.0 && alpha <= 1.0)) throw py::value_error("background: alpha in [0, 1]");
        o.background = glm::vec4(float(b[0] * alpha), float(b[1] * alpha), float(b[2] * alpha),
                                 float(alpha));
    }
    applyCamera(a, o);
    applyCvCamera(a, o);
    if (a.twoSided) o.twoSided = *a.twoSided;
    if (a.localViewer) o.localViewer = *a.localViewer;
    o.clamp = a.clamp;
    o.glCompat = a.glCompat;
    o.aovs.depth = a.depth;
    o.aovs.normal = a.normal;
    for (const std::string& name : a.aov)
        if (!enableAov(o.aovs, name))
            throw py::value_error("aov: unknown AOV \"" + name + "\" (" + aovNames() + ")");
    if (a.unlitExact && a.msaa != 1)
        throw py::value_error("unlit_exact: needs msaa=1 (no anti-aliasing)");
    o.unlitExact = a.unlitExact;
    o.shadows.all = a.shadows;
    if (a.shadowFilter) {
        const std::string& f = *a.shadowFilter;
        if (f == "hardware") o.shadows.filter = ShadowFilter::Hardware;
        else if (f == "pcf") o.shadows.filter = ShadowFilter::Pcf;
        else if (f == "pcss") o.shadows.filter = ShadowFilter::Pcss;
        else throw py::value_error("shadow_filter \"" + f + "\": hardware, pcf or pcss");
    }
    if (a.shadowCascades) {
        if (*a.shadowCascades < 1 || *a.shadowCascades > 8)
            throw py::value_error("shadow_cascades " + std::to_string(*a.shadowCascades) + ": 1 to 8");
        o.shadows.cascades = *a.shadowCascades;
    }
    if (!(a.lodError >= 0.0 && a.lodError <= 1e6))
        throw py::value_error("lod_error " + std::to_string(a.lodError) + ": 0 to 1e6 pixels");
    o.lodError = a.lodError;
    o.culling = a.culling;
    if (a.transparency) {
        const std::string& t = *a.transparency;
        if (t == "sorted") o.transparency = TransparencyMethod::Sorted;
        else if (t == "exact") o.transparency = TransparencyMethod::Exact;
        else if (t == "weighted") o.transparency = TransparencyMethod::Weighted;
        else throw py::value_error("transparency \"" + t + "\": sorted, exact or weighted");
    }
    return o;
}

PyRenderer::PyRenderer(const std::string& device, bool validation)
    : id(g_nextRendererId.fetch_add(1)) {
    RendererDesc desc;
    desc.deviceName = device;
    desc.validation = validation;
    auto r = Renderer::create(desc);
    if (!r) raise(r.error());
    renderer.emplace(std::move(*r));
}

py::object PyRenderer::render(PyScene& s, const RenderArgs& a) {
    const RenderOptions options = renderOptions(a);
    const auto& counts = renderer->device().msaaSampleCounts;
    if (std::find(counts.begin(), counts.end(), a.msaa) == counts.end()) {
        std::string supported;
        for (int c : counts) {
            if (!supported.empty()) supported += ", ";
            supported += std::to_string(c);
        }
        std::string message = "msaa " + std::to_string(a.msaa) + ": ";
        message += renderer->device().name;
        message += " supports " + supported;
        throw py::value_error(message);
    }
    // The upload is kept with the scene: a loop of renders reuses it, and only a structural
    // edit (a light added or removed) or another renderer uploads again. Moved vertices are
    // written again for their primitives alone.
    if (s.preparedFor != id || s.preparedGeneration != s.generation) {
        auto prepared = renderer->prepare(s.scene);
        if (!prepared) raise(prepared.error());
        s.prepared = std::move(*prepared);
        s.preparedFor = id;
        s.preparedGeneration = s.generation;
        ++s.uploads;
        s.movedVertices.clear();
    }
    for (auto it = s.movedVertices.begin(); it != s.movedVertices.end();) {
        if (auto r = renderer->updateVertices(s.prepared, it->first, it->second); !r)
            raise(r.error());
        it = s.movedVertices.erase(it);
    }
    auto image = renderer->render(s.prepared, options, a.time);
    if (!image) raise(image.error());
    if (!a.aov.empty()) return toAovArrays(std::move(*image));
    return toArrays(std::move(*image), a.depth, a.normal);
}

py::dict PyRenderer::device() const {
    const DeviceInfo& d = renderer->device();
    py::dict out;
    out["name"] = d.name;
    out["type"] = d.type;
    out["driver"] = d.driver;
    out["msaa"] = d.msaaSampleCounts;
    return out;
}

py::object toArrays(Image&& image, bool depth, bool normal) {
    auto* held = new Image(std::move(image));
    py::capsule owner(held, [](void* p) { delete static_cast<Image*>(p); });
    const py::ssize_t h = held->height, w = held->width, f = sizeof(float);
    py::array_t<float> rgba({h, w, py::ssize_t(4)}, {w * 4 * f, 4 * f, f}, held->rgba.data(),
                            owner);
    if (!depth && !normal) return rgba;
    py::list planes;
    planes.append(rgba);
    if (depth) planes.append(py::array_t<float>({h, w}, {w * f, f}, held->depth.data(), owner));
    if (normal)
        planes.append(py::array_t<float>({h, w, py::ssize_t(3)}, {w * 3 * f, 3 * f, f},
                                         held->normal.data(), owner));
    return py::tuple(planes);
}

py::object toAovArrays(Image&& image) {
    auto* held = new Image(std::move(image));
    py::capsule owner(held, [](void* p) { delete static_cast<Image*>(p); });
    const py::ssize_t h = held->height, w = held->width, f = 4;
    py::array_t<float> rgba({h, w, py::ssize_t(4)}, {w * 4 * f, 4 * f, f}, held->rgba.data(),
                            owner);
    py::dict planes;
    auto floats = [&](const char* name, std::vector<float>& p, py::ssize_t c) {
        if (p.empty()) return;
        if (c == 1) planes[name] = py::array_t<float>({h, w}, {w * f, f}, p.data(), owner);
        else planes[name] = py::array_t<float>({h, w, c}, {w * c * f, c * f, f}, p.data(), owner);
    };
    auto ids = [&](const char* name, std::vector<std::uint32_t>& p) {
        if (!p.empty())
            planes[name] = py::array_t<std::uint32_t>({h, w}, {w * f, f}, p.data(), owner);
    };
    floats("depth", held->depth, 1);
    floats("range", held->range, 1);
    floats("normal", held->normal, 3);
    floats("world_normal", held->worldNormal, 3);
    floats("uv", held->uv, 2);
    ids("instance", held->instance);
    ids("mesh", held->mesh);
    ids("primitive", held->primitive);
    ids("material", held->material);
    ids("semantic", held->semantic);
    // Cryptomatte ranks per pixel: id0, coverage0, id1, ... (ids are hashes read as floats).
    for (CryptomatteLayer& layer : held->cryptomatte)
        floats(layer.name == "CryptoObject" ? "crypto_object" : "crypto_material", layer.ranks,
               py::ssize_t(layer.levels) * 2);
    return py::make_tuple(rgba, planes);
}

Image fromArrays(const py::array_t<float, py::array::c_style | py::array::forcecast>& rgba,
                 const py::object& depth, const py::object& normal) {
    if (rgba.ndim() != 3 || rgba.shape(2) != 4)
        throw py::value_error("rgba: expected an array of shape (height, width, 4)");
    Image image(int(rgba.shape(1)), int(rgba.shape(0)));
    std::copy(rgba.data(), rgba.data() + image.rgba.size(), image.rgba.begin());
    if (!depth.is_none()) {
        auto d = depth.cast<py::array_t<float, py::array::c_style | py::array::forcecast>>();
        if (d.ndim() != 2 || d.shape(0) != image.height || d.shape(1) != image.width)
            throw py::value_error("depth: expected an array of shape (height, width)");
        image.depth.assign(d.data(), d.data() + image.pixelCount());
    }
    if (!normal.is_none()) {
        auto n = normal.cast<py::array_t<float, py::array::c_style | py::array::forcecast>>();
        if (n.ndim() != 3 || n.shape(0) != image.height || n.shape(1) != image.width ||
            n.shape(2) != 3)
            throw py::value_error("normal: expected an array of shape (height, width, 3)");
        image.normal.assign(n.data(), n.data() + image.pixelCount() * 3);
    }
    return image;
}

} // namespace lantern::python
