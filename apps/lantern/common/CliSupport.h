// CliSupport.h: shared pieces of the `lantern` subcommands: the stderr log sink, exit codes,
// number-list parsing and the camera/view options (--look-at, --perspective, --viewport,
// --depth...). Uses only Lantern's public API.
#pragma once

#include <CLI/CLI.hpp>
#include <lantern/Lantern.h>
#include <optional>
#include <string>
#include <vector>

namespace lantern::cli {

/// Exit statuses of the command line (spec/cli.md).
enum Exit : int { kOk = 0, kRefused = 1, kUsage = 2, kFailed = 3 };

/// Prints an error as "lantern: error: <file>: <object>: <message>" and returns its exit code.
int report(const Error& error);

/// A sink printing warnings and errors (and info with verbose) to stderr.
LogSink stderrSink(bool verbose);

/// Parses "a,b,c" into exactly `count` numbers; "inf" is allowed only where `allowInf` says.
Result<std::vector<double>> parseNumbers(const std::string& text, std::size_t count,
                                         const std::string& option,
                                         const std::vector<bool>& allowInf = {});

/// Refuses output paths whose extension is neither .exr nor .png (`option` names the option).
Result<void> checkImagePaths(const std::vector<std::string>& paths, const std::string& option);

/// Parses --background: "R,G,B" (opaque) or "R,G,B,A", linear, into a premultiplied colour.
Result<glm::vec4> parseBackground(const std::string& text);

/// The largest --max-size (64 GiB): the bound is a number of bytes, and -1 must not wrap around
/// to 2^64 - 1.
inline constexpr std::uint64_t kMaxMaxSize = std::uint64_t(1) << 36;

/// --max-size BYTES (1 to kMaxMaxSize): the largest file, buffer or image accepted and the most
/// one scene may make Lantern decode (accessors, images) in all.
void addMaxSizeOption(CLI::App& app, std::uint64_t& maxSize);

/// The camera and view options shared by render and view.
struct CameraOptions {
    std::vector<int> cameras; ///< --camera N (repeatable: one per --viewport)
    bool defaultCamera = false;
    std::string lookAt, perspective, ortho, frustum;
    std::vector<std::string> viewports;
    std::string layout;
    std::string depth; ///< --depth reversed|standard (default: reversed)
    std::string view;  ///< --view NAME: automatic framing from a named view

    void add(CLI::App& app);
    /// Fills options.camera / options.views; refuses bad values with the option named.
    Result<void> apply(RenderOptions& options) const;
};

/// The four views of --layout quad for a width x height image: top, front and side
/// (orthographic framing) and `perspective` in the bottom-right quarter.
std::vector<View> quadLayout(int width, int height, const CameraSpec& perspective);

/// The lighting/shading options shared by render and view.
struct ShadingOptions {
    std::string shading, specular;
    bool localViewer = false, twoSided = false, clamp = false, glCompat = false;
    int msaa = 1;

    void add(CLI::App& app);
    Result<void> apply(RenderOptions& options) const;
};

/// The device options shared by every subcommand that renders.
struct DeviceOptions {
    std::string device;
    bool validation = false;
    bool verbose = false;

    void add(CLI::App& app);
    RendererDesc desc() const; ///< validation also on when LANTERN_VALIDATION=1
};

} // namespace lantern::cli
