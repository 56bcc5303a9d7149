// buildFrame(): scene + options + time -> Frame. All composition is in double precision;
// nothing here is packed for a device.
#include "frame/Frame.h"

#include "math/Robust.h"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace lantern::frame {
namespace {

bool nonZero(const glm::dvec3& v) { return v.x != 0.0 || v.y != 0.0 || v.z != 0.0; }

LightFeatures lightFeatures(const std::vector<EyeLight>& lights, bool glDefault) {
    LightFeatures f;
    f.glDefault = glDefault;
    for (const EyeLight& l : lights) {
        const bool positional = l.type != LightType::Directional;
        if (l.type == LightType::Directional) ++f.directional;
        if (l.type == LightType::Point) ++f.point;
        if (l.type == LightType::Spot) ++f.spot;
        if (positional && l.falloff == LightFalloff::Gl && l.attenuation != glm::dvec3(1, 0, 0))
            f.glAttenuation = true;
        if (l.type == LightType::Spot && l.falloff == LightFalloff::Gl) f.glSpot = true;
        if (positional && l.falloff == LightFalloff::Gltf) f.gltfFalloff = true;
        if (nonZero(l.specular)) f.specular = true;
        f.kinds.emplace_back(l.type, l.falloff);
    }
    return f;
}

// A material as --unlit-exact draws it: unlit, its colour the base colour the scene wrote (the
// metallic-roughness base colour, or a Phong material's diffuse), nothing else applied.
Material exactLabel(const Material& m) {
    Material out;
    out.name = m.name;
    out.unlit = true;
    out.front.diffuse = m.pbr ? m.pbr->baseColor : m.front.diffuse;
    out.alphaMode = m.alphaMode == AlphaMode::Mask ? AlphaMode::Mask : AlphaMode::Opaque;
    out.alphaCutoff = m.alphaCutoff;
    out.doubleSided = m.doubleSided;
    return out;
}

std::vector<Material> frameMaterials(const Scene& scene, bool glCompat, bool unlitExact) {
    std::vector<Material> out = scene.materials;
    out.emplace_back();  // GL's default material, for primitives without one
    if (unlitExact)
        for (Material& m : out) m = exactLabel(m);
    if (glCompat)
        for (Material& m : out) {
            m.front.shininess = std::clamp(m.front.shininess, 0.0, 128.0);
            if (m.back) m.back->shininess = std::clamp(m.back->shininess, 0.0, 128.0);
        }
    return out;
}

DrawFeatures drawFeatures(const Material& mat, const Draw& d, const LightFeatures& lights,
                          const Lighting& lighting) {
    DrawFeatures f;
    f.twoSided = twoSidedLighting(lighting, mat);
    const bool unlit = mat.unlit || d.unlitForWantOfNormals;
    // Maps need texture coordinates and a surface (lines and points have no tangent frame);
    // gouraud and flat shading apply only the emissive map (docs/gl-differences.md).
    if (d.hasTexcoords && d.topology == Topology::Triangles && !unlit)
        f.maps = materialMaps(mat) &
                 (lighting.program == Program::Phong
                      ? kMapAll | kMapSecondSets
                      : kMapEmissive | (kMapEmissive << kMapSecondSetShift));
    // A metallic-roughness map gives specular colour per texel even where the factors give
    // none (a rough metal: specular 0).
    const bool materialSpecular = nonZero(mat.front.specular) ||
                                  (mat.back && nonZero(mat.back->specular)) ||
                                  (f.maps & kMapMetallicRoughness) != 0;
    f.specular = lights.specular && materialSpecular && !unlit;
    f.vertexColor = d.hasColors;
    f.texture = d.texture >= 0;
    f.alphaMask = mat.alphaMode == AlphaMode::Mask;
    f.blend = mat.alphaMode == AlphaMode::Blend;
    f.unlit = unlit;
    f.ambientFollowsDiffuse = mat.ambientFollowsDiffuse;
    return f;
}

// The draws of one node's mesh seen through `viewFromWorld`.
void addNodeDraws(const Scene& scene, const Frame& frame, std::size_t ni,
                  const glm::dmat4& viewFromWorld, std::vector<Draw>& opaque,
                  std::vector<Draw>& blended) {
    const Node& node = scene.nodes[ni];
    const glm::dmat4 nodeViewFromModel = viewFromWorld * frame.pose.worldFromNode[ni];
    const glm::dmat3 nodeNormals = normalMatrix(nodeViewFromModel);
    // Accurate: glm::determinant gets the sign wrong for scales 1e-6 and 1e6 under a
    // rotation, which would cull the visible faces.
    const bool nodeMirrored = math::accurateDeterminant(glm::dmat3(nodeViewFromModel)) < 0.0;
    const Mesh& mesh = scene.meshes[std::size_t(node.mesh)];
    const std::uint32_t defaultMaterial = std::uint32_t(scene.materials.size());
    for (std::size_t pi = 0; pi < mesh.primitives.size(); ++pi) {
        const Primitive& prim = mesh.primitives[pi];
        if (prim.elementCount() == 0) continue;
        // Skinned vertices are in world space: the node's own transform is not applied.
        const bool skinned = isSkinned(scene, int(ni), prim);
        const glm::dmat4 viewFromModel = skinned ? viewFromWorld : nodeViewFromModel;
        const glm::dmat3 normals = skinned ? normalMatrix(viewFromWorld) : nodeNormals;
        const bool mirrored =
            skinned ? math::accurateDeterminant(glm::dmat3(viewFromWorld)) < 0.0 : nodeMirrored;
        Draw d;
        d.node = std::uint32_t(ni);
        d.mesh = std::uint32_t(node.mesh);
        d.primitive = std::uint32_t(pi);
        d.material = prim.material >= 0 ? std::uint32_t(prim.material) : defaultMaterial;
        const Material& mat = frame.materials[d.material];
        d.viewFromModel = viewFromModel;
        d.normalMatrix = normals;
        d.mirrored = mirrored;
        d.cullBack = !mat.doubleSided;
        d.topology = prim.topology;
        d.unlitForWantOfNormals = prim.unlitForWantOfNormals();
        d.hasColors = !prim.colors.empty();
        d.hasTexcoords = !prim.texcoords.empty();
        d.deformed = isDeformed(scene, int(ni), prim);
        d.texture = (mat.baseColorTexture >= 0 && d.hasTexcoords) ? mat.baseColorTexture : -1;
        d.features = drawFeatures(mat, d, frame.lightFeatures, frame.lighting);
        if (d.features.blend) {
            // Sort key: the eye-space depth of the primitive's bounds centre.
            Bounds local;
            if (d.deformed)
                for (const glm::dvec3& p : deformPrimitive(scene, frame.pose, int(ni), prim).positions)
                    local.extend(p);
            else
                for (const glm::vec3& p : prim.positions) local.extend(glm::dvec3(p));
            d.sortDepth = (viewFromModel * glm::dvec4(local.center(), 1.0)).z;
            blended.push_back(std::move(d));
        } else {
            opaque.push_back(std::move(d));
        }
    }
}

// Opaque draws in node order (render/ groups them by pipeline variant for the GPU), then
// blended draws far to near (most negative eye z first), which is what compositing needs.
std::vector<Draw> orderDraws(std::vector<Draw> opaque, std::vector<Draw> blended) {
    std::stable_sort(blended.begin(), blended.end(),
                     [](const Draw& a, const Draw& b) { return a.sortDepth < b.sortDepth; });
    opaque.insert(opaque.end(), std::make_move_iterator(blended.begin()),
                  std::make_move_iterator(blended.end()));
    return opaque;
}

Result<void> checkViewport(const lantern::View& v, const RenderOptions& o) {
    if (v.width <= 0 || v.height <= 0 || v.x < 0 || v.y < 0 || v.x + v.width > o.width ||
        v.y + v.height > o.height)
        return makeError(ErrorCode::InvalidInput,
                         "viewport " + std::to_string(v.x) + "," + std::to_string(v.y) + "," +
                             std::to_string(v.width) + "," + std::to_string(v.height) +
                             " is empty or outside the " + std::to_string(o.width) + "x" +
                             std::to_string(o.height) + " image",
                         "--viewport");
    return {};
}

Result<View> buildView(const Scene& scene, const Frame& frame, const RenderOptions& o,
                       const lantern::View& v, const std::string& object) {
    LANTERN_TRY(checkViewport(v, o));
    if (const auto& k = v.camera.intrinsics; k && (k->width != v.width || k->height != v.height))
        return makeError(ErrorCode::InvalidInput,
                         "the intrinsics are for a " + std::to_string(k->width) + "x" +
                             std::to_string(k->height) + " image but the view is " +
                             std::to_string(v.width) + "x" + std::to_string(v.height),
                         object.empty() ? "intrinsics" : object);
    View view;
    view.x = v.x, view.y = v.y, view.width = v.width, view.height = v.height;
    auto cam = resolveCamera(scene, frame.pose, v.camera, double(v.width) / double(v.height),
                             o.depth, object);
    if (!cam) return std::move(cam).error();
    view.camera = std::move(*cam);
    // Lights that follow the camera are placed through the camera they were fixed to.
    view.lights = placeLights(scene, frame.pose,
                              o.lightsViewFromWorld ? *o.lightsViewFromWorld
                                                    : view.camera.viewFromWorld,
                              frame.lighting.glCompat);
    std::vector<Draw> opaque, blended;
    for (std::size_t ni = 0; ni < scene.nodes.size(); ++ni)
        if (frame.pose.visible[ni] && scene.nodes[ni].mesh >= 0)
            addNodeDraws(scene, frame, ni, view.camera.viewFromWorld, opaque, blended);
    view.draws = orderDraws(std::move(opaque), std::move(blended));
    return view;
}

} // namespace

std::size_t Frame::drawCount() const {
    std::size_t n = 0;
    for (const View& v : views) n += v.draws.size();
    return n;
}

const Draw* Frame::draw(std::uint32_t index, std::size_t* view) const {
    for (std::size_t vi = 0; vi < views.size(); ++vi) {
        const std::vector<Draw>& draws = views[vi].draws;
        if (draws.empty() || index < draws.front().index || index > draws.back().index) continue;
        if (view) *view = vi;
        return &draws[index - draws.front().index];
    }
    return nullptr;
}

Result<Frame> buildFrame(const Scene& scene, const RenderOptions& o, double time) {
    if (o.root < -1 || o.root >= int(scene.roots.size()))
        return makeError(ErrorCode::InvalidInput,
                         "scene " + std::to_string(o.root) + " does not exist (the file has " +
                             std::to_string(scene.roots.size()) + " scenes)",
                         "--scene");
    if (!std::isfinite(time))
        return makeError(ErrorCode::InvalidInput, "time must be a finite number", "--time");
    Frame frame;
    frame.root = o.root < 0 ? scene.defaultRoot : o.root;
    frame.time = time;
    frame.pose = evaluatePose(scene, frame.root, time);
    frame.lighting = resolveLighting(scene, frame.root, o);
    frame.materials = frameMaterials(scene, frame.lighting.glCompat, o.unlitExact);
    // Which lights exist does not depend on the camera: place them once to learn their needs.
    bool anyLight = false;
    for (std::size_t i = 0; i < scene.nodes.size(); ++i)
        anyLight |= frame.pose.visible[i] && scene.nodes[i].light >= 0;
    frame.lightFeatures = lightFeatures(
        placeLights(scene, frame.pose, glm::dmat4(1.0), frame.lighting.glCompat), !anyLight);

    std::vector<lantern::View> views = o.views;
    if (views.empty()) views.push_back(lantern::View{0, 0, o.width, o.height, o.camera});
    std::uint32_t index = 0;
    for (std::size_t vi = 0; vi < views.size(); ++vi) {
        const std::string object = o.views.empty() ? std::string("camera")
                                                   : "view " + std::to_string(vi);
        auto view = buildView(scene, frame, o, views[vi], object);
        if (!view) return std::move(view).error();
        // Numbered across the frame, so the id AOV names a draw of any view (--probe).
        for (Draw& d : view->draws) d.index = index++;
        frame.views.push_back(std::move(*view));
    }
    frame.shadows = planShadows(scene, frame, o);
    return frame;
}

} // namespace lantern::frame
