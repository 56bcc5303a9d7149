// `lantern view`'s command line without a window: its help, and the refusals that come before
// any window is opened (exit 2 usage, 1 refused, 3 no display).
#include "TestSupport.h"

#include <gtest/gtest.h>

namespace {

using lantern::test::runLantern;

TEST(ViewCli, HelpListsTheViewerOptions) {
    const auto r = runLantern({"view", "--help"});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    for (const char* option : {"--present-mode", "--frames-in-flight", "--watch", "--screenshot",
                               "--after-frames", "--screenshot-dir", "--no-panel", "--layout",
                               "--shading", "--headlight", "--wireframe", "--normals", "--stats"})
        EXPECT_NE(r.out.find(option), std::string::npos) << option;
    const auto top = runLantern({"--help"});
    EXPECT_NE(top.out.find("view"), std::string::npos);
}

struct Refusal {
    std::vector<std::string> args;
    int exitCode;
    const char* mentions;
    const char* why;
};

TEST(ViewCli, RefusesBadOptionsBeforeOpeningAWindow) {
    const Refusal rows[] = {
        {{"builtin:spheres", "--screenshot", "x.exr"}, 2, "--after-frames", "a screenshot needs a frame count"},
        {{"builtin:spheres", "--after-frames", "2", "--screenshot", "x.tif"}, 1, ".tif", "EXR or PNG only"},
        {{"builtin:spheres", "--present-mode", "vsync"}, 1, "vsync", "an unknown present mode"},
        {{"builtin:spheres", "--viewport", "0,0,10,10"}, 2, "--layout quad", "views follow the window"},
        {{"builtin:nothing"}, 1, "nothing", "an unknown scene"},
        {{"builtin:spheres", "--scene", "-4"}, 1, "--scene", "a glTF scene index that does not exist"},
        {{"builtin:spheres", "--camera", "3"}, 1, "camera 3", "a scene camera that does not exist"},
        {{"builtin:spheres", "--look-at", "0,0,0,0,0,0,0,1,0"}, 1, "--look-at", "eye == target"},
        {{"builtin:spheres", "--frames-in-flight", "9"}, 1, "frames-in-flight", "1 to 4 frames in flight"},
    };
    for (const Refusal& row : rows) {
        SCOPED_TRACE(row.why);
        std::vector<std::string> args{"view"};
        args.insert(args.end(), row.args.begin(), row.args.end());
        const auto r = runLantern(args, {"DISPLAY="});
        EXPECT_EQ(r.exitCode, row.exitCode) << r.err;
        EXPECT_NE(r.err.find(row.mentions), std::string::npos) << r.err;
    }
}

TEST(ViewCli, NoDisplayIsARendererFailure) {
    const auto r = runLantern({"view", "builtin:spheres"}, {"DISPLAY=", "WAYLAND_DISPLAY="});
    EXPECT_EQ(r.exitCode, 3) << r.err;
    EXPECT_NE(r.err.find("cannot open a window"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("DISPLAY"), std::string::npos) << r.err;
}

} // namespace
