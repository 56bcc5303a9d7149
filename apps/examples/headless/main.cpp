// A headless Lantern host: builds a scene entirely in code (meshes, materials, a light, a
// camera, node transforms and an animation), renders it into memory, steps the animation and
// writes the last frame to an EXR. Usage: lantern-headless-example [OUTPUT.exr]
#include <lantern/Lantern.h>

#include <glm/gtc/quaternion.hpp>

#include <cstdio>
#include <memory>
#include <string>

namespace {

// A 6 x 6 floor built vertex by vertex (Scene.h's helpers make spheres, planes and cubes too).
lantern::Primitive floorQuad(int material) {
    lantern::Primitive p;
    p.positions = {{-3.0f, 0.0f, -3.0f}, {3.0f, 0.0f, -3.0f}, {3.0f, 0.0f, 3.0f}, {-3.0f, 0.0f, 3.0f}};
    p.normals.assign(4, glm::vec3(0.0f, 1.0f, 0.0f));
    p.indices = {0, 2, 1, 0, 3, 2};  // counter-clockwise seen from above: the front faces
    p.material = material;
    return p;
}

lantern::Scene buildScene() {
    using namespace lantern;
    Scene s;
    s.sourcePath = "headless example";

    // Materials (GL's glMaterial terms): a shiny red and a matte grey.
    Material red;
    red.name = "red plastic";
    red.front.diffuse = {0.8, 0.1, 0.1, 1.0};
    red.front.ambient = {0.8, 0.1, 0.1};
    red.front.specular = {0.9, 0.9, 0.9};
    red.front.shininess = 60.0;
    Material grey;
    grey.name = "floor";
    grey.front.diffuse = {0.6, 0.6, 0.6, 1.0};
    s.materials = {red, grey};

    // Meshes: a sphere from the helper, the floor by hand.
    Mesh ball;
    ball.name = "ball";
    ball.primitives.push_back(makeSphere(0.75, 48, 24));
    ball.primitives[0].material = 0;
    Mesh floor;
    floor.name = "floor";
    floor.primitives.push_back(floorQuad(1));
    s.meshes = {ball, floor};

    // A point light with GL's attenuation, placed by its node.
    Light lamp;
    lamp.name = "lamp";
    lamp.type = LightType::Point;
    lamp.diffuse = {1.0, 0.95, 0.9};
    lamp.attenuation = {1.0, 0.0, 0.02};
    s.lights = {lamp};

    // A perspective camera aimed with gluLookAt parameters.
    Camera cam;
    cam.name = "main";
    cam.projection = Projection::makePerspective(glm::radians(45.0), 0.0, 0.1, kInfinity);
    cam.lookAt = LookAt{{0.0, 2.5, 6.0}, {0.0, 0.8, 0.0}, {0.0, 1.0, 0.0}};
    s.cameras = {cam};

    // Nodes: the ball (moved and squashed a little), the floor, the lamp and the camera.
    Node ballNode;
    ballNode.name = "ball";
    ballNode.mesh = 0;
    ballNode.translation = {0.0, 0.75, 0.0};
    ballNode.scale = {1.0, 0.9, 1.0};
    Node floorNode;
    floorNode.name = "floor";
    floorNode.mesh = 1;
    Node lampNode;
    lampNode.name = "lamp";
    lampNode.light = 0;
    lampNode.translation = {2.0, 4.0, 3.0};
    Node camNode;
    camNode.name = "camera";
    camNode.camera = 0;
    s.nodes = {ballNode, floorNode, lampNode, camNode};

    // An animation: the ball bounces (translation keys, linear) over one second.
    AnimationSampler bounce;
    bounce.interpolation = Interpolation::Linear;
    bounce.times = {0.0, 0.5, 1.0};
    bounce.values = {{0.0, 0.75, 0.0, 0.0}, {0.0, 2.0, 0.0, 0.0}, {0.0, 0.75, 0.0, 0.0}};
    Animation anim;
    anim.name = "bounce";
    anim.samplers = {bounce};
    anim.channels = {{0, AnimationPath::Translation, 0}};
    s.animations = {anim};

    SceneRoot root;
    root.name = "example";
    root.nodes = {0, 1, 2, 3};
    LightingModel lighting;
    lighting.globalAmbient = {0.1, 0.1, 0.1};
    root.lighting = lighting;
    s.roots = {root};
    return s;
}

int fail(const lantern::Error& e) {
    std::fprintf(stderr, "headless example: %s\n", e.describe().c_str());
    return lantern::exitCodeFor(e.code);  // 1 input refused, 2 usage, 3 renderer failed
}

} // namespace

int main(int argc, char** argv) {
    const std::string output = argc > 1 ? argv[1] : "headless.exr";

    // Lantern never prints: its messages arrive here, only if the host asks for them.
    lantern::RendererDesc desc;
    desc.log = [](lantern::LogLevel level, std::string_view message) {
        if (level >= lantern::LogLevel::Warning)
            std::fprintf(stderr, "lantern %s: %.*s\n", lantern::logLevelName(level),
                         int(message.size()), message.data());
    };
    auto renderer = lantern::Renderer::create(desc);
    if (!renderer) return fail(renderer.error());
    std::printf("device: %s (%s)\n", renderer->device().name.c_str(),
                renderer->device().driver.c_str());

    auto scene = std::make_shared<const lantern::Scene>(buildScene());
    auto prepared = renderer->prepare(scene);  // validates and uploads once
    if (!prepared) return fail(prepared.error());

    lantern::RenderOptions options;
    options.width = 160;
    options.height = 120;
    options.camera.source = lantern::CameraSpec::Source::SceneCamera;
    options.camera.sceneCamera = 0;
    options.specular = lantern::SpecularModel::Blinn;
    options.aovs.depth = true;  // a Z plane in the image and in the EXR
    // Transparent instead of the default opaque black: the EXR's alpha is then the coverage, for
    // compositing the ball and floor over another picture.
    options.background = {0.0f, 0.0f, 0.0f, 0.0f};

    // Step the animation: four frames across its range, each rendered into memory.
    const lantern::TimeRange range = lantern::animationRange(*scene);
    lantern::Image last;
    double lastTime = 0.0;
    for (int frame = 0; frame < 4; ++frame) {
        const double t = range.start + range.duration() * frame / 4.0;
        auto image = renderer->render(*prepared, options, t);
        if (!image) return fail(image.error());
        const float* centre = image->pixel(image->width / 2, image->height / 2);
        std::printf("t=%.3f s: %dx%d, centre pixel RGBA %.3f %.3f %.3f %.3f, %.2f ms on the CPU\n",
                    t, image->width, image->height, centre[0], centre[1], centre[2], centre[3],
                    renderer->lastFrameStats().cpuMs);
        last = std::move(*image);
        lastTime = t;
    }

    if (auto written = lantern::writeExr(output, last); !written) return fail(written.error());
    std::printf("wrote %s (%dx%d RGBA + Z, t=%.3f s)\n", output.c_str(), last.width, last.height,
                lastTime);
    return 0;
}
