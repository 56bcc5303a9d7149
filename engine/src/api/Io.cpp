// The public file entry points of lantern/Io.h: scenes in, images out and in. Each is the
// engine's own (io/SceneLoad.h, io/image/), with the checks that belong to the public contract
// (a frame view still valid, a band that fits).
#include <lantern/Io.h>
#include <lantern/Renderer.h>

#include "io/SceneLoad.h"
#include "io/gltf/GltfLoad.h"
#include "io/image/ImageIo.h"
#include "io/image/PngIo.h"
#include "scene/Builtins.h"

namespace lantern {
namespace {

Error staleView(const std::filesystem::path& path) {
    return makeError(ErrorCode::Usage,
                     "the frame view is no longer valid (its renderer rendered again)", {},
                     path.string());
}

} // namespace

Result<Scene> loadGltf(const std::filesystem::path& path, const LoadOptions& options) {
    auto format = io::sceneFormatOf(path);
    if (format && std::string_view((*format)->name) != "glTF")
        return makeError(ErrorCode::InvalidInput,
                         std::string("is a ") + (*format)->name +
                             " file, not glTF (loadScene reads every format)",
                         {}, path.string());
    return io::loadScene(path.string(), options);
}

std::vector<std::string> builtinSceneNames() { return scene::builtinSceneNames(); }

Result<Scene> builtinScene(std::string_view name) { return scene::builtinScene(name); }

Result<Scene> loadScene(std::string_view pathOrBuiltin, const LoadOptions& options) {
    return io::loadScene(pathOrBuiltin, options);
}

std::vector<std::string> sceneFileExtensions() {
    std::vector<std::string> out;
    for (const io::SceneFormat& f : io::sceneFormats())
        out.insert(out.end(), f.extensions.begin(), f.extensions.end());
    return out;
}

Result<void> writeExr(const std::filesystem::path& path, const Image& image,
                      const ExrOptions& options) {
    return io::writeExr(path, image, options);
}

Result<Image> readExr(const std::filesystem::path& path) { return io::readExr(path); }

Result<void> writePng(const std::filesystem::path& path, const Image& image) {
    return io::writePng(path, image);
}

Result<void> writePng(const std::filesystem::path& path, const FrameView& view) {
    if (!view.valid()) return staleView(path);
    return io::writePngRows(path, view.width(), view.height(),
                            [&](int y) { return view.row(y); });
}

Result<void> writeImage(const std::filesystem::path& path, const Image& image,
                        const ExrOptions& exrOptions) {
    return io::writeImage(path, image, exrOptions);
}

Result<CompareImage> readCompareImage(const std::filesystem::path& path) {
    return io::readCompareImage(path);
}

CompareImage toCompareImage(const Image& image, PixelEncoding encoding, std::string source) {
    return io::toCompareImage(image, encoding, std::move(source));
}

Result<CompareReport> compareFiles(const std::filesystem::path& reference,
                                   const std::filesystem::path& test, const CompareOptions& options) {
    auto ref = io::readCompareImage(reference);
    if (!ref) return std::move(ref).error();
    auto tst = io::readCompareImage(test);
    if (!tst) return std::move(tst).error();
    return compareImages(*ref, *tst, options);
}

// --- PngStream: io::PngBandWriter, fed from frame views -------------------------------------

struct PngStream::Impl {
    io::PngBandWriter writer;
};

Result<PngStream> PngStream::create(const std::filesystem::path& path, int width, int height) {
    auto writer = io::PngBandWriter::create(path, width, height);
    if (!writer) return std::move(writer).error();
    PngStream stream;
    stream.m_impl = std::make_unique<Impl>(Impl{std::move(*writer)});
    return stream;
}

PngStream::PngStream() = default;
PngStream::PngStream(PngStream&&) noexcept = default;
PngStream& PngStream::operator=(PngStream&&) noexcept = default;
PngStream::~PngStream() = default;

Result<void> PngStream::write(const FrameView& band) {
    if (!m_impl) return makeError(ErrorCode::Usage, "the PNG stream has failed or finished");
    if (!band.valid()) return staleView(m_impl->writer.file());
    return m_impl->writer.write(band.width(), band.height(), [&](int y) { return band.row(y); });
}

Result<void> PngStream::finish() {
    if (!m_impl) return makeError(ErrorCode::Usage, "the PNG stream has failed or finished");
    return m_impl->writer.finish();
}

} // namespace lantern
