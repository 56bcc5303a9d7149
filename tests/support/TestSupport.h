// TestSupport.h: what every Lantern test shares: paths (source tree, ../shared, build tree),
// a renderer on the test machine's device with validation on (GPU tests skip without one and
// fail on any validation message), checks for what a plain machine may lack (a test skips,
// naming it, rather than fails), running the `lantern` command, and image comparison that
// writes actual/expected/diff images on failure.
#pragma once

#include "gpu/Device.h"

#include <lantern/Lantern.h>

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace lantern::test {

/// True in an AddressSanitizer build (LANTERN_ASAN: cmake/LanternSanitizers.cmake).
#if defined(LANTERN_ASAN)
inline constexpr bool kAddressSanitizer = true;
#else
inline constexpr bool kAddressSanitizer = false;
#endif

std::filesystem::path sourceDir();   ///< the checkout
std::filesystem::path sharedDir();   ///< ../shared beside the checkout (test assets)
std::filesystem::path binaryDir();   ///< the build tree
std::filesystem::path cliPath();     ///< the built `lantern` executable
/// A fresh, empty folder for this test under the build tree (tests/output/<suite>.<test>).
std::filesystem::path testOutputDir();

/// The process-wide renderer for GPU tests (validation on), or nullptr when no Vulkan device
/// exists (the reason is in noDeviceReason()).
Renderer* sharedRenderer();
std::string noDeviceReason();
/// The engine's own gpu::Device (validation on) for tests that look inside the renderer
/// (frames, draw lists, pixel ids); made on first use; nullptr without a Vulkan device.
gpu::Device* sharedDevice();

/// Base fixture for tests that render: skips (reported as skipped) without a device and
/// fails the test if the validation layer reported anything during it.
class GpuTest : public ::testing::Test {
protected:
    void SetUp() override;
    void TearDown() override;
    Renderer& renderer() { return *m_renderer; }
    /// sharedDevice(); its validation messages fail the test too.
    gpu::Device& device();

private:
    Renderer* m_renderer = nullptr;
    std::uint64_t m_validationBefore = 0;
};

/// What a test needs from the machine that a plain one (a chroot, a container, a user's CI)
/// may lack. Each returns why a test must skip, naming what is missing and how to get it, or
/// an empty string when it is there. A test checks first, with LANTERN_SKIP_IF_MISSING, so that
/// a missing tool or privilege is reported as a skip with its reason, never as a failure.
/// `environment` entries are added for the probe's processes (tests of the probes use it).
///
/// An executable on $PATH (`debianPackage` installs it).
std::string missingProgram(const std::string& program, const std::string& debianPackage);

/// The path of the executable `program` in a folder of PATH, or empty.
std::string findOnPath(const std::string& program);
/// A Vulkan device (for tests that render through the `lantern` command or a window; GpuTest
/// fixtures check it themselves). Creates sharedRenderer() once per process.
std::string missingVulkanDevice();
/// {"--validation"} for a `lantern` command line when VK_LAYER_KHRONOS_validation is
/// installed; otherwise nothing, and a note on stderr (the command would warn that the layer
/// is missing, and tests check that it prints nothing about validation). As in GpuTest, a
/// missing layer means validation is not checked, not that the test fails or skips.
std::vector<std::string> validationFlag();
/// An unprivileged user namespace in which a tmpfs can be mounted (`unshare -rm`): Linux
/// refuses one inside a chroot, and Docker's default seccomp profile inside a container.
std::string missingUserNamespaceMount(const std::vector<std::string>& environment = {});

/// Skips the current test, with `reason` as the message, unless `reason` is empty.
#define LANTERN_SKIP_IF_MISSING(reason)                                                            \
    do {                                                                                           \
        if (const std::string lanternSkipReason_ = (reason); !lanternSkipReason_.empty())          \
            GTEST_SKIP() << lanternSkipReason_;                                                    \
    } while (false)

/// The result of running a command.
struct ProcessResult {
    int exitCode = -1;
    std::string out, err;
};
/// Runs `args` (argv[0] is the program) with extra environment entries; never throws.
ProcessResult runProcess(const std::vector<std::string>& args,
                         const std::vector<std::string>& environment = {},
                         double timeoutSeconds = 300.0);
/// Runs the `lantern` command with `args`.
ProcessResult runLantern(const std::vector<std::string>& args,
                         const std::vector<std::string>& environment = {});

/// The largest difference between two images' colour values (infinity when their sizes differ).
float maxAbsDifference(const Image& a, const Image& b);

/// In a forked child: adds `environment`, executes `args` (argv[0] searched on $PATH) and, if
/// that fails, reports it on stderr and exits with 127.
[[noreturn]] void execChild(const std::vector<std::string>& args,
                            const std::vector<std::string>& environment);

/// Number of NaN/Inf values in the image's colour and AOV planes.
std::size_t countNonFinite(const Image& image);
/// Pixels whose alpha is above `threshold`.
std::size_t countCovered(const Image& image, float threshold = 0.5f);

/// Writes actual, expected and a per-pixel |difference| image as EXRs into testOutputDir()
/// and returns a line naming them (for failure messages).
std::string saveComparison(const Image& actual, const Image& expected, const std::string& name);

/// A one-mesh scene: `primitive` with `material` at the origin, lit by `lights` (each placed
/// by its own node with the given world transform), seen by `camera` through `viewFromWorld`.
struct SimpleScene {
    Primitive primitive;
    Material material;
    std::vector<std::pair<Light, glm::dmat4>> lights;
    Projection projection = Projection::makePerspective(0.6981317007977318, 0.0, 0.1, kInfinity);
    LookAt lookAt{{0, 0, 4}, {0, 0, 0}, {0, 1, 0}};
    glm::dmat4 model{1.0};
    LightingModel lighting;
    Scene build() const;
};

} // namespace lantern::test
