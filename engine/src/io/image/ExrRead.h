// ExrRead.h: how every EXR reader of the engine opens a file (readExr for images,
// readCompareImage for `lantern compare`): OpenEXR's InputFile, the data window checked, and
// whatever OpenEXR throws turned into an error that names the file.
#pragma once

#include "io/image/ImageEncode.h"

#include <lantern/Result.h>

#include <ImfHeader.h>
#include <ImfInputFile.h>

#include <exception>
#include <filesystem>
#include <string>

namespace lantern::io {

/// The width and height of an EXR's data window; refused, naming the file, when it is empty or
/// holds more than 2^31 pixels.
inline Result<std::pair<int, int>> exrWindowSize(const ExrWindow& dw,
                                                 const std::filesystem::path& path) {
    const long long w = (long long)dw.maxX - dw.minX + 1, h = (long long)dw.maxY - dw.minY + 1;
    if (w <= 0 || h <= 0 || w * h > (1LL << 31))
        return makeError(ErrorCode::InvalidInput, "unsupported data window", {}, path.string());
    return std::pair<int, int>(int(w), int(h));
}

/// Opens `path` and calls read(file, window, width, height) inside OpenEXR's exception frame.
template <typename T, typename Read>
Result<T> withExrFile(const std::filesystem::path& path, Read&& read) {
    try {
        Imf::InputFile in(path.c_str());
        const Imath::Box2i dw = in.header().dataWindow();
        const ExrWindow window{dw.min.x, dw.min.y, dw.max.x, dw.max.y};
        auto size = exrWindowSize(window, path);
        if (!size) return std::move(size).error();
        return read(in, window, size->first, size->second);
    } catch (const std::exception& e) {
        return makeError(ErrorCode::InvalidInput,
                         std::string("not a readable OpenEXR file: ") + e.what(), {},
                         path.string());
    }
}

} // namespace lantern::io
