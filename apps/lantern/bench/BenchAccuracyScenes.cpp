// The analytic scenes of the accuracy benchmark (numerics.md section 7.1): S1, a lit sphere
// (tessellation against shading mode, highlight loss), and S2, a spot on a plane (Gouraud's
// classic failure: the cone falls between vertices). Built in code from the public API.
#include "bench/BenchAccuracy.h"

#include <glm/gtc/quaternion.hpp>

namespace lantern::cli {
namespace {

constexpr double kPi = 3.14159265358979323846;

Material benchMaterial(double shininess) {
    Material m;
    m.name = "bench";
    m.front.ambient = {0.2, 0.2, 0.2};
    m.front.diffuse = {0.8, 0.8, 0.8, 1.0};
    m.front.specular = {1.0, 1.0, 1.0};
    m.front.shininess = shininess;
    return m;
}

// One mesh (the shape at `segments`), one light, one camera; every node in the root.
BenchScene assemble(const std::string& name, const AnalyticShape& shape, int segments,
                    double shininess, const Node& object, const Light& light, const Node& lightNode,
                    const LookAt& lookAt) {
    BenchScene b;
    Scene& s = b.scene;
    s.sourcePath = "bench:" + name;
    Primitive prim = tessellate(shape, segments);
    prim.material = 0;
    b.triangles = prim.triangleCount();
    s.meshes.push_back(Mesh{name, {std::move(prim)}});
    s.materials.push_back(benchMaterial(shininess));
    s.lights.push_back(light);
    s.nodes = {object, lightNode};
    Camera camera;
    camera.name = "bench camera";
    camera.projection = Projection::makePerspective(40.0 * kPi / 180.0, 0.0, 0.1, kInfinity);
    camera.lookAt = lookAt;
    s.cameras.push_back(camera);
    SceneRoot root;
    root.name = name;
    root.nodes = {0, 1};
    root.lighting = LightingModel{};
    s.roots.push_back(root);
    b.shapes = {shape};
    b.shapes[0].mesh = 0;
    return b;
}

} // namespace

const std::vector<std::string>& benchSceneNames() {
    static const std::vector<std::string> names{"sphere", "spot"};
    return names;
}

BenchScene makeBenchScene(const std::string& name, double shininess, int segments) {
    Node object;
    object.name = name;
    object.mesh = 0;
    Node lightNode;
    lightNode.light = 0;
    Light light;
    if (name == "spot") {
        // The plane's normal turned from +Z to +Y; the spot's -Z turned to -Y (down). The spot
        // sits off the vertex grid so that no tessellation puts a vertex under its axis.
        const glm::dquat down = glm::angleAxis(-kPi / 2.0, glm::dvec3(1, 0, 0));
        object.rotation = down;
        lightNode.name = "spot";
        lightNode.translation = {0.3, 2.0, -0.2};
        lightNode.rotation = down;
        light.name = "spot";
        light.type = LightType::Spot;
        light.spotCutoffDeg = 30.0;
        light.spotExponent = 16.0;
        light.attenuation = {1.0, 0.1, 0.01};
        return assemble(name, AnalyticShape::plane(0, 8.0), segments, shininess, object, light,
                        lightNode, LookAt{{0.0, 3.5, 5.0}, {0.0, 0.0, -0.5}, {0.0, 1.0, 0.0}});
    }
    // "sphere": the camera at (0, 0, 4) looks down -Z, so world (2, 2, 4) is eye (2, 2, 0).
    lightNode.name = "point";
    lightNode.translation = {2.0, 2.0, 4.0};
    light.name = "point";
    light.type = LightType::Point;
    return assemble(name, AnalyticShape::sphere(0, 1.0), segments, shininess, object, light,
                    lightNode, LookAt{{0.0, 0.0, 4.0}, {0.0, 0.0, 0.0}, {0.0, 1.0, 0.0}});
}

} // namespace lantern::cli
