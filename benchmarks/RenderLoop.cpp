// lantern_render_loop: renders per second of one scene through the C++ API, the loop that
// benchmarks/render_loop.py runs through the Python module (benchmarks/python-vs-cpp.sh times
// the two interleaved). Usage: lantern_render_loop [SCENE] [WIDTH] [HEIGHT] [RENDERS] [WARMUP]
#include <lantern/Lantern.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

int main(int argc, char** argv) {
    const std::string sceneName = argc > 1 ? argv[1] : "builtin:teapot";
    const int width = argc > 2 ? std::atoi(argv[2]) : 256;
    const int height = argc > 3 ? std::atoi(argv[3]) : 256;
    const int renders = argc > 4 ? std::atoi(argv[4]) : 200;
    const int warmup = argc > 5 ? std::atoi(argv[5]) : 10;
    auto renderer = lantern::Renderer::create();
    if (!renderer) return std::fprintf(stderr, "%s\n", renderer.error().describe().c_str()), 3;
    auto scene = lantern::loadScene(sceneName);
    if (!scene) return std::fprintf(stderr, "%s\n", scene.error().describe().c_str()), 1;
    auto prepared = renderer->prepare(std::make_shared<const lantern::Scene>(std::move(*scene)));
    if (!prepared) return std::fprintf(stderr, "%s\n", prepared.error().describe().c_str()), 3;
    lantern::RenderOptions options;
    options.width = width;
    options.height = height;
    double checksum = 0.0; // uses every picture, as the Python loop holds each array
    auto loop = [&](int n) {
        for (int i = 0; i < n; ++i) {
            auto image = renderer->render(*prepared, options, 0.0);
            if (!image) std::exit(3);
            checksum += image->pixel(width / 2, height / 2)[0]; // the centre's red, as Python
        }
    };
    loop(warmup);
    const auto t0 = std::chrono::steady_clock::now();
    loop(renders);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("c++ %s %dx%d: %d renders in %.3f s: %.2f renders/s (checksum %g)\n",
                sceneName.c_str(), width, height, renders, seconds, renders / seconds, checksum);
    return 0;
}
