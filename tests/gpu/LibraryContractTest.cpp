// What docs/library.md promises a host: Lantern prints nothing of its own when no log sink is
// given (failures included: they come back as errors), and a prepared scene belongs to the
// renderer that prepared it (another renderer refuses it instead of touching a foreign device).
#include "TestSupport.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>

namespace {

using namespace lantern;
using lantern::test::GpuTest;

class LibraryContract_ : public GpuTest {};

TEST_F(LibraryContract_, PrintsNothingWithoutALogSink) {
    const auto dir = test::testOutputDir();
    ::testing::internal::CaptureStdout();
    ::testing::internal::CaptureStderr();
    std::string failures;
    {
        RendererDesc desc;  // no log sink
        desc.validation = true;
        auto r = Renderer::create(desc);
        if (!r) failures += "create: " + r.error().describe() + "\n";
        auto scene = builtinScene("spheres-animated");
        if (r && scene) {
            RenderOptions o;
            o.width = 64;
            o.height = 48;
            o.aovs.depth = true;
            if (auto img = r->render(*scene, o, 0.5); !img)
                failures += "render: " + img.error().describe() + "\n";
            else if (auto w = writeExr(dir / "frame.exr", *img); !w)
                failures += "writeExr: " + w.error().describe() + "\n";
            o.msaa = 3;  // refused
            if (r->render(*scene, o, 0.0)) failures += "msaa 3 was accepted\n";
        }
        // Failures of every kind: they must come back as errors, not as output.
        if (loadScene((dir / "missing.gltf").string())) failures += "a missing file loaded\n";
        if (builtinScene("no-such-scene")) failures += "an unknown built-in loaded\n";
        if (loadScene((test::sharedDir() / "assets/gltf-invalid").string()))
            failures += "a folder loaded\n";
        if (auto w = writeImage(dir / "frame.tiff", Image(4, 4)); w)
            failures += "a .tiff was written\n";
    }
    const std::string out = ::testing::internal::GetCapturedStdout();
    const std::string err = ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(failures, "");
    EXPECT_EQ(out, "") << "Lantern printed to stdout";
    EXPECT_EQ(err, "") << "Lantern printed to stderr";
}

TEST_F(LibraryContract_, RefusesASceneAnotherRendererPrepared) {
    auto scene = builtinScene("spheres");
    ASSERT_TRUE(scene);
    auto prepared = renderer().prepare(std::make_shared<const Scene>(std::move(*scene)));
    ASSERT_TRUE(prepared) << prepared.error().describe();
    auto other = Renderer::create(RendererDesc{});
    ASSERT_TRUE(other) << other.error().describe();
    RenderOptions o;
    o.width = 32;
    o.height = 32;
    auto img = other->render(*prepared, o, 0.0);
    ASSERT_FALSE(img) << "a scene prepared on another device was drawn";
    EXPECT_EQ(img.error().code, ErrorCode::Usage);
    EXPECT_NE(img.error().message.find("another Renderer"), std::string::npos)
        << img.error().describe();
    // Its own renderer still draws it.
    EXPECT_TRUE(renderer().render(*prepared, o, 0.0));
}

} // namespace
