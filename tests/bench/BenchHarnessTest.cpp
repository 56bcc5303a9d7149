// The benchmark harness, not its numbers: `lantern bench accuracy` and `lantern bench speed` run
// a tiny sweep and write a CSV with one row per configuration, named columns and finite values,
// a plot (matplotlib) and a summary; bad options are refused with exit 1 (2 for unknown ones).
// Nothing here is timed.
#include "TestSupport.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <gtest/gtest.h>
#include <map>
#include <set>
#include <sstream>

namespace {

using namespace lantern;
using lantern::test::GpuTest;
using lantern::test::runLantern;

// A CSV file as rows of named cells.
struct Csv {
    std::vector<std::string> header;
    std::vector<std::map<std::string, std::string>> rows;
};

std::vector<std::string> split(const std::string& line) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ','))
        cells.push_back(cell);
    if (!line.empty() && line.back() == ',') cells.emplace_back();
    return cells;
}

Csv readCsv(const std::filesystem::path& path) {
    Csv csv;
    std::ifstream in(path);
    std::string line;
    if (!std::getline(in, line)) return csv;
    csv.header = split(line);
    while (std::getline(in, line)) {
        const auto cells = split(line);
        EXPECT_EQ(cells.size(), csv.header.size()) << "ragged row: " << line;
        std::map<std::string, std::string> row;
        for (std::size_t i = 0; i < cells.size() && i < csv.header.size(); ++i)
            row[csv.header[i]] = cells[i];
        csv.rows.push_back(row);
    }
    return csv;
}

double number(const std::map<std::string, std::string>& row, const std::string& column) {
    const auto it = row.find(column);
    if (it == row.end() || it->second.empty()) return std::nan("");
    char* end = nullptr;
    const double v = std::strtod(it->second.c_str(), &end);
    return end && *end == '\0' ? v : std::nan("");
}

std::string readText(const std::filesystem::path& path) {
    std::ifstream in(path);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

class BenchHarness : public GpuTest {};

// The plot of the sweep, drawn by benchmarks/plot_accuracy.py when matplotlib is installed: an
// SVG whose legend names every curve, the Pareto front and the acceptance line, and a PNG.
// Without matplotlib the run says how to draw it.
void expectPlot(const std::filesystem::path& dir, const std::string& err) {
    // The pythons `lantern bench accuracy` tries: the one on PATH, then Debian's.
    const bool matplotlib =
        test::runProcess({"python3", "-c", "import matplotlib"}).exitCode == 0 ||
        test::runProcess({"/usr/bin/python3", "-c", "import matplotlib"}).exitCode == 0;
    if (!matplotlib) {
        EXPECT_NE(err.find("python3-matplotlib"), std::string::npos) << err;
        EXPECT_NE(err.find("plot_accuracy.py"), std::string::npos) << err;
        return;
    }
    const std::string svg = readText(dir / "accuracy.svg");
    ASSERT_FALSE(svg.empty()) << "no accuracy.svg: " << err;
    EXPECT_NE(svg.find("</svg>"), std::string::npos);
    for (const char* label : {"flat, 1x MSAA", "gouraud, 1x MSAA", "phong, 1x MSAA",
                              "flat, 4x MSAA", "gouraud, 4x MSAA", "phong, 4x MSAA",
                              "Pareto front", "1e-3 acceptance", "sphere, shininess 128, 64x48",
                              "spot, shininess 128, 64x48"})
        EXPECT_NE(svg.find(label), std::string::npos) << "the plot has no \"" << label << "\"";
    EXPECT_GT(std::filesystem::file_size(dir / "accuracy.png"), 1000u);
    if (std::system("command -v rsvg-convert >/dev/null 2>&1") == 0) {
        const auto png = dir / "accuracy-rsvg.png";
        const auto c =
            test::runProcess({"rsvg-convert", (dir / "accuracy.svg").string(), "-o", png.string()});
        EXPECT_EQ(c.exitCode, 0) << "another SVG reader refuses the plot: " << c.err;
    }
}

TEST_F(BenchHarness, TinyAccuracySweepWritesOneFiniteRowPerConfiguration) {
    const auto dir = test::testOutputDir();
    const auto r = runLantern({"bench",
                               "accuracy",
                               "--sections",
                               "shading",
                               "--shading",
                               "flat,gouraud,phong",
                               "--segments",
                               "8,16",
                               "--msaa",
                               "1,4",
                               "--width",
                               "64",
                               "--height",
                               "48",
                               "--rounds",
                               "1",
                               "--frames",
                               "1",
                               "--warmup",
                               "1",
                               "--reference-samples",
                               "4",
                               "-q",
                               "-o",
                               dir.string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Csv csv = readCsv(dir / "accuracy.csv");
    for (const char* column :
         {"scene", "shading", "segments", "triangles", "msaa", "ms_per_frame", "rmse",
          "interior_rmse", "silhouette_rmse", "peak_ratio", "psnr_db", "floor_ms", "x_floor",
          "nonfinite", "pareto_interior", "pareto_whole"})
        EXPECT_NE(std::find(csv.header.begin(), csv.header.end(), column), csv.header.end())
            << column;
    // 2 scenes x 3 modes x 2 tessellations x 2 sample counts, each exactly once.
    ASSERT_EQ(csv.rows.size(), 24u);
    std::set<std::string> seen;
    const std::map<std::string, std::map<int, int>> triangles{{"sphere", {{8, 48}, {16, 224}}},
                                                              {"spot", {{8, 128}, {16, 512}}}};
    std::map<std::string, int> frontSizes;
    for (const auto& row : csv.rows) {
        const std::string key = row.at("scene") + "/" + row.at("shading") + "/" +
                                row.at("segments") + "/" + row.at("msaa");
        EXPECT_TRUE(seen.insert(key).second) << "duplicate row " << key;
        EXPECT_EQ(number(row, "triangles"),
                  triangles.at(row.at("scene")).at(int(number(row, "segments"))))
            << key;
        for (const char* column : {"ms_per_frame", "ms_wall", "first_frame_ms", "floor_ms",
                                   "x_floor", "rmse", "max_error", "interior_rmse", "interior_max",
                                   "interior_p99", "silhouette_rmse", "peak_ratio"}) {
            const double v = number(row, column);
            EXPECT_TRUE(std::isfinite(v) && v >= 0.0)
                << key << ": " << column << " = " << row.at(column);
        }
        EXPECT_GT(number(row, "ms_per_frame"), 0.0) << key;
        EXPECT_GT(number(row, "interior_pixels"), 100.0) << key;
        EXPECT_EQ(number(row, "nonfinite"), 0.0) << key;
        frontSizes[row.at("scene")] += int(number(row, "pareto_interior"));
        // Phong shading of a plane interpolates a constant normal and exact positions: at one
        // sample per pixel the reference must agree to float precision (a wrong camera or
        // light placement would not; MSAA shades at sample centroids, not pixel centres).
        if (row.at("scene") == "spot" && row.at("shading") == "phong" && row.at("msaa") == "1") {
            EXPECT_LT(number(row, "interior_rmse"), 1e-5) << key;
        }
    }
    EXPECT_GE(frontSizes["sphere"], 1);
    EXPECT_GE(frontSizes["spot"], 1);

    const std::string md = readText(dir / "accuracy.md");
    EXPECT_NE(md.find("Pareto front"), std::string::npos);
    EXPECT_NE(md.find("fastest setting"), std::string::npos);
    EXPECT_NE(md.find("lantern bench accuracy --sections shading --shading flat,gouraud,phong"), std::string::npos)
        << "the summary names the command that reproduces it";
    expectPlot(dir, r.err);
}

// The shadow scenes sweep map resolution x filter x cascades against the exact shadow rays
// (PCSS against lights with a size), the transparency scenes the three methods against the
// exact composite: the finer map gets fewer pixels wrong than the coarsest, cascades fewer than
// one map over the long field, and exact transparency's error is far below sorting's.
TEST_F(BenchHarness, ShadowAndTransparencySectionsMeasureTheirTrades) {
    const auto dir = test::testOutputDir();
    const auto r = runLantern({"bench", "accuracy", "--sections", "shading", "--scenes", "shadow,field,crossing,foliage", "--shading", "phong",
                               "--segments", "32", "--msaa", "1", "--width", "96", "--height", "72",
                               "--shadow-resolution", "32,1024", "--shadow-filter", "hardware,pcf,pcss",
                               "--shadow-cascades", "1,4", "--rounds", "1", "--frames", "1", "--warmup", "1",
                               "--reference-samples", "2", "--no-floor", "-q", "-o", dir.string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Csv csv = readCsv(dir / "accuracy.csv");
    ASSERT_EQ(csv.rows.size(), 2u * 12u + 6u);  // 2 resolutions x 3 filters x 2 cascades; 2 x 3 methods
    std::map<std::string, double> wrong, interior;
    for (const auto& row : csv.rows) {
        const std::string key = row.at("scene") + "/" + row.at("shadow_resolution") + "/" +
                                row.at("shadow_filter") + "/" + row.at("shadow_cascades") +
                                row.at("transparency");
        if (row.at("scene") != "crossing" && row.at("scene") != "foliage") {
            wrong[key] = number(row, "wrong_shadow_share");
            EXPECT_TRUE(wrong[key] >= 0.0 && wrong[key] <= 1.0) << key;
        } else {
            EXPECT_TRUE(row.at("wrong_shadow_share").empty()) << key;
        }
        interior[key] = number(row, "interior_rmse");
    }
    for (const char* f : {"hardware", "pcf"}) {
        const std::string coarse = std::string("shadow/32/") + f + "/1", fine = std::string("shadow/1024/") + f + "/1";
        EXPECT_LT(wrong.at(fine), wrong.at(coarse)) << f;
        EXPECT_LT(wrong.at(fine), 0.01) << f;
        EXPECT_LT(wrong.at(std::string("field/1024/") + f + "/4"), wrong.at(std::string("field/1024/") + f + "/1")) << f;
    }
    EXPECT_LT(wrong.at("shadow/1024/pcss/4"), 0.02);
    EXPECT_LT(interior.at("crossing///exact"), 1e-3);
    // Leaves cut by a textured mask over one blended pond: one blended layer, so every method
    // composites it alike, and the reference samples the mask as the device does (but for the
    // few pixels whose centre falls on a stripe's edge: 7.4e-3 at 96 x 72, 2.2e-3 at 480 x 270).
    EXPECT_LT(interior.at("foliage///exact"), 2e-2);
    EXPECT_EQ(interior.at("foliage///sorted"), interior.at("foliage///exact"));
    EXPECT_GT(interior.at("crossing///sorted"), 10.0 * interior.at("crossing///exact"));
    const std::string md = readText(dir / "accuracy.md");
    EXPECT_NE(md.find("wrong shadow %"), std::string::npos);
    EXPECT_NE(md.find("4 cascades"), std::string::npos);
}

// The level-of-detail section times each --lod-error bound against the exact frame and
// measures its error against it: the exact row is the reference (no error), coarser bounds
// draw fewer triangles and differ from it, and the fronts hold the fastest and the most exact.
TEST_F(BenchHarness, LevelOfDetailSectionMeasuresEachBoundAgainstTheExactFrame) {
    const auto dir = test::testOutputDir();
    const auto r = runLantern({"bench", "accuracy", "--sections", "lod", "--lod-grid", "3",
                               "--lod-segments", "48", "--lod-errors", "16,0.5", "--width", "96",
                               "--height", "64", "--rounds", "1", "--frames", "1", "--warmup", "1",
                               "-q", "-o", dir.string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Csv csv = readCsv(dir / "lod.csv");
    ASSERT_EQ(csv.rows.size(), 3u);  // 0 is always timed; the bounds in increasing order
    EXPECT_EQ(csv.rows[0].at("lod_error"), "0");
    EXPECT_EQ(csv.rows[1].at("lod_error"), "0.5");
    EXPECT_EQ(csv.rows[2].at("lod_error"), "16");
    const auto& exact = csv.rows[0];
    const auto& coarse = csv.rows[2];
    EXPECT_EQ(number(exact, "rmse"), 0.0);
    EXPECT_EQ(number(exact, "pareto"), 1.0);
    EXPECT_EQ(number(exact, "clustered_triangles"), 9.0 * 48 * 46);  // 24 rings, two of fans
    EXPECT_LT(number(coarse, "clustered_triangles_drawn"),
              0.5 * number(exact, "clustered_triangles_drawn"));
    EXPECT_GT(number(coarse, "rmse"), 0.0);
    EXPECT_GT(number(coarse, "flip_mean"), 0.0);
    EXPECT_LT(number(coarse, "flip_mean"), 0.5);
    const auto* fastest = &csv.rows[0];
    for (const auto& row : csv.rows) {
        EXPECT_TRUE(std::isfinite(number(row, "ms_per_frame")) && number(row, "ms_per_frame") > 0.0);
        EXPECT_EQ(number(row, "nonfinite"), 0.0);
        if (number(row, "ms_per_frame") < number(*fastest, "ms_per_frame")) fastest = &row;
    }
    EXPECT_EQ(number(*fastest, "pareto"), 1.0) << "the fastest bound is on the front";
    const std::string md = readText(dir / "accuracy.md");
    EXPECT_NE(md.find("## Level of detail"), std::string::npos) << md;
    EXPECT_NE(md.find("--sections lod"), std::string::npos) << "names the command";
    EXPECT_FALSE(std::filesystem::exists(dir / "accuracy.csv")) << "the shading section did not run";
}

// bench frame takes render's camera options and reports the in-place path (renderView) beside
// render() with its copy; with AOVs (which renderView does not return) it reports render() only.
TEST_F(BenchHarness, FrameTakesRendersCameraAndTimesRenderView) {
    const auto r = runLantern({"bench", "frame", "builtin:spheres", "--runs", "1", "--width", "64",
                               "--height", "48", "--look-at", "0,2,6,0,0,0,0,1,0", "--no-culling"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("render only: renderView (no copy)"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("render only: render() + readback"), std::string::npos) << r.out;
    const auto aov = runLantern({"bench", "frame", "builtin:spheres", "--runs", "1", "--width", "64",
                                 "--height", "48", "--aov", "depth", "--view", "front"});
    ASSERT_EQ(aov.exitCode, 0) << aov.err;
    EXPECT_EQ(aov.out.find("renderView"), std::string::npos) << aov.out;
    const auto bad = runLantern({"bench", "frame", "builtin:spheres", "--runs", "1", "--width", "64",
                                 "--height", "48", "--look-at", "0,0,0,0,0,0,0,1,0"});
    EXPECT_EQ(bad.exitCode, 1) << bad.err;
    EXPECT_NE(bad.err.find("--look-at"), std::string::npos) << bad.err;
}

TEST_F(BenchHarness, TinySpeedRunGivesEveryTimeAsAMultipleOfTheFloor) {
    const auto dir = test::testOutputDir();
    const auto r = runLantern({"bench",       "speed",     "builtin:teapot",
                               "--width",     "64",        "--height",
                               "48",          "--lights",  "1,3",
                               "--triangles", "1000",      "--rounds",
                               "1",           "--frames",  "1",
                               "--warmup",    "1",         "-q",
                               "-o",          dir.string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Csv csv = readCsv(dir / "speed.csv");
    std::map<std::string, int> perSection;
    for (const auto& row : csv.rows) {
        ++perSection[row.at("section")];
        for (const char* column : {"ms_per_frame", "floor_ms", "x_floor"}) {
            const double v = number(row, column);
            EXPECT_TRUE(std::isfinite(v) && v > 0.0) << row.at("section") << " " << column;
        }
        if (row.at("features") == "floor") {
            EXPECT_EQ(number(row, "x_floor"), 1.0);
        }
    }
    // modes: floor + 3 modes x (specialised, all-features); lights: floor + 2 counts x 3 modes;
    // triangles: floor + 3 modes.
    EXPECT_EQ(perSection["modes"], 7);
    EXPECT_EQ(perSection["lights"], 7);
    EXPECT_EQ(perSection["triangles"], 4);
    std::set<double> lights;
    for (const auto& row : csv.rows)
        if (row.at("section") == "lights") lights.insert(number(row, "lights"));
    EXPECT_EQ(lights, (std::set<double>{1.0, 3.0}));
    const std::string md = readText(dir / "speed.md");
    EXPECT_NE(md.find("all-features / specialised"), std::string::npos);
}

struct BadOption {
    const char* name;
    std::vector<std::string> args;
    int exitCode;
    const char* message;
};

TEST_F(BenchHarness, RefusesBadOptionsBeforeRendering) {
    const auto dir = test::testOutputDir();
    const std::vector<BadOption> cases = {
        {"segments", {"accuracy", "--segments", "2"}, 1, "--segments"},
        {"width", {"accuracy", "--width", "0", "--height", "5"}, 1, "--width"},
        {"sizes", {"accuracy", "--width", "64,128,256", "--height", "48,96"}, 1, "--width/--height"},
        {"old spelling", {"accuracy", "--resolutions", "64x48"}, 2, "--resolution"},
        {"scene", {"accuracy", "--scenes", "cube"}, 1, "--scenes"},
        {"shading", {"accuracy", "--shading", "toon"}, 1, "--shading"},
        {"shininess", {"accuracy", "--shininess", "-1"}, 1, "--shininess"},
        {"accuracy section", {"accuracy", "--sections", "speed"}, 1, "--sections"},
        {"lod bound", {"accuracy", "--lod-errors", "-1"}, 1, "--lod-errors"},
        {"section", {"speed", "--sections", "fog"}, 1, "--sections"},
        {"lights", {"speed", "--lights", "0"}, 1, "--lights"},
        {"output", {"accuracy", "-o", "/proc/lantern-bench"}, 3, "--output"},
    };
    for (const BadOption& c : cases) {
        std::vector<std::string> args{"bench"};
        args.insert(args.end(), c.args.begin(), c.args.end());
        if (c.exitCode != 3) args.insert(args.end(), {"-o", (dir / c.name).string()});
        const auto r = runLantern(args);
        EXPECT_EQ(r.exitCode, c.exitCode) << c.name << ": " << r.err;
        EXPECT_NE(r.err.find(c.message), std::string::npos) << c.name << ": " << r.err;
    }
}

} // namespace
