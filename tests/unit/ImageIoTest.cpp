// EXR and PNG output: exact float round trip, half precision and clamping, AOV channel names,
// metadata, atomic writes (nothing left behind on failure, a full disk at any write included),
// and other tools reading the files.
#include "TestSupport.h"
#include "io/AtomicFile.h"

#include <lantern/Io.h>

#include <gtest/gtest.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iterator>
#include <random>

namespace {

using namespace lantern;
using lantern::test::runProcess;
using lantern::test::testOutputDir;

Image randomImage(int w, int h, bool aovs) {
    std::mt19937 rng(42);
    std::uniform_real_distribution<float> hdr(-4.0f, 1000.0f);
    Image img(w, h);
    for (float& v : img.rgba) v = hdr(rng);
    img.rgba[0] = 1e30f;    // beyond half
    img.rgba[1] = 1e-30f;   // below half
    img.rgba[2] = -0.0f;
    if (aovs) {
        img.depth.resize(img.pixelCount());
        img.normal.resize(img.pixelCount() * 3);
        for (float& v : img.depth) v = hdr(rng) + 5.0f;
        for (float& v : img.normal) v = hdr(rng) / 1000.0f;
    }
    img.metadata = {{"lantern:test", "hello"}, {"lantern:frame", "7"}};
    return img;
}

std::size_t filesIn(const std::filesystem::path& dir) {
    std::size_t n = 0;
    for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++n;
    return n;
}

TEST(ImageIo, ExrFloatRoundTripIsExact) {
    const auto dir = testOutputDir();
    const Image img = randomImage(37, 23, true);
    for (ExrCompression c : {ExrCompression::None, ExrCompression::Zip, ExrCompression::Piz,
                             ExrCompression::Rle, ExrCompression::Zips}) {
        const auto path = dir / (std::string("float_") + toString(c) + ".exr");
        ExrOptions o;
        o.compression = c;
        ASSERT_TRUE(writeExr(path, img, o)) << toString(c);
        auto back = readExr(path);
        ASSERT_TRUE(back) << back.error().describe();
        ASSERT_EQ(back->width, 37);
        ASSERT_EQ(back->height, 23);
        EXPECT_EQ(back->rgba, img.rgba) << toString(c);
        EXPECT_EQ(back->depth, img.depth) << toString(c);
        EXPECT_EQ(back->normal, img.normal) << toString(c);
        bool found = false;
        for (const auto& [k, v] : back->metadata) found |= k == "lantern:test" && v == "hello";
        EXPECT_TRUE(found);
    }
}

// The zip level and the line-block threads change how fast a file is written, never what it
// holds: each level reads back exactly and a higher one is no larger; the bytes are the same
// whether this thread alone or OpenEXR's pool compressed the blocks; a level outside 1..9 is
// refused before anything is written.
TEST(ImageIo, ZipLevelsReadBackExactlyAndThreadsWriteTheSameBytes) {
    const auto dir = testOutputDir();
    Image img(300, 97); // 7 blocks of 16 lines for zip, 97 single lines for zips
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            for (int c = 0; c < 4; ++c)
                img.pixel(x, y)[c] = float((x * (c + 1) + y * 3) % 251) / 64.0f + float((x / 7) % 3);
    auto bytes = [](const std::filesystem::path& p) {
        std::ifstream in(p, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(in), {});
    };
    for (ExrCompression c : {ExrCompression::Zip, ExrCompression::Zips}) {
        std::uintmax_t previous = 0;
        for (int level : {9, 4, 2, 1}) {
            const auto path = dir / ("level" + std::to_string(level) + toString(c) + ".exr");
            ExrOptions o;
            o.compression = c;
            o.zipLevel = level;
            o.threads = 1;
            ASSERT_TRUE(writeExr(path, img, o));
            auto back = readExr(path);
            ASSERT_TRUE(back) << back.error().describe();
            EXPECT_EQ(back->rgba, img.rgba) << level;
            const std::uintmax_t size = std::filesystem::file_size(path);
            EXPECT_GE(size, previous) << "level " << level << " wrote a smaller file than a higher level";
            previous = size;
            for (int threads : {0, 4}) {
                o.threads = threads;
                const auto pooled = dir / ("pooled" + std::to_string(threads) + ".exr");
                ASSERT_TRUE(writeExr(pooled, img, o));
                EXPECT_EQ(bytes(pooled), bytes(path)) << toString(c) << " level " << level << ", " << threads << " threads";
            }
        }
    }
    ExrOptions bad;
    bad.zipLevel = 0;
    const auto refused = dir / "refused.exr";
    auto r = writeExr(refused, img, bad);
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error().code, ErrorCode::InvalidInput);
    EXPECT_FALSE(std::filesystem::exists(refused));
}

TEST(ImageIo, ExrHalfIsWithinHalfPrecisionAndClampsInsteadOfInf) {
    const auto path = testOutputDir() / "half.exr";
    const Image img = randomImage(16, 16, false);
    std::uint64_t clamped = 0;
    ExrOptions o;
    o.half = true;
    o.clampedCount = &clamped;
    ASSERT_TRUE(writeExr(path, img, o));
    EXPECT_EQ(clamped, 1u);  // the 1e30
    auto back = readExr(path);
    ASSERT_TRUE(back);
    EXPECT_EQ(back->rgba[0], 65504.0f);
    for (std::size_t i = 3; i < img.rgba.size(); ++i) {
        const float a = img.rgba[i], b = back->rgba[i];
        ASSERT_TRUE(std::isfinite(b));
        if (std::abs(a) >= 6.1e-5f) {
            EXPECT_LE(std::abs(a - b) / std::abs(a), 4.9e-4f) << a;
        }
    }
}

TEST(ImageIo, UnwritableOutputLeavesNothingBehind) {
    const auto dir = testOutputDir();
    const Image img = randomImage(8, 8, false);
    // A folder that does not exist, and a "folder" that is a file.
    const auto missing = writeExr(dir / "no" / "such" / "dir" / "x.exr", img);
    ASSERT_FALSE(missing);
    EXPECT_EQ(missing.error().code, ErrorCode::IoError);
    EXPECT_NE(missing.error().file.find("x.exr"), std::string::npos);
    std::ofstream(dir / "plainfile") << "x";
    EXPECT_FALSE(writePng(dir / "plainfile" / "x.png", img));
    // procfs refuses new files even to root.
    const auto proc = writeExr("/proc/lantern-test.exr", img);
    EXPECT_FALSE(proc);
    EXPECT_EQ(filesIn(dir), 1u);  // only "plainfile"
}

TEST(ImageIo, AFailedWriteKeepsTheOldFile) {
    const auto dir = testOutputDir();
    const auto path = dir / "keep.exr";
    ASSERT_TRUE(writeExr(path, randomImage(8, 8, false)));
    const auto before = std::filesystem::file_size(path);
    Image bad;  // no pixels: refused before anything is written
    EXPECT_FALSE(writeExr(path, bad));
    EXPECT_EQ(std::filesystem::file_size(path), before);
    EXPECT_EQ(filesIn(dir), 1u);
}

// An EXR that reads back, or a PNG that ends with its IEND chunk.
bool isComplete(const std::filesystem::path& path) {
    if (path.extension() == ".exr") return bool(readExr(path));
    std::ifstream f(path, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    return bytes.size() > 12 && bytes.compare(bytes.size() - 8, 4, "IEND") == 0;
}

constexpr const char* kNoHooks =
    "this build has no fault-injection hooks (LANTERN_TESTING_HOOKS=OFF)";

// Disarms the I/O fault hook when a test ends, however it ends.
struct IoFaultsCleared {
    ~IoFaultsCleared() { io::clearIoFaults(); }
};

// A disk that fills at any one of a file's writes: an IoError naming the file and saying the
// disk is full, and neither a partial file nor a temporary one left. EXR's last write is its
// offset table, which OpenEXR rewrites in a destructor that swallows errors; the file must
// still not be committed. Once the disk has room, the same call writes a complete file.
TEST(ImageIo, AFullDiskAtAnyWriteLeavesNothingBehind) {
    IoFaultsCleared cleared;
    if (!io::injectIoFault(io::IoOp::Write, ENOSPC, 1 << 30)) GTEST_SKIP() << kNoHooks;
    const auto dir = testOutputDir();
    // 96x96 float RGBA + Z + N, uncompressed: about 290 kB, several of the stream's writes.
    const Image img = randomImage(96, 96, true);
    ExrOptions exr;
    exr.compression = ExrCompression::None;
    struct Row {
        const char* name;
        int minimumWrites;
        std::function<Result<void>(const std::filesystem::path&)> write;
    };
    const Row rows[] = {
        {"full.exr", 5, [&](const auto& p) { return writeExr(p, img, exr); }},
        {"full.png", 1, [&](const auto& p) { return writePng(p, img); }},
    };
    for (const Row& row : rows) {
        SCOPED_TRACE(row.name);
        const auto path = dir / row.name;
        int failedAt = 0;
        for (; failedAt < 200; ++failedAt) {
            io::injectIoFault(io::IoOp::Write, ENOSPC, failedAt);
            const auto r = writeImage(path, img, exr);
            io::clearIoFaults();
            if (r) break;
            EXPECT_EQ(r.error().code, ErrorCode::IoError);
            EXPECT_EQ(r.error().file, path.string());
            EXPECT_NE(r.error().message.find("No space left on device (the disk is full)"),
                      std::string::npos)
                << r.error().describe();
            EXPECT_EQ(filesIn(dir), 0u) << "left behind after a full disk at write " << failedAt;
        }
        EXPECT_GE(failedAt, row.minimumWrites) << "the file took fewer writes than expected";
        ASSERT_TRUE(std::filesystem::exists(path));
        EXPECT_TRUE(isComplete(path)) << "the file written once the disk had room is not complete";
        std::filesystem::remove(path);
    }
}

// A failed fsync or rename (EIO, a read-only remount) keeps the old file and leaves no
// temporary one.
TEST(ImageIo, AFailedFsyncOrRenameKeepsTheOldFile) {
    IoFaultsCleared cleared;
    if (!io::injectIoFault(io::IoOp::Fsync, EIO, 1 << 30)) GTEST_SKIP() << kNoHooks;
    io::clearIoFaults();
    const auto dir = testOutputDir();
    const Image old = randomImage(8, 8, false), replacement = randomImage(16, 16, false);
    struct Row {
        io::IoOp op;
        int error;
        const char* expected;
    };
    const Row rows[] = {
        {io::IoOp::Fsync, EIO, "fsync failed: Input/output error"},
        {io::IoOp::Rename, EROFS, "cannot rename the finished file into place: Read-only"},
    };
    for (const Row& row : rows)
        for (const char* name : {"keep.exr", "keep.png"}) {
            SCOPED_TRACE(std::string(name) + ": " + row.expected);
            const auto path = dir / name;
            ASSERT_TRUE(writeImage(path, old));
            const auto before = std::filesystem::file_size(path);
            io::injectIoFault(row.op, row.error);
            const auto r = writeImage(path, replacement);
            io::clearIoFaults();
            ASSERT_FALSE(r);
            EXPECT_EQ(r.error().code, ErrorCode::IoError);
            EXPECT_NE(r.error().message.find(row.expected), std::string::npos)
                << r.error().describe();
            EXPECT_EQ(std::filesystem::file_size(path), before);
            EXPECT_EQ(filesIn(dir), 1u);
            std::filesystem::remove(path);
        }
}

TEST(ImageIo, PngIsSrgbEncodedAndUnpremultiplied) {
    const auto path = testOutputDir() / "p.png";
    Image img(2, 1);
    const float px[8] = {0.5f, 0.5f, 0.5f, 1.0f, 0.25f, 0.0f, 0.0f, 0.5f};
    std::copy(px, px + 8, img.rgba.begin());
    ASSERT_TRUE(writePng(path, img));
    std::ifstream f(path, std::ios::binary);
    char sig[8];
    f.read(sig, 8);
    EXPECT_EQ(std::string(sig + 1, 3), "PNG");
    EXPECT_FALSE(writeImage(testOutputDir() / "x.tiff", img));
}

TEST(ImageIo, OpenImageIoReadsTheExr) {
    if (std::system("command -v oiiotool >/dev/null 2>&1") != 0)
        GTEST_SKIP() << "oiiotool (Debian package openimageio-tools) is not installed";
    const auto path = testOutputDir() / "oiio.exr";
    ASSERT_TRUE(writeExr(path, randomImage(64, 32, true)));
    const auto r = runProcess({"oiiotool", "--info", "-v", path.string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("64 x   32, 8 channel, float openexr"), std::string::npos) << r.out;
    // OIIO lists channels in canonical order: colour, then Z, then the rest.
    EXPECT_NE(r.out.find("R, G, B, A, Z, N.X, N.Y, N.Z"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("compression: \"zip\""), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("lantern:test"), std::string::npos) << r.out;
}

} // namespace
