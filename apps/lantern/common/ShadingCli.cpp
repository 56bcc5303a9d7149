// The shading options every rendering subcommand shares (render, view, bench frame): the
// lighting model's switches, anti-aliasing, point and line sizes, shadows, transparency and
// instancing.
#include "common/CliSupport.h"

#include <algorithm>
#include <string>

namespace lantern::cli {

void ShadingOptions::add(CLI::App& app) {
    app.add_option("--shading", shading, help::kShading)
        ->check(CLI::IsMember({"flat", "gouraud", "phong"}));
    app.add_option("--specular", specular, help::kSpecular)
        ->check(CLI::IsMember({"blinn", "phong"}));
    app.add_flag("--local-viewer", localViewer,
                 "View vector towards the eye (GL_LIGHT_MODEL_LOCAL_VIEWER)");
    app.add_flag("--two-sided", twoSided,
                 "Light back faces with the back material (GL_LIGHT_MODEL_TWO_SIDE)");
    app.add_flag("--clamp", clamp, "Clamp lit colours to [0,1]");
    app.add_flag("--gl-compat", glCompat,
                 "Reproduce OpenGL's fixed-function pipeline (provoking-vertex flat, per-vertex "
                 "clamp, limits)");
    app.add_option("--msaa", msaa, help::kMsaa)->capture_default_str()->check(CLI::IsMember({1, 2, 4, 8}));
    app.add_option("--point-size", pointSize,
                   "Pixels across a point (glTF POINTS, GL_POINTS), 1 to 255; above 1 the device "
                   "needs largePoints")
        ->capture_default_str()
        ->check(CLI::Range(1.0, 255.0));
    app.add_option("--line-width", lineWidth,
                   "Pixels across a line (glTF LINES, LINE_STRIP, LINE_LOOP; GL_LINES), 1 to 255; "
                   "above 1 the device needs wideLines")
        ->capture_default_str()
        ->check(CLI::Range(1.0, 255.0));
    app.add_flag("--shadows", shadows,
                 "Every light casts shadows (without it, only lights with LANTERN_lights_shadow)");
    app.add_option("--shadow-resolution", shadowResolution,
                   "Texels per side of each shadow map (a cube face for point lights)")
        ->capture_default_str()
        ->check(CLI::Range(16, 16384));
    app.add_option("--shadow-filter", shadowFilter,
                   "How shadow maps are filtered: hardware (the device's 2 x 2 comparison), pcf "
                   "(kernel x kernel comparisons) or pcss (soft: a blocker search, then PCF over "
                   "the penumbra a light of --shadow-light-radius or --shadow-sun-radius casts)")
        ->capture_default_str()
        ->check(CLI::IsMember({"hardware", "pcf", "pcss"}));
    app.add_option("--shadow-kernel", shadowKernel,
                   "Comparisons per side for pcf and pcss (odd, 1 to 9)")
        ->capture_default_str()
        ->check(CLI::IsMember({1, 3, 5, 7, 9}));
    app.add_option("--shadow-cascades", shadowCascades,
                   "Shadow maps per directional light, fitted to consecutive depth ranges of the "
                   "view (1 to 8; 1: one map around the scene)")
        ->capture_default_str()
        ->check(CLI::Range(1, kMaxShadowCascades));
    app.add_option("--shadow-light-radius", shadowLightRadius,
                   "pcss: the radius of point and spot lights, in world units")
        ->capture_default_str()
        ->check(CLI::Range(0.0, 1e30));
    app.add_option("--shadow-sun-radius", shadowSunRadius,
                   "pcss: the angular radius of directional lights, in degrees (the sun's is 0.27)")
        ->capture_default_str()
        ->check(CLI::Range(0.0, 45.0));
    app.add_option("--shadow-bias", shadowBias, "Shadow depth bias, in units of the depth's slope")
        ->capture_default_str()
        ->check(CLI::Range(0.0, 1000.0));
    app.add_option("--shadow-normal-offset", shadowNormalOffset,
                   "Texels the shadow lookup moves along the surface normal")
        ->capture_default_str()
        ->check(CLI::Range(0.0, 1000.0));
    app.add_option("--transparency", transparency,
                   "How blended materials are composited: exact (per-pixel fragment lists sorted "
                   "by depth; the default), sorted (by object, far to near, as GL programs do; the "
                   "default with --gl-compat) or weighted (weighted blended OIT, approximate)")
        ->check(CLI::IsMember({"sorted", "exact", "weighted"}));
    app.add_flag("--no-instancing", noInstancing,
                 "Draw every node on its own, not nodes that share a mesh as one instanced draw "
                 "(the same picture; to measure what instancing buys)");
    app.add_flag("--no-culling", noCulling,
                 "Draw everything: every cluster of a large mesh, not only those in view and "
                 "facing it, and every caster into every shadow map (the same picture; to "
                 "measure what culling buys)");
    app.add_option("--lod-error", lodError,
                   "Level of detail: draw each large mesh at the coarsest simplified level whose "
                   "error stays under this many pixels on screen (0: the full mesh, exact)")
        ->capture_default_str()
        ->check(CLI::Range(0.0, 1e6));
}

Result<void> ShadingOptions::apply(RenderOptions& o) const {
    if (!shading.empty()) o.shading = parseShadingMode(shading);
    if (!specular.empty()) o.specular = parseSpecularModel(specular);
    if (localViewer) o.localViewer = true;
    if (twoSided) o.twoSided = true;
    o.clamp = clamp;
    o.glCompat = glCompat;
    o.msaa = msaa;
    o.pointSize = pointSize;
    o.lineWidth = lineWidth;
    o.instancing = !noInstancing;
    o.shadows.all = shadows;
    o.shadows.resolution = shadowResolution;
    o.culling = !noCulling;
    o.lodError = lodError;
    o.shadows.filter = parseShadowFilter(shadowFilter);
    o.shadows.kernel = shadowKernel;
    o.shadows.cascades = shadowCascades;
    o.shadows.lightRadius = shadowLightRadius;
    o.shadows.sunRadius = shadowSunRadius;
    o.shadows.slopeBias = shadowBias;
    o.shadows.normalOffset = shadowNormalOffset;
    if (!transparency.empty()) o.transparency = parseTransparencyMethod(transparency);
    return {};
}

ShadowFilter parseShadowFilter(const std::string& text) {
    return text == "hardware" ? ShadowFilter::Hardware
           : text == "pcss"   ? ShadowFilter::Pcss
                              : ShadowFilter::Pcf;
}

const char* shadowFilterName(ShadowFilter f) {
    switch (f) {
    case ShadowFilter::Hardware: return "hardware";
    case ShadowFilter::Pcf: return "pcf";
    case ShadowFilter::Pcss: return "pcss";
    }
    return "pcf";
}

TransparencyMethod parseTransparencyMethod(const std::string& text) {
    return text == "sorted" ? TransparencyMethod::Sorted
           : text == "weighted" ? TransparencyMethod::Weighted
                                : TransparencyMethod::Exact;
}

const char* transparencyName(TransparencyMethod m) {
    switch (m) {
    case TransparencyMethod::Sorted: return "sorted";
    case TransparencyMethod::Exact: return "exact";
    case TransparencyMethod::Weighted: return "weighted";
    }
    return "exact";
}

Result<void> ShadingOptions::checkDevice(const DeviceInfo& device) const {
    return checkMsaa(msaa, device);
}

Result<void> checkMsaa(int msaa, const DeviceInfo& device) {
    const auto& counts = device.msaaSampleCounts;
    if (std::find(counts.begin(), counts.end(), msaa) != counts.end()) return {};
    std::string supported;
    for (int c : counts)
        supported += (supported.empty() ? "" : ", ") + std::to_string(c);
    return makeError(ErrorCode::Usage,
                     std::to_string(msaa) + " samples per pixel: " + device.name + " supports " +
                         supported,
                     "--msaa");
}

} // namespace lantern::cli
