// lantern_microbench: Google Benchmark micro-benchmarks of the CPU-side paths a frame or a file
// goes through. The GPU side is measured by `lantern bench` (frame, sequence, speed, accuracy);
// these are the parts a host pays on its own thread. Compare rows of one run (ratios), never
// absolute numbers across runs. See docs/performance.md for the results and the command.
#include "GltfEncode.h"
#include "reference/Lighting.h"
#include "render/FrameRender.h"

#include <lantern/Lantern.h>

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <unistd.h>
#include <vector>

namespace {

using namespace lantern;
namespace fs = std::filesystem;

// A cube of cubes, n per side, seen from a corner; everything shifted by `offset`. The
// camera-relative path composes viewFromWorld * worldFromNode in double for every draw: at 1e7
// this must cost what it costs at the origin.
Scene gridScene(int n, double offset) {
    const glm::dvec3 o(offset, 0.5 * offset, -0.75 * offset);
    Scene s;
    s.sourcePath = "microbench";
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
        node.translation = o + glm::dvec3(i % n, (i / n) % n, i / (n * n)) - glm::dvec3(n / 2.0);
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
    camera.lookAt = LookAt{o + glm::dvec3(1.3 * n, 0.9 * n, 1.6 * n), o, {0, 1, 0}};
    s.cameras.push_back(camera);
    s.roots.push_back(root);
    return s;
}

// Frame planning (cameras, eye-space lights, materials, one draw per node) for 16^3 nodes;
// argument 0: at the origin, 1: scene and camera 1e7 units away.
void BM_BuildFramePlan(benchmark::State& state) {
    const Scene scene = gridScene(16, state.range(0) ? 1e7 : 0.0);
    RenderOptions options;
    options.width = 640;
    options.height = 360;
    for (auto _ : state) {
        auto plan = render::planFrame(scene, options, 0.0);
        if (!plan) {
            state.SkipWithError(plan.error().describe().c_str());
            break;
        }
        benchmark::DoNotOptimize(plan);
    }
    state.SetItemsProcessed(state.iterations() * 4096);
    state.SetLabel(state.range(0) ? "at 1e7" : "at the origin");
}
BENCHMARK(BM_BuildFramePlan)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

// The one operation the camera-relative path adds per draw: a double 4x4 product.
void BM_CameraRelativeCompose(benchmark::State& state) {
    const Scene scene = gridScene(16, 1e7);
    const glm::dmat4 viewFromWorld =
        lookAt(scene.cameras[0].lookAt->eye, scene.cameras[0].lookAt->target, {0, 1, 0});
    std::vector<glm::dmat4> worldFromNode;
    for (const Node& n : scene.nodes) worldFromNode.push_back(n.localTransform());
    std::vector<glm::mat4> out(worldFromNode.size());
    for (auto _ : state) {
        for (std::size_t i = 0; i < worldFromNode.size(); ++i)
            out[i] = glm::mat4(viewFromWorld * worldFromNode[i]);
        benchmark::DoNotOptimize(out.data());
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(state.iterations() * std::int64_t(worldFromNode.size()));
}
BENCHMARK(BM_CameraRelativeCompose);

// A whole frame on the device (plan, record, render 640x360, read back) of the same grid, at
// the origin and 1e7 away: the camera-relative path must cost nothing measurable. Skipped,
// saying so, without a Vulkan device.
void BM_RenderFrame(benchmark::State& state) {
    static auto renderer = Renderer::create();
    if (!renderer) {
        state.SkipWithError(("no Vulkan device: " + renderer.error().describe()).c_str());
        return;
    }
    auto prepared =
        renderer->prepare(std::make_shared<const Scene>(gridScene(16, state.range(0) ? 1e7 : 0.0)));
    if (!prepared) {
        state.SkipWithError(prepared.error().describe().c_str());
        return;
    }
    RenderOptions options;
    options.width = 640;
    options.height = 360;
    for (auto _ : state) {
        auto image = renderer->render(*prepared, options, 0.0);
        if (!image) {
            state.SkipWithError(image.error().describe().c_str());
            break;
        }
        benchmark::DoNotOptimize(image);
    }
    state.SetLabel(state.range(0) ? "at 1e7" : "at the origin");
}
BENCHMARK(BM_RenderFrame)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

// A 64 x 32 sphere with GL's default material under one directional light, seen from (0, 0, 3).
Scene litSphereScene() {
    Scene scene;
    scene.materials.push_back(Material{});
    Primitive sphere = makeSphere(1.0, 64, 32);
    sphere.material = 0;
    scene.meshes.push_back(Mesh{"sphere", {sphere}});
    Node node;
    node.mesh = 0;
    scene.nodes.push_back(node);
    Light light;
    light.type = LightType::Directional;
    scene.lights.push_back(light);
    Node sun;
    sun.light = 0;
    scene.nodes.push_back(sun);
    Camera camera;
    camera.projection = Projection::makePerspective(0.8, 0.0, 0.1, kInfinity);
    camera.lookAt = LookAt{{0, 0, 3}, {0, 0, 0}, {0, 1, 0}};
    scene.cameras.push_back(camera);
    scene.roots.push_back(SceneRoot{"", {0, 1}, {}});
    return scene;
}

// One sphere under one directional light at 1920x1080 (the frame lantern_peer_gl times against
// OpenGL), its float pixels read back: arg 0 staged (LANTERN_TEST_READBACK=staged: copied into
// a buffer on the device, then into the Image), arg 1 in place where the device allows it (the
// Image filled straight from the rendered linear image), arg 2 in place into one Image kept
// across frames (Renderer::render(..., Image& into): no fresh pages to fault in). Counters:
// gpu_ms, the render pass (GPU timestamps); wait_ms, the fence wait and the readback into the
// Image. Needs a build with the testing hooks (the tests' builds) to force the staged path; says
// so otherwise.
void BM_Readback1080p(benchmark::State& state) {
    const bool staged = state.range(0) == 0;
    struct Made {
        std::optional<Renderer> renderer;
        std::string path;  // how the colour is read back, from the debug log
    };
    static Made made[2];
    Made& m = made[staged ? 0 : 1];
    if (!m.renderer) {
        if (staged) ::setenv("LANTERN_TEST_READBACK", "staged", 1);
        RendererDesc desc;
        desc.log = [&m](LogLevel, std::string_view line) {
            const std::string_view prefix = "colour 1920x1080 read back ";
            if (line.substr(0, prefix.size()) == prefix) m.path = line.substr(prefix.size());
        };
        auto r = Renderer::create(desc);
        ::unsetenv("LANTERN_TEST_READBACK");
        if (!r) {
            state.SkipWithError(("no Vulkan device: " + r.error().describe()).c_str());
            return;
        }
        m.renderer.emplace(std::move(*r));
    }
    auto prepared = m.renderer->prepare(std::make_shared<const Scene>(litSphereScene()));
    if (!prepared) {
        state.SkipWithError(prepared.error().describe().c_str());
        return;
    }
    RenderOptions options;
    options.width = 1920;
    options.height = 1080;
    options.shading = ShadingMode::Gouraud;
    if (!m.renderer->render(*prepared, options, 0.0)) {
        state.SkipWithError("the first frame failed");
        return;
    }
    if (staged != (m.path.rfind("staged", 0) == 0)) {
        state.SkipWithError(("the colour is read back " + m.path).c_str());
        return;
    }
    double gpuMs = 0, waitMs = 0;
    Image kept;
    for (auto _ : state) {
        if (state.range(0) == 2) {
            if (auto done = m.renderer->render(*prepared, options, 0.0, kept); !done) {
                state.SkipWithError(done.error().describe().c_str());
                break;
            }
            benchmark::DoNotOptimize(kept.rgba.data());
        } else {
            auto image = m.renderer->render(*prepared, options, 0.0);
            if (!image) {
                state.SkipWithError(image.error().describe().c_str());
                break;
            }
            benchmark::DoNotOptimize(image);
        }
        gpuMs += m.renderer->lastFrameStats().gpuMs;
        waitMs += m.renderer->lastFrameStats().waitMs;
    }
    state.counters["gpu_ms"] = benchmark::Counter(gpuMs, benchmark::Counter::kAvgIterations);
    state.counters["wait_ms"] = benchmark::Counter(waitMs, benchmark::Counter::kAvgIterations);
    state.SetLabel(state.range(0) == 2 ? m.path + ", into one Image" : m.path);
}
BENCHMARK(BM_Readback1080p)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// A plane of 257 x 257 vertices (131072 triangles) bent about +Y by a two-bone skin: unskinned
// (arg 0: the same mesh without joints or skin), skinned with 4 influences per vertex (arg 4,
// JOINTS_0 only) or 8 (arg 8, JOINTS_0 and JOINTS_1). The frame's pose changes every iteration, so the pre-pass runs every frame.
Scene skinnedPlaneScene(int influences) {
    Scene s;
    Primitive p = makePlane(2.0, 256);
    if (influences > 0)
        for (const glm::vec3& v : p.positions) {
            const float w1 = std::clamp(v.x + 0.5f, 0.0f, 1.0f), w0 = 1.0f - w1;
            if (influences == 8) {
                p.joints0.push_back({0, 1, 0, 1});
                p.weights0.push_back({w0 / 2, w1 / 2, 0, 0});
                p.joints1.push_back({0, 1, 0, 1});
                p.weights1.push_back({w0 / 2, w1 / 2, 0, 0});
            } else {
                p.joints0.push_back({0, 1, 0, 0});
                p.weights0.push_back({w0, w1, 0, 0});
            }
        }
    s.meshes.push_back(Mesh{"plane", {p}, {}});
    Node bone0, bone1, plane;
    bone0.children = {1};
    plane.mesh = 0;
    plane.skin = influences > 0 ? 0 : -1;
    s.nodes = {bone0, bone1, plane};
    if (influences > 0) s.skins.push_back(Skin{"bones", {0, 1}, {glm::dmat4(1.0), glm::dmat4(1.0)}, -1});
    AnimationSampler smp;
    smp.times = {0.0, 1.0};
    smp.values = {glm::dvec4(0, 0, 0, 1), glm::dvec4(0, std::sin(0.785398), 0, std::cos(0.785398))};
    Animation a;
    a.samplers.push_back(smp);
    a.channels.push_back({1, AnimationPath::Rotation, 0});
    s.animations.push_back(a);
    s.roots.push_back(SceneRoot{"", {0, 2}, std::nullopt});
    return s;
}

void BM_RenderSkinned(benchmark::State& state) {
    static auto renderer = Renderer::create();
    if (!renderer) {
        state.SkipWithError(("no Vulkan device: " + renderer.error().describe()).c_str());
        return;
    }
    auto prepared = renderer->prepare(
        std::make_shared<const Scene>(skinnedPlaneScene(int(state.range(0)))));
    if (!prepared) {
        state.SkipWithError(prepared.error().describe().c_str());
        return;
    }
    RenderOptions options;
    options.width = 640;
    options.height = 360;
    // A fixed camera: automatic framing would sample the animation's bounds on the CPU.
    options.camera.lookAt = LookAt{{0, 2, 4}, {0, 0, 0}, {0, 1, 0}};
    double t = 0.0;
    for (auto _ : state) {
        auto image = renderer->render(*prepared, options, t);
        if (!image) {
            state.SkipWithError(image.error().describe().c_str());
            break;
        }
        benchmark::DoNotOptimize(image);
        t = t >= 1.0 ? 0.0 : t + 0.05;
    }
    state.SetLabel(state.range(0) == 0 ? "unskinned" : state.range(0) == 4 ? "skinned, 4 influences"
                                                                           : "skinned, 8 influences");
}
BENCHMARK(BM_RenderSkinned)->Arg(0)->Arg(4)->Arg(8)->Unit(benchmark::kMillisecond)->UseRealTime();

// Angle-weighted smooth normals (what a glTF without NORMAL costs at load) on a sphere of
// about 2 * segments^2 / 2 triangles.
void BM_SmoothNormals(benchmark::State& state) {
    const int segments = int(state.range(0));
    const Primitive sphere = makeSphere(1.0, segments, segments / 2);
    for (auto _ : state) {
        auto normals = computeSmoothNormals(sphere.positions, sphere.indices);
        benchmark::DoNotOptimize(normals.data());
    }
    state.SetItemsProcessed(state.iterations() * std::int64_t(sphere.triangleCount()));
    state.counters["triangles"] = double(sphere.triangleCount());
}
BENCHMARK(BM_SmoothNormals)->Arg(64)->Arg(512)->Unit(benchmark::kMicrosecond);

// The double-precision reference equation at one point with N point lights (the per-sample
// cost of the ray caster and of --probe).
void BM_ReferenceLighting(benchmark::State& state) {
    const int n = int(state.range(0));
    std::vector<ref::EyeLight> lights(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
        const double a = 6.283185307179586 * i / n;
        lights[std::size_t(i)].type = LightType::Point;
        lights[std::size_t(i)].position = {3 * std::cos(a), 3 * std::sin(a), 1.0};
        lights[std::size_t(i)].attenuation = {1.0, 0.1, 0.01};
        lights[std::size_t(i)].diffuse = glm::dvec3(1.0 / n);
        lights[std::size_t(i)].specular = glm::dvec3(1.0 / n);
    }
    MaterialSide m;
    m.specular = {1, 1, 1};
    m.shininess = 128;
    ref::Settings settings;
    const glm::dvec3 V(0.1, -0.2, -4.0), normal = glm::normalize(glm::dvec3(0.1, -0.2, 1.0));
    for (auto _ : state) {
        auto sums = ref::evaluateLighting(V, normal, m, lights, settings);
        benchmark::DoNotOptimize(sums);
    }
    state.SetItemsProcessed(state.iterations() * n);
}
BENCHMARK(BM_ReferenceLighting)->Arg(1)->Arg(8)->Arg(64)->Arg(256);

fs::path sharedDir() {
    if (const char* env = std::getenv("LANTERN_SHARED_DIR")) return env;
    return LANTERN_DEFAULT_SHARED_DIR;
}

// The timed loop of the load benchmarks: loadGltf(path), stopping at the first error.
void loadEachIteration(benchmark::State& state, const fs::path& path) {
    for (auto _ : state) {
        auto scene = loadGltf(path);
        if (!scene) {
            state.SkipWithError(scene.error().describe().c_str());
            break;
        }
        benchmark::DoNotOptimize(scene);
    }
}

// Loading and validating a glTF from ../shared/assets (skipped, saying so, when absent).
void BM_LoadGltf(benchmark::State& state, const char* relative) {
    const fs::path path = sharedDir() / "assets" / "gltf-samples" / relative;
    if (!fs::exists(path)) {
        state.SkipWithError(("not found (../shared absent): " + path.string()).c_str());
        return;
    }
    loadEachIteration(state, path);
}
BENCHMARK_CAPTURE(BM_LoadGltf, Suzanne, "Suzanne/glTF/Suzanne.gltf")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_LoadGltf, Duck, "Duck/glTF-Binary/Duck.glb")->Unit(benchmark::kMillisecond);

// One UV sphere of 1 000 000 triangles (501 x 1001 vertices with normals and texcoords) written
// as .glb once per run in each encoding (GltfEncode.h: the test suite's encoders), then loaded:
// what decompression costs against reading the same mesh plain. The file size is a counter.
class CompressedSpheres {
public:
    ~CompressedSpheres() {
        std::error_code ec;
        for (const auto& [encoding, path] : m_paths) fs::remove(path, ec);
    }
    const fs::path& path(test::Encoding e) {
        auto it = m_paths.find(e);
        if (it != m_paths.end()) return it->second;
        if (m_sphere.indices.empty()) m_sphere = test::makeSphere(500, 1000);
        test::GltfBuilder b;
        test::addEncodedMesh(b, m_sphere, e);
        const std::string name =
            "lantern-microbench-" + std::to_string(::getpid()) + "-" + test::encodingName(e);
        return m_paths[e] = b.write(fs::temp_directory_path(), name, test::GltfBuilder::Storage::Glb);
    }

private:
    test::TestMesh m_sphere;
    std::map<test::Encoding, fs::path> m_paths;
};

void BM_LoadCompressedGltf(benchmark::State& state) {
    static CompressedSpheres spheres;
    const auto encoding = test::Encoding(state.range(0));
    const fs::path& path = spheres.path(encoding);
    loadEachIteration(state, path);
    state.counters["MiB"] = double(fs::file_size(path)) / (1024.0 * 1024.0);
    state.SetLabel(test::encodingName(encoding));
}
BENCHMARK(BM_LoadCompressedGltf)
    ->Arg(int(test::Encoding::Float))
    ->Arg(int(test::Encoding::Quantized))
    ->Arg(int(test::Encoding::MeshoptFloat))
    ->Arg(int(test::Encoding::MeshoptQuantized))
    ->Arg(int(test::Encoding::Draco))
    ->Unit(benchmark::kMillisecond);

} // namespace

BENCHMARK_MAIN();
