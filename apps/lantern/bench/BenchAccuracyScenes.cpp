// The analytic scenes of the accuracy benchmark (numerics.md section 7.1): S1, a lit sphere
// (tessellation against shading mode, highlight loss), and S2, a spot on a plane (Gouraud's
// classic failure: the cone falls between vertices); and the transparency scenes T1-T3, where
// sorting blended objects by their centres is wrong somewhere. Built in code from the public
// API.
#include "bench/BenchAccuracy.h"

#include <glm/gtc/quaternion.hpp>

#include <algorithm>

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

// The camera (40 degrees, no far plane) at `lookAt`, and the root holding every node.
void addCameraAndRoot(Scene& s, const std::string& name, const LookAt& lookAt) {
    Camera camera;
    camera.name = "bench camera";
    camera.projection = Projection::makePerspective(40.0 * kPi / 180.0, 0.0, 0.1, kInfinity);
    camera.lookAt = lookAt;
    s.cameras.push_back(camera);
    SceneRoot root;
    root.name = name;
    for (int i = 0; i < int(s.nodes.size()); ++i) root.nodes.push_back(i);
    root.lighting = LightingModel{};
    s.roots.push_back(root);
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
    addCameraAndRoot(s, name, lookAt);
    b.shapes = {shape};
    b.shapes[0].mesh = 0;
    return b;
}

// One blended (or, with alpha 1, opaque) surface of a layered scene.
struct Layer {
    AnalyticShape shape;
    glm::dvec4 colour;  ///< diffuse and alpha
    Node node;
};

// The transparency scenes: each layer a mesh of its own with its material (blended and
// double-sided where alpha < 1, so a glass's far side is drawn too), the point light and
// camera of S1 looking at the origin from `eye`.
BenchScene layered(const std::string& name, const std::vector<Layer>& layers, int segments,
                   double shininess, const glm::dvec3& eye) {
    BenchScene b;
    Scene& s = b.scene;
    s.sourcePath = "bench:" + name;
    Light light;
    light.name = "point";
    s.lights.push_back(light);
    Node lightNode;
    lightNode.name = "point";
    lightNode.light = 0;
    lightNode.translation = {2.0, 2.0, 4.0};
    s.nodes.push_back(lightNode);
    for (const Layer& l : layers) {
        Primitive prim = tessellate(l.shape, segments);
        prim.material = int(s.materials.size());
        b.triangles += prim.triangleCount();
        Material m = benchMaterial(shininess);
        m.front.diffuse = l.colour;
        if (l.colour.a < 1.0) {
            m.alphaMode = AlphaMode::Blend;
            m.doubleSided = true;
        }
        s.materials.push_back(m);
        b.shapes.push_back(l.shape);
        b.shapes.back().mesh = int(s.meshes.size());
        s.meshes.push_back(Mesh{name, {std::move(prim)}});
        Node n = l.node;
        n.mesh = b.shapes.back().mesh;
        s.nodes.push_back(n);
    }
    addCameraAndRoot(s, name, LookAt{eye, {0.0, 0.0, 0.0}, {0.0, 1.0, 0.0}});
    return b;
}

Node placed(const glm::dvec3& translation, const glm::dquat& rotation = glm::dquat(1, 0, 0, 0)) {
    Node n;
    n.translation = translation;
    n.rotation = rotation;
    return n;
}

// T1 "crossing": two blended squares that cross (each is in front on one side of the line
// where they meet). T4 "torus": one blended torus that overlaps itself (its triangles drawn in
// index order, so sorting by object cannot order them). T2 "nested": an opaque sphere inside two blended glass spheres. T3
// "beside": a large blended floor and a small blended sphere standing on its far half (the
// floor's centre is nearer the eye than the sphere's, though the sphere hides the floor behind
// it: pyrender issue 206).
BenchScene transparencyScene(const std::string& name, double shininess, int segments) {
    const glm::dvec3 up(0, 1, 0), right(1, 0, 0);
    if (name == "crossing")
        return layered(name,
                       {{AnalyticShape::plane(0, 2.0), {0.9, 0.2, 0.1, 0.5}, placed({}, glm::angleAxis(0.6, up))},
                        {AnalyticShape::plane(0, 2.0), {0.1, 0.3, 0.9, 0.5}, placed({}, glm::angleAxis(-0.6, up))}},
                       segments, shininess, {0.0, 0.6, 4.0});
    if (name == "torus")  // tilted, so the far half of the tube shows through the near half
        return layered(name,
                       {{AnalyticShape::torus(0, 1.0, 0.35), {0.3, 0.6, 0.9, 0.5}, placed({}, glm::angleAxis(-1.1, right))}},
                       segments, shininess, {0.0, 0.6, 4.0});
    if (name == "nested")
        return layered(name,
                       {{AnalyticShape::sphere(0, 1.0), {0.6, 0.8, 0.9, 0.3}, placed({})},
                        {AnalyticShape::sphere(0, 0.7), {0.9, 0.7, 0.2, 0.5}, placed({})},
                        {AnalyticShape::sphere(0, 0.4), {0.8, 0.2, 0.2, 1.0}, placed({})}},
                       segments, shininess, {0.0, 0.0, 4.0});
    return layered(name,
                   {{AnalyticShape::plane(0, 6.0), {0.3, 0.8, 0.4, 0.4}, placed({0, -0.5, 0}, glm::angleAxis(-kPi / 2, right))},
                    {AnalyticShape::sphere(0, 0.5), {0.9, 0.6, 0.2, 0.6}, placed({0.3, 0.0, -1.5})}},
                   segments, shininess, {0.0, 1.5, 4.0});
}

// A leaf's mask: 32 x 32 texels, opaque inside an ellipse as long as the texture and half as
// wide, transparent outside, its colour striped (sRGB), sampled nearest.
Texture leafTexture() {
    Texture t;
    t.name = "leaf";
    t.width = t.height = 32;
    t.nearest = true;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
            const double u = (x - 15.5) / 15.0, v = (y - 15.5) / 8.0;
            const bool inside = u * u + v * v < 1.0;
            const std::uint8_t stripe = x % 4 < 2 ? 255 : 170;
            t.rgba8.insert(t.rgba8.end(), {stripe, 255, stripe, std::uint8_t(inside ? 255 : 0)});
        }
    return t;
}

// T5: six alpha-masked leaves over a blended pond: the leaves are cut by their mask (opaque
// where it keeps them), the pond composited behind and between them.
BenchScene foliageScene(double shininess, int segments) {
    const glm::dvec3 right(1, 0, 0), up(0, 1, 0);
    std::vector<Layer> layers{
        {AnalyticShape::plane(0, 6.0), {0.2, 0.4, 0.8, 0.5}, placed({0, -0.5, 0}, glm::angleAxis(-kPi / 2, right))}};
    const double spots[6][3] = {{-1.2, 0.3, 0.4}, {-0.4, 0.6, -0.6}, {0.5, 0.2, 0.5},
                                {1.1, 0.7, -0.3}, {0.0, 1.0, 0.9}, {-0.8, 0.1, -1.4}};
    for (int i = 0; i < 6; ++i)
        layers.push_back({AnalyticShape::plane(0, 1.0), {0.3, 0.7, 0.2, 1.0},
                          placed({spots[i][0], spots[i][1], spots[i][2]},
                                 glm::angleAxis(0.9 * i, up) * glm::angleAxis(-0.9, right))});
    BenchScene b = layered("foliage", layers, segments, shininess, {0.0, 1.5, 4.0});
    b.scene.textures.push_back(leafTexture());
    for (std::size_t m = 1; m < b.scene.materials.size(); ++m) {
        Material& leaf = b.scene.materials[m];
        leaf.alphaMode = AlphaMode::Mask;
        leaf.alphaCutoff = 0.5;
        leaf.doubleSided = true;
        leaf.baseColorTexture = 0;
    }
    return b;
}

// H1: the sphere over the plane, its shadow cast by a directional light that casts them.
BenchScene shadowScene(double shininess, int segments) {
    const glm::dvec3 right(1, 0, 0);
    BenchScene b = layered("shadow",
                           {{AnalyticShape::plane(0, 4.0), {0.8, 0.8, 0.8, 1.0}, placed({}, glm::angleAxis(-kPi / 2, right))},
                            {AnalyticShape::sphere(0, 0.5), {0.9, 0.6, 0.2, 1.0}, placed({0.0, 1.0, 0.0})}},
                           segments, shininess, {0.0, 4.0, 3.5});
    Light& light = b.scene.lights[0];
    light.name = "sun";
    light.type = LightType::Directional;
    light.castShadows = true;
    Node& node = b.scene.nodes[0];  // the light's (layered() puts it first)
    node.name = "sun";
    node.translation = {0.0, 0.0, 0.0};
    node.rotation = glm::quatLookAtRH(-glm::normalize(glm::dvec3(1.25, 1.0, 0.3)), glm::dvec3(0, 1, 0));
    return b;
}

// H2: five spheres in a row along a 40 x 40 plane, seen from low down at one end, so the
// shadows near the eye need finer texels than one map over the whole plane gives.
BenchScene fieldScene(double shininess, int segments) {
    const glm::dvec3 right(1, 0, 0);
    std::vector<Layer> layers{
        {AnalyticShape::plane(0, 40.0), {0.8, 0.8, 0.8, 1.0}, placed({}, glm::angleAxis(-kPi / 2, right))}};
    for (double z : {12.0, 6.0, 0.0, -6.0, -12.0})
        layers.push_back({AnalyticShape::sphere(0, 0.5), {0.9, 0.6, 0.2, 1.0}, placed({0.8, 0.7, z})});
    BenchScene b = layered("field", layers, segments, shininess, {0.0, 1.5, 18.0});
    Light& light = b.scene.lights[0];
    light.name = "sun";
    light.type = LightType::Directional;
    light.castShadows = true;
    Node& node = b.scene.nodes[0];
    node.name = "sun";
    node.translation = {0.0, 0.0, 0.0};
    node.rotation = glm::quatLookAtRH(-glm::normalize(glm::dvec3(-1.0, 1.2, 0.4)), glm::dvec3(0, 1, 0));
    return b;
}

} // namespace

bool isShadowScene(const std::string& name) { return name == "shadow" || name == "field"; }

bool isTransparencyScene(const std::string& name) {
    return name == "crossing" || name == "nested" || name == "beside" || name == "torus" ||
           name == "foliage";
}

const std::vector<std::string>& benchSceneNames() {
    static const std::vector<std::string> names{"sphere", "spot", "crossing", "nested", "beside", "torus", "foliage", "shadow", "field"};
    return names;
}

double shadowWrongShare(const Image& render, const ReferenceImage& shadowed, const ReferenceImage& lit) {
    const std::size_t n = render.pixelCount();
    if (n == 0 || shadowed.centre.pixelCount() != n || lit.centre.pixelCount() != n) return -1.0;
    auto sum = [](const float* p) { return double(p[0]) + p[1] + p[2]; };
    double fall = 0.0;
    for (std::size_t i = 0; i < n; ++i)
        fall = std::max(fall, sum(&lit.centre.rgba[4 * i]) - sum(&shadowed.centre.rgba[4 * i]));
    std::size_t interior = 0, wrong = 0;
    for (std::size_t i = 0; i < n; ++i) {
        if (!shadowed.interior[i] || !lit.interior[i]) continue;
        const double l = sum(&lit.centre.rgba[4 * i]);
        const bool exact = l - sum(&shadowed.centre.rgba[4 * i]) > 0.5 * fall;
        const bool mapped = l - sum(&render.rgba[4 * i]) > 0.5 * fall;
        ++interior;
        wrong += exact != mapped;
    }
    return interior > 0 && fall > 0.0 ? double(wrong) / double(interior) : -1.0;
}

BenchScene makeBenchScene(const std::string& name, double shininess, int segments) {
    if (name == "foliage") return foliageScene(shininess, segments);
    if (isTransparencyScene(name)) return transparencyScene(name, shininess, segments);
    if (name == "shadow") return shadowScene(shininess, segments);
    if (name == "field") return fieldScene(shininess, segments);
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
