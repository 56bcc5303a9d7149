// FarmTestSupport.h: what the farm tests share: file bytes and listings, the single-machine
// reference render a farm's frames must equal byte for byte, and the comparison itself.
#pragma once

#include "TestSupport.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

namespace lantern::test::farm {

inline std::string fileBytes(const std::filesystem::path& p) {
    std::ifstream f(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

inline std::vector<std::string> concat(std::vector<std::string> a,
                                       const std::vector<std::string>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

/// `text` split at spaces (for command lines whose words hold none).
inline std::vector<std::string> words(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string w; in >> w;)
        out.push_back(w);
    return out;
}

/// The names in `dir` that end with `suffix`, sorted.
inline std::vector<std::string> filesEndingWith(const std::filesystem::path& dir,
                                                const std::string& suffix) {
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(dir)) {
        const std::string n = e.path().filename().string();
        if (n.size() >= suffix.size() &&
            n.compare(n.size() - suffix.size(), suffix.size(), suffix) == 0)
            names.push_back(n);
    }
    std::sort(names.begin(), names.end());
    return names;
}

/// The animated sample every farm test renders: small, and with frames that differ.
inline std::vector<std::string> sampleRenderOptions() {
    return {"--fps", "6", "--width", "64", "--height", "48"};
}

/// Renders frames `range` of the sample on this machine in one process into dir/f_##.exr.
inline void renderReference(const std::filesystem::path& dir, const std::string& range) {
    std::filesystem::create_directories(dir);
    std::vector<std::string> args = {"render", "builtin:spheres-animated", "--frames", range,
                                     "-o",     (dir / "f_##.exr").string()};
    const auto options = sampleRenderOptions();
    args.insert(args.end(), options.begin(), options.end());
    const auto r = runLantern(args);
    ASSERT_EQ(r.exitCode, 0) << r.err;
}

/// Every EXR of `reference` exists in `actual` with the same bytes, and no other EXR does.
inline void expectSameFrames(const std::filesystem::path& reference,
                             const std::filesystem::path& actual) {
    const auto names = filesEndingWith(reference, ".exr");
    ASSERT_FALSE(names.empty());
    EXPECT_EQ(filesEndingWith(actual, ".exr"), names);
    for (const std::string& n : names)
        EXPECT_TRUE(fileBytes(reference / n) == fileBytes(actual / n))
            << n << " differs from the single-machine render";
}

} // namespace lantern::test::farm
