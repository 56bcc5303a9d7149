// Shared command-line pieces: error reporting, number lists, camera/shading/device options.
#include "common/CliSupport.h"
#include "common/CvCameraCli.h"

#include <algorithm>
#include <atomic>
#include <csignal>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <limits>
#include <mutex>
#include <sstream>

namespace lantern::cli {

int report(const Error& error) {
    std::cerr << "lantern: error: " << error.describe() << "\n";
    return exitCodeFor(error.code);
}

LogSink stderrSink(bool verbose) {
    auto mutex = std::make_shared<std::mutex>();
    return [verbose, mutex](LogLevel level, std::string_view message) {
        if (level == LogLevel::Debug || (level == LogLevel::Info && !verbose)) return;
        std::lock_guard lock(*mutex);
        std::cerr << "lantern: " << logLevelName(level) << ": " << message << "\n";
    };
}

Result<std::vector<double>> parseNumbers(const std::string& text, std::size_t count,
                                         const std::string& option,
                                         const std::vector<bool>& allowInf) {
    std::vector<double> values;
    std::stringstream ss(text);
    std::string item;
    while (std::getline(ss, item, ',')) {
        const std::size_t i = values.size();
        const bool infOk = i < allowInf.size() && allowInf[i];
        if (item == "inf" || item == "+inf" || item == "infinity") {
            if (!infOk)
                return makeError(ErrorCode::InvalidInput,
                                 "value " + std::to_string(i + 1) + " must be finite", option);
            values.push_back(kInfinity);
            continue;
        }
        char* end = nullptr;
        const double v = std::strtod(item.c_str(), &end);
        if (item.empty() || end != item.c_str() + item.size())
            return makeError(ErrorCode::InvalidInput, "\"" + item + "\" is not a number", option);
        if (!std::isfinite(v))
            return makeError(ErrorCode::InvalidInput,
                             "value " + std::to_string(i + 1) + " (" + item + ") is not finite",
                             option);
        values.push_back(v);
    }
    if (values.size() != count)
        return makeError(ErrorCode::InvalidInput,
                         "expected " + std::to_string(count) + " comma-separated numbers, got " +
                             std::to_string(values.size()),
                         option);
    return values;
}

Result<void> checkImagePaths(const std::vector<std::string>& paths, const std::string& option) {
    for (const std::string& out : paths) {
        const std::string ext = std::filesystem::path(out).extension().string();
        if (ext != ".exr" && ext != ".png")
            return makeError(ErrorCode::InvalidInput,
                             "unknown image type \"" + ext + "\" (use .exr or .png)", option, out);
    }
    return {};
}

namespace {

std::string shortNumber(double v) {
    std::ostringstream os;
    os << v;
    return os.str();
}

} // namespace

Result<glm::vec4> parseBackground(const std::string& text) {
    const bool rgba = std::count(text.begin(), text.end(), ',') == 3;
    auto v = parseNumbers(text, rgba ? 4 : 3, "--background");
    if (!v) return std::move(v).error();
    // The picture is float: 1e39 is finite as a double and infinite as a float.
    for (std::size_t i = 0; i < v->size(); ++i)
        if (std::abs((*v)[i]) > double(std::numeric_limits<float>::max()))
            return makeError(ErrorCode::InvalidInput,
                             "value " + std::to_string(i + 1) + " (" + shortNumber((*v)[i]) +
                                 ") is beyond the float range (+-3.4e38)",
                             "--background");
    // Premultiplied: an opaque background is (r, g, b, 1); a translucent one scales rgb.
    const double alpha = rgba ? (*v)[3] : 1.0;
    if (alpha < 0.0 || alpha > 1.0)
        return makeError(ErrorCode::InvalidInput, "alpha must be in [0, 1]", "--background");
    return glm::vec4(float((*v)[0] * alpha), float((*v)[1] * alpha), float((*v)[2] * alpha),
                     float(alpha));
}

void CameraOptions::add(CLI::App& app) {
    app.add_option_function<std::vector<std::string>>(
        "--camera",
        [this](const std::vector<std::string>& values) {
            for (const std::string& v : values)
                if (isCameraIndex(v))
                    cameras.push_back(cameraIndex(v));
                else
                    cameraFiles.push_back(v);
        },
        "Use the scene's camera N (glTF index; repeat once per --viewport), or the camera of a "
        "JSON file: intrinsics K, pose, size (docs/cameras.md)");
    app.add_option("--intrinsics", intrinsics,
                   "OpenCV intrinsics in pixels, pixel centres at integers: FX,FY,CX,CY[,NEAR,FAR] "
                   "(FAR may be inf)");
    app.add_option("--world-to-camera", worldToCamera,
                   "Pose as OpenCV's world-to-camera [R|t] (x right, y down, z forward): 16 "
                   "numbers, row-major");
    app.add_option("--camera-to-world", cameraToWorld,
                   "Pose as a glTF camera node's world matrix (x right, y up, looking down -z): 16 "
                   "numbers, row-major");
    app.add_flag("--default-camera", defaultCamera,
                 "The GL default camera: origin, looking down -Z, orthographic 2x2x2 cube");
    std::vector<std::string> views;
    for (ViewDirection v : kViewDirections) views.emplace_back(toString(v));
    app.add_option("--view", view,
                   "Frame the scene from a named view instead of the scene's camera: "
                   "three-quarter (the automatic default: front right, 30 degrees above), front, "
                   "back, left, right, top, bottom, iso")
        ->check(CLI::IsMember(views));
    app.add_option("--look-at", lookAt,
                   "Place the camera as gluLookAt: EX,EY,EZ,TX,TY,TZ,UX,UY,UZ");
    app.add_option("--perspective", perspective,
                   "Projection as gluPerspective: FOVY_DEG,ASPECT,NEAR,FAR (FAR may be inf)");
    app.add_option("--ortho", ortho, "Projection as glOrtho: L,R,B,T,N,F");
    app.add_option("--frustum", frustum, "Projection as glFrustum: L,R,B,T,N,F (F may be inf)");
    app.add_option("--viewport", viewports,
                   "Draw into X,Y,W,H (pixels, origin bottom-left as glViewport); repeatable");
    app.add_option("--layout", layout,
                   "quad: top, front, side (orthographic) and the perspective camera")
        ->check(CLI::IsMember({"quad"}));
    app.add_option("--depth", depth,
                   "Depth scheme with the float depth buffer: reversed (near at 1, the default: "
                   "uniform relative precision) or standard (near at 0)")
        ->check(CLI::IsMember({"reversed", "standard"}));
}

Result<void> CameraOptions::applyOverrides(CameraSpec& spec) const {
    if (!lookAt.empty()) {
        auto v = parseNumbers(lookAt, 9, "--look-at");
        if (!v) return std::move(v).error();
        const auto& n = *v;
        // As in scene files: beyond 1e30 the camera's matrices (the EXR header's worldToCamera,
        // worldToNDC) would overflow float on the way to an image.
        for (std::size_t i = 0; i < n.size(); ++i)
            if (std::abs(n[i]) > 1e30)
                return makeError(ErrorCode::InvalidInput,
                                 "value " + std::to_string(i + 1) + " (" + shortNumber(n[i]) +
                                     ") is beyond +-1e30, where the camera's matrices would "
                                     "overflow",
                                 "--look-at");
        LookAt la{{n[0], n[1], n[2]}, {n[3], n[4], n[5]}, {n[6], n[7], n[8]}};
        LANTERN_TRY(checkLookAt(la, "--look-at"));
        spec.lookAt = la;
    }
    if (!perspective.empty()) {
        auto v = parseNumbers(perspective, 4, "--perspective", {false, false, false, true});
        if (!v) return std::move(v).error();
        const auto& n = *v;
        if (!(n[1] > 0.0))
            return makeError(ErrorCode::InvalidInput, "aspect must be > 0", "--perspective");
        Projection p =
            Projection::makePerspective(n[0] * 3.14159265358979323846 / 180.0, n[1], n[2], n[3]);
        LANTERN_TRY(checkProjection(p, "--perspective"));
        spec.projection = p;
    }
    if (!ortho.empty()) {
        auto v = parseNumbers(ortho, 6, "--ortho");
        if (!v) return std::move(v).error();
        const auto& n = *v;
        Projection p = Projection::makeOrtho(n[0], n[1], n[2], n[3], n[4], n[5]);
        LANTERN_TRY(checkProjection(p, "--ortho"));
        spec.projection = p;
    }
    if (!frustum.empty()) {
        auto v = parseNumbers(frustum, 6, "--frustum", {false, false, false, false, false, true});
        if (!v) return std::move(v).error();
        const auto& n = *v;
        Projection p = Projection::makeFrustum(n[0], n[1], n[2], n[3], n[4], n[5]);
        LANTERN_TRY(checkProjection(p, "--frustum"));
        spec.projection = p;
    }
    return {};
}

Result<void> CameraOptions::apply(RenderOptions& o) const {
    const int projections = !perspective.empty() + !ortho.empty() + !frustum.empty();
    if (projections > 1)
        return makeError(ErrorCode::Usage,
                         "give at most one of --perspective, --ortho and --frustum",
                         "--perspective/--ortho/--frustum");
    if (defaultCamera && !cameras.empty())
        return makeError(ErrorCode::Usage, "give either --camera or --default-camera", "--camera");
    if (!depth.empty()) o.depth = *parseDepthMode(depth); // CLI11 checked the spelling
    if (!view.empty() && (defaultCamera || !cameras.empty()))
        return makeError(ErrorCode::Usage,
                         "--view frames the scene automatically: it cannot be combined with " +
                             std::string(defaultCamera ? "--default-camera" : "--camera"),
                         "--view");
    CameraSpec spec;
    if (defaultCamera) spec.source = CameraSpec::Source::GlDefault;
    if (!view.empty()) spec = CameraSpec::framed(*parseViewDirection(view)); // CLI11 checked it
    LANTERN_TRY(applyOverrides(spec));
    LANTERN_TRY(applyCvCamera(o, spec));
    if (!layout.empty() && !viewports.empty())
        return makeError(ErrorCode::Usage, "--layout and --viewport cannot be combined",
                         "--layout");
    if (cameras.size() > 1 && cameras.size() != viewports.size())
        return makeError(ErrorCode::Usage,
                         "give one --camera, or one per --viewport (" +
                             std::to_string(viewports.size()) + " viewports, " +
                             std::to_string(cameras.size()) + " cameras)",
                         "--camera");
    auto withCamera = [&](CameraSpec s, std::size_t i) {
        if (!cameras.empty()) {
            s.source = CameraSpec::Source::SceneCamera;
            s.sceneCamera = cameras[cameras.size() == 1 ? 0 : i];
        }
        return s;
    };
    o.camera = withCamera(spec, 0);
    o.views.clear();
    for (std::size_t i = 0; i < viewports.size(); ++i) {
        auto v = parseNumbers(viewports[i], 4, "--viewport");
        if (!v) return std::move(v).error();
        const auto& n = *v;
        for (double x : n)
            if (x != std::floor(x) || x < 0 || x > 1e6)
                return makeError(ErrorCode::InvalidInput,
                                 "viewport values must be whole pixels >= 0", "--viewport");
        o.views.push_back(View{int(n[0]), int(n[1]), int(n[2]), int(n[3]), withCamera(spec, i)});
    }
    if (layout == "quad") o.views = quadLayout(o.width, o.height, o.camera);
    return {};
}

Result<void> CameraOptions::applyCvCamera(const RenderOptions& o, CameraSpec& spec) const {
    const bool file = !cameraFiles.empty();
    if (cameraFiles.size() > 1 || (file && !cameras.empty()))
        return makeError(ErrorCode::Usage, "give one camera file, without scene camera indices",
                         "--camera");
    if (!worldToCamera.empty() && !cameraToWorld.empty())
        return makeError(ErrorCode::Usage, "give either --world-to-camera or --camera-to-world",
                         "--world-to-camera");
    const char* conflict = !lookAt.empty() ? "--look-at" : defaultCamera ? "--default-camera"
                           : !view.empty() ? "--view" : !perspective.empty() ? "--perspective"
                           : !ortho.empty() ? "--ortho" : !frustum.empty() ? "--frustum"
                           : !intrinsics.empty() ? "--intrinsics"
                           : !worldToCamera.empty() ? "--world-to-camera"
                           : !cameraToWorld.empty() ? "--camera-to-world" : nullptr;
    if (file && conflict)
        return makeError(ErrorCode::Usage,
                         std::string("a camera file sets the whole camera: leave out ") + conflict,
                         "--camera");
    if (!intrinsics.empty() && (!perspective.empty() || !ortho.empty() || !frustum.empty()))
        return makeError(ErrorCode::Usage,
                         "--intrinsics is the projection: leave out --perspective, --ortho and "
                         "--frustum",
                         "--intrinsics");
    if ((!worldToCamera.empty() || !cameraToWorld.empty()) && !lookAt.empty())
        return makeError(ErrorCode::Usage, "a pose places the camera: leave out --look-at",
                         !worldToCamera.empty() ? "--world-to-camera" : "--camera-to-world");
    const bool whole = file || !intrinsics.empty();
    if (whole && (!viewports.empty() || !layout.empty()))
        return makeError(ErrorCode::Usage,
                         "intrinsics describe the whole image: not with --viewport or --layout",
                         file ? "--camera" : "--intrinsics");
    if (file) LANTERN_TRY(applyCameraFile(cameraFiles.front(), spec));
    if (!intrinsics.empty()) LANTERN_TRY(applyIntrinsics(intrinsics, o.width, o.height, spec));
    if (!worldToCamera.empty())
        LANTERN_TRY(applyPose(worldToCamera, PoseConvention::OpenCV, "--world-to-camera", spec));
    if (!cameraToWorld.empty())
        LANTERN_TRY(applyPose(cameraToWorld, PoseConvention::Gltf, "--camera-to-world", spec));
    return {};
}

std::vector<View> quadLayout(int width, int height, const CameraSpec& perspective) {
    // A classic modeller's four views (GL origin bottom-left): top view top-left, front
    // top-right, side bottom-left, the perspective camera bottom-right.
    const int w = width / 2, h = height / 2;
    auto orthoView = [](ViewDirection view) { return CameraSpec::framed(view, true); };
    return {
        View{0, height - h, w, h, orthoView(ViewDirection::Top)},
        View{w, height - h, width - w, h, orthoView(ViewDirection::Front)},
        View{0, 0, w, height - h, orthoView(ViewDirection::Right)},
        View{w, 0, width - w, height - h, perspective},
    };
}

std::pair<CLI::Option*, CLI::Option*> addSizeOptions(CLI::App& app, int& width, int& height) {
    return {app.add_option("--width", width, help::kWidth)->capture_default_str()->check(CLI::Range(1, 16384)),
            app.add_option("--height", height, help::kHeight)->capture_default_str()->check(CLI::Range(1, 16384))};
}

void addSizeListOptions(CLI::App& app, std::vector<int>& widths, std::vector<int>& heights) {
    app.add_option("--width", widths, help::kWidthList)->delimiter(',')->capture_default_str()->check(CLI::Range(1, 16384));
    app.add_option("--height", heights, help::kHeightList)->delimiter(',')->capture_default_str()->check(CLI::Range(1, 16384));
}

Result<std::vector<std::pair<int, int>>> pairSizes(const std::vector<int>& widths,
                                                   const std::vector<int>& heights) {
    for (const auto& [list, option] : {std::pair{&widths, "--width"}, {&heights, "--height"}}) {
        if (list->empty()) return makeError(ErrorCode::InvalidInput, "the list is empty", option);
        for (int v : *list)
            if (v < 1 || v > 16384)
                return makeError(ErrorCode::InvalidInput,
                                 std::to_string(v) + " is outside 1..16384", option);
    }
    if (widths.size() != heights.size() && widths.size() != 1 && heights.size() != 1)
        return makeError(ErrorCode::InvalidInput,
                         std::to_string(widths.size()) + " widths and " +
                             std::to_string(heights.size()) +
                             " heights: give as many of each, or one of either",
                         "--width/--height");
    std::vector<std::pair<int, int>> sizes;
    for (std::size_t i = 0; i < std::max(widths.size(), heights.size()); ++i)
        sizes.emplace_back(widths[widths.size() == 1 ? 0 : i],
                           heights[heights.size() == 1 ? 0 : i]);
    return sizes;
}

Result<void> makeParentFolders(const std::vector<std::string>& paths, int frame,
                               const std::string& option) {
    for (const std::string& path : paths) {
        const std::filesystem::path parent =
            std::filesystem::path(expandFramePattern(path, frame)).parent_path();
        if (parent.empty()) continue;
        std::error_code ec;
        std::filesystem::create_directories(parent, ec);
        if (ec && !std::filesystem::is_directory(parent))
            return makeError(ErrorCode::IoError,
                             "cannot create the folder " + parent.string() + ": " + ec.message(),
                             option, path);
    }
    return {};
}

void DeviceOptions::add(CLI::App& app) {
    app.add_option("--device", device,
                   "The Vulkan device: its index in `lantern info --devices`, or the best one "
                   "whose name contains NAME; wins over LANTERN_DEVICE");
    app.add_flag("--validation", validation, "Enable the Khronos validation layer");
    app.add_flag("-v,--verbose", verbose, "Print the device chosen and other information");
}

RendererDesc DeviceOptions::desc() const {
    RendererDesc d;
    d.deviceName = device;
    const char* env = std::getenv("LANTERN_VALIDATION");
    d.validation = validation || (env && std::string(env) != "0" && std::string(env) != "");
    d.log = stderrSink(verbose);
    return d;
}

void addAllowFolderOption(CLI::App& app, std::vector<std::string>& folders) {
    app.add_option("--allow-folder", folders,
                   "A folder besides the scene's own that its external buffers, images, MTL "
                   "libraries and textures may come from (repeat for several; names may then "
                   "contain \"..\")")
        ->check(CLI::ExistingDirectory);
}

void addVariantOption(CLI::App& app, std::string& variant) {
    app.add_option("--variant", variant,
                   "Draw the scene's material variant NAME (glTF KHR_materials_variants; "
                   "`lantern info` lists them); default: the file's own materials");
}

void addUpOption(CLI::App& app, std::string& up) {
    app.add_option("--up", up,
                   "The file's up axis: y (glTF, OBJ, most files) or z (CAD, most STL and PLY "
                   "scans: turned so that +Z points up)")
        ->capture_default_str()
        ->check(CLI::IsMember({"y", "z"}));
}

UpAxis upAxisOf(const std::string& up) { return parseUpAxis(up).value_or(UpAxis::Y); }

void SceneFileOptions::add(CLI::App& app) {
    addMaxSizeOption(app, maxSize);
    addVariantOption(app, variant);
    addAllowFolderOption(app, allowFolders);
    addUpOption(app, up);
}

LoadOptions SceneFileOptions::load(LogSink log) const {
    LoadOptions o;
    o.maxBytes = maxSize;
    o.variant = variant;
    o.allowedFolders.assign(allowFolders.begin(), allowFolders.end());
    o.up = upAxisOf(up);
    o.log = std::move(log);
    return o;
}

void addMaxSizeOption(CLI::App& app, std::uint64_t& maxSize) {
    app.add_option("--max-size", maxSize,
                   "Largest file, buffer or image accepted, and the most memory one scene's load "
                   "may hold (parsed JSON, buffers, accessors, images, a mesh file's vertices and "
                   "faces), in bytes (1 to " +
                       std::to_string(kMaxMaxSize) + ")")
        ->capture_default_str()
        ->check(CLI::Range(std::uint64_t(1), kMaxMaxSize));
}

namespace {
std::atomic<int> g_stopSignal{0};
extern "C" void onStopSignal(int signal) { g_stopSignal.store(signal); }
} // namespace

std::vector<std::string> processArguments() {
    std::ifstream in("/proc/self/cmdline", std::ios::binary);
    const std::string all((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::vector<std::string> args;
    for (std::size_t start = 0; start < all.size();) {
        std::size_t end = all.find('\0', start);
        if (end == std::string::npos) end = all.size();
        args.push_back(all.substr(start, end - start));
        start = end + 1;
    }
    return args;
}

void installStopHandlers() {
    struct sigaction sa {};
    sa.sa_handler = onStopSignal;
    sa.sa_flags = SA_RESETHAND;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, nullptr);
    sigaction(SIGTERM, &sa, nullptr);
}

int stopSignal() { return g_stopSignal.load(); }

} // namespace lantern::cli
