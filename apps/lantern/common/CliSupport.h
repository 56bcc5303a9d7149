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

/// Exit statuses of the command line (docs/cli.md).
enum Exit : int { kOk = 0, kRefused = 1, kUsage = 2, kFailed = 3 };

/// The descriptions of the options several subcommands share, so that the same name means the
/// same thing everywhere (CliNames.* in tests/robustness/CliReferenceTest.cpp checks it).
namespace help {
inline constexpr const char* kWidth = "Width in pixels (1 to 16384)";
inline constexpr const char* kHeight = "Height in pixels (1 to 16384)";
inline constexpr const char* kWidthList =
    "Widths in pixels, comma-separated (paired with --height by position; 1 to 16384)";
inline constexpr const char* kHeightList =
    "Heights in pixels, comma-separated (paired with --width by position; 1 to 16384)";
inline constexpr const char* kShading = "Where lighting is evaluated: flat, gouraud or phong";
inline constexpr const char* kShadingList = "Shading modes, comma-separated: flat, gouraud, phong";
inline constexpr const char* kSpecular = "Specular term: blinn or phong";
inline constexpr const char* kMsaa =
    "Samples per pixel: 1, 2, 4 or 8, as the device supports (lantern info --devices)";
inline constexpr const char* kMsaaList =
    "Samples per pixel, comma-separated: 1, 2, 4, 8 (those the device lacks are left out)";
inline constexpr const char* kBackground =
    "Background colour R,G,B (opaque) or R,G,B,A, linear (default 0,0,0: opaque black; "
    "0,0,0,0 for a transparent background)";
} // namespace help

/// Adds --width and --height (one size) with the shared descriptions; returns both options
/// for the caller's checks.
std::pair<CLI::Option*, CLI::Option*> addSizeOptions(CLI::App& app, int& width, int& height);
/// Adds --width and --height as comma-separated lists, paired by position.
void addSizeListOptions(CLI::App& app, std::vector<int>& widths, std::vector<int>& heights);
/// Pairs the --width and --height lists by position (a single value on one side goes with every
/// value of the other); InvalidInput naming the option for an empty list, a size outside
/// 1..16384 or lists of different lengths.
Result<std::vector<std::pair<int, int>>> pairSizes(const std::vector<int>& widths,
                                                   const std::vector<int>& heights);

/// Creates the folders the output files will go to (the frame number `frame` fills the '#'
/// runs of their names): IoError naming `option` when one cannot be made.
Result<void> makeParentFolders(const std::vector<std::string>& paths, int frame,
                               const std::string& option);

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
/// --variant NAME: the KHR_materials_variants variant whose materials the scene is drawn with.
void addVariantOption(CLI::App& app, std::string& variant);
/// --allow-folder DIR (repeatable): LoadOptions::allowedFolders.
void addAllowFolderOption(CLI::App& app, std::vector<std::string>& folders);
/// --up y|z: LoadOptions::up, the file's up axis (z: +Z becomes +Y).
void addUpOption(CLI::App& app, std::string& up);

/// How a scene file is read, as render, view and info take it: --max-size, --variant,
/// --allow-folder, --up.
struct SceneFileOptions {
    std::uint64_t maxSize = kDefaultMaxBytes;
    std::string variant;  ///< KHR_materials_variants; empty: the file's own materials
    std::vector<std::string> allowFolders;
    std::string up = "y";

    void add(CLI::App& app);
    /// The LoadOptions they say, with warnings going to `log`.
    LoadOptions load(LogSink log) const;
};

/// The --up value as LoadOptions::up (the option's check admits only y and z).
UpAxis upAxisOf(const std::string& up);

/// The camera and view options shared by render and view.
struct CameraOptions {
    std::vector<int> cameras; ///< --camera N (repeatable: one per --viewport)
    std::vector<std::string> cameraFiles;  ///< --camera FILE (a value that is not an index)
    bool defaultCamera = false;
    std::string lookAt, perspective, ortho, frustum;
    std::string intrinsics, worldToCamera, cameraToWorld;  ///< common/CvCameraCli.h
    std::vector<std::string> viewports;
    std::string layout;
    std::string depth; ///< --depth reversed|standard (default: reversed)
    std::string view;  ///< --view NAME: automatic framing from a named view

    void add(CLI::App& app);
    /// Fills options.camera / options.views; refuses bad values with the option named.
    Result<void> apply(RenderOptions& options) const;

private:
    /// --look-at and the projection options into `spec`.
    Result<void> applyOverrides(CameraSpec& spec) const;
    /// --camera FILE, --intrinsics, --world-to-camera, --camera-to-world into `spec`.
    Result<void> applyCvCamera(const RenderOptions& o, CameraSpec& spec) const;
};

/// The four views of --layout quad for a width x height image: top, front and side
/// (orthographic framing) and `perspective` in the bottom-right quarter.
std::vector<View> quadLayout(int width, int height, const CameraSpec& perspective);

/// The lighting/shading options shared by render and view.
struct ShadingOptions {
    std::string shading, specular;
    bool localViewer = false, twoSided = false, clamp = false, glCompat = false;
    bool noInstancing = false, noCulling = false;
    double lodError = 0.0;
    bool shadows = false;
    int shadowResolution = 2048, shadowKernel = 3, shadowCascades = 2;
    std::string shadowFilter = "pcf";
    std::string transparency;  ///< empty: exact (sorted under --gl-compat)
    double shadowBias = 2.0, shadowNormalOffset = 1.5;
    double shadowLightRadius = 0.05, shadowSunRadius = 0.5;
    int msaa = 1;
    double pointSize = 1.0, lineWidth = 1.0;

    void add(CLI::App& app);
    Result<void> apply(RenderOptions& options) const;
    /// Refuses (Usage, exit 2) a --msaa value the device does not support, naming the values it
    /// does; checked before anything is rendered.
    Result<void> checkDevice(const DeviceInfo& device) const;
};

/// "hardware", "pcf" or "pcss" (checked by the option) as the filter, and back.
ShadowFilter parseShadowFilter(const std::string& text);
const char* shadowFilterName(ShadowFilter filter);

/// "sorted", "exact" or "weighted" (checked by the option) as the method, and back.
TransparencyMethod parseTransparencyMethod(const std::string& text);
const char* transparencyName(TransparencyMethod method);

/// Refuses (Usage) a sample count the device lacks: "--msaa 8: DEVICE supports 1, 4".
Result<void> checkMsaa(int msaa, const DeviceInfo& device);

/// The device options shared by every subcommand that renders.
struct DeviceOptions {
    std::string device;
    bool validation = false;
    bool verbose = false;

    void add(CLI::App& app);
    RendererDesc desc() const; ///< validation also on when LANTERN_VALIDATION=1
};

/// Makes the first SIGINT or SIGTERM a request to stop (stopSignal() then returns it) rather
/// than the end of the process; the handler resets itself, so a second one ends the process
/// at once. Sequences, batches and the viewer stop cleanly between frames or jobs.
void installStopHandlers();
/// This process's arguments as it was started (/proc/self/cmdline), argv[0] first.
std::vector<std::string> processArguments();
/// The signal that asked to stop since installStopHandlers() (0: none).
int stopSignal();

} // namespace lantern::cli
