// Textures a scene brings, decoded or refused with what is wrong: empty, truncated, too large,
// not an image (never stb's bare "unknown image type"); WebP through libwebp
// (EXT_texture_webp, preferred over its PNG fallback); KHR_texture_basisu's fallback used, or
// the material drawn untextured with a warning, or the file refused when it requires the
// extension and gives no fallback. And `lantern compare` says the same of a bad PNG.
#include "GltfTestSupport.h"
#include "io/image/ImageDecode.h"

#include <lantern/Io.h>

#include <gtest/gtest.h>
#include <webp/encode.h>

#include <fstream>

namespace {

using namespace lantern;
using namespace lantern::test;
using nlohmann::json;

std::vector<unsigned char> readAll(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A real PNG of w x h pixels of one colour, written by Lantern's own writer.
std::vector<unsigned char> pngOf(int w, int h, glm::vec4 colour) {
    Image img(w, h);
    for (std::size_t i = 0; i < img.pixelCount(); ++i)
        for (int c = 0; c < 4; ++c) img.rgba[i * 4 + std::size_t(c)] = colour[c];
    const auto path = testOutputDir() / "colour.png";
    EXPECT_TRUE(writePng(path, img));
    return readAll(path);
}

std::vector<unsigned char> webpOf(int w, int h, std::uint8_t r, std::uint8_t g, std::uint8_t b) {
    std::vector<std::uint8_t> rgba(std::size_t(w) * std::size_t(h) * 4);
    for (std::size_t i = 0; i < rgba.size(); i += 4) {
        rgba[i] = r, rgba[i + 1] = g, rgba[i + 2] = b, rgba[i + 3] = 255;
    }
    std::uint8_t* out = nullptr;
    const std::size_t size = WebPEncodeLosslessRGBA(rgba.data(), w, h, w * 4, &out);
    std::vector<unsigned char> bytes(out, out + size);
    WebPFree(out);
    return bytes;
}

std::string describeFailure(const std::vector<unsigned char>& bytes) {
    auto info = io::inspectImage(bytes.data(), bytes.size());
    if (!info) return info.error().message;
    auto pixels = io::decodeRgba8(bytes.data(), bytes.size(), *info);
    return pixels ? std::string("decoded") : pixels.error().message;
}

TEST(ImageDecode, EveryFailureSaysWhatIsWrong) {
    const auto png = pngOf(8, 4, {1, 0, 0, 1});
    EXPECT_EQ(describeFailure(png), "decoded");
    EXPECT_NE(describeFailure({}).find("is empty"), std::string::npos);
    // Cut in its data: truncated, with the size the header declared.
    const std::vector<unsigned char> cut(png.begin(), png.begin() + std::ptrdiff_t(png.size() - 20));
    EXPECT_NE(describeFailure(cut).find("PNG of 8x4 pixels that is truncated"), std::string::npos)
        << describeFailure(cut);
    const std::vector<unsigned char> header(png.begin(), png.begin() + 20);
    EXPECT_NE(describeFailure(header).find("cut short in its header"), std::string::npos);
    // A header declaring 100000 x 100000 pixels, and one declaring none.
    std::vector<unsigned char> huge = png;
    for (int k : {16, 20}) {
        huge[std::size_t(k)] = 0, huge[std::size_t(k) + 1] = 0x01;
        huge[std::size_t(k) + 2] = 0x86, huge[std::size_t(k) + 3] = 0xA0;
    }
    auto info = io::inspectImage(huge.data(), huge.size());
    ASSERT_TRUE(info);
    EXPECT_EQ(info->width, 100000);
    std::vector<unsigned char> none = png;
    std::fill(none.begin() + 16, none.begin() + 20, 0);
    EXPECT_NE(describeFailure(none).find("PNG of 0x4 pixels (empty)"), std::string::npos);
    const std::vector<unsigned char> text = {'h', 'e', 'l', 'l', 'o'};
    EXPECT_NE(describeFailure(text).find("not an image Lantern reads (PNG, JPEG or WebP; it starts with 68 65"),
              std::string::npos)
        << describeFailure(text);
    const auto webp = webpOf(6, 3, 10, 200, 30);
    EXPECT_EQ(describeFailure(webp), "decoded");
    const std::vector<unsigned char> webpCut(webp.begin(), webp.begin() + 14);
    EXPECT_NE(describeFailure(webpCut).find("WebP"), std::string::npos);
}

// A textured triangle whose texture's image is `uri` (with `extension` on the texture).
GltfBuilder texturedTriangle(const json& images, const json& texture) {
    GltfBuilder b;
    b.addTriangle({{"attributes", {{"TEXCOORD_0", 0}}}});
    b.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = b.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    b.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = b.addFloats({0, 0, 1, 0, 0, 1}, "VEC2");
    b.doc["images"] = images;
    b.doc["textures"] = json::array({texture});
    b.doc["materials"] = json::array({json{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
    b.doc["meshes"][0]["primitives"][0]["material"] = 0;
    return b;
}

TEST(ImageDecode, AScenesBadImagesAreNamedWithTheirProblem) {
    auto png = pngOf(8, 4, {1, 0, 0, 1});  // (testOutputDir() empties the folder)
    const auto dir = testOutputDir();
    GltfBuilder::writeBytes(dir / "empty.png", {});
    GltfBuilder::writeBytes(dir / "cut.png", std::vector<unsigned char>(png.begin(), png.end() - 20));
    std::vector<unsigned char> huge = png;
    for (int k : {16, 20}) huge[std::size_t(k) + 1] = 0x01, huge[std::size_t(k) + 2] = 0x86, huge[std::size_t(k) + 3] = 0xA0;
    GltfBuilder::writeBytes(dir / "huge.png", huge);
    const std::tuple<const char*, const char*, const char*> cases[] = {
        {"empty.png", "images[0].uri", "is empty (0 bytes)"},
        {"cut.png", "images[0]", "is a PNG of 8x4 pixels that is truncated"},
        {"huge.png", "images[0]", "100000x100000 is outside the supported texture size"},
    };
    for (const auto& [file, object, fragment] : cases) {
        GltfBuilder b = texturedTriangle(json::array({{{"uri", file}}}), {{"source", 0}});
        auto o = loadCapturing(b.write(dir, "bad"));
        EXPECT_TRUE(refusedWith(o, object, fragment)) << file;
    }
    // `lantern compare` reads PNG references with the same words.
    auto cut = readCompareImage(dir / "cut.png");
    ASSERT_FALSE(cut);
    EXPECT_NE(cut.error().message.find("truncated"), std::string::npos) << cut.error().describe();
    auto empty = readCompareImage(dir / "empty.png");
    ASSERT_FALSE(empty);
    EXPECT_NE(empty.error().message.find("is empty"), std::string::npos) << empty.error().describe();
}

TEST(ImageDecode, WebpIsPreferredOverItsFallbackAndBasisuFallsBack) {
    const auto red = pngOf(4, 4, {1, 0, 0, 1});  // (testOutputDir() empties the folder)
    const auto dir = testOutputDir();
    GltfBuilder::writeBytes(dir / "green.webp", webpOf(4, 4, 0, 255, 0));
    GltfBuilder::writeBytes(dir / "red.png", red);
    GltfBuilder::writeBytes(dir / "tex.ktx2", {0xAB, 'K', 'T', 'X', ' ', '2', '0'});
    const json images = json::array({{{"uri", "green.webp"}}, {{"uri", "red.png"}}, {{"uri", "tex.ktx2"}}});

    GltfBuilder webp = texturedTriangle(images, {{"source", 1}, {"extensions", {{"EXT_texture_webp", {{"source", 0}}}}}});
    webp.doc["extensionsUsed"] = {"EXT_texture_webp"};
    webp.doc["extensionsRequired"] = {"EXT_texture_webp"};
    auto w = loadCapturing(webp.write(dir, "webp"));
    ASSERT_TRUE(w.scene) << w.scene.error().describe() << w.allWarnings();
    ASSERT_EQ(w.scene->textures.size(), 1u);
    EXPECT_EQ(w.scene->textures[0].rgba8[0], 0);   // green, from the WebP, not the red fallback
    EXPECT_EQ(w.scene->textures[0].rgba8[1], 255);

    GltfBuilder basis = texturedTriangle(images, {{"source", 1}, {"extensions", {{"KHR_texture_basisu", {{"source", 2}}}}}});
    basis.doc["extensionsUsed"] = {"KHR_texture_basisu"};
    basis.doc["extensionsRequired"] = {"KHR_texture_basisu"};
    auto fallback = loadCapturing(basis.write(dir, "basis"));
    ASSERT_TRUE(fallback.scene) << fallback.scene.error().describe();
    EXPECT_EQ(fallback.scene->textures.at(0).rgba8[0], 255);  // the PNG fallback

    basis.doc["textures"][0].erase("source");
    auto required = loadCapturing(basis.write(dir, "basis-required"));
    EXPECT_TRUE(refusedWith(required, "extensionsRequired[0]", "KHR_texture_basisu"));
    basis.doc.erase("extensionsRequired");
    auto untextured = loadCapturing(basis.write(dir, "basis-used"));
    ASSERT_TRUE(untextured.scene) << untextured.scene.error().describe();
    EXPECT_TRUE(untextured.scene->textures.empty());
    EXPECT_EQ(untextured.scene->materials.at(0).baseColorTexture, -1);
    EXPECT_TRUE(untextured.warned("KHR_texture_basisu")) << untextured.allWarnings();
}

} // namespace
