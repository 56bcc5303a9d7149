// Two renderers in one process, each on its own thread, rendering at the same time: each
// frame equals, bit for bit, the frame one renderer renders alone (renderers share nothing
// but the Vulkan loader and driver), and neither draws the validation layer's attention.
#include "TestSupport.h"

#include <gtest/gtest.h>

#include <iostream>
#include <latch>
#include <memory>
#include <string>
#include <thread>
#include <vector>

namespace {

using namespace lantern;
using lantern::test::GpuTest;

// One frame of the work: which scene, at which time, with which shading.
struct Frame {
    const char* scene;
    double time;
    ShadingMode shading;
};

// Each thread renders a different list, so both pipelines and scenes differ while they run.
const std::vector<Frame> kWork[2] = {
    {{"spheres-animated", 0.0, ShadingMode::Phong},
     {"spheres-animated", 0.75, ShadingMode::Phong},
     {"teapot", 0.0, ShadingMode::Gouraud},
     {"spheres-animated", 1.5, ShadingMode::Flat}},
    {{"teapot", 0.0, ShadingMode::Phong},
     {"spheres-animated", 0.25, ShadingMode::Gouraud},
     {"spheres", 0.0, ShadingMode::Phong},
     {"teapot", 0.0, ShadingMode::Flat}},
};

RenderOptions optionsFor(const Frame& f) {
    RenderOptions o;
    o.width = 64;
    o.height = 64;
    o.shading = f.shading;
    return o;
}

class TwoRenderers_ : public GpuTest {};

TEST_F(TwoRenderers_, RenderOnTwoThreadsAtOnceAsOneRendererAlone) {
    // The scenes, shared read-only by both threads (a Scene is a value; reading it from
    // several threads at once is allowed).
    std::vector<std::shared_ptr<const Scene>> scenes[2];
    for (int t = 0; t < 2; ++t)
        for (const Frame& f : kWork[t]) {
            auto s = builtinScene(f.scene);
            ASSERT_TRUE(s) << s.error().describe();
            scenes[t].push_back(std::make_shared<const Scene>(std::move(*s)));
        }

    // What one renderer renders alone, one frame after another.
    std::vector<Image> alone[2];
    for (int t = 0; t < 2; ++t)
        for (std::size_t i = 0; i < kWork[t].size(); ++i) {
            auto img = renderer().render(*scenes[t][i], optionsFor(kWork[t][i]), kWork[t][i].time);
            ASSERT_TRUE(img) << img.error().describe();
            alone[t].push_back(std::move(*img));
        }

    std::vector<Image> together[2];
    std::string failure[2];
    std::uint64_t messages[2] = {0, 0};
    std::latch created(2);
    auto work = [&](int t) {
        RendererDesc desc;
        desc.validation = true;
        desc.log = [t](LogLevel level, std::string_view message) {
            if (level >= LogLevel::Warning)
                std::cerr << "[renderer " << t << "] " << message << "\n";
        };
        auto r = Renderer::create(desc);
        created.count_down();
        if (!r) {
            failure[t] = r.error().describe();
            return;
        }
        created.wait();  // both renderers exist before either renders
        for (std::size_t i = 0; i < kWork[t].size(); ++i) {
            auto prepared = r->prepare(scenes[t][i]);
            if (!prepared) {
                failure[t] = prepared.error().describe();
                return;
            }
            auto img = r->render(*prepared, optionsFor(kWork[t][i]), kWork[t][i].time);
            if (!img) {
                failure[t] = img.error().describe();
                return;
            }
            together[t].push_back(std::move(*img));
        }
        messages[t] = r->validationMessageCount();
    };
    std::thread a(work, 0), b(work, 1);
    a.join();
    b.join();

    for (int t = 0; t < 2; ++t) {
        SCOPED_TRACE("thread " + std::to_string(t));
        ASSERT_TRUE(failure[t].empty()) << failure[t];
        EXPECT_EQ(messages[t], 0u) << "validation messages (see stderr)";
        ASSERT_EQ(together[t].size(), alone[t].size());
        for (std::size_t i = 0; i < alone[t].size(); ++i) {
            SCOPED_TRACE(std::string(kWork[t][i].scene) + " frame " + std::to_string(i));
            EXPECT_GT(test::countCovered(alone[t][i]), 0u) << "nothing drawn";
            EXPECT_EQ(together[t][i].rgba, alone[t][i].rgba)
                << test::saveComparison(together[t][i], alone[t][i],
                                        "thread" + std::to_string(t) + "-" + std::to_string(i));
        }
    }
}

} // namespace
