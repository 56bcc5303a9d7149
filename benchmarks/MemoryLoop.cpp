// lantern_memory_loop: resident memory (RSS) of one process rendering the same small picture
// many times through the C++ API (benchmarks/memory_loop.py is the same loop through the Python
// module). Prints RSS after renders 1, 100, 1000, 10000 (those within --renders) and the last,
// and the growth after the first hundred; exits 1 when that growth exceeds --max-growth percent
// (the suite's MemoryLoop tests, label memory). --leak-bytes N leaks N bytes per render on
// purpose, to show that the check catches a leak (MemoryLoop.CatchesADeliberateLeak).
//
// Usage: lantern_memory_loop [--scene S] [--width W] [--height H] [--renders N]
//                            [--max-growth PERCENT] [--leak-bytes N]
#include <lantern/Lantern.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <string>
#include <unistd.h>
#include <vector>

namespace {

double residentMiB() {
    std::ifstream statm("/proc/self/statm");
    long pages = 0, resident = 0;
    statm >> pages >> resident;
    return double(resident) * double(sysconf(_SC_PAGESIZE)) / 1048576.0;
}

struct Args {
    std::string scene = "builtin:spheres-animated";
    int width = 64, height = 64, renders = 10000;
    double maxGrowth = -1.0;  ///< percent; negative: report only
    long leakBytes = 0;
};

bool parse(int argc, char** argv, Args& a) {
    for (int i = 1; i < argc; ++i) {
        const std::string k = argv[i];
        if (i + 1 >= argc) return false;
        const char* v = argv[++i];
        if (k == "--scene") a.scene = v;
        else if (k == "--width") a.width = std::atoi(v);
        else if (k == "--height") a.height = std::atoi(v);
        else if (k == "--renders") a.renders = std::atoi(v);
        else if (k == "--max-growth") a.maxGrowth = std::atof(v);
        else if (k == "--leak-bytes") a.leakBytes = std::atol(v);
        else return false;
    }
    return a.renders >= 100 && a.width > 0 && a.height > 0 && a.leakBytes >= 0;
}

} // namespace

int main(int argc, char** argv) {
    Args a;
    if (!parse(argc, argv, a)) {
        std::fprintf(stderr, "usage: lantern_memory_loop [--scene S] [--width W] [--height H] "
                             "[--renders N>=100] [--max-growth PERCENT] [--leak-bytes N]\n");
        return 2;
    }
    auto renderer = lantern::Renderer::create();
    if (!renderer) return std::fprintf(stderr, "%s\n", renderer.error().describe().c_str()), 3;
    auto scene = lantern::loadScene(a.scene);
    if (!scene) return std::fprintf(stderr, "%s\n", scene.error().describe().c_str()), 1;
    auto prepared = renderer->prepare(std::make_shared<const lantern::Scene>(std::move(*scene)));
    if (!prepared) return std::fprintf(stderr, "%s\n", prepared.error().describe().c_str()), 3;
    lantern::RenderOptions options;
    options.width = a.width;
    options.height = a.height;
    std::vector<std::unique_ptr<char[]>> leaked;  // --leak-bytes: held, written, never freed
    double at100 = 0.0, checksum = 0.0;
    std::printf("c++ %s %dx%d: resident MiB after render", a.scene.c_str(), a.width, a.height);
    for (int i = 1; i <= a.renders; ++i) {
        // Time moves, as a sequence's would (an animated scene poses differently each frame).
        auto image = renderer->render(*prepared, options, double(i % 60) / 30.0);
        if (!image) return std::fprintf(stderr, "%s\n", image.error().describe().c_str()), 3;
        checksum += image->pixel(a.width / 2, a.height / 2)[0];
        if (a.leakBytes > 0) {
            leaked.emplace_back(new char[std::size_t(a.leakBytes)]);
            std::memset(leaked.back().get(), i & 0xff, std::size_t(a.leakBytes));
        }
        const bool report = i == 1 || i == 100 || i == 1000 || i == 10000 || i == a.renders;
        if (i == 100) at100 = residentMiB();
        if (report) std::printf(" %d: %.1f", i, residentMiB());
        std::fflush(stdout);
    }
    const double growth = 100.0 * (residentMiB() - at100) / at100;
    std::printf("\ngrowth after render 100: %+.2f%% (checksum %g)\n", growth, checksum);
    if (a.maxGrowth >= 0.0 && growth > a.maxGrowth) {
        std::fprintf(stderr, "resident memory grew %.2f%% after render 100, more than %.2f%%\n",
                     growth, a.maxGrowth);
        return 1;
    }
    return 0;
}
