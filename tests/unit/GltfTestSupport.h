// GltfTestSupport.h: loading a glTF file in a test with its warnings captured, and checking
// that a refusal names the file, the object and the problem.
#pragma once

#include "GltfTestBuilder.h"
#include "TestSupport.h"

#include <lantern/Io.h>

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

namespace lantern::test {

struct LoadOutcome {
    Result<Scene> scene = makeError(ErrorCode::Internal, "not loaded");
    std::shared_ptr<std::vector<std::string>> warnings = std::make_shared<std::vector<std::string>>();

    bool warned(const std::string& fragment) const {
        for (const std::string& w : *warnings)
            if (w.find(fragment) != std::string::npos) return true;
        return false;
    }
    std::string allWarnings() const {
        std::string s;
        for (const std::string& w : *warnings) s += w + "\n";
        return s;
    }
};

inline LoadOutcome loadCapturing(const std::filesystem::path& path, std::uint64_t maxBytes = std::uint64_t(1) << 30) {
    LoadOutcome out;
    LoadOptions options;
    options.maxBytes = maxBytes;
    auto sink = out.warnings;
    options.log = [sink](LogLevel, std::string_view message) { sink->emplace_back(message); };
    out.scene = loadGltf(path, options);
    return out;
}

/// A file's own JSON (a .glb's JSON chunk), parsed independently of the loader.
inline nlohmann::json fileJson(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::string bytes(std::filesystem::file_size(path), '\0');
    in.read(bytes.data(), std::streamsize(bytes.size()));
    if (path.extension() == ".glb") {
        std::uint32_t length = 0;
        std::memcpy(&length, bytes.data() + 12, 4);
        bytes = bytes.substr(20, length);
    }
    return nlohmann::json::parse(bytes);
}

/// The number of primitives the file's meshes list.
inline std::size_t primitivesIn(const nlohmann::json& doc) {
    std::size_t n = 0;
    for (const auto& mesh : doc.value("meshes", nlohmann::json::array())) n += mesh["primitives"].size();
    return n;
}

/// Asserts a refusal whose object is `object` and whose message contains `fragment`.
inline ::testing::AssertionResult refusedWith(const LoadOutcome& o, const std::string& object,
                                              const std::string& fragment) {
    if (o.scene) return ::testing::AssertionFailure() << "loaded; expected a refusal at " << object;
    const Error& e = o.scene.error();
    if (e.code != ErrorCode::InvalidInput)
        return ::testing::AssertionFailure() << "error code " << errorCodeName(e.code) << ": " << e.describe();
    if (e.file.empty()) return ::testing::AssertionFailure() << "no file named: " << e.describe();
    if (e.object != object)
        return ::testing::AssertionFailure() << "object \"" << e.object << "\", expected \"" << object
                                             << "\": " << e.describe();
    if (e.message.find(fragment) == std::string::npos)
        return ::testing::AssertionFailure() << "message lacks \"" << fragment << "\": " << e.describe();
    if (e.describe().find('\n') != std::string::npos)
        return ::testing::AssertionFailure() << "not one line: " << e.describe();
    return ::testing::AssertionSuccess();
}

} // namespace lantern::test
