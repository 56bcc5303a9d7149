// lantern::Renderer: the public face of the engine (context + Engine + FramePlan).
#include <lantern/Renderer.h>
#include <lantern/Version.h>

#include "render/Probe.h"
#include "render/RendererImpl.h"

#include <chrono>
#include <cstdio>
#include <set>
#include <sstream>

namespace lantern {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

std::string matrixText(const glm::dmat4& m) {
    // Row-major text, 17 significant digits: the exact double the frame was built from.
    std::ostringstream s;
    s.precision(17);
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) s << (r || c ? " " : "") << m[c][r];
    return s.str();
}

std::string numberText(double v) {
    char b[64];
    std::snprintf(b, sizeof b, "%.17g", v);
    return b;
}

// A shared_ptr that does not own: for rendering a caller's Scene synchronously.
std::shared_ptr<const Scene> borrow(const Scene& scene) {
    return std::shared_ptr<const Scene>(std::shared_ptr<const Scene>(), &scene);
}

} // namespace

void attachMetadata(Image& image, const render::FramePlan& p, const DeviceInfo& device,
                    double time) {
    auto& md = image.metadata;
    md.emplace_back("lantern:version", versionString());
    md.emplace_back("lantern:device", device.name);
    md.emplace_back("lantern:time", numberText(time));
    md.emplace_back("lantern:shading", toString(p.lighting.model.shading));
    md.emplace_back("lantern:specular", toString(p.lighting.model.specular));
    md.emplace_back("lantern:glCompat", p.lighting.glCompat ? "true" : "false");
    if (!p.views.empty()) {
        md.emplace_back("lantern:camera", p.views[0].camera.description);
        md.emplace_back("lantern:viewFromWorld", matrixText(p.views[0].camera.viewFromWorld));
        md.emplace_back("lantern:clipFromView", matrixText(p.views[0].camera.clipFromView));
        image.camera = CameraMetadata{p.views[0].camera.viewFromWorld, p.views[0].camera.clipFromView};
    }
}

const Scene& PreparedScene::scene() const { return m_gpu->scene(); }

Renderer::Renderer(std::unique_ptr<Impl> impl) : m_impl(std::move(impl)) {}
Renderer::Renderer(Renderer&&) noexcept = default;
Renderer& Renderer::operator=(Renderer&&) noexcept = default;
Renderer::~Renderer() = default;

Result<Renderer> Renderer::create(const RendererDesc& desc) {
    if (desc.framesInFlight < 1 || desc.framesInFlight > 8)
        return makeError(ErrorCode::Usage, "framesInFlight must be between 1 and 8");
    gpu::ContextDesc cd;
    cd.deviceName = desc.deviceName;
    cd.validation = desc.validation;
    cd.synchronizationValidation = desc.synchronizationValidation;
    cd.log = desc.log;
    cd.instanceExtensions = desc.instanceExtensions;
    cd.swapchain = desc.presentation;
    auto ctx = gpu::Context::create(cd);
    if (!ctx) return std::move(ctx).error();
    auto engine = render::Engine::create(*ctx, std::uint32_t(desc.framesInFlight));
    if (!engine) return std::move(engine).error();

    auto impl = std::make_unique<Impl>();
    impl->ctx = std::move(*ctx);
    impl->engine = std::move(*engine);
    impl->presentation = desc.presentation;
    const auto& p = impl->ctx->properties();
    DeviceInfo& info = impl->info;
    info.name = p.deviceName;
    info.driver = impl->ctx->driverInfo();
    switch (p.deviceType) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: info.type = "discrete-gpu"; break;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: info.type = "integrated-gpu"; break;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: info.type = "virtual-gpu"; break;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: info.type = "cpu"; break;
    default: info.type = "other"; break;
    }
    info.apiVersion = p.apiVersion;
    info.validationEnabled = impl->ctx->validationEnabled();
    for (int s : {1, 2, 4, 8})
        if (impl->ctx->capabilities().colorDepthSampleCounts & std::uint32_t(s))
            info.msaaSampleCounts.push_back(s);
    return Renderer(std::move(impl));
}

const DeviceInfo& Renderer::device() const { return m_impl->info; }

std::uint64_t Renderer::validationMessageCount() const {
    return m_impl->ctx->validationMessageCount();
}

const FrameStats& Renderer::lastFrameStats() const { return m_impl->stats; }

Result<PreparedScene> Renderer::prepare(std::shared_ptr<const Scene> scene) {
    if (!scene) return makeError(ErrorCode::Usage, "prepare() needs a scene");
    LANTERN_TRY(scene->validate());
    auto gpuScene = render::GpuScene::create(m_impl->ctx, std::move(scene),
                                             m_impl->engine->textureLayout());
    if (!gpuScene) return std::move(gpuScene).error();
    PreparedScene prepared;
    prepared.m_gpu = std::move(*gpuScene);
    return prepared;
}

namespace {
// Submits a planned frame and waits for it (synchronous rendering), recording its stats.
Result<render::FrameResult> renderPlanned(render::Engine& engine,
                                          const std::shared_ptr<render::GpuScene>& scene,
                                          const render::FramePlan& plan,
                                          const RenderOptions& options, Clock::time_point t0,
                                          FrameStats& stats) {
    const std::size_t pipelinesBefore = engine.pipelineCount();
    // Drain any slot still in flight from a sequence before reusing it.
    const std::uint32_t next = engine.nextSlot();
    if (engine.busy(next)) {
        auto drained = engine.collect(next, options);
        if (!drained) return std::move(drained).error();
    }
    auto slot = engine.submit(scene, plan, options);
    if (!slot) return std::move(slot).error();
    stats = FrameStats{};
    stats.cpuMs = msSince(t0);
    const auto t1 = Clock::now();
    auto frame = engine.collect(*slot, options);
    if (!frame) return std::move(frame).error();
    stats.waitMs = msSince(t1);
    stats.gpuMs = frame->gpuMs;
    stats.draws = frame->draws;
    stats.nonFinite = frame->nonFinite;
    stats.pipelinesCreated = engine.pipelineCount() - pipelinesBefore;
    return frame;
}
} // namespace

Result<Image> Renderer::render(const PreparedScene& prepared, const RenderOptions& options,
                               double time) {
    if (!prepared) return makeError(ErrorCode::Usage, "render() needs a prepared scene");
    render::Engine& engine = *m_impl->engine;
    LANTERN_TRY(engine.checkOptions(options));
    const auto t0 = Clock::now();
    auto plan = render::buildFramePlan(prepared.scene(), options, time);
    if (!plan) return std::move(plan).error();
    auto frame = renderPlanned(engine, prepared.m_gpu, *plan, options, t0, m_impl->stats);
    if (!frame) return std::move(frame).error();

    Image image = std::move(frame->image);
    attachMetadata(image, *plan, m_impl->info, time);
    return image;
}

Result<Image> Renderer::render(const Scene& scene, const RenderOptions& options, double time) {
    LANTERN_TRY(m_impl->engine->checkOptions(options));
    auto prepared = prepare(borrow(scene));
    if (!prepared) return std::move(prepared).error();
    return render(*prepared, options, time);
}

Result<render::ExplainedFrame> render::RendererAccess::renderExplained(
    Renderer& renderer, const Scene& scene, const RenderOptions& options, double time,
    const std::function<void(FramePlan&)>& edit) {
    render::ExplainedFrame f;
    f.options = options;
    f.options.aovs.depth = f.options.aovs.normal = true;
    render::Engine& engine = *renderer.m_impl->engine;
    LANTERN_TRY(engine.checkOptions(f.options));
    auto prepared = renderer.prepare(borrow(scene));
    if (!prepared) return std::move(prepared).error();
    const auto t0 = Clock::now();
    auto plan = render::buildFramePlan(scene, f.options, time);
    if (!plan) return std::move(plan).error();
    if (edit) edit(*plan);
    auto frame =
        renderPlanned(engine, prepared->m_gpu, *plan, f.options, t0, renderer.m_impl->stats);
    if (!frame) return std::move(frame).error();
    f.plan = std::move(*plan);
    f.frame = std::move(*frame);
    return f;
}

Result<ProbeReport> Renderer::probe(const Scene& scene, const RenderOptions& options,
                                    double time, int x, int y) {
    if (x < 0 || y < 0 || x >= options.width || y >= options.height)
        return makeError(ErrorCode::InvalidInput,
                         "pixel " + std::to_string(x) + "," + std::to_string(y) +
                             " is outside the " + std::to_string(options.width) + "x" +
                             std::to_string(options.height) + " image",
                         "--probe");
    // One sample per pixel: the probe explains the surface at the pixel centre.
    RenderOptions single = options;
    single.msaa = 1;
    auto f = render::RendererAccess::renderExplained(*this, scene, single, time);
    if (!f) return std::move(f).error();
    return render::probePixel(scene, *f, x, y);
}

Result<FeatureReport> Renderer::explain(const Scene& scene, const RenderOptions& options,
                                        double time) {
    return explainScene(scene, options, time);
}

Result<FeatureReport> explainScene(const Scene& scene, const RenderOptions& options, double time) {
    LANTERN_TRY(scene.validate());
    auto plan = render::buildFramePlan(scene, options, time);
    if (!plan) return std::move(plan).error();
    FeatureReport report;
    report.features = plan->features;
    std::set<std::string> seen;
    for (const render::ViewPlan& v : plan->views)
        for (const render::DrawItem& d : v.draws) {
            const std::string line = d.key.describe();
            if (seen.insert(line).second) report.variants.push_back(line);
        }
    return report;
}

} // namespace lantern
