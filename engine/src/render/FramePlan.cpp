// Scene + options + time -> FramePlan: cameras, eye-space lights, materials, features, draws.
// All composition is in double precision; only camera-relative results become float.
#include "render/FramePlan.h"

#include "math/Robust.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_access.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

namespace lantern::render {
namespace {

constexpr double kPi = 3.14159265358979323846;

Vec4 vec4(const glm::dvec3& v, double w = 0.0) {
    return {float(v.x), float(v.y), float(v.z), float(w)};
}
Vec4 vec4(const glm::dvec4& v) { return {float(v.x), float(v.y), float(v.z), float(v.w)}; }

Mat4 toMat4(const glm::dmat4& m) {
    Mat4 r;
    for (int c = 0; c < 4; ++c)
        for (int k = 0; k < 4; ++k) r.m[c * 4 + k] = float(m[c][k]);
    return r;
}

bool nonZero(const glm::dvec3& v) { return v.x != 0.0 || v.y != 0.0 || v.z != 0.0; }

// The rigid part (rotation + translation) of a world transform: a camera node's scale must
// not distort the view.
glm::dmat4 rigid(const glm::dmat4& m) {
    glm::dvec3 x(m[0]), y(m[1]), z(m[2]);
    x = glm::length(x) > 0 ? glm::normalize(x) : glm::dvec3(1, 0, 0);
    y = y - glm::dot(y, x) * x;
    y = glm::length(y) > 0 ? glm::normalize(y) : glm::dvec3(0, 1, 0);
    z = glm::cross(x, y);
    glm::dmat4 r(1.0);
    r[0] = glm::dvec4(x, 0);
    r[1] = glm::dvec4(y, 0);
    r[2] = glm::dvec4(z, 0);
    r[3] = m[3];
    return r;
}

// The inverse of a rigid transform, exact in structure.
glm::dmat4 inverseRigid(const glm::dmat4& m) {
    const glm::dmat3 rt = glm::transpose(glm::dmat3(m));
    glm::dmat4 inv(rt);
    inv[3] = glm::dvec4(-(rt * glm::dvec3(m[3])), 1.0);
    return inv;
}

int findCameraNode(const Scene& scene, const Pose& pose, int camera) {
    for (std::size_t i = 0; i < scene.nodes.size(); ++i)
        if (pose.visible[i] && scene.nodes[i].camera == camera) return int(i);
    return -1;
}

ResolvedCamera framingCamera(const Scene& scene, int root, const CameraSpec& spec,
                             double aspect) {
    ResolvedCamera rc;
    const Bounds b = animationBounds(scene, root);
    glm::dvec3 c(0.0);
    double r = 1.0;
    if (!b.empty()) {
        c = b.center();
        r = b.radius();
        if (!(r > 0.0)) r = std::max(1e-6, glm::length(c) * 1e-6);
    }
    glm::dvec3 dir = glm::length(spec.framingDirection) > 0 ? glm::normalize(spec.framingDirection)
                                                            : glm::dvec3(0, 0, -1);
    glm::dvec3 up(0, 1, 0);
    if (std::abs(glm::dot(dir, up)) > 0.99) up = dir.y < 0 ? glm::dvec3(0, 0, -1) : glm::dvec3(0, 0, 1);
    const double margin = 1.08;
    if (spec.framingOrthographic) {
        const double d = 2.0 * r;
        rc.viewFromWorld = lookAt(c - dir * d, c, up);
        // Fit the bounds' box as seen from this direction (a modeller's top, front and side
        // views), not its bounding sphere: a flat ground seen edge-on must not shrink the
        // objects standing on it. The box is centred on the view axis.
        double hw = 0.0, hh = 0.0;
        for (int i = 0; i < 8 && !b.empty(); ++i) {
            const glm::dvec3 corner((i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y,
                                    (i & 4) ? b.max.z : b.min.z);
            const glm::dvec4 p = rc.viewFromWorld * glm::dvec4(corner, 1.0);
            hw = std::max(hw, std::abs(p.x));
            hh = std::max(hh, std::abs(p.y));
        }
        if (!(hw > 1e-6 * r) && !(hh > 1e-6 * r)) hw = hh = r;
        double h = std::max(hh, 1e-6 * r) * margin, w = std::max(hw, 1e-6 * r) * margin;
        if (w / h < aspect) w = h * aspect; else h = w / aspect;
        rc.projection = Projection::makeOrtho(-w, w, -h, h, d - 1.5 * r, d + 1.5 * r);
        rc.description = "automatic framing (orthographic)";
    } else {
        const double yfov = 45.0 * kPi / 180.0;
        const double xfov = 2.0 * std::atan(std::tan(yfov / 2.0) * aspect);
        const double d = r * margin / std::sin(std::min(yfov, xfov) / 2.0);
        rc.viewFromWorld = lookAt(c - dir * d, c, up);
        rc.projection = Projection::makePerspective(yfov, 0.0, std::max(d - 1.5 * r, d * 1e-3),
                                                    kInfinity);
        rc.description = "automatic framing";
    }
    return rc;
}

std::string cameraName(const Scene& scene, int i) {
    std::string s = "camera " + std::to_string(i);
    if (!scene.cameras[i].name.empty()) s += " \"" + scene.cameras[i].name + "\"";
    return s;
}

} // namespace

const char* toString(Program p) noexcept {
    switch (p) {
    case Program::Phong: return "phong";
    case Program::Gouraud: return "gouraud";
    case Program::Flat: return "flat";
    case Program::GlFlat: return "gl-flat";
    case Program::Floor: return "floor";
    }
    return "?";
}

ResolvedLighting resolveLighting(const Scene& scene, int root, const RenderOptions& o) {
    ResolvedLighting r;
    const int ri = root < 0 ? scene.defaultRoot : root;
    if (ri >= 0 && ri < int(scene.roots.size()) && scene.roots[ri].lighting)
        r.model = *scene.roots[ri].lighting;
    if (o.shading) r.model.shading = *o.shading;
    if (o.specular) r.model.specular = *o.specular;
    if (o.localViewer) r.model.localViewer = *o.localViewer;
    if (o.twoSided) r.model.twoSided = *o.twoSided;
    // GL's default shading is GL_SMOOTH: with --gl-compat a scene that does not choose a mode
    // (no LANTERN_lighting) is shaded per vertex, as OpenGL would.
    const bool sceneChoosesShading =
        ri >= 0 && ri < int(scene.roots.size()) && scene.roots[ri].lighting.has_value();
    if (o.glCompat && !o.shading && !sceneChoosesShading) r.model.shading = ShadingMode::Gouraud;
    r.glCompat = o.glCompat;
    r.clamp = o.glCompat ? LANTERN_CLAMP_GL : o.clamp ? LANTERN_CLAMP_FRAGMENT : LANTERN_CLAMP_NONE;
    switch (r.model.shading) {
    case ShadingMode::Phong: r.program = Program::Phong; break;
    case ShadingMode::Gouraud: r.program = Program::Gouraud; break;
    case ShadingMode::Flat: r.program = o.glCompat ? Program::GlFlat : Program::Flat; break;
    }
    return r;
}

std::string VariantKey::describe() const {
    std::ostringstream s;
    s << toString(program) << ": lights=";
    const std::uint32_t t = constants[LANTERN_SC_LIGHT_TYPES];
    bool any = false;
    for (auto [bit, name] : {std::pair{LANTERN_LIGHT_BIT_DIRECTIONAL, "directional"},
                             std::pair{LANTERN_LIGHT_BIT_POINT, "point"},
                             std::pair{LANTERN_LIGHT_BIT_SPOT, "spot"}})
        if (t & std::uint32_t(bit)) {
            s << (any ? "+" : "") << name;
            any = true;
        }
    if (!any) s << "none";
    const char* spec[] = {"none", "blinn", "phong"};
    s << " specular=" << spec[std::min<std::uint32_t>(constants[LANTERN_SC_SPECULAR], 2)];
    auto flag = [&](int id, const char* name) {
        if (constants[id]) s << " " << name;
    };
    flag(LANTERN_SC_GL_ATTENUATION, "attenuation");
    flag(LANTERN_SC_GL_SPOT, "gl-spot");
    flag(LANTERN_SC_GLTF_FALLOFF, "gltf-falloff");
    flag(LANTERN_SC_LOCAL_VIEWER, "local-viewer");
    flag(LANTERN_SC_TWO_SIDED, "two-sided");
    flag(LANTERN_SC_VERTEX_COLOR, "vertex-color");
    flag(LANTERN_SC_TEXTURE, "texture");
    flag(LANTERN_SC_ALPHA_MASK, "alpha-mask");
    flag(LANTERN_SC_UNLIT, "unlit");
    flag(LANTERN_SC_AMBIENT_FOLLOWS_DIFFUSE, "ambient=diffuse");
    const char* clamps[] = {"", " clamp", " gl-clamp"};
    s << clamps[std::min<std::uint32_t>(constants[LANTERN_SC_CLAMP], 2)];
    s << (constants[LANTERN_SC_OPAQUE] ? " opaque" : "");
    if (blend) s << " blend";
    if (aov) s << " aov";
    if (samples > 1) s << " msaa=" << samples;
    if (!reversedZ) s << " standard-z";
    return s.str();
}

std::size_t VariantKeyHash::operator()(const VariantKey& k) const noexcept {
    std::size_t h = std::size_t(k.program) * 1000003u;
    for (std::uint32_t c : k.constants) h = h * 31u + c;
    h = h * 31u + (k.blend ? 1u : 0u);
    h = h * 31u + (k.aov ? 1u : 0u);
    h = h * 31u + k.samples;
    h = h * 31u + (k.reversedZ ? 1u : 0u);
    return h;
}

Bounds animationBounds(const Scene& scene, int root) {
    // Sample every key time of every animation (and t = 0): the framing then contains the
    // whole motion (between keys, linear motion stays inside the keys' hull for translations).
    std::vector<double> times{0.0};
    for (const Animation& a : scene.animations)
        for (const AnimationSampler& s : a.samplers)
            times.insert(times.end(), s.times.begin(), s.times.end());
    std::sort(times.begin(), times.end());
    times.erase(std::unique(times.begin(), times.end()), times.end());
    if (times.size() > 64) {  // bound the cost for long animations
        std::vector<double> picked;
        for (std::size_t i = 0; i < 64; ++i) picked.push_back(times[i * (times.size() - 1) / 63]);
        times = picked;
    }
    Bounds b;
    for (double t : times) {
        const Bounds bt = computeBounds(scene, evaluatePose(scene, root, t));
        if (!bt.empty()) {
            b.extend(bt.min);
            b.extend(bt.max);
        }
    }
    return b;
}

Result<ResolvedCamera> resolveCamera(const Scene& scene, const Pose& pose, const CameraSpec& spec,
                                     double aspect, DepthMode depth, const std::string& object) {
    ResolvedCamera rc;
    using Source = CameraSpec::Source;
    Source source = spec.source;
    int camera = spec.sceneCamera;
    if (source == Source::Automatic) {
        source = Source::Framing;
        for (std::size_t i = 0; i < scene.cameras.size(); ++i)
            if (scene.cameras[i].lookAt || findCameraNode(scene, pose, int(i)) >= 0) {
                source = Source::SceneCamera;
                camera = int(i);
                break;
            }
    }
    switch (source) {
    case Source::SceneCamera: {
        if (camera < 0 || camera >= int(scene.cameras.size()))
            return makeError(ErrorCode::InvalidInput,
                             "camera " + std::to_string(camera) + " does not exist (the scene has " +
                                 std::to_string(scene.cameras.size()) + " cameras)",
                             object);
        const Camera& cam = scene.cameras[camera];
        if (cam.lookAt) {
            rc.viewFromWorld = lookAt(cam.lookAt->eye, cam.lookAt->target, cam.lookAt->up);
        } else {
            const int node = findCameraNode(scene, pose, camera);
            if (node < 0)
                return makeError(ErrorCode::InvalidInput,
                                 cameraName(scene, camera) + " is not placed by any node of scene " +
                                     std::to_string(pose.root),
                                 object);
            rc.viewFromWorld = inverseRigid(rigid(pose.worldFromNode[node]));
        }
        rc.projection = cam.projection;
        rc.description = cameraName(scene, camera);
        break;
    }
    case Source::GlDefault: {
        const Camera c = glDefaultCamera();
        rc.viewFromWorld = glm::dmat4(1.0);
        rc.projection = c.projection;
        rc.description = "GL default camera";
        break;
    }
    case Source::Framing:
    case Source::Automatic: rc = framingCamera(scene, pose.root, spec, aspect); break;
    }
    if (spec.lookAt) {
        LANTERN_TRY(checkLookAt(*spec.lookAt, object.empty() ? "lookAt" : object));
        rc.viewFromWorld = lookAt(spec.lookAt->eye, spec.lookAt->target, spec.lookAt->up);
        rc.description += " with lookAt";
    }
    if (spec.projection) {
        LANTERN_TRY(checkProjection(*spec.projection, object.empty() ? "projection" : object));
        rc.projection = *spec.projection;
        rc.description += " with explicit projection";
    }
    rc.clipFromView = vulkanClipFromView(rc.projection, aspect, depth);
    return rc;
}

LightData packLight(const Light& l, const glm::dmat4& viewFromLight, bool glCompat) {
    LightData d;
    const glm::dvec3 position(viewFromLight[3]);
    glm::dvec3 axis = glm::dmat3(viewFromLight) * glm::dvec3(0, 0, -1);
    const double len = glm::length(axis);
    axis = (len > 0.0 && std::isfinite(len)) ? axis / len : glm::dvec3(0, 0, -1);

    std::uint32_t type = LANTERN_LIGHT_POINT;
    if (l.type == LightType::Directional) type = LANTERN_LIGHT_DIRECTIONAL;
    if (l.type == LightType::Spot &&
        !(l.falloff == LightFalloff::Gl && l.spotCutoffDeg == 180.0))
        type = LANTERN_LIGHT_SPOT;

    d.position = type == LANTERN_LIGHT_DIRECTIONAL ? vec4(-axis, 0.0) : vec4(position, 1.0);
    d.ambient = vec4(l.ambient);
    d.diffuse = vec4(l.diffuse);
    d.specular = vec4(l.specular);
    // 1 - cos(cutoff) as 2 sin^2(cutoff / 2): exact for small cutoffs (lighting.glsl's
    // glSpotFactor compares 1 - cos(angle) with it).
    const double halfCutoff = std::min(l.spotCutoffDeg, 90.0) * kPi / 360.0;
    d.spotDirection = vec4(axis, 2.0 * std::sin(halfCutoff) * std::sin(halfCutoff));
    const double invRange = std::isinf(l.range) ? 0.0 : 1.0 / l.range;
    d.attenuation = vec4(glm::dvec4(l.attenuation, invRange));
    const double exponent = glCompat ? std::min(l.spotExponent, 128.0) : l.spotExponent;
    const double cosOuter = std::cos(l.outerConeAngle), cosInner = std::cos(l.innerConeAngle);
    d.spot = vec4(glm::dvec4(exponent, cosOuter, 1.0 / std::max(cosInner - cosOuter, 1e-6), 0.0));
    d.info.x = type;
    d.info.y = l.falloff == LightFalloff::Gl ? LANTERN_FALLOFF_GL : LANTERN_FALLOFF_GLTF;
    return d;
}

MaterialData packMaterial(const Material& m, bool glCompat) {
    auto side = [&](const MaterialSide& s) {
        MaterialSideData d;
        d.ambient = vec4(s.ambient);
        d.diffuse = vec4(s.diffuse);
        const double shininess = glCompat ? std::clamp(s.shininess, 0.0, 128.0) : s.shininess;
        d.specular = vec4(s.specular, shininess);
        d.emission = vec4(s.emission);
        return d;
    };
    MaterialData d;
    d.front = side(m.front);
    d.back = m.back ? side(*m.back) : d.front;
    // A cutoff of -1 never discards: the all-features pipeline runs the mask test everywhere.
    d.params.x = m.alphaMode == AlphaMode::Mask ? float(m.alphaCutoff) : -1.0f;
    return d;
}

Result<FramePlan> buildFramePlan(const Scene& scene, const RenderOptions& o, double time) {
    FramePlan plan;
    if (o.root < -1 || o.root >= int(scene.roots.size()))
        return makeError(ErrorCode::InvalidInput,
                         "scene " + std::to_string(o.root) + " does not exist (the file has " +
                             std::to_string(scene.roots.size()) + " scenes)",
                         "--scene");
    if (!std::isfinite(time))
        return makeError(ErrorCode::InvalidInput, "time must be a finite number", "--time");
    const int root = o.root < 0 ? scene.defaultRoot : o.root;
    plan.pose = evaluatePose(scene, root, time);
    plan.lighting = resolveLighting(scene, root, o);
    const ResolvedLighting& lit = plan.lighting;
    const bool all = o.features == FeatureMode::AllFeatures;

    // Materials: the scene's, then the default one (GL's defaults) for primitives without.
    for (const Material& m : scene.materials) plan.materials.push_back(packMaterial(m, lit.glCompat));
    const Material defaultMaterial;
    plan.materials.push_back(packMaterial(defaultMaterial, lit.glCompat));
    const std::uint32_t defaultMaterialIndex = std::uint32_t(scene.materials.size());

    // Lights placed by visible nodes (index order), or GL's default light 0.
    struct PlacedLight {
        const Light* light;
        int node;
    };
    std::vector<PlacedLight> placed;
    for (std::size_t i = 0; i < scene.nodes.size(); ++i)
        if (plan.pose.visible[i] && scene.nodes[i].light >= 0)
            placed.push_back({&scene.lights[scene.nodes[i].light], int(i)});
    static const Light kDefaultLight = [] {
        Light l;
        l.name = "GL default light 0";
        l.type = LightType::Directional;
        return l;
    }();

    // Scene-level features.
    std::uint32_t lightTypes = 0;
    bool glAttenuation = false, glSpot = false, gltfFalloff = false, lightSpecular = false;
    std::size_t counts[3] = {0, 0, 0};
    auto noteLight = [&](const Light& l) {
        const bool positional = l.type != LightType::Directional;
        const bool isSpot = l.type == LightType::Spot &&
                            !(l.falloff == LightFalloff::Gl && l.spotCutoffDeg == 180.0);
        const std::uint32_t bit = !positional ? LANTERN_LIGHT_BIT_DIRECTIONAL
                                  : isSpot    ? LANTERN_LIGHT_BIT_SPOT
                                              : LANTERN_LIGHT_BIT_POINT;
        lightTypes |= bit;
        ++counts[bit == LANTERN_LIGHT_BIT_DIRECTIONAL ? 0 : bit == LANTERN_LIGHT_BIT_POINT ? 1 : 2];
        if (positional && l.falloff == LightFalloff::Gl && l.attenuation != glm::dvec3(1, 0, 0))
            glAttenuation = true;
        if (isSpot && l.falloff == LightFalloff::Gl) glSpot = true;
        if (positional && l.falloff == LightFalloff::Gltf) gltfFalloff = true;
        if (nonZero(l.specular)) lightSpecular = true;
    };
    if (placed.empty())
        noteLight(kDefaultLight);
    else
        for (const PlacedLight& p : placed) noteLight(*p.light);

    auto& f = plan.features;
    if (placed.empty()) f.push_back("light:gl-default (headlight, directional)");
    if (counts[0]) f.push_back("light:directional x" + std::to_string(counts[0]));
    if (counts[1]) f.push_back("light:point x" + std::to_string(counts[1]));
    if (counts[2]) f.push_back("light:spot x" + std::to_string(counts[2]));
    if (glAttenuation) f.push_back("attenuation:gl");
    if (glSpot) f.push_back("spot-cone:gl");
    if (gltfFalloff) f.push_back("falloff:gltf");
    f.push_back(std::string("shading:") + toString(lit.model.shading) +
                (lit.program == Program::GlFlat ? " (provoking vertex)" : ""));
    if (lit.model.localViewer) f.push_back("local-viewer");
    if (lit.model.twoSided) f.push_back("two-sided");
    if (lit.clamp == LANTERN_CLAMP_GL) f.push_back("clamp:gl (per vertex)");
    if (lit.clamp == LANTERN_CLAMP_FRAGMENT) f.push_back("clamp");
    if (o.aovs.any()) f.push_back("aov");
    if (o.msaa > 1) f.push_back("msaa:" + std::to_string(o.msaa));
    if (o.lightsViewFromWorld) f.push_back("lights-follow-camera");

    // Views: the explicit list, or one covering the image.
    std::vector<View> views = o.views;
    if (views.empty()) views.push_back(View{0, 0, o.width, o.height, o.camera});

    bool anyVertexColor = false, anyTexture = false, anyMask = false, anyBlend = false,
         anyUnlit = false, anySpecular = false;
    std::uint32_t drawCount = 0;
    for (std::size_t vi = 0; vi < views.size(); ++vi) {
        const View& v = views[vi];
        const std::string viewObject = o.views.empty() ? std::string("camera")
                                                       : "view " + std::to_string(vi);
        if (v.width <= 0 || v.height <= 0 || v.x < 0 || v.y < 0 || v.x + v.width > o.width ||
            v.y + v.height > o.height)
            return makeError(ErrorCode::InvalidInput,
                             "viewport " + std::to_string(v.x) + "," + std::to_string(v.y) + "," +
                                 std::to_string(v.width) + "," + std::to_string(v.height) +
                                 " is empty or outside the " + std::to_string(o.width) + "x" +
                                 std::to_string(o.height) + " image",
                             "--viewport");
        ViewPlan vp;
        vp.x = v.x, vp.y = v.y, vp.width = v.width, vp.height = v.height;
        auto cam = resolveCamera(scene, plan.pose, v.camera, double(v.width) / double(v.height),
                                 o.depth, viewObject);
        if (!cam) return std::move(cam).error();
        vp.camera = std::move(*cam);
        const glm::dmat4& viewFromWorld = vp.camera.viewFromWorld;

        vp.frame.clipFromView = toMat4(vp.camera.clipFromView);
        vp.frame.globalAmbient = vec4(lit.model.globalAmbient);
        vp.frame.viewIndex = std::uint32_t(vi);
        if (placed.empty()) {
            // GL's light 0 is defined in eye space: a headlight along +Z.
            vp.lights.push_back(packLight(kDefaultLight, glm::dmat4(1.0), lit.glCompat));
        } else {
            // Lights that follow the camera are placed through the camera they were fixed to.
            const glm::dmat4& lightsView = o.lightsViewFromWorld ? *o.lightsViewFromWorld : viewFromWorld;
            for (const PlacedLight& p : placed)
                vp.lights.push_back(
                    packLight(*p.light, lightsView * plan.pose.worldFromNode[p.node], lit.glCompat));
        }
        vp.frame.lightCount = std::uint32_t(vp.lights.size());

        std::vector<DrawItem> opaque, blended;
        for (std::size_t ni = 0; ni < scene.nodes.size(); ++ni) {
            const Node& node = scene.nodes[ni];
            if (!plan.pose.visible[ni] || node.mesh < 0) continue;
            const glm::dmat4 viewFromModel = viewFromWorld * plan.pose.worldFromNode[ni];
            const glm::dmat3 normals = normalMatrix(viewFromModel);
            // Accurate: glm::determinant gets the sign wrong for scales 1e-6 and 1e6 under a
            // rotation, which would cull the visible faces.
            const bool mirrored = math::accurateDeterminant(glm::dmat3(viewFromModel)) < 0.0;
            const Mesh& mesh = scene.meshes[node.mesh];
            for (std::size_t pi = 0; pi < mesh.primitives.size(); ++pi) {
                const Primitive& prim = mesh.primitives[pi];
                if (prim.triangleCount() == 0) continue;
                const Material& mat =
                    prim.material >= 0 ? scene.materials[prim.material] : defaultMaterial;
                DrawItem d;
                d.mesh = std::uint32_t(node.mesh);
                d.primitive = std::uint32_t(pi);
                d.node = std::uint32_t(ni);
                d.viewFromModel = viewFromModel;
                for (int c = 0; c < 4; ++c)
                    for (int r = 0; r < 4; ++r) d.block.viewFromModel[c * 4 + r] = float(viewFromModel[c][r]);
                for (int c = 0; c < 3; ++c)
                    for (int r = 0; r < 3; ++r) d.block.normalMatrix[c * 4 + r] = float(normals[c][r]);
                d.block.materialIndex =
                    prim.material >= 0 ? std::uint32_t(prim.material) : defaultMaterialIndex;
                d.hasColors = !prim.colors.empty();
                d.hasTexcoords = !prim.texcoords.empty();
                d.block.flags = d.hasColors ? kDrawFlagVertexColor : 0u;
                d.texture = (mat.baseColorTexture >= 0 && d.hasTexcoords) ? mat.baseColorTexture : -1;
                d.cullBack = !mat.doubleSided;
                d.mirrored = mirrored;

                const bool blend = mat.alphaMode == AlphaMode::Blend;
                const bool materialSpecular =
                    nonZero(mat.front.specular) || (mat.back && nonZero(mat.back->specular));
                VariantKey& k = d.key;
                k.program = o.features == FeatureMode::Floor ? Program::Floor : lit.program;
                k.blend = blend;
                k.aov = o.aovs.any();
                k.samples = std::uint32_t(o.msaa);
                k.reversedZ = o.depth == DepthMode::ReversedZ;
                auto& sc = k.constants;
                const std::uint32_t model = lit.model.specular == SpecularModel::Blinn
                                                ? LANTERN_SPECULAR_BLINN
                                                : LANTERN_SPECULAR_PHONG;
                sc[LANTERN_SC_LIGHT_TYPES] = all ? 7u : lightTypes;
                sc[LANTERN_SC_GL_ATTENUATION] = all || glAttenuation;
                sc[LANTERN_SC_GL_SPOT] = all || glSpot;
                sc[LANTERN_SC_GLTF_FALLOFF] = all || gltfFalloff;
                sc[LANTERN_SC_SPECULAR] =
                    (all || (lightSpecular && materialSpecular && !mat.unlit)) ? model
                                                                               : LANTERN_SPECULAR_NONE;
                sc[LANTERN_SC_LOCAL_VIEWER] = lit.model.localViewer;
                sc[LANTERN_SC_TWO_SIDED] = lit.model.twoSided;
                sc[LANTERN_SC_VERTEX_COLOR] = all || d.hasColors;
                sc[LANTERN_SC_TEXTURE] = all || d.texture >= 0;
                sc[LANTERN_SC_ALPHA_MASK] = all || mat.alphaMode == AlphaMode::Mask;
                sc[LANTERN_SC_CLAMP] = lit.clamp;
                sc[LANTERN_SC_UNLIT] = mat.unlit;
                sc[LANTERN_SC_AMBIENT_FOLLOWS_DIFFUSE] = mat.ambientFollowsDiffuse;
                sc[LANTERN_SC_OPAQUE] = !blend;

                anyVertexColor |= d.hasColors;
                anyTexture |= d.texture >= 0;
                anyMask |= mat.alphaMode == AlphaMode::Mask;
                anyBlend |= blend;
                anyUnlit |= mat.unlit;
                anySpecular |= sc[LANTERN_SC_SPECULAR] != LANTERN_SPECULAR_NONE;

                if (blend) {
                    // Sort key: the eye-space depth of the primitive's bounds centre.
                    Bounds local;
                    for (const glm::vec3& p : prim.positions) local.extend(glm::dvec3(p));
                    d.sortDepth = float((viewFromModel * glm::dvec4(local.center(), 1.0)).z);
                    blended.push_back(std::move(d));
                } else {
                    opaque.push_back(std::move(d));
                }
            }
        }
        // Opaque: grouped by variant (fewer pipeline binds), order otherwise kept (stable, so
        // frames are deterministic). Blended: far to near (most negative eye z first).
        std::stable_sort(opaque.begin(), opaque.end(), [](const DrawItem& a, const DrawItem& b) {
            if (a.key.program != b.key.program) return a.key.program < b.key.program;
            return a.key.constants < b.key.constants;
        });
        std::stable_sort(blended.begin(), blended.end(),
                         [](const DrawItem& a, const DrawItem& b) { return a.sortDepth < b.sortDepth; });
        vp.draws = std::move(opaque);
        vp.draws.insert(vp.draws.end(), std::make_move_iterator(blended.begin()),
                        std::make_move_iterator(blended.end()));
        // Numbered across the frame, so the ids AOV names a draw of any view (--probe).
        for (DrawItem& d : vp.draws) d.block.drawIndex = drawCount++;
        plan.views.push_back(std::move(vp));
    }
    // The specular model only matters when some draw has a specular term at all.
    f.push_back(anySpecular ? std::string("specular:") + toString(lit.model.specular)
                            : std::string("specular:none (no specular light on a specular "
                                          "material)"));
    if (anyVertexColor) f.push_back("vertex-colors");
    if (anyTexture) f.push_back("texture");
    if (anyMask) f.push_back("alpha-mask");
    if (anyBlend) f.push_back("alpha-blend");
    if (anyUnlit) f.push_back("unlit");
    return plan;
}

} // namespace lantern::render
