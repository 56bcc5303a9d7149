// Built-in scenes, generated in code (no files needed at run time).
#include "scene/Builtins.h"

#include "scene/Teapot.h"


#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

namespace lantern {
namespace scene {

void addSpheresLightsAndCamera(Scene& s);

Scene makeSpheresScene() {
    Scene s;
    s.sourcePath = "builtin:spheres";
    auto material = [](const char* name, glm::dvec3 a, glm::dvec3 d, glm::dvec3 sp, double sh) {
        Material m;
        m.name = name;
        m.front.ambient = a;
        m.front.diffuse = glm::dvec4(d, 1.0);
        m.front.specular = sp;
        m.front.shininess = sh;
        return m;
    };
    s.materials = {
        material("red plastic", {0.0, 0.0, 0.0}, {0.5, 0.0, 0.0}, {0.7, 0.6, 0.6}, 32.0),
        material("gold", {0.24725, 0.1995, 0.0745}, {0.75164, 0.60648, 0.22648},
                 {0.628281, 0.555802, 0.366065}, 51.2),
        material("jade", {0.135, 0.2225, 0.1575}, {0.54, 0.89, 0.63},
                 {0.316228, 0.316228, 0.316228}, 12.8),
        material("ground", {0.2, 0.2, 0.2}, {0.45, 0.45, 0.5}, {0.1, 0.1, 0.1}, 8.0),
    };
    // Meshes 0-2: a sphere in each material; mesh 3: the ground.
    for (int i = 0; i < 3; ++i) {
        Mesh m{"sphere " + std::to_string(i), {makeSphere(1.0, 64, 32)}};
        m.primitives[0].material = i;
        s.meshes.push_back(std::move(m));
        Node n;
        n.name = "sphere " + std::to_string(i);
        n.mesh = i;
        n.translation = {-2.4 + 2.4 * i, 0.0, 0.0};
        s.nodes.push_back(n);
    }
    Mesh ground{"ground", {makePlane(12.0, 8)}};
    ground.primitives[0].material = 3;
    s.meshes.push_back(std::move(ground));
    Node floor;
    floor.name = "ground";
    floor.mesh = 3;
    floor.translation = {0.0, -1.0, 0.0};
    floor.rotation = glm::angleAxis(-glm::pi<double>() / 2.0, glm::dvec3(1, 0, 0));
    s.nodes.push_back(floor);
    addSpheresLightsAndCamera(s);

    SceneRoot root;
    root.name = "spheres";
    for (int i = 0; i < int(s.nodes.size()); ++i) root.nodes.push_back(i);
    LightingModel lm;
    lm.globalAmbient = {0.2, 0.2, 0.2};
    root.lighting = lm;
    s.roots = {root};
    return s;
}

// The spheres' sun (from the upper left, in front), warm lamp and camera, with their nodes.
void addSpheresLightsAndCamera(Scene& s) {
    Light sun;
    sun.name = "sun";
    sun.type = LightType::Directional;
    sun.diffuse = {0.8, 0.8, 0.8};
    sun.specular = {1.0, 1.0, 1.0};
    Node sunNode;
    sunNode.name = "sun";
    sunNode.light = 0;
    // Shines down its local -Z: tilt it to come from the upper left, in front.
    sunNode.rotation = glm::quatLookAtRH(glm::normalize(glm::dvec3(0.5, -1.0, -0.7)), glm::dvec3(0, 1, 0));
    Light lamp;
    lamp.name = "lamp";
    lamp.type = LightType::Point;
    lamp.diffuse = {0.6, 0.55, 0.5};
    lamp.specular = {0.6, 0.55, 0.5};
    lamp.attenuation = {1.0, 0.05, 0.01};
    Node lampNode;
    lampNode.name = "lamp";
    lampNode.light = 1;
    lampNode.translation = {3.0, 3.0, 4.0};
    s.lights = {sun, lamp};
    s.nodes.push_back(sunNode);
    s.nodes.push_back(lampNode);

    Camera cam;
    cam.name = "main";
    cam.projection = Projection::makePerspective(glm::radians(40.0), 0.0, 0.1, kInfinity);
    s.cameras.push_back(cam);
    Node camNode;
    camNode.name = "camera";
    camNode.camera = 0;
    camNode.translation = {0.0, 2.2, 9.0};
    camNode.rotation = glm::quatLookAtRH(glm::normalize(glm::dvec3(0.0, -2.2, -9.0)), glm::dvec3(0, 1, 0));
    s.nodes.push_back(camNode);
}

Scene makeAnimatedSpheresScene() {
    Scene s = makeSpheresScene();
    s.sourcePath = "builtin:spheres-animated";
    // The lamp (node 5) circles above the spheres in 4 seconds; the middle sphere (node 1)
    // bounces with a cubic spline.
    Animation a;
    a.name = "orbit and bounce";
    AnimationSampler orbit;
    orbit.interpolation = Interpolation::Linear;
    for (int k = 0; k <= 16; ++k) {
        const double t = 0.25 * k, angle = 2.0 * glm::pi<double>() * t / 4.0;
        orbit.times.push_back(t);
        orbit.values.emplace_back(4.0 * std::sin(angle), 3.0, 4.0 * std::cos(angle), 0.0);
    }
    AnimationSampler bounce;
    bounce.interpolation = Interpolation::CubicSpline;
    bounce.times = {0.0, 1.0, 2.0};
    // in-tangent, value, out-tangent per key
    bounce.values = {{0, 0, 0, 0}, {0, 0, 0, 0}, {0, 3, 0, 0},   {0, 0, 0, 0}, {0, 1.2, 0, 0},
                     {0, 0, 0, 0}, {0, -3, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}};
    a.samplers = {orbit, bounce};
    a.channels = {{5, AnimationPath::Translation, 0}, {1, AnimationPath::Translation, 1}};
    s.animations.push_back(a);
    return s;
}

namespace {

// glutSolidTeapot(size), as the Red Book's GLUT drew it: Newell's teapot turned from z up to
// y up, scaled by size/2 and centred on Newell's z = 1.5 (glRotated(270, 1, 0, 0);
// glScaled(0.5 size); glTranslated(0, 0, -1.5)). The embedded teaset coordinates are Newell's
// divided by 3.525 and lowered by 0.15 (teapotControlPoints()), hence this scale and offset.
constexpr double kNewellPerTeasetUnit = 3.525;
constexpr double kNewellBase = 0.15;
constexpr double kGlutTeapotCentre = 1.5;

Material glMaterial(const ClassicMaterial& m) {
    Material out;
    out.name = std::string(m.name);
    out.front.ambient = {m.ambient[0], m.ambient[1], m.ambient[2]};
    out.front.diffuse = {m.diffuse[0], m.diffuse[1], m.diffuse[2], 1.0};
    out.front.specular = {m.specular[0], m.specular[1], m.specular[2]};
    out.front.emission = {0.0, 0.0, 0.0};
    out.front.shininess = m.shininess;
    return out;
}

// The example's light and lighting model: GL_LIGHT0 at (0, 3, 3, 0), a directional light
// given while the modelview was the identity (so in eye space), ambient 0, diffuse and
// specular 1 (specular is GL_LIGHT0's default); global ambient 0.2, distant viewer.
void addRedbookLighting(Scene& s, SceneRoot& root) {
    Light light;
    light.name = "GL_LIGHT0";
    light.type = LightType::Directional;
    light.ambient = {0.0, 0.0, 0.0};
    light.diffuse = {1.0, 1.0, 1.0};
    light.specular = {1.0, 1.0, 1.0};
    s.lights.push_back(light);
    Node n;
    n.name = "GL_LIGHT0";
    n.light = int(s.lights.size()) - 1;
    // A directional light shines down its node's -Z: away from (0, 3, 3).
    n.rotation =
        glm::quatLookAtRH(glm::normalize(glm::dvec3(0.0, -3.0, -3.0)), glm::dvec3(0, 1, 0));
    s.nodes.push_back(n);
    root.nodes.push_back(int(s.nodes.size()) - 1);
    LightingModel lm;
    lm.globalAmbient = {0.2, 0.2, 0.2};
    lm.localViewer = false;
    lm.twoSided = false; // GL's default light model: back faces drawn are lit one-sided
    root.lighting = lm;
}

// glutSolidTeapot(1.0) at `at` in material `m`: a material, a mesh (a primitive carries its
// material, so each teapot has its own copy of `teapot`) and a node that places it.
void addGlutTeapot(Scene& s, SceneRoot& root, const Primitive& teapot, const ClassicMaterial& m,
                   glm::dvec3 at) {
    const int index = int(s.materials.size());
    s.materials.push_back(glMaterial(m));
    Mesh mesh{s.materials.back().name + " teapot", {teapot}};
    mesh.primitives[0].material = index;
    s.meshes.push_back(std::move(mesh));
    Node n;
    n.name = s.meshes.back().name;
    n.mesh = int(s.meshes.size()) - 1;
    n.scale = glm::dvec3(0.5 * kNewellPerTeasetUnit);
    n.translation = at + glm::dvec3(0.0, 0.5 * (kNewellBase - kGlutTeapotCentre), 0.0);
    s.nodes.push_back(n);
    root.nodes.push_back(int(s.nodes.size()) - 1);
}

} // namespace

Scene makeTeapotsScene() {
    Scene s;
    s.sourcePath = "builtin:teapots";
    SceneRoot root;
    root.name = "teapots";
    const Primitive teapot = makeTeapot();
    const auto materials = redbookMaterials();
    for (std::size_t i = 0; i < materials.size(); ++i) {
        // renderTeapot(x, y, ...): columns at x = 2, 6, 10, 14 (gems, metals, plastics,
        // rubbers), each from y = 17 at the top down to y = 2.
        const glm::dvec3 at(2.0 + 4.0 * double(i / 6), 17.0 - 3.0 * double(i % 6), 0.0);
        addGlutTeapot(s, root, teapot, materials[i], at);
    }
    addRedbookLighting(s, root);

    // The example's window is 500 x 600: glOrtho(0, 16, 0, 19.2, -10, 10) with an identity
    // view, and its reshape widens the box to the window's aspect; fitViewportAspect does the
    // same for any image size (at 16:9 the 19.2 units of height are widened about x = 8).
    Camera camera;
    camera.name = "glOrtho";
    camera.projection = Projection::makeOrtho(0.0, 16.0, 0.0, 16.0 * 600.0 / 500.0, -10.0, 10.0);
    camera.projection.fitViewportAspect = true;
    camera.lookAt = LookAt{{0.0, 0.0, 0.0}, {0.0, 0.0, -1.0}, {0.0, 1.0, 0.0}};
    s.cameras.push_back(camera);
    s.roots = {root};
    return s;
}

Scene makeTeapotScene() {
    Scene s;
    s.sourcePath = "builtin:teapot";
    SceneRoot root;
    root.name = "teapot";
    const auto materials = redbookMaterials();
    const auto gold = std::find_if(materials.begin(), materials.end(),
                                   [](const ClassicMaterial& m) { return m.name == "gold"; });
    addGlutTeapot(s, root, makeTeapot(), gold != materials.end() ? *gold : materials.front(),
                  glm::dvec3(0.0));
    // Seen from above, the open spout shows its inside: back faces, drawn (as GL draws them
    // without GL_CULL_FACE) rather than culled to the background.
    s.materials[0].doubleSided = true;
    addRedbookLighting(s, root);
    Camera camera;
    camera.name = "main";
    camera.projection = Projection::makePerspective(glm::radians(30.0), 0.0, 0.1, kInfinity);
    camera.lookAt = LookAt{{1.5, 2.0, 5.5}, {0.1, 0.0, 0.0}, {0.0, 1.0, 0.0}};
    s.cameras.push_back(camera);
    s.roots = {root};
    return s;
}

} // namespace scene

namespace {
struct Builtin {
    const char* name;
    std::function<Scene()> make;
};
const std::vector<Builtin>& registry() {
    static const std::vector<Builtin> builtins = {
        {"default", scene::makeTeapotsScene},
        {"teapots", scene::makeTeapotsScene},
        {"teapot", scene::makeTeapotScene},
        {"spheres", scene::makeSpheresScene},
        {"spheres-animated", scene::makeAnimatedSpheresScene},
    };
    return builtins;
}
} // namespace

std::vector<std::string> scene::builtinSceneNames() {
    std::vector<std::string> names;
    for (const Builtin& b : registry()) names.push_back(b.name);
    return names;
}

Result<Scene> scene::builtinScene(std::string_view name) {
    for (const Builtin& b : registry())
        if (name == b.name) return b.make();
    std::string known;
    for (const Builtin& b : registry()) known += std::string(known.empty() ? "" : ", ") + b.name;
    return makeError(ErrorCode::InvalidInput,
                     "unknown built-in scene \"" + std::string(name) + "\" (built-ins: " + known + ")",
                     {}, "builtin:" + std::string(name));
}

} // namespace lantern
