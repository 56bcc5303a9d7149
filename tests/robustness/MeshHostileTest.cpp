// Hostile mesh files (no GPU): the MTL libraries and textures an OBJ names are confined like a
// glTF's URIs (no absolute path, no "..", no symbolic link out, no FIFO or device), a count in a
// header is checked against the file before anything is allocated, and no input makes the
// loader hang: PLY without end_header, polygons of 10^5 corners. Refusals reach `lantern info`
// as one line naming the file, the object and the problem, with exit status 1.
#include "MeshTestSupport.h"

#include <gtest/gtest.h>

#include <chrono>
#include <sys/stat.h>
#include <unistd.h>

namespace {

using namespace lantern;
using lantern::test::loadAny;
using lantern::test::refusedWith;
using lantern::test::testOutputDir;
using lantern::test::writeText;

double secondsSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

const std::string kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl m\nf 1 2 3\n";

TEST(MeshHostile, MtlLibrariesAndTexturesStayInTheScenesFolder) {
    const auto root = testOutputDir();
    const auto dir = root / "scene";
    std::filesystem::create_directories(dir);
    writeText(root / "secret.mtl", "newmtl m\nKd 1 0 0\n");
    std::filesystem::create_symlink("../secret.mtl", dir / "link.mtl");
    ASSERT_EQ(::mkfifo((dir / "fifo.mtl").c_str(), 0600), 0);
    ASSERT_EQ(::mkfifo((dir / "fifo.png").c_str(), 0600), 0);
    struct Case {
        std::string mtllib, mtl, object, fragment;
    };
    const Case cases[] = {
        {"../secret.mtl", "", "mtllib \"../secret.mtl\"", "contains \"..\""},
        {"/etc/passwd", "", "mtllib \"/etc/passwd\"", "absolute path"},
        // tinyobjloader reads a backslash in mtllib as an escape: "C:\models\m.mtl" is "C:modelsm.mtl".
        {"C:\\models\\m.mtl", "", "mtllib \"C:modelsm.mtl\"", "absolute Windows path"},
        {"link.mtl", "", "mtllib \"link.mtl\"", "leads outside the scene's folder"},
        {"fifo.mtl", "", "mtllib \"fifo.mtl\"", "a FIFO"},
        {"m.mtl", "newmtl m\nmap_Kd /dev/zero\n", "materials \"m\".map_Kd", "absolute path"},
        {"m.mtl", "newmtl m\nmap_Kd fifo.png\n", "materials \"m\".map_Kd", "a FIFO"},
        {"m.mtl", "newmtl m\nnorm ../secret.mtl\n", "materials \"m\".norm", "contains \"..\""},
    };
    for (const Case& c : cases) {
        if (!c.mtl.empty()) writeText(dir / "m.mtl", c.mtl);
        const auto path = writeText(dir / "hostile.obj", "mtllib " + c.mtllib + "\n" + kTriangle);
        const auto start = std::chrono::steady_clock::now();
        EXPECT_TRUE(refusedWith(loadAny(path), c.object, c.fragment)) << c.mtllib << " " << c.mtl;
        EXPECT_LT(secondsSince(start), 2.0) << "a FIFO is never waited on";
    }
    // An allowed folder admits ".." into it, and nothing else.
    LoadOptions allowed;
    allowed.allowedFolders = {root};
    writeText(dir / "up.obj", "mtllib ../secret.mtl\n" + kTriangle);
    auto o = loadAny(dir / "up.obj", allowed);
    ASSERT_TRUE(o.scene) << o.scene.error().describe();
    EXPECT_EQ(o.scene->materials.at(0).front.diffuse, glm::dvec4(1, 0, 0, 1));
    writeText(dir / "abs.obj", "mtllib /etc/passwd\n" + kTriangle);
    EXPECT_TRUE(refusedWith(loadAny(dir / "abs.obj", allowed), "mtllib \"/etc/passwd\"", "absolute path"));
}

TEST(MeshHostile, EndlessOrOversizedReferencesAreRefusedBeforeReading) {
    const auto dir = testOutputDir();
    // A library larger than the budget left is not read into memory.
    writeText(dir / "big.mtl", "newmtl m\n" + std::string(1 << 20, '#') + "\n");
    const auto path = writeText(dir / "big.obj", "mtllib big.mtl\n" + kTriangle);
    LoadOptions small;
    small.maxBytes = 64 << 10;
    EXPECT_TRUE(refusedWith(loadAny(path, small), "mtllib \"big.mtl\"", "--max-size"));
    // A library of a million materials in 9 MB: charged (about 1.6 KB each) before it is parsed.
    std::string many;
    for (int i = 0; i < 1000000; ++i) many += "newmtl \n";
    writeText(dir / "many.mtl", many);
    writeText(dir / "many.obj", "mtllib many.mtl\n" + kTriangle);
    small.maxBytes = 256 << 20;
    EXPECT_TRUE(refusedWith(loadAny(dir / "many.obj", small), "mtllib \"many.mtl\"", "1000000 materials"));
}

TEST(MeshHostile, HeadersClaimingHugeCountsAreRefusedAtOnce) {
    const auto dir = testOutputDir();
    writeText(dir / "huge.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 1000000000000\n"
                                "property float x\nproperty float y\nproperty float z\nend_header\n" +
                                    std::string(36, '\0'));
    writeText(dir / "huge.off", "OFF\n1000000000000 1000000000000 0\n0 0 0\n");
    writeText(dir / "nohead.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 3\n"
                                  "property float x\n" + std::string(1 << 20, 'x'));
    const std::pair<const char*, const char*> files[] = {
        {"huge.ply", "claims 1000000000000 records"},
        {"huge.off", "need more than the"},
        {"nohead.ply", "no end_header"}};
    for (const auto& [name, fragment] : files) {
        const auto start = std::chrono::steady_clock::now();
        EXPECT_TRUE(refusedWith(loadAny(dir / name), "header", fragment)) << name;
        EXPECT_LT(secondsSince(start), 1.0) << name;
    }
}

// The polygon's corners. AddressSanitizer's strict_string_checks (the asan test preset's) makes
// every atoi tinyobjloader calls measure the rest of its line, which on one line of 100,000
// indices is quadratic (22 s): that build gets a polygon of 20,000 corners, still far beyond the
// ear-clipping budget (4 n^2 > 2^26 from n = 4097 on).
constexpr int kCorners = test::kAddressSanitizer ? 20000 : 100000;

TEST(MeshHostile, PolygonsOfAHundredThousandCornersTakeLinearTime) {
    const auto dir = testOutputDir();
    // A concave star: ear clipping would take 10^10 steps; beyond the load's budget it is fanned.
    std::string obj, off = "OFF\n" + std::to_string(kCorners) + " 1 0\n";
    std::string face = "f", offFace = std::to_string(kCorners);
    for (int i = 0; i < kCorners; ++i) {
        const double a = i * 6.283185307179586 / kCorners, r = i % 2 ? 1.0 : 0.5;
        const std::string v = std::to_string(r * std::cos(a)) + " " + std::to_string(r * std::sin(a)) + " 0\n";
        obj += "v " + v;
        off += v;
        face += " " + std::to_string(i + 1);
        offFace += " " + std::to_string(i);
    }
    writeText(dir / "star.obj", obj + face + "\n");
    writeText(dir / "star.off", off + offFace + "\n");
    for (const char* name : {"star.obj", "star.off"}) {
        const auto start = std::chrono::steady_clock::now();
        auto o = loadAny(dir / name);
        ASSERT_TRUE(o.scene) << name << ": " << o.scene.error().describe();
        EXPECT_EQ(o.scene->meshes[0].primitives[0].triangleCount(), std::size_t(kCorners - 2));
        EXPECT_TRUE(o.warned("ear-clipping budget")) << o.allWarnings();
        EXPECT_LT(secondsSince(start), 5.0) << name;
    }
}

TEST(MeshHostile, LanternInfoPrintsOneLineAndExits1) {
    const auto dir = testOutputDir();
    writeText(dir / "bad.obj", "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n");
    writeText(dir / "bad.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n");
    writeText(dir / "bad.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n");
    writeText(dir / "bad.stl", "solid\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n");
    const std::pair<const char*, const char*> files[] = {
        {"bad.obj", "bad.obj: vertex 2: \"nan\" is not a finite number (line 2)"},
        {"bad.ply", "bad.ply: header: has no end_header line"},
        {"bad.off", "bad.off: face 0: corner 2: \"7\" is not a vertex index"},
        {"bad.stl", "bad.stl: facet 0: expected \"endfacet\", got \"\""}};
    for (const auto& [name, expected] : files) {
        const auto run = test::runLantern({"info", (dir / name).string()});
        EXPECT_EQ(run.exitCode, 1) << name << ": " << run.err;
        EXPECT_NE(run.err.find(expected), std::string::npos) << run.err;
        EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    }
}

} // namespace
