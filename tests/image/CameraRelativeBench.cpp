// lantern_camera_bench: what the camera-relative path costs. Plans (render::buildFramePlan)
// and renders a many-node scene with the scene and camera at the origin and 1e7 units away,
// interleaved, and times the one extra operation camera-relative rendering does per draw: a
// double-precision viewFromWorld * worldFromNode product. Not a test (timings are noisy);
// docs/cameras.md quotes its output. Usage: lantern_camera_bench [NODES] [FRAMES]
#include "render/FramePlan.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <lantern/Lantern.h>
#include <vector>

namespace {

using namespace lantern;
using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

// A cube of cubes, n per side, the camera looking at it from a corner; everything shifted by
// `offset` (world coordinates).
Scene gridScene(int n, const glm::dvec3& offset) {
    Scene s;
    s.sourcePath = "bench";
    Material m;
    m.front.diffuse = {0.7, 0.6, 0.5, 1.0};
    m.front.specular = {0.3, 0.3, 0.3};
    m.front.shininess = 20;
    s.materials.push_back(m);
    Primitive cube = makeCube(0.6);
    cube.material = 0;
    s.meshes.push_back(Mesh{"cube", {cube}});
    SceneRoot root;
    for (int i = 0; i < n * n * n; ++i) {
        Node node;
        node.mesh = 0;
        node.translation =
            offset + glm::dvec3(i % n, (i / n) % n, i / (n * n)) - glm::dvec3(n / 2.0);
        s.nodes.push_back(node);
        root.nodes.push_back(i);
    }
    Light sun;
    sun.type = LightType::Directional;
    Node sunNode;
    sunNode.light = 0;
    sunNode.rotation = glm::angleAxis(-0.6, glm::normalize(glm::dvec3(1, 1, 0)));
    s.lights.push_back(sun);
    s.nodes.push_back(sunNode);
    root.nodes.push_back(int(s.nodes.size()) - 1);
    Camera camera;
    camera.projection = Projection::makePerspective(0.8, 0.0, 0.1, kInfinity);
    camera.lookAt = LookAt{offset + glm::dvec3(1.3 * n, 0.9 * n, 1.6 * n), offset, {0, 1, 0}};
    s.cameras.push_back(camera);
    s.roots.push_back(root);
    return s;
}

} // namespace

int main(int argc, char** argv) {
    const int perSide = argc > 1 ? std::max(1, int(std::cbrt(std::atof(argv[1])))) : 16;
    const int frames = argc > 2 ? std::max(3, std::atoi(argv[2])) : 15;
    const double offsets[] = {0.0, 1e7};
    std::vector<Scene> scenes;
    for (double o : offsets)
        scenes.push_back(gridScene(perSide, glm::dvec3(o, 0.5 * o, -0.75 * o)));
    const std::size_t nodes = std::size_t(perSide) * perSide * perSide;
    std::printf("scene: %zu cube nodes (%zu triangles), frames: %d, interleaved\n", nodes,
                nodes * 12, frames);

    RenderOptions options;
    options.width = 640;
    options.height = 360;

    // 1. Planning only (CPU): buildFramePlan.
    std::vector<double> plan[2];
    for (int f = 0; f < frames * 4; ++f)
        for (int i = 0; i < 2; ++i) {
            const auto t0 = Clock::now();
            auto p = render::buildFramePlan(scenes[i], options, 0.0);
            plan[i].push_back(msSince(t0));
            if (!p) {
                std::fprintf(stderr, "plan failed: %s\n", p.error().describe().c_str());
                return 1;
            }
        }

    // 2. The extra work of the camera-relative path: one double 4x4 product per draw.
    const glm::dmat4 viewFromWorld =
        lookAt(scenes[1].cameras[0].lookAt->eye, scenes[1].cameras[0].lookAt->target, {0, 1, 0});
    std::vector<glm::dmat4> worldFromNode;
    for (const Node& n : scenes[1].nodes)
        worldFromNode.push_back(n.localTransform());
    std::vector<double> compose;
    double sink = 0.0;
    for (int f = 0; f < frames * 4; ++f) {
        const auto t0 = Clock::now();
        for (const glm::dmat4& m : worldFromNode)
            sink += (viewFromWorld * m)[3][2];
        compose.push_back(msSince(t0));
    }

    // 3. Whole frames on the device (planning, recording, rendering, read-back).
    auto renderer = Renderer::create();
    std::vector<double> frame[2], cpu[2];
    if (!renderer) {
        std::fprintf(stderr, "no renderer (%s): frame times skipped\n",
                     renderer.error().describe().c_str());
    } else {
        std::vector<PreparedScene> prepared;
        for (const Scene& s : scenes) {
            auto p = renderer->prepare(std::make_shared<const Scene>(s));
            if (!p) {
                std::fprintf(stderr, "prepare failed: %s\n", p.error().describe().c_str());
                return 1;
            }
            prepared.push_back(*p);
        }
        for (int i = 0; i < 2; ++i)
            (void)renderer->render(prepared[i], options, 0.0); // warm
        for (int f = 0; f < frames; ++f)
            for (int i = 0; i < 2; ++i) {
                const auto t0 = Clock::now();
                auto image = renderer->render(prepared[i], options, 0.0);
                frame[i].push_back(msSince(t0));
                cpu[i].push_back(renderer->lastFrameStats().cpuMs);
                if (!image) {
                    std::fprintf(stderr, "render failed: %s\n", image.error().describe().c_str());
                    return 1;
                }
            }
        std::printf("device: %s\n", renderer->device().name.c_str());
    }

    std::printf("| | at the origin | at 1e7 |\n|---|---|---|\n");
    std::printf("| buildFramePlan, median ms | %.3f | %.3f |\n", median(plan[0]), median(plan[1]));
    if (!frame[0].empty()) {
        std::printf("| frame CPU (plan + record + submit), median ms | %.3f | %.3f |\n",
                    median(cpu[0]), median(cpu[1]));
        std::printf("| whole frame %dx%d, median ms | %.2f | %.2f |\n", options.width,
                    options.height, median(frame[0]), median(frame[1]));
    }
    std::printf("camera-relative composition (viewFromWorld * worldFromNode, double): %.4f ms "
                "per frame for %zu draws = %.1f ns per draw (checksum %g)\n",
                median(compose), worldFromNode.size(),
                median(compose) * 1e6 / double(worldFromNode.size()), sink);
    return 0;
}
