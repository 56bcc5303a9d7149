// The Python module `lantern._lantern` (pybind11): scenes, the renderer, images as NumPy arrays,
// writing EXR/PNG, and the build and device facts. lantern/__init__.py adds the pure-Python
// parts (frames of an animation, the module-level render). docs/python.md is its guide.
#include "PythonScene.h"

#include <pybind11/stl.h>

namespace py = pybind11;
using namespace lantern;
using namespace lantern::python;

namespace {

std::shared_ptr<PyScene> loadPyScene(const std::string& pathOrBuiltin, const std::string& variant,
                                     const std::string& up) {
    LoadOptions options;
    options.variant = variant;
    const auto axis = parseUpAxis(up);
    if (!axis) raise(makeError(ErrorCode::Usage, "up must be \"y\" or \"z\", not \"" + up + "\"", "up"));
    options.up = *axis;
    auto loaded = lantern::loadScene(pathOrBuiltin, options);
    if (!loaded) raise(loaded.error());
    auto s = std::make_shared<PyScene>();
    s->scene = std::make_shared<Scene>(std::move(*loaded));
    return s;
}

py::dict summaryOf(const PyScene& s) {
    const SceneSummary sum = summarize(*s.scene);
    py::dict d;
    d["nodes"] = sum.nodes;
    d["meshes"] = sum.meshes;
    d["triangles"] = sum.triangles;
    d["lines"] = sum.lines;
    d["points"] = sum.points;
    d["vertices"] = sum.vertices;
    d["materials"] = sum.materials;
    d["lights"] = sum.lights;
    d["cameras"] = sum.cameras;
    d["animations"] = sum.animations;
    return d;
}

void writeImageFile(const std::string& path, const py::array_t<float, py::array::c_style |
                                                                      py::array::forcecast>& rgba,
                    const py::object& depth, const py::object& normal, bool half) {
    const Image image = fromArrays(rgba, depth, normal);
    ExrOptions exr;
    exr.half = half;
    if (auto r = writeImage(path, image, exr); !r) raise(r.error());
}

py::dict buildFacts() {
    const BuildInfo b = buildInfo();
    py::dict d;
    d["version"] = b.version;
    d["commit"] = b.commit;
    d["build_type"] = b.buildType;
    d["compiler"] = b.compiler;
    d["library"] = b.library;
    d["vulkan_loader"] = b.vulkanLoader;
    return d;
}

py::list deviceList(const std::string& name) {
    auto list = listDevices(name);
    if (!list) raise(list.error());
    py::list out;
    for (const DeviceListing& d : list->devices) {
        py::dict e;
        e["name"] = d.name;
        e["type"] = d.type;
        e["driver"] = d.driver;
        e["vulkan"] = d.apiVersion;
        e["usable"] = d.usable;
        e["why_not"] = d.whyNot;
        e["msaa"] = d.msaaSampleCounts;
        e["chosen"] = d.chosen;
        out.append(e);
    }
    return out;
}

void defineScene(py::module_& m) {
    py::class_<PyScene, std::shared_ptr<PyScene>>(
        m, "Scene", "A scene: loaded from a scene file or a built-in; its lights can be edited")
        .def_property_readonly(
            "path", [](const PyScene& s) { return s.scene->sourcePath; },
            "The file it came from, or builtin:NAME")
        .def_property_readonly(
            "animation_range",
            [](const PyScene& s) {
                const TimeRange r = animationRange(*s.scene);
                return py::make_tuple(r.start, r.end);
            },
            "(start, end) in seconds of all its animations; (0, 0) without any")
        .def_property_readonly("summary", &summaryOf, "Counts of nodes, meshes, triangles...")
        .def_property_readonly(
            "variants", [](const PyScene& s) { return s.scene->variants; },
            "The material variants' names (glTF KHR_materials_variants); load(path, variant=NAME) "
            "draws one")
        .def_property_readonly("lights", &PyScene::lights, "The lights: name, type, colours")
        .def("add_light", &PyScene::addLight, py::arg("type"), py::kw_only(),
             py::arg("position") = py::none(), py::arg("direction") = py::none(),
             py::arg("color") = std::vector<double>{1.0, 1.0, 1.0},
             py::arg("ambient") = std::vector<double>{0.0, 0.0, 0.0},
             py::arg("attenuation") = std::vector<double>{1.0, 0.0, 0.0},
             py::arg("spot_cutoff_deg") = 45.0, py::arg("spot_exponent") = 0.0,
             py::arg("name") = std::string(),
             "Adds a GL light in world space: directional (direction), point (position) or "
             "spot (both); color is its diffuse and specular, linear RGB")
        .def("clear_lights", &PyScene::clearLights,
             "Removes every light (a scene without lights gets GL's default light 0)")
        .def_property_readonly("nodes", &PyScene::nodes,
                               "The nodes: name, mesh, translation, rotation (x, y, z, w), "
                               "scale, matrix (4 rows, or None), children")
        .def("set_transform", &PyScene::setNodeTransform, py::arg("node"), py::kw_only(),
             py::arg("translation") = py::none(), py::arg("rotation") = py::none(),
             py::arg("scale") = py::none(), py::arg("matrix") = py::none(),
             "Moves node `node` (index or name) relative to its parent: any of translation, "
             "rotation (a quaternion x, y, z, w) and scale, or a 4x4 matrix given as rows; "
             "the next render uses it (no upload)")
        .def("positions", &PyScene::positions, py::arg("mesh"), py::arg("primitive") = 0,
             "A copy of a primitive's vertex positions: an (n, 3) float32 array")
        .def("normals", &PyScene::normals, py::arg("mesh"), py::arg("primitive") = 0,
             "A copy of a primitive's vertex normals, (n, 3) float32, or None")
        .def("set_vertices", &PyScene::setVertices, py::arg("mesh"), py::arg("positions"),
             py::kw_only(), py::arg("primitive") = 0, py::arg("normals") = py::none(),
             "Replaces a primitive's vertex positions (and normals when given; else they are "
             "kept): (n, 3) arrays of the same n; the next render writes that primitive's "
             "vertices again, not the whole scene")
        .def_property_readonly(
            "upload_count", [](const PyScene& s) { return s.uploads; },
            "How many times the whole scene was uploaded to a device (a light added or "
            "removed, or another renderer, uploads it again; moved nodes and vertices do not)")
        .def("__repr__", [](const PyScene& s) {
            return "<lantern.Scene " + s.scene->sourcePath + ">";
        });
}

const char* const kRenderDoc =
    "Renders `scene` at `time` seconds: a (height, width, 4) float32 array of linear, "
    "premultiplied RGBA; with depth=True and/or normal=True a tuple (rgba, depth, "
    "normal) of the planes asked for; with aov=[names] (docs/aovs.md) a tuple (rgba, "
    "dict) of float32 data planes and uint32 id planes by name. Computer-vision cameras: "
    "intrinsics=(fx, fy, cx, cy) or a 3x3 K in OpenCV pixels (centres at integers), "
    "near/far, world_to_camera (OpenCV axes) or camera_to_world (glTF axes) as 4x4 "
    "matrices, or camera=\"FILE.json\" (docs/cameras.md). shadows=True: every light casts "
    "shadows (docs/shadows.md), filtered by shadow_filter=\"pcf\" (the default), "
    "\"hardware\" or \"pcss\" (soft), with shadow_cascades=2 maps per directional light. "
    "lod_error=PIXELS draws large meshes at the coarsest level of detail within that error on "
    "screen (0: exact); culling=False draws every cluster (the same picture). "
    "transparency=\"exact\" (the default; \"sorted\" with "
    "gl_compat), \"sorted\" or \"weighted\": how blended materials are composited "
    "(docs/transparency.md)";

void defineRenderer(py::module_& m) {
    py::class_<PyRenderer>(m, "Renderer",
                           "The renderer: creates the Vulkan device once; keep it for many "
                           "renders (pipelines and uploads are reused)")
        .def(py::init<const std::string&, bool>(), py::arg("device") = std::string(),
             py::arg("validation") = false)
        .def_property_readonly("device", &PyRenderer::device,
                               "The device: name, type, driver, supported msaa values")
        .def_property_readonly(
            "validation_enabled",
            [](const PyRenderer& r) { return r.renderer->device().validationEnabled; },
            "Whether the Khronos validation layer is on (Renderer(validation=True) and the "
            "layer installed)")
        .def_property_readonly(
            "validation_messages",
            [](const PyRenderer& r) { return r.renderer->validationMessageCount(); },
            "How many messages the validation layer has reported so far")
        .def(
            "render",
            [](PyRenderer& r, PyScene& scene, double time, int width, int height,
               std::optional<std::string> shading, std::optional<std::string> specular, int msaa,
               std::optional<std::vector<double>> background,
               std::optional<std::vector<std::vector<double>>> lookAt,
               std::optional<std::vector<double>> perspective,
               std::optional<std::vector<double>> ortho,
               std::optional<std::variant<int, std::string>> camera,
               std::optional<bool> twoSided, std::optional<bool> localViewer, bool clamp,
               bool glCompat, bool depth, bool normal, double pointSize, double lineWidth,
               std::vector<std::string> aov, bool unlitExact, py::object intrinsics,
               std::optional<std::vector<std::vector<double>>> worldToCamera,
               std::optional<std::vector<std::vector<double>>> cameraToWorld,
               std::optional<double> znear, std::optional<double> zfar, bool shadows,
               std::optional<std::string> transparency, std::optional<std::string> shadowFilter,
               std::optional<int> shadowCascades, double lodError, bool culling) {
                RenderArgs a{time,       width,   height,      std::move(shading),
                             std::move(specular), msaa, std::move(background), std::move(lookAt),
                             std::move(perspective), std::move(ortho), std::nullopt, twoSided,
                             localViewer, clamp, glCompat, depth, normal, pointSize, lineWidth};
                a.aov = std::move(aov);
                a.unlitExact = unlitExact;
                // camera=N is a scene camera; camera="PATH" a camera JSON file.
                if (camera && std::holds_alternative<int>(*camera))
                    a.camera = std::get<int>(*camera);
                else if (camera)
                    a.cameraFile = std::get<std::string>(*camera);
                a.intrinsics = std::move(intrinsics);
                a.worldToCamera = std::move(worldToCamera);
                a.cameraToWorld = std::move(cameraToWorld);
                a.znear = znear;
                a.zfar = zfar;
                a.shadows = shadows;
                a.transparency = std::move(transparency);
                a.shadowFilter = std::move(shadowFilter);
                a.shadowCascades = shadowCascades;
                a.lodError = lodError;
                a.culling = culling;
                return r.render(scene, a);
            },
            py::arg("scene"), py::kw_only(), py::arg("time") = 0.0, py::arg("width") = 1280,
            py::arg("height") = 720, py::arg("shading") = py::none(),
            py::arg("specular") = py::none(), py::arg("msaa") = 1,
            py::arg("background") = py::none(), py::arg("look_at") = py::none(),
            py::arg("perspective") = py::none(), py::arg("ortho") = py::none(),
            py::arg("camera") = py::none(), py::arg("two_sided") = py::none(),
            py::arg("local_viewer") = py::none(), py::arg("clamp") = false,
            py::arg("gl_compat") = false, py::arg("depth") = false, py::arg("normal") = false,
            py::arg("point_size") = 1.0, py::arg("line_width") = 1.0,
            py::arg("aov") = std::vector<std::string>{}, py::arg("unlit_exact") = false,
            py::arg("intrinsics") = py::none(), py::arg("world_to_camera") = py::none(),
            py::arg("camera_to_world") = py::none(), py::arg("near") = py::none(),
            py::arg("far") = py::none(), py::arg("shadows") = false,
            py::arg("transparency") = py::none(), py::arg("shadow_filter") = py::none(),
            py::arg("shadow_cascades") = py::none(), py::arg("lod_error") = 0.0,
            py::arg("culling") = true, kRenderDoc);
}

} // namespace

PYBIND11_MODULE(_lantern, m) {
    m.doc() = "Lantern: a Vulkan renderer for the classic camera, light and material model";
    py::register_exception<LanternException>(m, "Error", PyExc_RuntimeError);
    m.attr("__version__") = versionString();
    defineScene(m);
    defineRenderer(m);
    m.def("load", &loadPyScene, py::arg("path"), py::kw_only(), py::arg("variant") = "",
          py::arg("up") = "y",
          "Loads a scene file (glTF/GLB, OBJ, PLY, STL, OFF) or builtin:NAME; variant: a "
          "KHR_materials_variants variant to draw (the scene's `variants` lists them); up=\"z\" "
          "turns a Z-up file (CAD, STL) so that +Z points up");
    m.def("builtin_scenes", &builtinSceneNames, "The names builtin:NAME accepts");
    m.def("write_image", &writeImageFile, py::arg("path"), py::arg("rgba"), py::kw_only(),
          py::arg("depth") = py::none(), py::arg("normal") = py::none(), py::arg("half") = false,
          "Writes .exr (float, or half) or .png (8-bit sRGB) by extension, atomically");
    m.def("build_info", &buildFacts, "Version, commit, build type, compiler, Vulkan loader");
    m.def("list_devices", &deviceList, py::arg("device") = std::string(),
          "The Vulkan devices and the one a Renderer(device=...) would choose");
}
