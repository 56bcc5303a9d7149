// PythonScene.h: what the Python module `lantern` wraps: a scene the host may edit (lights), the
// renderer that keeps its device between calls, and the options of one render as keyword
// arguments. Uses Lantern's public API only.
#pragma once

#include <lantern/Lantern.h>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace lantern::python {

namespace py = pybind11;

/// A Lantern error as a Python exception (lantern.Error, a RuntimeError).
struct LanternException : std::runtime_error {
    using std::runtime_error::runtime_error;
};
/// Raises the error: ValueError for refused input or misuse, OSError for a file that cannot be
/// read or written, lantern.Error otherwise.
[[noreturn]] void raise(const Error& error);

/// A scene and the upload of it to the renderer that last drew it. Structural edits (lights
/// added or removed) bump `generation`, so the next render uploads it again; moved vertices
/// are listed in `movedVertices`, so the next render writes only those primitives again
/// (Renderer::updateVertices); node transforms are read afresh by every render.
struct PyScene {
    std::shared_ptr<Scene> scene;
    std::uint64_t generation = 0;
    std::uint64_t preparedFor = 0;          ///< PyRenderer::id of the upload (0: none)
    std::uint64_t preparedGeneration = 0;
    PreparedScene prepared;
    std::uint64_t uploads = 0;  ///< whole uploads made (Python: Scene.upload_count)
    std::set<std::pair<int, int>> movedVertices;  ///< (mesh, primitive) edited since the upload

    // PythonEdit.cpp: nodes and vertices edited between renders.
    py::list nodes() const;
    void setNodeTransform(const py::object& node, std::optional<std::vector<double>> translation,
                          std::optional<std::vector<double>> rotation,
                          std::optional<std::vector<double>> scale,
                          std::optional<std::vector<std::vector<double>>> matrix);
    py::array_t<float> positions(int mesh, int primitive) const;
    py::object normals(int mesh, int primitive) const;
    void setVertices(int mesh,
                     const py::array_t<float, py::array::c_style | py::array::forcecast>& positions,
                     int primitive, const py::object& normals);

    void addLight(const std::string& type, std::optional<std::vector<double>> position,
                  std::optional<std::vector<double>> direction, std::vector<double> color,
                  std::vector<double> ambient, std::vector<double> attenuation,
                  double spotCutoffDeg, double spotExponent, const std::string& name);
    void clearLights();
    py::list lights() const;
};

/// The options of one render, as Renderer.render's keyword arguments give them.
struct RenderArgs {
    double time = 0.0;
    int width = 1280, height = 720;
    std::optional<std::string> shading, specular;
    int msaa = 1;
    std::optional<std::vector<double>> background;
    std::optional<std::vector<std::vector<double>>> lookAt; ///< eye, target, up
    std::optional<std::vector<double>> perspective;         ///< fovy_deg, [aspect,] near, far
    std::optional<std::vector<double>> ortho;               ///< l, r, b, t, n, f
    std::optional<int> camera;                              ///< the scene's camera N
    std::optional<bool> twoSided, localViewer;
    bool clamp = false, glCompat = false;
    bool depth = false, normal = false;
    double pointSize = 1.0, lineWidth = 1.0;  ///< pixels across points and lines
    std::vector<std::string> aov;  ///< aov=: AOV names (docs/aovs.md); a dict of arrays back
    bool unlitExact = false;       ///< unlit_exact=: exact label colours
    bool shadows = false;          ///< shadows=: every light casts shadows
    std::optional<std::string> shadowFilter;  ///< shadow_filter=: "hardware", "pcf" or "pcss"
    std::optional<int> shadowCascades;        ///< shadow_cascades=: 1 to 8
    double lodError = 0.0;                    ///< lod_error=: pixels, 0 exact (--lod-error)
    bool culling = true;                      ///< culling=: False draws everything (--no-culling)
    std::optional<std::string> transparency;  ///< transparency=: "sorted", "exact" or "weighted"
    /// Computer-vision cameras (docs/python.md): intrinsics (fx, fy, cx, cy) or a 3x3 K in
    /// OpenCV pixels; a pose as OpenCV's world_to_camera or glTF's camera_to_world (4x4);
    /// near and far for the intrinsics; a camera JSON file (`camera` given as a path).
    py::object intrinsics = py::none();
    std::optional<std::vector<std::vector<double>>> worldToCamera, cameraToWorld;
    std::optional<double> znear, zfar;
    std::optional<std::string> cameraFile;
};

/// Builds the RenderOptions (ValueError naming the keyword for a bad value).
RenderOptions renderOptions(const RenderArgs& a);

/// The renderer: created once (the device, its pipelines and uploads stay for every render).
struct PyRenderer {
    std::uint64_t id = 0;
    std::optional<Renderer> renderer;

    PyRenderer(const std::string& device, bool validation);
    py::object render(PyScene& scene, const RenderArgs& args);
    py::dict device() const;
};

/// The picture's planes as NumPy arrays sharing the Image's memory (no copy): RGBA, and the
/// depth and normal planes when asked for.
py::object toArrays(Image&& image, bool depth, bool normal);
/// The planes of aov=: (rgba, {name: array}) sharing the Image's memory; float32 data planes,
/// uint32 id planes ("primitive" gives "mesh" and "primitive").
py::object toAovArrays(Image&& image);
/// An Image from a (H, W, 4) float32 array (and optional (H, W) depth, (H, W, 3) normal).
Image fromArrays(const py::array_t<float, py::array::c_style | py::array::forcecast>& rgba,
                 const py::object& depth, const py::object& normal);

} // namespace lantern::python
