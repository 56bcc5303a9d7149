// The load's budget (--max-size) follows the memory a scene file really makes Lantern
// hold: for glTF the parsed JSON and the models built from it included, for OBJ tinyobjloader's
// model, for PLY, STL and OFF what their readers build. This binary counts every
// operator new and delete (global replacements below) to find the true peak of a load, then
// checks that the budget charged for it is neither far below (a file could then allocate more
// than --max-size) nor far above (a legitimate file would be refused).
#include "TestSupport.h"

#include <lantern/Io.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <iostream>
#include <malloc.h>
#include <new>
#include <string>

namespace {

std::atomic<std::uint64_t> g_live{0};
std::atomic<std::uint64_t> g_peak{0};

void* counted(std::size_t size) {
    void* p = std::malloc(size == 0 ? 1 : size);
    if (!p) throw std::bad_alloc();
    const std::uint64_t live = g_live += malloc_usable_size(p);
    std::uint64_t peak = g_peak.load(std::memory_order_relaxed);
    while (live > peak && !g_peak.compare_exchange_weak(peak, live)) {
    }
    return p;
}

void uncounted(void* p) noexcept {
    if (!p) return;
    g_live -= malloc_usable_size(p);
    std::free(p);
}

} // namespace

void* operator new(std::size_t size) { return counted(size); }
void* operator new[](std::size_t size) { return counted(size); }
void operator delete(void* p) noexcept { uncounted(p); }
void operator delete[](void* p) noexcept { uncounted(p); }
void operator delete(void* p, std::size_t) noexcept { uncounted(p); }
void operator delete[](void* p, std::size_t) noexcept { uncounted(p); }

namespace {

namespace fs = std::filesystem;
using namespace lantern;

struct Measured {
    std::uint64_t peak = 0;  ///< bytes held at the worst moment of the load, above the start
    bool loaded = false;
    std::string error;
};

Measured loadMeasured(const fs::path& file, std::uint64_t maxBytes) {
    LoadOptions options;
    options.maxBytes = maxBytes;
    options.log = [](LogLevel, std::string_view) {};
    const std::uint64_t before = g_live.load();
    g_peak = before;
    Measured m;
    {
        auto scene = loadScene(file.string(), options);
        m.peak = g_peak.load() - before;
        m.loaded = bool(scene);
        if (!scene) m.error = scene.error().describe();
    }
    return m;
}

std::uint64_t fileSize(const fs::path& p) { return fs::file_size(p); }

// Writes `text` as `name` in the test's folder.
fs::path writeScene(const std::string& name, const std::string& text) {
    const fs::path p = test::testOutputDir() / name;
    std::ofstream(p, std::ios::binary) << text;
    return p;
}

std::string header(const std::string& rootNodes) {
    return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[)" + rootNodes +
           "]}],\"nodes\":[";
}

// Each document: the true peak of its load (P), then the same load under budgets around it.
// The budget must refuse the load at 0.8 of the true peak less the file's own bytes (the file
// is bounded by itself, read before the budget starts), and must admit it at twice the true
// peak. (Measured when written: the smallest budget that admits each of these files is 1.03 to
// 1.42 times its true peak.)
void expectBudgetFollowsThePeak(const fs::path& file) {
    const std::uint64_t size = fileSize(file);
    const Measured free = loadMeasured(file, std::uint64_t(1) << 36);
    ASSERT_TRUE(free.loaded) << free.error;
    ASSERT_GT(free.peak, size);
    const std::uint64_t held = free.peak - size;
    const Measured twice = loadMeasured(file, 2 * free.peak);
    EXPECT_TRUE(twice.loaded) << file.filename() << ": refused at twice its true peak ("
                              << 2 * free.peak << " bytes): " << twice.error;
    const std::uint64_t under = std::max<std::uint64_t>(size, held / 5 * 4);
    const Measured tight = loadMeasured(file, under);
    EXPECT_FALSE(tight.loaded) << file.filename() << " (" << size << " bytes) loaded within "
                               << under << " bytes of budget, 0.8 of the " << held
                               << " it really held beyond its own bytes";
    if (!tight.loaded) {
        EXPECT_NE(tight.error.find("budget"), std::string::npos) << tight.error;
    }
    std::cout << file.filename().string() << ": " << size << " bytes, true peak " << free.peak
              << " bytes (" << double(free.peak) / double(size) << "x the file)\n";
}

TEST(LoadBudget, AChainOfNodesIsChargedForItsDocumentAndModels) {
    constexpr int n = 200'000;
    std::string text = header("0");
    for (int i = 0; i < n; ++i) text += i + 1 < n ? R"({"children":[)" + std::to_string(i + 1) + "]}," : "{}";
    expectBudgetFollowsThePeak(writeScene("chain.gltf", text + "]}"));
}

TEST(LoadBudget, AFlatSceneOfEmptyNodesIsChargedForItsDocumentAndModels) {
    constexpr int n = 200'000;
    std::string roots, nodes;
    for (int i = 0; i < n; ++i) {
        roots += (i ? "," : "") + std::to_string(i);
        nodes += i ? ",{}" : "{}";
    }
    expectBudgetFollowsThePeak(writeScene("flat.gltf", header(roots) + nodes + "]}"));
}

TEST(LoadBudget, ExtrasAndExtensionsKeptAsValueTreesAreCharged) {
    // tinygltf keeps every value under "extras" as a 152-byte tinygltf::Value: two bytes of
    // JSON ("0,") become hundreds of bytes.
    constexpr int n = 2'000;
    std::string text = header("0") + R"({"extras":{"a":[)";
    for (int i = 0; i < 100 * n; ++i) text += i ? ",0" : "0";
    text += R"(],"b":{)";
    for (int i = 0; i < n; ++i) text += (i ? "," : "") + std::string("\"k") + std::to_string(i) + "\":[]";
    text += "}}}]}";
    expectBudgetFollowsThePeak(writeScene("extras.gltf", text));
}

TEST(LoadBudget, LongNamesAndManyMeshesAreCharged) {
    // Many meshes (each a Mesh and a Primitive in both models) with long names.
    constexpr int n = 20'000;
    std::string text =
        R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],)"
        R"("bufferViews":[{"buffer":0,"byteLength":36}],)"
        R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}],"meshes":[)";
    const std::string longName(200, 'm');
    for (int i = 0; i < n; ++i)
        text += std::string(i ? "," : "") + R"({"name":")" + longName + R"(","primitives":[{"attributes":{"POSITION":0}}]})";
    text += R"(],"nodes":[{"mesh":0}],"scene":0,"scenes":[{"nodes":[0]}]})";
    expectBudgetFollowsThePeak(writeScene("meshes.gltf", text));
}

TEST(LoadBudget, ZeroFilledAccessorsAndComputedNormalsAreCharged) {
    // Accessors without a buffer view (zeros the loader makes), read by four primitives
    // without NORMAL (smooth normals computed): decoded data a 1 KB file decides.
    std::string text = R"({"asset":{"version":"2.0"},"accessors":[)";
    for (int i = 0; i < 4; ++i)
        text += std::string(i ? "," : "") +
                R"({"componentType":5126,"count":300000,"type":"VEC3","min":[0,0,0],"max":[0,0,0]})";
    text += R"(],"meshes":[{"primitives":[)";
    for (int i = 0; i < 4; ++i)
        text += std::string(i ? "," : "") + R"({"attributes":{"POSITION":)" + std::to_string(i) + "}}";
    text += R"(]}],"nodes":[{"mesh":0}],"scene":0,"scenes":[{"nodes":[0]}]})";
    expectBudgetFollowsThePeak(writeScene("zeros.gltf", text));
}

// The mesh formats: a grid of N x N quads (2 N^2 triangles) in each.
constexpr int kGrid = 300;

std::string gridVertex(int i, int j) {
    return std::to_string(i) + " " + std::to_string(j) + " " + std::to_string((i * j) % 7);
}

TEST(LoadBudget, AnObjIsChargedForTinyobjloadersModelAndItsVertices) {
    std::string text = "o grid\ns 1\n";
    for (int i = 0; i <= kGrid; ++i)
        for (int j = 0; j <= kGrid; ++j)
            text += "v " + gridVertex(i, j) + "\nvt 0.5 0.5\n";
    for (int i = 0; i < kGrid; ++i)
        for (int j = 0; j < kGrid; ++j) {
            const int a = i * (kGrid + 1) + j + 1, b = a + kGrid + 1;
            const auto c = [](int v) { return std::to_string(v) + "/" + std::to_string(v); };
            text += "f " + c(a) + " " + c(b) + " " + c(b + 1) + " " + c(a + 1) + "\n";
        }
    expectBudgetFollowsThePeak(writeScene("grid.obj", text));
}

TEST(LoadBudget, PlyStlAndOffAreChargedForWhatTheirReadersBuild) {
    std::string ply = "ply\nformat ascii 1.0\nelement vertex " + std::to_string((kGrid + 1) * (kGrid + 1)) +
                      "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
                      std::to_string(kGrid * kGrid) + "\nproperty list uchar int vertex_indices\nend_header\n";
    std::string off = "OFF\n" + std::to_string((kGrid + 1) * (kGrid + 1)) + " " +
                      std::to_string(kGrid * kGrid) + " 0\n";
    std::string stl = "solid grid\n", vertices, faces;
    for (int i = 0; i <= kGrid; ++i)
        for (int j = 0; j <= kGrid; ++j) vertices += gridVertex(i, j) + "\n";
    for (int i = 0; i < kGrid; ++i)
        for (int j = 0; j < kGrid; ++j) {
            const int a = i * (kGrid + 1) + j, b = a + kGrid + 1;
            faces += "4 " + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(b + 1) +
                     " " + std::to_string(a + 1) + "\n";
            stl += "facet normal 0 0 1\nouter loop\nvertex " + gridVertex(i, j) + "\nvertex " +
                   gridVertex(i + 1, j) + "\nvertex " + gridVertex(i, j + 1) + "\nendloop\nendfacet\n";
        }
    expectBudgetFollowsThePeak(writeScene("grid.ply", ply + vertices + faces));
    expectBudgetFollowsThePeak(writeScene("grid.off", off + vertices + faces));
    expectBudgetFollowsThePeak(writeScene("grid.stl", stl + "endsolid grid\n"));
}

} // namespace
