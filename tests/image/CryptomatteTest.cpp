// Cryptomatte layers (docs/aovs.md): MurmurHash3_x86_32 against published vectors, the
// spec's float conversion, and a scene of two quads whose edges fall at known fractions of a
// pixel, so each pixel's coverage is known exactly: 1 inside, 3/4 and 1/4 where the quads meet,
// 1/2 against the background; the manifest; the EXR channels and header through a round trip,
// the command line and, where installed, oiiotool.
#include "GltfTestBuilder.h"
#include "TestSupport.h"

#include <lantern/Cryptomatte.h>

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <random>

namespace {

using namespace lantern;
using lantern::test::GpuTest;
using lantern::test::GltfBuilder;
using nlohmann::json;

// Published MurmurHash3_x86_32 vectors (also computed with an independent Python port of
// Appleby's reference while writing this test), and the Cryptomatte specification's manifest
// example: "bunny" 13851a76, "default" 42c9679f.
TEST(CryptomatteIds, MurmurHashMatchesPublishedVectors) {
    EXPECT_EQ(murmurHash3_32(""), 0u);
    EXPECT_EQ(murmurHash3_32("", 1), 0x514e28b7u);
    EXPECT_EQ(murmurHash3_32("", 0xffffffffu), 0x81f16f39u);
    EXPECT_EQ(murmurHash3_32(std::string_view("\0\0\0\0", 4)), 0x2362f9deu);
    EXPECT_EQ(murmurHash3_32("Hello, world!", 1234), 0xfaf6cdb3u);
    EXPECT_EQ(murmurHash3_32("The quick brown fox jumps over the lazy dog"), 0x2e4ff723u);
    EXPECT_EQ(murmurHash3_32("aaaa", 0x9747b28cu), 0x5a97808au);
    EXPECT_EQ(murmurHash3_32("abc"), 0xb3dd93fau);  // a 3-byte tail
    EXPECT_EQ(murmurHash3_32("bunny"), 0x13851a76u);
    EXPECT_EQ(murmurHash3_32("default"), 0x42c9679fu);
    EXPECT_EQ(cryptomatteKey("CryptoObject"), "3ae39a5");  // hash 3ae39a58
}

TEST(CryptomatteIds, IdsAreNeverNanInfiniteZeroOrDenormal) {
    // The hash of "" is 0 (exponent 0): bit 23 flipped gives the smallest normal float.
    EXPECT_EQ(cryptomatteId(0u), 0x00800000u);
    EXPECT_EQ(cryptomatteId(0x7f800000u), 0x7f000000u);  // +inf's exponent: flipped
    EXPECT_EQ(cryptomatteId(0xffc00001u), 0xff400001u);  // a NaN
    EXPECT_EQ(cryptomatteId(0x13851a76u), 0x13851a76u);  // a normal float is kept
    std::mt19937 random(21);
    std::vector<std::uint32_t> hashes = {0u, 1u, 0x007fffffu, 0x80000000u, 0x807fffffu,
                                         0x7f800000u, 0x7fffffffu, 0xff800000u, 0xffffffffu};
    for (int i = 0; i < 100000; ++i) hashes.push_back(std::uint32_t(random()));
    for (std::uint32_t h : hashes) {
        const float f = std::bit_cast<float>(cryptomatteId(h));
        EXPECT_TRUE(std::isnormal(f)) << std::hex << h;
        // Only bit 23 may change.
        EXPECT_EQ((cryptomatteId(h) ^ h) & ~(1u << 23), 0u) << std::hex << h;
    }
    EXPECT_EQ(cryptomatteFloat("bunny"), std::bit_cast<float>(0x13851a76u));
}

// Two quads in the z = 0 plane seen from +Z through an orthographic camera of 5 x 5 units on
// 40 x 40 pixels (8 pixels a unit): "bunny" (material "red") from x = -2 to 5/128, an unnamed
// node (no material: "default") from 5/128 to 2, both from y = -1 to 17/16. Pixel column 20 is
// x 0 .. 1/8, so the quads meet 5/16 into it: one of 4 sample columns at 1/8, 3/8, 5/8, 7/8
// of the pixel is left of it, and one of 2 at 1/4, 3/4. Row 11 is y 1 .. 9/8, so the top edge
// halves it. No sample lies on an edge.
std::filesystem::path writeScene(const std::filesystem::path& dir) {
    GltfBuilder b;
    b.doc["materials"] = json::array(
        {{{"name", "red"}, {"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.2, 0.2, 1.0}}}}}});
    auto quad = [&](float x0, float x1, int material) {
        const float y0 = -1.0f, y1 = 17.0f / 16.0f;
        json prim = {{"attributes",
                      {{"POSITION", b.addFloats({x0, y0, 0, x1, y0, 0, x1, y1, 0, x0, y1, 0}, "VEC3")}}},
                     {"indices", b.addIndices({0, 1, 2, 0, 2, 3})}};
        if (material >= 0) prim["material"] = material;
        return b.addMesh(prim);
    };
    const int left = quad(-2.0f, 5.0f / 128.0f, 0);
    const int right = quad(5.0f / 128.0f, 2.0f, -1);
    b.addNode({{"name", "bunny"}, {"mesh", left}});
    b.addNode({{"mesh", right}});
    return b.write(dir, "crypto");
}

constexpr int kSize = 40;

RenderOptions cryptoOptions() {
    RenderOptions o;
    o.width = o.height = kSize;
    o.background = glm::vec4(0.0f);
    EXPECT_TRUE(enableAov(o.aovs, "crypto_object"));
    EXPECT_TRUE(enableAov(o.aovs, "crypto_material"));
    o.camera.lookAt = LookAt{{0.0, 0.0, 5.0}, {0.0, 0.0, 0.0}, {0.0, 1.0, 0.0}};
    o.camera.projection = Projection::makeOrtho(-2.5, 2.5, -2.5, 2.5, 0.5, 20.0);
    return o;
}

class Cryptomatte : public GpuTest {
protected:
    Image render(const RenderOptions& o) {
        auto scene = loadScene(writeScene(test::testOutputDir()).string());
        EXPECT_TRUE(scene) << scene.error().describe();
        if (!scene) return {};
        auto image = renderer().render(*scene, o, 0.0);
        EXPECT_TRUE(image) << image.error().describe();
        return image ? std::move(*image) : Image{};
    }
};

// Pixel (x, y)'s ranks of `layer` as (id, coverage) pairs.
std::vector<std::pair<float, float>> ranksAt(const Image& image, const CryptomatteLayer& layer,
                                             int x, int y) {
    std::vector<std::pair<float, float>> out;
    const float* p = layer.ranks.data() + (std::size_t(y) * image.width + x) * layer.levels * 2;
    for (int r = 0; r < layer.levels; ++r) out.emplace_back(p[r * 2], p[r * 2 + 1]);
    return out;
}

TEST_F(Cryptomatte, CoverageOfEachIdIsCountedFromSixteenSamples) {
    const Image image = render(cryptoOptions());
    ASSERT_EQ(image.cryptomatte.size(), 2u);
    const CryptomatteLayer& objects = image.cryptomatte[0];
    const CryptomatteLayer& materials = image.cryptomatte[1];
    EXPECT_EQ(objects.name, "CryptoObject");
    EXPECT_EQ(materials.name, "CryptoMaterial");
    ASSERT_EQ(objects.levels, 4);
    ASSERT_EQ(objects.ranks.size(), image.pixelCount() * 8);
    const float bunny = cryptomatteFloat("bunny"), other = cryptomatteFloat("node 1");
    const float red = cryptomatteFloat("red"), fallback = cryptomatteFloat("default");
    using Ranks = std::vector<std::pair<float, float>>;
    // Well inside each quad, and in the background.
    EXPECT_EQ(ranksAt(image, objects, 10, 20), (Ranks{{bunny, 1.0f}, {0, 0}, {0, 0}, {0, 0}}));
    EXPECT_EQ(ranksAt(image, objects, 30, 20), (Ranks{{other, 1.0f}, {0, 0}, {0, 0}, {0, 0}}));
    EXPECT_EQ(ranksAt(image, materials, 10, 20), (Ranks{{red, 1.0f}, {0, 0}, {0, 0}, {0, 0}}));
    EXPECT_EQ(ranksAt(image, objects, 20, 2), (Ranks{{0, 0}, {0, 0}, {0, 0}, {0, 0}}));
    // Where the quads meet: 12 of 16 samples on the right, 4 on the left; sum 1.
    EXPECT_EQ(ranksAt(image, objects, 20, 20), (Ranks{{other, 0.75f}, {bunny, 0.25f}, {0, 0}, {0, 0}}));
    EXPECT_EQ(ranksAt(image, materials, 20, 20),
              (Ranks{{fallback, 0.75f}, {red, 0.25f}, {0, 0}, {0, 0}}));
    // The top edge: half the samples see the background, which has no id.
    EXPECT_EQ(ranksAt(image, objects, 10, 11), (Ranks{{bunny, 0.5f}, {0, 0}, {0, 0}, {0, 0}}));
    EXPECT_EQ(ranksAt(image, objects, 20, 11), (Ranks{{other, 0.375f}, {bunny, 0.125f}, {0, 0}, {0, 0}}));
    // Everywhere: coverages in (0, 1], most first, summing to at most 1; ids are hashes.
    for (const CryptomatteLayer* layer : {&objects, &materials})
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x) {
                float sum = 0.0f, last = 1.0f;
                for (const auto& [id, coverage] : ranksAt(image, *layer, x, y)) {
                    EXPECT_LE(coverage, last) << x << "," << y;
                    EXPECT_GE(coverage, 0.0f);
                    EXPECT_EQ(id == 0.0f, coverage == 0.0f) << x << "," << y;
                    if (id != 0.0f) {
                        EXPECT_TRUE(id == bunny || id == other || id == red || id == fallback);
                    }
                    sum += coverage, last = coverage;
                }
                EXPECT_LE(sum, 1.0f) << x << "," << y;
            }
    using Manifest = std::vector<std::pair<std::string, std::uint32_t>>;
    EXPECT_EQ(objects.manifest, (Manifest{{"bunny", 0x13851a76u},
                                          {"node 1", std::bit_cast<std::uint32_t>(other)}}));
    EXPECT_EQ(materials.manifest, (Manifest{{"default", 0x42c9679fu},
                                            {"red", std::bit_cast<std::uint32_t>(red)}}));
}

TEST_F(Cryptomatte, LevelsAndSamplesAreOptionsAndBadOnesAreRefused) {
    RenderOptions o = cryptoOptions();
    o.aovs.cryptomatteLevels = 2;
    o.aovs.cryptomatteSamples = 2;  // one sample column each side of the meeting line
    const Image image = render(o);
    ASSERT_EQ(image.cryptomatte.size(), 2u);
    const float bunny = cryptomatteFloat("bunny"), other = cryptomatteFloat("node 1");
    const auto ranks = ranksAt(image, image.cryptomatte[0], 20, 20);
    ASSERT_EQ(ranks.size(), 2u);
    // Equal coverage: the smaller id bits first.
    const bool bunnyFirst = std::bit_cast<std::uint32_t>(bunny) < std::bit_cast<std::uint32_t>(other);
    EXPECT_EQ(ranks[0], std::make_pair(bunnyFirst ? bunny : other, 0.5f));
    EXPECT_EQ(ranks[1], std::make_pair(bunnyFirst ? other : bunny, 0.5f));
    for (int bad : {0, 3, 18}) {
        RenderOptions b = cryptoOptions();
        b.aovs.cryptomatteLevels = bad;
        auto scene = loadScene(writeScene(test::testOutputDir()).string());
        ASSERT_TRUE(scene);
        auto refused = renderer().render(*scene, b, 0.0);
        ASSERT_FALSE(refused) << bad;
        EXPECT_NE(refused.error().message.find("levels must be an even number"), std::string::npos);
    }
    // An enlarged size no device holds is refused, saying which render it was.
    RenderOptions wide = cryptoOptions();
    wide.width = 4096;
    wide.height = 1;
    wide.aovs.cryptomatteSamples = 16;
    auto scene = loadScene(writeScene(test::testOutputDir()).string());
    ASSERT_TRUE(scene);
    auto refused = renderer().render(*scene, wide, 0.0);
    ASSERT_FALSE(refused);
    EXPECT_NE(refused.error().message.find("the Cryptomatte id render (16x the size) failed"),
              std::string::npos)
        << refused.error().message;
}

TEST_F(Cryptomatte, ExrHoldsFloatChannelsAndTheSpecsHeader) {
    const Image image = render(cryptoOptions());
    ASSERT_EQ(image.cryptomatte.size(), 2u);
    const auto path = test::testOutputDir() / "crypto.exr";
    ExrOptions half;
    half.half = true;  // halves the colour only: Cryptomatte ids need all 32 bits
    ASSERT_TRUE(writeExr(path, image, half));
    auto back = readExr(path);
    ASSERT_TRUE(back) << back.error().describe();
    ASSERT_EQ(back->cryptomatte.size(), 2u);
    for (std::size_t i = 0; i < 2; ++i) {
        const CryptomatteLayer& a = image.cryptomatte[i];
        const CryptomatteLayer* b = nullptr;
        for (const CryptomatteLayer& l : back->cryptomatte)
            if (l.name == a.name) b = &l;
        ASSERT_NE(b, nullptr) << a.name;
        EXPECT_EQ(b->levels, a.levels);
        EXPECT_EQ(b->ranks, a.ranks) << a.name;  // bit for bit (the ids are 32-bit floats)
        EXPECT_EQ(b->manifest, a.manifest) << a.name;
    }
    auto attribute = [&](const std::string& key) {
        for (const auto& [k, v] : back->metadata)
            if (k == key) return v;
        return std::string("(missing)");
    };
    const std::string object = "cryptomatte/" + cryptomatteKey("CryptoObject") + "/";
    EXPECT_EQ(attribute(object + "name"), "CryptoObject");
    EXPECT_EQ(attribute(object + "hash"), "MurmurHash3_32");
    EXPECT_EQ(attribute(object + "conversion"), "uint32_to_float32");
    const json manifest = json::parse(attribute(object + "manifest"));
    EXPECT_EQ(manifest.at("bunny"), "13851a76");
    char hex[9];
    std::snprintf(hex, sizeof hex, "%08x",
                  unsigned(std::bit_cast<std::uint32_t>(cryptomatteFloat("node 1"))));
    EXPECT_EQ(manifest.at("node 1"), hex);
    EXPECT_EQ(manifest.size(), 2u);
    const std::string material = "cryptomatte/" + cryptomatteKey("CryptoMaterial") + "/";
    EXPECT_EQ(attribute(material + "name"), "CryptoMaterial");
    EXPECT_EQ(json::parse(attribute(material + "manifest")).at("default"), "42c9679f");
}

TEST_F(Cryptomatte, TheCommandWritesTheLayersThatOiiotoolLists) {
    const auto dir = test::testOutputDir();
    const auto scene = writeScene(dir);
    const auto out = dir / "cli-crypto.exr";
    const auto r = test::runLantern({"render", scene.string(), "-o", out.string(), "--width", "32",
                                     "--height", "32", "--aov", "crypto_object,crypto_material",
                                     "--cryptomatte-levels", "6", "--cryptomatte-samples", "3"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    auto image = readExr(out);
    ASSERT_TRUE(image) << image.error().describe();
    ASSERT_EQ(image->cryptomatte.size(), 2u);
    EXPECT_EQ(image->cryptomatte[0].levels, 6);
    const auto bad = test::runLantern({"render", scene.string(), "-o", (dir / "x.exr").string(),
                                       "--aov", "crypto_object", "--cryptomatte-levels", "5"});
    EXPECT_NE(bad.exitCode, 0);
    EXPECT_NE(bad.err.find("even"), std::string::npos) << bad.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "x.exr"));
    // A sequence makes the layers for every frame, the same as a single image of that frame.
    const auto seq = test::runLantern({"render", scene.string(), "-o", (dir / "s_#.exr").string(),
                                       "--frames", "0-2", "--width", "32", "--height", "32", "--aov",
                                       "crypto_object,crypto_material", "--cryptomatte-levels", "6",
                                       "--cryptomatte-samples", "3", "--encoder-threads", "2"});
    ASSERT_EQ(seq.exitCode, 0) << seq.err;
    for (const char* name : {"s_0.exr", "s_1.exr", "s_2.exr"}) {
        auto frame = readExr(dir / name);
        ASSERT_TRUE(frame) << name << ": " << frame.error().describe();
        ASSERT_EQ(frame->cryptomatte.size(), 2u) << name;
        for (std::size_t l = 0; l < 2; ++l) {
            EXPECT_EQ(frame->cryptomatte[l].name, image->cryptomatte[l].name) << name;
            EXPECT_EQ(frame->cryptomatte[l].ranks, image->cryptomatte[l].ranks) << name;
            EXPECT_EQ(frame->cryptomatte[l].manifest, image->cryptomatte[l].manifest) << name;
        }
    }
    const auto info = test::runProcess({"oiiotool", "--info", "-v", out.string()});
    if (info.exitCode == 127) GTEST_SKIP() << "oiiotool is not installed";
    ASSERT_EQ(info.exitCode, 0) << info.err;
    for (const char* channel : {"CryptoObject00.R", "CryptoObject02.A", "CryptoMaterial01.G"})
        EXPECT_NE(info.out.find(channel), std::string::npos) << channel << "\n" << info.out;
    EXPECT_NE(info.out.find("cryptomatte/" + cryptomatteKey("CryptoObject") + "/manifest"),
              std::string::npos)
        << info.out;
}

} // namespace

// In a sequence every frame's layers are made at that frame's time: an animated scene's frames
// have the layers a single render at the same time has, and they change as the spheres move.
TEST_F(Cryptomatte, EachFrameOfASequenceHasItsOwnLayers) {
    auto scene = builtinScene("spheres-animated");
    ASSERT_TRUE(scene);
    auto prepared = renderer().prepare(std::make_shared<const Scene>(std::move(*scene)));
    ASSERT_TRUE(prepared) << prepared.error().describe();
    RenderOptions o;
    o.width = 36;
    o.height = 24;
    ASSERT_TRUE(enableAov(o.aovs, "crypto_object"));
    o.aovs.cryptomatteSamples = 2;
    const auto dir = test::testOutputDir();
    SequenceOptions s;
    s.frames = {0, 6};
    s.fps = 4;
    s.encoderThreads = 2;
    s.outputs = {(dir / "f_#.exr").string()};
    auto report = renderer().renderSequence(*prepared, o, s);
    ASSERT_TRUE(report) << report.error().describe();
    ASSERT_EQ(report->framesWritten.size(), 7u);
    std::vector<float> previous;
    int changed = 0;
    for (int frame = 0; frame <= 6; ++frame) {
        auto written = readExr(dir / ("f_" + std::to_string(frame) + ".exr"));
        ASSERT_TRUE(written) << written.error().describe();
        ASSERT_EQ(written->cryptomatte.size(), 1u);
        auto single = renderer().render(*prepared, o, frame / s.fps);
        ASSERT_TRUE(single) << single.error().describe();
        ASSERT_EQ(single->cryptomatte.size(), 1u);
        EXPECT_EQ(written->cryptomatte[0].ranks, single->cryptomatte[0].ranks) << "frame " << frame;
        EXPECT_EQ(written->cryptomatte[0].manifest, single->cryptomatte[0].manifest);
        if (!previous.empty() && previous != written->cryptomatte[0].ranks) ++changed;
        previous = written->cryptomatte[0].ranks;
    }
    EXPECT_GE(changed, 3) << "the animation should move the mattes";
}
