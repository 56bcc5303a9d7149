// Pixels explained: the ray through a pixel centre meets the triangle the renderer drew there,
// and the lighting equation is evaluated in double precision where the shading mode evaluates
// it (shaders/mesh.vert + phong.frag, pervertex.vert + pervertex.frag are the rules mirrored).
#include "render/Probe.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

namespace lantern::render {
namespace {

struct Triangle {
    std::uint32_t vertices[3] = {};
    glm::dvec3 eye[3];    ///< eye-space positions
    glm::dvec3 normal[3]; ///< normal matrix times the vertex normal (not normalised)
};

// Where the ray through the pixel centre meets the triangle's plane, with the perspective-
// correct barycentrics the rasteriser interpolates with (the eye-space barycentrics of that
// point), and whether the triangle faces the ray (counter-clockwise as seen).
struct RayHit {
    glm::dvec3 point{0.0};
    glm::dvec3 barycentric{1.0 / 3.0};
    bool counterClockwise = true;
};

RayHit intersect(const Triangle& t, const glm::dvec3& origin, const glm::dvec3& dir) {
    RayHit h;
    const glm::dvec3 e1 = t.eye[1] - t.eye[0], e2 = t.eye[2] - t.eye[0];
    h.counterClockwise = glm::dot(glm::cross(e1, e2), dir) < 0.0;
    const glm::dvec3 p = glm::cross(dir, e2);
    const double det = glm::dot(e1, p);
    if (det == 0.0 || !std::isfinite(det)) { // seen edge-on: it covers no pixel centre
        h.point = (t.eye[0] + t.eye[1] + t.eye[2]) / 3.0;
        return h;
    }
    const glm::dvec3 s = origin - t.eye[0];
    const glm::dvec3 q = glm::cross(s, e1);
    const double u = glm::dot(s, p) / det, w = glm::dot(dir, q) / det;
    h.barycentric = {1.0 - u - w, u, w};
    h.point = t.eye[0] * h.barycentric.x + t.eye[1] * h.barycentric.y + t.eye[2] * h.barycentric.z;
    return h;
}

template <class T> T interpolate(const glm::dvec3& b, const T& a0, const T& a1, const T& a2) {
    return a0 * b.x + a1 * b.y + a2 * b.z;
}

// The draw's feature switches, read from its specialisation constants so that the reference
// follows exactly what the pipeline compiled.
struct DrawRules {
    ref::Settings settings;
    bool vertexColour = false;
    bool colourScales = false; ///< COLOR_0 scales (unlit, PBR-mapped) instead of replacing
    bool ambientFollowsDiffuse = false;
    bool glClamp = false, fragmentClamp = false;
    bool opaque = true;
    bool twoSided = false;
};

DrawRules rulesOf(const DrawItem& d, const ResolvedLighting& lit) {
    const auto& sc = d.key.constants;
    DrawRules r;
    r.settings.globalAmbient = lit.model.globalAmbient;
    r.settings.localViewer = sc[LANTERN_SC_LOCAL_VIEWER] != 0;
    r.settings.specular = sc[LANTERN_SC_SPECULAR] == LANTERN_SPECULAR_PHONG ? SpecularModel::Phong
                                                                            : SpecularModel::Blinn;
    r.settings.specularOn = sc[LANTERN_SC_SPECULAR] != LANTERN_SPECULAR_NONE;
    r.settings.unlit = sc[LANTERN_SC_UNLIT] != 0;
    r.vertexColour = sc[LANTERN_SC_VERTEX_COLOR] != 0 && d.hasColors;
    r.colourScales = sc[LANTERN_SC_UNLIT] != 0 || sc[LANTERN_SC_AMBIENT_FOLLOWS_DIFFUSE] != 0;
    r.ambientFollowsDiffuse = sc[LANTERN_SC_AMBIENT_FOLLOWS_DIFFUSE] != 0;
    r.glClamp = sc[LANTERN_SC_CLAMP] == LANTERN_CLAMP_GL;
    r.fragmentClamp = sc[LANTERN_SC_CLAMP] != LANTERN_CLAMP_NONE;
    r.opaque = sc[LANTERN_SC_OPAQUE] != 0;
    r.twoSided = sc[LANTERN_SC_TWO_SIDED] != 0;
    return r;
}

// One evaluation of the equation (evaluateLighting + materialColours + splitColour).
ProbeEvaluation evaluate(const std::string& where, double weight, const glm::dvec3& V,
                         const glm::dvec3& n, const MaterialSide& side,
                         const glm::dvec4* vertexColour, const std::vector<ref::EyeLight>& lights,
                         const DrawRules& rules, bool perLight) {
    ProbeEvaluation e;
    e.where = where;
    e.weight = weight;
    e.position = V;
    e.normal = n;
    std::vector<ref::LightContribution> terms;
    const ref::LightSums sums =
        ref::evaluateLighting(V, n, side, lights, rules.settings, perLight ? &terms : nullptr);
    const ref::MaterialColours mc = ref::materialColours(side, vertexColour, rules.colourScales);
    e.ambientM = mc.ambient;
    e.diffuseM = mc.diffuse;
    e.alpha = mc.alpha;
    if (!rules.settings.unlit) {
        e.emission = side.emission;
        e.globalAmbient = mc.ambient * rules.settings.globalAmbient;
    }
    for (std::size_t i = 0; i < terms.size(); ++i) {
        const ref::LightContribution& c = terms[i];
        ProbeLight p;
        p.name = lights[i].name;
        p.type = lights[i].type;
        p.attenuation = c.attenuation;
        p.spot = c.spot;
        p.nDotL = c.nDotL;
        p.specularTerm = c.specularTerm;
        p.ambient = c.ambient * mc.ambient;
        p.diffuse = c.diffuse * mc.diffuse;
        p.specular = c.specular;
        e.lights.push_back(std::move(p));
    }
    const ref::SplitColour split =
        ref::splitColour(sums, mc.ambient, mc.diffuse, rules.ambientFollowsDiffuse, rules.glClamp);
    e.colour = split.base + split.textured; // a white texel
    return e;
}

} // namespace

PixelReference::PixelReference(const Scene& scene, const FramePlan& plan,
                               const RenderOptions& options)
    : m_scene(scene), m_plan(plan), m_imageHeight(options.height) {
    for (std::size_t vi = 0; vi < plan.views.size(); ++vi) {
        m_lights.push_back(ref::eyeLights(scene, plan.pose, plan.views[vi].camera.viewFromWorld,
                                          plan.lighting.glCompat));
        for (std::size_t di = 0; di < plan.views[vi].draws.size(); ++di) {
            const std::uint32_t index = plan.views[vi].draws[di].block.drawIndex;
            if (m_draws.size() <= index) m_draws.resize(index + 1, {~std::size_t(0), 0});
            m_draws[index] = {vi, di};
        }
    }
}

const DrawItem* PixelReference::draw(std::uint32_t drawIndex, std::size_t* view) const {
    if (drawIndex >= m_draws.size() || m_draws[drawIndex].first == ~std::size_t(0)) return nullptr;
    const auto [vi, di] = m_draws[drawIndex];
    if (view) *view = vi;
    return &m_plan.views[vi].draws[di];
}

ProbeReport PixelReference::explain(int x, int y, std::uint32_t drawId, std::uint32_t triangle,
                                    bool perLight) const {
    const ResolvedLighting& lit = m_plan.lighting;
    ProbeReport r;
    r.x = x;
    r.y = y;
    r.shading = lit.model.shading;
    r.specular = lit.model.specular;
    r.localViewer = lit.model.localViewer;
    r.twoSided = lit.model.twoSided;
    r.glCompat = lit.glCompat;
    r.clamped = lit.clamp != LANTERN_CLAMP_NONE;
    std::size_t vi = 0;
    const DrawItem* d = drawId == 0 ? nullptr : draw(drawId - 1, &vi);
    if (!d) return r;
    const Primitive& prim = m_scene.meshes[d->mesh].primitives[d->primitive];
    if (triangle >= prim.triangleCount()) return r;
    const ViewPlan& view = m_plan.views[vi];
    const DrawRules rules = rulesOf(*d, lit);

    Triangle t;
    const glm::dmat3 normals = normalMatrix(d->viewFromModel);
    for (int c = 0; c < 3; ++c) {
        const std::uint32_t v =
            prim.indices.empty() ? std::uint32_t(triangle * 3 + c) : prim.indices[triangle * 3 + c];
        t.vertices[c] = v;
        t.eye[c] = glm::dvec3(d->viewFromModel * glm::dvec4(glm::dvec3(prim.positions[v]), 1.0));
        t.normal[c] = normals * glm::dvec3(prim.normals[v]);
    }

    // The pixel centre's ray in eye space: unproject two depths of the centre through this
    // view's viewport (Vulkan framebuffer: origin top-left; the view's rectangle is GL's).
    const double fx = x + 0.5, fy = y + 0.5;
    const double top = double(m_imageHeight - view.y - view.height);
    const double nx = (fx - view.x) / view.width * 2.0 - 1.0;
    const double ny = (fy - top) / view.height * 2.0 - 1.0;
    const glm::dmat4 viewFromClip = glm::inverse(view.camera.clipFromView);
    auto unproject = [&](double depth) {
        const glm::dvec4 p = viewFromClip * glm::dvec4(nx, ny, depth, 1.0);
        return glm::dvec3(p) / p.w;
    };
    const glm::dvec3 a = unproject(0.25), b = unproject(0.75);
    glm::dvec3 dir = glm::normalize(b - a);
    if (dir.z > 0.0) dir = -dir; // every GL camera looks down -Z
    const RayHit hit = intersect(t, a, dir);

    r.hit = true;
    r.view = int(vi);
    r.node = int(d->node);
    r.nodeName = m_scene.nodes[d->node].name;
    r.mesh = int(d->mesh);
    r.primitive = int(d->primitive);
    r.triangle = triangle;
    for (int c = 0; c < 3; ++c)
        r.vertices[c] = t.vertices[c];
    r.barycentric = hit.barycentric;
    r.position = hit.point;
    // A mirroring transform makes clockwise triangles the front ones (Engine::record).
    r.backFacing = d->mirrored ? hit.counterClockwise : !hit.counterClockwise;
    r.backMaterial = r.backFacing && rules.twoSided;
    const double sign = r.backMaterial ? -1.0 : 1.0;

    static const Material kDefaultMaterial;
    const Material& mat = prim.material >= 0 ? m_scene.materials[prim.material] : kDefaultMaterial;
    r.material = prim.material;
    r.materialName = mat.name;
    r.materialSide = r.backMaterial && mat.back ? *mat.back : mat.front;
    if (lit.glCompat) r.materialSide.shininess = std::clamp(r.materialSide.shininess, 0.0, 128.0);
    r.unlit = rules.settings.unlit;
    r.textured = d->texture >= 0;
    r.specularPresent = rules.settings.specularOn;

    const std::vector<ref::EyeLight>& lights = m_lights[vi];
    auto colourAt = [&](std::uint32_t v) -> glm::dvec4 { return glm::dvec4(prim.colors[v]); };
    const glm::dvec3& bc = hit.barycentric;
    r.normal = sign * ref::safeNormalize(interpolate(bc, t.normal[0], t.normal[1], t.normal[2]));

    switch (d->key.program) {
    case Program::Phong: {
        glm::dvec4 colour(1.0);
        if (rules.vertexColour)
            colour = interpolate(bc, colourAt(t.vertices[0]), colourAt(t.vertices[1]),
                                 colourAt(t.vertices[2]));
        r.evaluations.push_back(evaluate("surface point", 1.0, hit.point, r.normal, r.materialSide,
                                         rules.vertexColour ? &colour : nullptr, lights, rules,
                                         perLight));
        break;
    }
    case Program::Gouraud:
        for (int c = 0; c < 3; ++c) {
            const glm::dvec4 colour =
                rules.vertexColour ? colourAt(t.vertices[c]) : glm::dvec4(1.0);
            r.evaluations.push_back(evaluate("vertex " + std::to_string(t.vertices[c]), bc[c],
                                             t.eye[c], sign * ref::safeNormalize(t.normal[c]),
                                             r.materialSide, rules.vertexColour ? &colour : nullptr,
                                             lights, rules, perLight));
        }
        break;
    case Program::GlFlat: {
        // GL_FLAT: the whole triangle takes the colour lit at its provoking (last) vertex.
        const std::uint32_t v = t.vertices[2];
        const glm::dvec4 colour = rules.vertexColour ? colourAt(v) : glm::dvec4(1.0);
        r.evaluations.push_back(evaluate("provoking vertex " + std::to_string(v), 1.0, t.eye[2],
                                         sign * ref::safeNormalize(t.normal[2]), r.materialSide,
                                         rules.vertexColour ? &colour : nullptr, lights, rules,
                                         perLight));
        break;
    }
    case Program::Floor:
        // The floor's constant white is not the equation: there is nothing to evaluate.
        r.evaluations.push_back(ProbeEvaluation{"floor (constant white, unlit)", 1.0});
        r.evaluations.back().colour = glm::dvec3(1.0);
        break;
    case Program::Flat: {
        // At the centroid with the face normal, both from the object-space positions as the
        // flat streams are built (render/GpuScene.cpp); COLOR_0 averaged.
        glm::dvec3 p[3];
        for (int c = 0; c < 3; ++c)
            p[c] = glm::dvec3(prim.positions[t.vertices[c]]);
        const glm::dvec3 cross = glm::cross(p[1] - p[0], p[2] - p[0]);
        const double len = glm::length(cross);
        const glm::dvec3 face = (len > 0.0 && std::isfinite(len)) ? cross / len : glm::dvec3(0.0);
        const glm::dvec3 centroid =
            glm::dvec3(d->viewFromModel * glm::dvec4((p[0] + p[1] + p[2]) / 3.0, 1.0));
        r.normal = sign * ref::safeNormalize(normals * face);
        glm::dvec4 colour(1.0);
        if (rules.vertexColour)
            colour =
                (colourAt(t.vertices[0]) + colourAt(t.vertices[1]) + colourAt(t.vertices[2])) / 3.0;
        r.evaluations.push_back(evaluate("triangle centroid", 1.0, centroid, r.normal,
                                         r.materialSide, rules.vertexColour ? &colour : nullptr,
                                         lights, rules, perLight));
        break;
    }
    }

    glm::dvec3 colour(0.0);
    double alpha = 0.0;
    for (const ProbeEvaluation& e : r.evaluations) {
        colour += e.weight * e.colour;
        alpha += e.weight * e.alpha;
    }
    if (rules.fragmentClamp) colour = glm::clamp(colour, 0.0, 1.0);
    r.materialAlpha = alpha;
    r.colour = glm::dvec4(colour, rules.opaque ? 1.0 : alpha);
    return r;
}

ProbeReport probePixel(const Scene& scene, const ExplainedFrame& f, int x, int y) {
    const PixelReference reference(scene, f.plan, f.options);
    const std::size_t i = std::size_t(y) * std::size_t(f.frame.image.width) + std::size_t(x);
    ProbeReport r = reference.explain(x, y, f.frame.ids[i * 2], f.frame.ids[i * 2 + 1]);
    const float* px = f.frame.image.pixel(x, y);
    r.pixel = glm::dvec4(px[0], px[1], px[2], px[3]);
    return r;
}

} // namespace lantern::render
