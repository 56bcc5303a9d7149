// lantern::Renderer: the public face of the engine: a gpu::Device and the renderer's core
// (render/FrameRender.h), with the metadata every rendered image carries.
#include <lantern/Renderer.h>
#include <lantern/Version.h>

#include "api/RendererImpl.h"
#include "io/image/ImageEncode.h"
#include "render/Cryptomatte.h"
#include "render/FrameRender.h"

#include <cstdio>
#include <cstring>
#include <sstream>

namespace lantern {
namespace {

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

void attachMetadata(Image& image, const frame::Frame& p, const DeviceInfo& device, double time) {
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
        const frame::View& v = p.views[0];
        const CameraMetadata camera{v.camera.viewFromWorld, v.camera.clipFromView,
                                    v.camera.depth == DepthMode::ReversedZ,
                                    p.views.size() == 1 && v.x == 0 && v.y == 0 &&
                                        v.width == image.width && v.height == image.height};
        // A camera whose standard EXR matrices overflow float (a scene at 1e38, a camera at
        // 1e300) keeps its double-precision text above; the matrices are left out, and the
        // picture says why.
        if (io::exrCameraMatrices(camera))
            image.camera = camera;
        else
            md.emplace_back("lantern:warning",
                            "the camera's worldToCamera and worldToNDC are not finite in float; "
                            "they are left out of the picture's header");
    }
}

const Scene& PreparedScene::scene() const { return gpu::Device::sceneOf(*m_gpu); }

Renderer::Renderer(std::unique_ptr<Impl> impl) : m_impl(std::move(impl)) {}
Renderer::Renderer(Renderer&&) noexcept = default;
Renderer& Renderer::operator=(Renderer&&) noexcept = default;
Renderer::~Renderer() = default;

namespace {

Result<void> checkDesc(const RendererDesc& desc) {
    if (desc.framesInFlight < 1 || desc.framesInFlight > 8)
        return makeError(ErrorCode::Usage, "framesInFlight must be between 1 and 8",
                         "RendererDesc.framesInFlight");
    return {};
}

gpu::DeviceDesc deviceDesc(const RendererDesc& desc) {
    gpu::DeviceDesc d;
    d.deviceName = desc.deviceName;
    d.validation = desc.validation;
    d.synchronizationValidation = desc.synchronizationValidation;
    d.log = desc.log;
    d.instanceExtensions = desc.instanceExtensions;
    d.presentation = desc.presentation;
    d.framesInFlight = std::uint32_t(desc.framesInFlight);
    d.pipelineCacheOnDisk = desc.pipelineCacheOnDisk;
    d.pipelineCacheFolder = desc.pipelineCacheFolder;
    return d;
}

} // namespace

Result<Renderer> Renderer::create(const RendererDesc& desc) {
    LANTERN_TRY(checkDesc(desc));
    auto device = gpu::Device::create(deviceDesc(desc));
    if (!device) return std::move(device).error();
    auto impl = std::make_unique<Impl>();
    impl->device = std::move(*device);
    return Renderer(std::move(impl));
}

Result<Renderer> Renderer::create(const ExternalDevice& device, const RendererDesc& desc) {
    LANTERN_TRY(checkDesc(desc));
    auto adopted = gpu::Device::adopt(device, deviceDesc(desc));
    if (!adopted) return std::move(adopted).error();
    auto impl = std::make_unique<Impl>();
    impl->device = std::move(*adopted);
    return Renderer(std::move(impl));
}

const DeviceInfo& Renderer::device() const { return m_impl->device->info(); }

std::uint64_t Renderer::validationMessageCount() const {
    return m_impl->device->validationMessageCount();
}

const FrameStats& Renderer::lastFrameStats() const { return m_impl->stats; }

std::uint64_t Renderer::deviceMemoryBytes() const { return m_impl->device->deviceBytes(); }

Result<PreparedScene> Renderer::prepare(std::shared_ptr<const Scene> scene) {
    if (!scene) return makeError(ErrorCode::Usage, "prepare() needs a scene");
    LANTERN_TRY(scene->validate());
    auto buffers = m_impl->device->upload(std::move(scene));
    if (!buffers) return std::move(buffers).error();
    PreparedScene prepared;
    prepared.m_gpu = std::move(*buffers);
    return prepared;
}

Result<void> Renderer::updateVertices(const PreparedScene& prepared, int mesh, int primitive) {
    if (!prepared) return makeError(ErrorCode::Usage, "updateVertices() needs a prepared scene");
    if (mesh < 0 || primitive < 0)
        return makeError(ErrorCode::Usage, "the scene has no such primitive",
                         "mesh " + std::to_string(mesh) + " primitive " +
                             std::to_string(primitive));
    return m_impl->device->updateVertices(*prepared.m_gpu, std::uint32_t(mesh),
                                          std::uint32_t(primitive));
}

Result<Image> Renderer::render(const PreparedScene& prepared, const RenderOptions& options,
                               double time) {
    Image image;
    LANTERN_TRY(render(prepared, options, time, image));
    return image;
}

Result<void> Renderer::render(const PreparedScene& prepared, const RenderOptions& options,
                              double time, Image& into) {
    if (!prepared) return makeError(ErrorCode::Usage, "render() needs a prepared scene");
    gpu::Device& device = *m_impl->device;
    LANTERN_TRY(render::checkOptions(device, options));
    LANTERN_TRY(render::checkCryptomatte(options.aovs));
    auto frame = render::renderFrame(device, prepared.m_gpu, prepared.scene(), options, time,
                                     m_impl->stats, {}, std::move(into));
    into = Image{};
    if (!frame) return std::move(frame).error();
    if (frame->readback.nonFinite > 0)
        return render::nonFiniteFrame(device, prepared.m_gpu, prepared.scene(), options, time,
                                      frame->readback);
    into = std::move(frame->readback.image);
    attachMetadata(into, frame->frame, device.info(), time);
    if (options.aovs.anyCryptomatte()) return addCryptomatte(prepared, options, time, into);
    return {};
}

Result<FrameView> Renderer::renderView(const PreparedScene& prepared, const RenderOptions& options,
                                      double time) {
    if (!prepared) return makeError(ErrorCode::Usage, "renderView() needs a prepared scene");
    if (options.aovs.any() || options.aovs.anyCryptomatte())
        return makeError(ErrorCode::Usage,
                         "renderView() reads the colour only: render() returns AOV planes",
                         "options.aovs");
    gpu::Device& device = *m_impl->device;
    LANTERN_TRY(render::checkOptions(device, options));
    auto frame = render::renderFrame(device, prepared.m_gpu, prepared.scene(), options, time,
                                     m_impl->stats, {}, {}, /*inPlace=*/true);
    if (!frame) return std::move(frame).error();
    if (frame->readback.nonFinite > 0)
        return render::nonFiniteFrame(device, prepared.m_gpu, prepared.scene(), options, time,
                                      frame->readback);
    FrameView view;
    view.m_header = std::move(frame->readback.image);
    attachMetadata(view.m_header, frame->frame, device.info(), time);
    view.m_data = frame->readback.view.data;
    view.m_rowPitch = frame->readback.view.rowPitch;
    view.m_live = std::move(frame->readback.view.live);
    return view;
}

Result<void> Renderer::renderBands(const PreparedScene& prepared, const RenderOptions& options,
                                   double time, int rows, const BandSink& sink) {
    if (!prepared) return makeError(ErrorCode::Usage, "renderBands() needs a prepared scene");
    if (options.aovs.any() || options.aovs.anyCryptomatte())
        return makeError(ErrorCode::Usage,
                         "renderBands() reads the colour only: render() returns AOV planes",
                         "options.aovs");
    if (rows < 0) return makeError(ErrorCode::Usage, "a band has at least one row", "rows");
    gpu::Device& device = *m_impl->device;
    LANTERN_TRY(render::checkOptions(device, options));
    return render::renderBands(
        device, prepared.m_gpu, prepared.scene(), options, time, rows, m_impl->stats,
        [&](const gpu::FrameReadback& band, int top) {
            FrameView view;
            view.m_header.width = band.image.width;
            view.m_header.height = band.image.height;
            view.m_data = band.view.data;
            view.m_rowPitch = band.view.rowPitch;
            view.m_live = band.view.live;
            return sink(view, top);
        });
}

const float* FrameView::row(int y) const {
    if (!valid() || y < 0 || y >= height()) return nullptr;
    return reinterpret_cast<const float*>(m_data + std::size_t(y) * m_rowPitch);
}

const float* FrameView::pixel(int x, int y) const {
    const float* r = row(y);
    return r && x >= 0 && x < width() ? r + std::size_t(x) * 4 : nullptr;
}

Image FrameView::toImage() const {
    if (!valid()) return Image{};
    Image image = m_header;
    const std::size_t rowFloats = std::size_t(width()) * 4;
    image.rgba.resize(rowFloats * std::size_t(height()));
    for (int y = 0; y < height(); ++y)
        std::memcpy(image.rgba.data() + std::size_t(y) * rowFloats, row(y), rowFloats * 4);
    return image;
}

Result<void> Renderer::addCryptomatte(const PreparedScene& prepared, const RenderOptions& options,
                                      double time, Image& into) {
    // A second render of the ids alone at samples x samples the size (docs/aovs.md); the
    // frame's statistics stay those of the picture.
    auto layers = render::renderCryptomatte(*m_impl->device, prepared.m_gpu, prepared.scene(),
                                            options, time);
    if (!layers) {
        into = Image{};
        return std::move(layers).error();
    }
    into.cryptomatte = std::move(*layers);
    return {};
}

Result<Image> Renderer::render(const Scene& scene, const RenderOptions& options, double time) {
    LANTERN_TRY(render::checkOptions(*m_impl->device, options));
    auto prepared = prepare(borrow(scene));
    if (!prepared) return std::move(prepared).error();
    return render(*prepared, options, time);
}

Result<ProbeReport> Renderer::probe(const Scene& scene, const RenderOptions& options,
                                    double time, int x, int y) {
    auto prepared = prepare(borrow(scene));
    if (!prepared) return std::move(prepared).error();
    return render::probe(*m_impl->device, prepared->m_gpu, scene, options, time, x, y,
                         m_impl->stats);
}

Result<FeatureReport> Renderer::explain(const Scene& scene, const RenderOptions& options,
                                        double time) {
    return explainScene(scene, options, time);
}

Result<FeatureReport> explainScene(const Scene& scene, const RenderOptions& options, double time) {
    return render::explain(scene, options, time);
}

} // namespace lantern
