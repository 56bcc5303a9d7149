// PngIo.h: the PNG writer's entry points inside the engine. Rows come from anywhere (an
// Image, a frame left in the device's memory): row(y) is `width` premultiplied linear RGBA
// floats, y = 0 the top. The public writePng and PngStream (lantern/Io.h, api/Io.cpp) are
// these, with their arguments checked.
#pragma once

#include <lantern/Image.h>
#include <lantern/Result.h>

#include <filesystem>
#include <functional>
#include <memory>
#include <string>

namespace lantern::io {

using PngRowFn = std::function<const float*(int y)>;

/// Writes an 8-bit sRGB PNG (un-premultiplied, clamped, sRGB-encoded) atomically.
Result<void> writePngRows(const std::filesystem::path& path, int width, int height,
                          const PngRowFn& row);
Result<void> writePng(const std::filesystem::path& path, const Image& image);

/// A PNG written band by band into its atomic file: complete at finish() or absent.
class PngBandWriter {
public:
    static Result<PngBandWriter> create(const std::filesystem::path& path, int width, int height);
    PngBandWriter();
    PngBandWriter(PngBandWriter&&) noexcept;
    PngBandWriter& operator=(PngBandWriter&&) noexcept;
    ~PngBandWriter();
    /// Appends `rows` rows of `width` pixels (Usage when they do not fit what is left).
    Result<void> write(int width, int rows, const PngRowFn& row);
    /// After the last row: ends the file and moves it into place.
    Result<void> finish();
    std::string file() const;  ///< the destination

    struct Impl;

private:
    std::unique_ptr<Impl> m_impl;
};

} // namespace lantern::io
