// Editing a scene between renders from Python without a new renderer or a new upload (pyrender
// issue 43): node transforms, which every render reads afresh, and a primitive's vertex
// positions and normals, which the next render writes again for that primitive alone
// (Renderer::updateVertices).
#include "PythonScene.h"

#include <glm/gtc/quaternion.hpp>

#include <cmath>
#include <cstring>

namespace lantern::python {
namespace {

bool finite(const std::vector<double>& v) {
    for (double x : v)
        if (!std::isfinite(x)) return false;
    return true;
}

std::vector<double> numbers(const std::optional<std::vector<double>>& v, std::size_t count,
                            const char* keyword) {
    if (v->size() != count)
        throw py::value_error(std::string(keyword) + ": expected " + std::to_string(count) +
                              " numbers, got " + std::to_string(v->size()));
    if (!finite(*v)) throw py::value_error(std::string(keyword) + ": numbers must be finite");
    return *v;
}

// A node given by index or name.
int nodeIndex(const Scene& s, const py::object& node) {
    if (py::isinstance<py::str>(node)) {
        const std::string name = node.cast<std::string>();
        for (std::size_t i = 0; i < s.nodes.size(); ++i)
            if (s.nodes[i].name == name) return int(i);
        throw py::value_error("no node is named \"" + name + "\"");
    }
    const long i = node.cast<long>();
    if (i < 0 || std::size_t(i) >= s.nodes.size())
        throw py::index_error("node " + std::to_string(i) + ": the scene has " +
                              std::to_string(s.nodes.size()) + " nodes");
    return int(i);
}

Primitive& primitiveOf(Scene& s, int mesh, int primitive) {
    if (mesh < 0 || std::size_t(mesh) >= s.meshes.size())
        throw py::index_error("mesh " + std::to_string(mesh) + ": the scene has " +
                              std::to_string(s.meshes.size()) + " meshes");
    auto& prims = s.meshes[std::size_t(mesh)].primitives;
    if (primitive < 0 || std::size_t(primitive) >= prims.size())
        throw py::index_error("mesh " + std::to_string(mesh) + " primitive " +
                              std::to_string(primitive) + ": the mesh has " +
                              std::to_string(prims.size()) + " primitives");
    return prims[std::size_t(primitive)];
}

py::array_t<float> copyOf(const std::vector<glm::vec3>& v) {
    py::array_t<float> out({py::ssize_t(v.size()), py::ssize_t(3)});
    if (!v.empty()) std::memcpy(out.mutable_data(), v.data(), v.size() * sizeof(glm::vec3));
    return out;
}

// An (n, 3) float array's rows as vec3, checked: its shape and finite values.
std::vector<glm::vec3>
vectorsOf(const py::array_t<float, py::array::c_style | py::array::forcecast>& a, std::size_t n,
          const std::string& what) {
    if (a.ndim() != 2 || a.shape(1) != 3 || std::size_t(a.shape(0)) != n)
        throw py::value_error(what + ": expected an array of shape (" + std::to_string(n) +
                              ", 3), the primitive's vertex count (it cannot change)");
    std::vector<glm::vec3> out(n);
    std::memcpy(out.data(), a.data(), n * sizeof(glm::vec3));
    for (const glm::vec3& p : out)
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            throw py::value_error(what + ": values must be finite");
    return out;
}

} // namespace

py::list PyScene::nodes() const {
    py::list out;
    for (const Node& n : scene->nodes) {
        py::dict d;
        d["name"] = n.name;
        d["mesh"] = n.mesh;
        d["translation"] = py::make_tuple(n.translation.x, n.translation.y, n.translation.z);
        d["rotation"] = py::make_tuple(n.rotation.x, n.rotation.y, n.rotation.z, n.rotation.w);
        d["scale"] = py::make_tuple(n.scale.x, n.scale.y, n.scale.z);
        if (n.matrix) {
            py::list rows;
            for (int r = 0; r < 4; ++r)
                rows.append(py::make_tuple((*n.matrix)[0][r], (*n.matrix)[1][r],
                                           (*n.matrix)[2][r], (*n.matrix)[3][r]));
            d["matrix"] = rows;
        } else {
            d["matrix"] = py::none();
        }
        d["children"] = n.children;
        out.append(d);
    }
    return out;
}

void PyScene::setNodeTransform(const py::object& node,
                               std::optional<std::vector<double>> translation,
                               std::optional<std::vector<double>> rotation,
                               std::optional<std::vector<double>> scale,
                               std::optional<std::vector<std::vector<double>>> matrix) {
    Node& n = scene->nodes[std::size_t(nodeIndex(*scene, node))];
    const bool trs = translation || rotation || scale;
    if (matrix && trs) throw py::value_error("give matrix, or translation/rotation/scale");
    // Everything is checked before the node changes: a refused edit leaves it as it was.
    if (matrix) {
        if (matrix->size() != 4) throw py::value_error("matrix: expected 4 rows of 4 numbers");
        glm::dmat4 m(1.0);
        for (int r = 0; r < 4; ++r) {
            const auto row = numbers((*matrix)[std::size_t(r)], 4, "matrix row");
            for (int c = 0; c < 4; ++c)
                m[c][r] = row[std::size_t(c)];  // rows given, glm stores columns
        }
        n.matrix = m;
        return;
    }
    glm::dvec3 t = n.translation, s = n.scale;
    glm::dquat q = n.rotation;
    if (translation) {
        const auto v = numbers(translation, 3, "translation");
        t = {v[0], v[1], v[2]};
    }
    if (rotation) {
        const auto v = numbers(rotation, 4, "rotation (x, y, z, w)");
        const glm::dquat given(v[3], v[0], v[1], v[2]);
        const double len = glm::length(given);
        if (!(len > 0.0)) throw py::value_error("rotation: the quaternion must not be zero");
        q = given / len;
    }
    if (scale) {
        const auto v = numbers(scale, 3, "scale");
        s = {v[0], v[1], v[2]};
    }
    n.translation = t;
    n.rotation = q;
    n.scale = s;
    n.matrix.reset();  // TRS given: it replaces a matrix the node had
}

py::array_t<float> PyScene::positions(int mesh, int primitive) const {
    return copyOf(primitiveOf(*scene, mesh, primitive).positions);
}

py::object PyScene::normals(int mesh, int primitive) const {
    const Primitive& p = primitiveOf(*scene, mesh, primitive);
    if (p.normals.empty()) return py::none();
    return copyOf(p.normals);
}

void PyScene::setVertices(
    int mesh, const py::array_t<float, py::array::c_style | py::array::forcecast>& positions,
    int primitive, const py::object& normals) {
    Primitive& p = primitiveOf(*scene, mesh, primitive);
    const std::size_t n = p.positions.size();
    std::vector<glm::vec3> newPositions = vectorsOf(positions, n, "positions");
    std::vector<glm::vec3> newNormals;
    if (!normals.is_none())
        newNormals = vectorsOf(
            normals.cast<py::array_t<float, py::array::c_style | py::array::forcecast>>(), n,
            "normals");
    p.positions = std::move(newPositions);
    if (!normals.is_none()) p.normals = std::move(newNormals);
    movedVertices.emplace(mesh, primitive);
}

} // namespace lantern::python
