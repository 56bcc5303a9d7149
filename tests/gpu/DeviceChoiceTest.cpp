// Choosing the device: RendererDesc::deviceName and LANTERN_DEVICE, as an index into
// listDevices() or a name, the explicit choice winning; a choice that matches nothing is
// NoDevice listing the devices found; with no Vulkan driver at all, `lantern render` names the
// manifests the loader read and how to install lavapipe.
#include "TestSupport.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

namespace {

using namespace lantern;
using lantern::test::runLantern;

// Sets LANTERN_DEVICE for one scope and puts back what was there.
class ScopedDeviceEnv {
public:
    explicit ScopedDeviceEnv(const char* value) {
        if (const char* old = std::getenv("LANTERN_DEVICE")) m_old = old;
        if (value)
            setenv("LANTERN_DEVICE", value, 1);
        else
            unsetenv("LANTERN_DEVICE");
    }
    ~ScopedDeviceEnv() {
        if (m_old)
            setenv("LANTERN_DEVICE", m_old->c_str(), 1);
        else
            unsetenv("LANTERN_DEVICE");
    }

private:
    std::optional<std::string> m_old;
};

class DeviceChoice : public test::GpuTest {
protected:
    void SetUp() override {
        test::GpuTest::SetUp();
        if (IsSkipped()) return;
        auto list = listDevices();
        ASSERT_TRUE(list) << list.error().describe();
        ASSERT_FALSE(list->devices.empty());
        m_first = list->devices[0];
    }
    Result<Renderer> create(const std::string& deviceName = {}) {
        RendererDesc desc;
        desc.deviceName = deviceName;
        desc.pipelineCacheOnDisk = false;
        return Renderer::create(desc);
    }
    DeviceListing m_first;
};

TEST_F(DeviceChoice, AnIndexPicksThatDeviceOfTheList) {
    ASSERT_TRUE(m_first.usable) << m_first.whyNot;
    auto r = create("0");
    ASSERT_TRUE(r) << r.error().describe();
    EXPECT_EQ(r->device().name, m_first.name);
    ScopedDeviceEnv env("0");
    auto fromEnv = create();
    ASSERT_TRUE(fromEnv) << fromEnv.error().describe();
    EXPECT_EQ(fromEnv->device().name, m_first.name);
    auto list = listDevices();
    ASSERT_TRUE(list);
    EXPECT_TRUE(list->devices[0].chosen);
    EXPECT_NE(list->choice.find("as LANTERN_DEVICE=0 asks"), std::string::npos) << list->choice;
}

TEST_F(DeviceChoice, ANamePicksByCaseInsensitiveSubstring) {
    if (m_first.name.find("llvmpipe") == std::string::npos)
        GTEST_SKIP() << "the first device is not lavapipe: " << m_first.name;
    auto r = create("LLVMpipe");
    ASSERT_TRUE(r) << r.error().describe();
    EXPECT_EQ(r->device().name, m_first.name);
    ScopedDeviceEnv env("llvmpipe");
    auto fromEnv = create();
    ASSERT_TRUE(fromEnv) << fromEnv.error().describe();
    EXPECT_EQ(fromEnv->device().name, m_first.name);
}

TEST_F(DeviceChoice, ANameThatMatchesNothingListsTheDevicesFound) {
    ScopedDeviceEnv env("no-such-device");
    auto r = create();
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error().code, ErrorCode::NoDevice);
    const std::string text = r.error().describe();
    EXPECT_NE(text.find("LANTERN_DEVICE=no-such-device: no usable Vulkan device's name contains "
                        "\"no-such-device\""),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("[0] " + m_first.name + " (" + m_first.type + ")"), std::string::npos)
        << text;
    // The explicit name wins over the environment, and is named when it fails itself.
    auto explicitOne = create("0");
    ASSERT_TRUE(explicitOne) << explicitOne.error().describe();
    auto explicitBad = create("nothing-like-it");
    ASSERT_FALSE(explicitBad);
    EXPECT_NE(explicitBad.error().describe().find("device \"nothing-like-it\""),
              std::string::npos)
        << explicitBad.error().describe();
    auto list = listDevices();
    ASSERT_TRUE(list);
    for (const DeviceListing& d : list->devices)
        EXPECT_FALSE(d.chosen) << d.name;
    EXPECT_NE(list->choice.find("none: LANTERN_DEVICE=no-such-device"), std::string::npos)
        << list->choice;
}

TEST_F(DeviceChoice, AnIndexOutOfRangeListsTheDevicesFound) {
    auto r = create("99");
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error().code, ErrorCode::NoDevice);
    const std::string text = r.error().describe();
    EXPECT_NE(text.find("device \"99\": there is no device 99; the loader found"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("[0] " + m_first.name), std::string::npos) << text;
}

TEST_F(DeviceChoice, TheCommandLineFollowsLanternDeviceAndDeviceWins) {
    const auto out = test::testOutputDir();
    const std::vector<std::string> render = {"render", "builtin:spheres", "--width", "16",
                                             "--height", "16", "-o", (out / "a.png").string()};
    const auto bad = runLantern(render, {"LANTERN_DEVICE=no-such-device"});
    EXPECT_EQ(bad.exitCode, 3) << bad.err;
    EXPECT_NE(bad.err.find("LANTERN_DEVICE=no-such-device"), std::string::npos) << bad.err;
    EXPECT_NE(bad.err.find("[0] " + m_first.name), std::string::npos) << bad.err;
    EXPECT_FALSE(std::filesystem::exists(out / "a.png"));
    auto withDevice = render;
    withDevice.insert(withDevice.end(), {"--device", "0"});
    const auto good = runLantern(withDevice, {"LANTERN_DEVICE=no-such-device"});
    EXPECT_EQ(good.exitCode, 0) << good.err;
    const auto info = runLantern({"info", "--devices"}, {"LANTERN_DEVICE=0"});
    EXPECT_EQ(info.exitCode, 0) << info.err;
    EXPECT_NE(info.out.find("  * [0] " + m_first.name + "\n"), std::string::npos) << info.out;
}

// No driver at all (the loader pointed at a manifest that does not exist, or at an empty one):
// `lantern render` fails as a device failure (exit 3, docs/cli.md) with what the loader saw and
// how to install lavapipe and point the loader at it. Needs no device itself.
TEST(NoVulkanDriver, TheErrorNamesTheManifestsAndHowToInstallLavapipe) {
    const auto out = test::testOutputDir();
    const std::string empty = (out / "empty.json").string();
    std::ofstream(empty).flush();
    const std::vector<std::string> render = {"render", "builtin:spheres", "--width", "16",
                                             "--height", "16", "-o", (out / "a.exr").string()};
    for (const std::string variable : {"VK_DRIVER_FILES", "VK_ICD_FILENAMES"}) {
        for (const std::string& manifest : {std::string("/nonexistent/none.json"), empty}) {
            const std::vector<std::string> env = {variable + "=" + manifest,
                                                  variable == "VK_DRIVER_FILES"
                                                      ? "VK_ICD_FILENAMES="
                                                      : "VK_DRIVER_FILES="};
            const auto r = runLantern(render, env);
            const std::string what = variable + "=" + manifest + ": " + r.err;
            EXPECT_EQ(r.exitCode, 3) << what;
            EXPECT_NE(r.err.find("no Vulkan device found"), std::string::npos) << what;
            EXPECT_NE(r.err.find(variable + "=" + manifest + " (the loader reads only these)"),
                      std::string::npos)
                << what;
            if (manifest != empty) {
                EXPECT_NE(r.err.find(manifest + " does not exist"), std::string::npos) << what;
            }
            EXPECT_NE(r.err.find("apt install mesa-vulkan-drivers"), std::string::npos) << what;
            EXPECT_NE(r.err.find("VK_DRIVER_FILES=/usr/share/vulkan/icd.d/lvp_icd."),
                      std::string::npos)
                << what;
            EXPECT_FALSE(std::filesystem::exists(out / "a.exr")) << what;
        }
    }
}

} // namespace
