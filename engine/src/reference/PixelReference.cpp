// Pixels explained: the ray through a pixel centre meets the triangle the renderer drew there,
// and the lighting equation is evaluated in double precision where the shading mode evaluates
// it (shaders/mesh.vert + phong.frag, pervertex.vert + pervertex.frag are the rules mirrored).
#include "reference/PixelReference.h"

#include <functional>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

namespace lantern::ref {
namespace {

// A triangle, line or point of a draw (`corners` of the three are used; the unused repeat the
// last, with weight 0).
struct Triangle {
    std::size_t corners = 3;
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

// Where a line or a point is met at the pixel centre (fx, fy) in framebuffer coordinates: a
// line at the centre's projection onto the segment in window space, its parameter made
// perspective-correct (the Vulkan rule for line attributes); a point at its vertex.
RayHit intersectLineOrPoint(const Triangle& t, const glm::dmat4& clipFromView,
                            const glm::dvec4& viewport, const glm::dvec2& centre) {
    RayHit h;
    h.barycentric = {1.0, 0.0, 0.0};
    h.point = t.eye[0];
    if (t.corners != 2) return h;
    glm::dvec2 win[2];
    double w[2];
    for (int c = 0; c < 2; ++c) {
        const glm::dvec4 clip = clipFromView * glm::dvec4(t.eye[c], 1.0);
        w[c] = clip.w;
        win[c] = {viewport.x + (clip.x / clip.w + 1.0) * 0.5 * viewport.z,
                  viewport.y + (clip.y / clip.w + 1.0) * 0.5 * viewport.w};
    }
    const glm::dvec2 d = win[1] - win[0];
    const double len2 = glm::dot(d, d);
    double s = len2 > 0.0 && std::isfinite(len2) ? glm::dot(centre - win[0], d) / len2 : 0.0;
    s = std::clamp(std::isfinite(s) ? s : 0.0, 0.0, 1.0);
    double u = s;
    if (w[0] > 0.0 && w[1] > 0.0) u = (s / w[1]) / ((1.0 - s) / w[0] + s / w[1]);
    h.barycentric = {1.0 - u, u, 0.0};
    h.point = t.eye[0] * (1.0 - u) + t.eye[1] * u;
    return h;
}

template <class T> T interpolate(const glm::dvec3& b, const T& a0, const T& a1, const T& a2) {
    return a0 * b.x + a1 * b.y + a2 * b.z;
}

bool nonZero(const glm::dvec3& v) { return v.x != 0.0 || v.y != 0.0 || v.z != 0.0; }

// Which terms of the equation apply to a primitive, decided from the scene's data (its
// material, its vertex streams) and the frame's lighting switches, never from a pipeline.
struct DrawRules {
    Settings settings;
    bool vertexColor = false;
    bool colorScales = false; ///< COLOR_0 scales (unlit, PBR-mapped) instead of replacing
    bool ambientFollowsDiffuse = false;
    bool glClamp = false, fragmentClamp = false;
    bool opaque = true;
    bool twoSided = false;
    bool textured = false;
};

DrawRules rulesOf(const Material& mat, const Primitive& prim, const frame::Lighting& lit) {
    DrawRules r;
    r.settings.globalAmbient = lit.model.globalAmbient;
    r.settings.localViewer = lit.model.localViewer;
    r.settings.specular = lit.model.specular;
    const bool unlit = mat.unlit || prim.unlitForWantOfNormals();
    r.settings.unlit = unlit;
    r.vertexColor = !prim.colors.empty();
    r.colorScales = unlit || mat.ambientFollowsDiffuse;
    r.ambientFollowsDiffuse = mat.ambientFollowsDiffuse;
    r.glClamp = lit.clamp == frame::Clamp::Gl;
    r.fragmentClamp = lit.clamp != frame::Clamp::None;
    r.opaque = mat.alphaMode != AlphaMode::Blend;
    r.twoSided = frame::twoSidedLighting(lit, mat);
    r.textured = (mat.baseColorTexture >= 0 || frame::materialMaps(mat) != 0) &&
                 !prim.texcoords.empty();
    return r;
}

// One light's exact shadow at a point (the probe's shadow ray).
struct Shadow {
    bool casts = false;
    double visibility = 1.0;
    int occluder = -1;  ///< node
};

// Whether the segment origin + t dir, tMin < t < tMax, crosses triangle (a, b, c)
// (Moller-Trumbore, both faces).
bool crosses(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
             const glm::dvec3& origin, const glm::dvec3& dir, double tMin, double tMax) {
    const glm::dvec3 e1 = b - a, e2 = c - a, p = glm::cross(dir, e2);
    const double det = glm::dot(e1, p);
    if (det == 0.0 || !std::isfinite(det)) return false;
    const glm::dvec3 s = origin - a;
    const double u = glm::dot(s, p) / det;
    if (!(u >= 0.0 && u <= 1.0)) return false;
    const glm::dvec3 q = glm::cross(s, e1);
    const double v = glm::dot(dir, q) / det;
    if (!(v >= 0.0 && u + v <= 1.0)) return false;
    const double t = glm::dot(e2, q) / det;
    return t > tMin && t < tMax;
}

// One evaluation of the equation (evaluateLighting + materialColours + splitColour).
ProbeEvaluation evaluate(const std::string& where, double weight, const glm::dvec3& V,
                         const glm::dvec3& n, const MaterialSide& side,
                         const glm::dvec4* vertexColor, const std::vector<EyeLight>& lights,
                         const DrawRules& rules, bool perLight, const std::vector<Shadow>& shadows) {
    ProbeEvaluation e;
    e.where = where;
    e.weight = weight;
    e.position = V;
    e.normal = n;
    std::vector<LightContribution> terms;
    std::vector<double> visibility;
    for (const Shadow& sh : shadows) visibility.push_back(sh.visibility);
    const LightSums sums = evaluateLighting(V, n, side, lights, rules.settings,
                                            perLight ? &terms : nullptr,
                                            shadows.empty() ? nullptr : &visibility);
    const MaterialColours mc = materialColours(side, vertexColor, rules.colorScales);
    e.ambientM = mc.ambient;
    e.diffuseM = mc.diffuse;
    e.alpha = mc.alpha;
    if (!rules.settings.unlit) {
        e.emission = side.emission;
        e.globalAmbient = mc.ambient * rules.settings.globalAmbient;
    }
    for (std::size_t i = 0; i < terms.size(); ++i) {
        const LightContribution& c = terms[i];
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
        if (i < shadows.size()) {
            p.castsShadows = shadows[i].casts;
            p.visibility = shadows[i].visibility;
            p.occluderNode = shadows[i].occluder;
        }
        e.lights.push_back(std::move(p));
    }
    const SplitColour split =
        splitColour(sums, mc.ambient, mc.diffuse, rules.ambientFollowsDiffuse, rules.glClamp);
    e.colour = split.base + split.textured; // a white texel
    return e;
}

} // namespace

PixelReference::PixelReference(const Scene& scene, const frame::Frame& frame, int imageHeight)
    : m_scene(scene), m_frame(frame), m_imageHeight(imageHeight) {}

const DeformedPrimitive& PixelReference::deformed(const frame::Draw& d) const {
    std::lock_guard lock(m_mutex);
    const auto key = std::pair{d.node, d.primitive};
    auto it = m_deformed.find(key);
    if (it == m_deformed.end()) {
        const Primitive& prim = m_scene.meshes[d.mesh].primitives[d.primitive];
        it = m_deformed.emplace(key, deformPrimitive(m_scene, m_frame.pose, int(d.node), prim)).first;
    }
    return it->second;
}

namespace {

// A draw's vertices in its model space: the primitive's own, or as the pose deforms them.
struct Vertices {
    const Primitive& prim;
    const DeformedPrimitive* deformed = nullptr;
    glm::dvec3 position(std::uint32_t v) const {
        return deformed ? deformed->positions[v] : glm::dvec3(prim.positions[v]);
    }
    glm::dvec3 normal(std::uint32_t v) const {
        if (deformed) return deformed->normals[v];
        return prim.normals.empty() ? glm::dvec3(0.0) : glm::dvec3(prim.normals[v]);
    }
};

// The triangle, line or point a draw drew, in the draw's eye space.
Triangle eyeTriangle(const Vertices& vs, const frame::Draw& d, std::uint32_t element) {
    const Primitive& prim = vs.prim;
    Triangle t;
    t.corners = prim.verticesPerElement();
    for (std::size_t c = 0; c < 3; ++c) {
        const std::size_t i = element * t.corners + std::min(c, t.corners - 1);
        const std::uint32_t v = prim.indices.empty() ? std::uint32_t(i) : prim.indices[i];
        t.vertices[c] = v;
        t.eye[c] = glm::dvec3(d.viewFromModel * glm::dvec4(vs.position(v), 1.0));
        t.normal[c] = d.normalMatrix * vs.normal(v);
    }
    return t;
}

// The node of the first opaque triangle the view draws that crosses the shadow ray from V, or
// -1. Blended draws, lines and points cast none, as with the maps (gpu/Shadows.h).
int firstOccluder(const Scene& scene, const frame::View& view, const glm::dvec3& V,
                  const ShadowRay& ray, double tMin,
                  const std::function<const DeformedPrimitive&(const frame::Draw&)>& deformed) {
    for (const frame::Draw& d : view.draws) {
        if (d.features.blend || d.topology != Topology::Triangles) continue;
        const Primitive& prim = scene.meshes[d.mesh].primitives[d.primitive];
        const Vertices vs{prim, d.deformed ? &deformed(d) : nullptr};
        for (std::uint32_t k = 0; k < prim.elementCount(); ++k) {
            const Triangle t = eyeTriangle(vs, d, k);
            if (crosses(t.eye[0], t.eye[1], t.eye[2], V, ray.dir, tMin, ray.tMax)) return int(d.node);
        }
    }
    return -1;
}

// The exact shadow of each light of view `vi` at eye-space point V: for a light that casts
// shadows in the frame, its shadow rays (ref::shadowRays: one segment towards it, unbounded
// towards a directional light, or a light disc's under PCSS) against every opaque triangle the
// view draws; the visibility is the share of rays that get through, and the first occluder
// met names its node. Empty when no light casts.
std::vector<Shadow> exactShadows(const Scene& scene, const frame::Frame& frame, std::size_t vi,
                                 const glm::dvec3& V,
                                 const std::function<const DeformedPrimitive&(const frame::Draw&)>& deformed) {
    std::vector<Shadow> out;
    const frame::View& view = frame.views[vi];
    if (!frame.shadows.any()) return out;
    out.resize(view.lights.size());
    for (std::size_t i = 0; i < view.lights.size() && i < frame.shadows.firstMap.size(); ++i) {
        if (frame.shadows.firstMap[i] < 0) continue;
        const EyeLight& l = view.lights[i];
        Shadow& sh = out[i];
        sh.casts = true;
        const bool directional = l.type == LightType::Directional;
        // Off the point's own surface: a millionth of the way to the light (of |V| for a
        // directional light).
        const double tMin = directional ? 1e-6 * (1.0 + glm::length(V)) : 1e-6;
        const std::vector<ShadowRay> rays = shadowRays(l, V, frame.shadows.options);
        int blocked = 0;
        for (const ShadowRay& ray : rays) {
            const int node = firstOccluder(scene, view, V, ray, tMin, deformed);
            if (node < 0) continue;
            ++blocked;
            if (sh.occluder < 0) sh.occluder = node;
        }
        sh.visibility = 1.0 - double(blocked) / double(rays.size());
    }
    return out;
}

// The ray through pixel (x, y)'s centre in eye space: two depths of the centre unprojected
// through the view's viewport (Vulkan framebuffer: origin top-left; the view's rectangle is
// GL's, origin bottom-left).
void pixelRay(const frame::View& view, int imageHeight, int x, int y, glm::dvec3& origin,
              glm::dvec3& dir) {
    const double fx = x + 0.5, fy = y + 0.5;
    const double top = double(imageHeight - view.y - view.height);
    const double nx = (fx - view.x) / view.width * 2.0 - 1.0;
    const double ny = (fy - top) / view.height * 2.0 - 1.0;
    const glm::dmat4 viewFromClip = glm::inverse(view.camera.clipFromView);
    auto unproject = [&](double depth) {
        const glm::dvec4 p = viewFromClip * glm::dvec4(nx, ny, depth, 1.0);
        return glm::dvec3(p) / p.w;
    };
    origin = unproject(0.25);
    dir = glm::normalize(unproject(0.75) - origin);
    if (dir.z > 0.0) dir = -dir;  // every GL camera looks down -Z
}

// Evaluates the equation where the frame's shading rule evaluates it, appending to r.
struct RuleEvaluator {
    const Primitive& prim;
    const Vertices& vertices;
    const frame::Draw& draw;
    const Triangle& t;
    const RayHit& hit;
    const DrawRules& rules;
    const std::vector<EyeLight>& lights;
    bool perLight;
    double sign;  ///< -1 when the back material (and the negated normal) is used
    /// The lights' exact shadows at a point (null: no light casts).
    std::function<std::vector<Shadow>(const glm::dvec3&)> shadows;

    glm::dvec4 colorAt(std::uint32_t v) const { return glm::dvec4(prim.colors[v]); }
    void add(ProbeReport& r, const std::string& where, double weight, const glm::dvec3& point,
             const glm::dvec3& normal, const glm::dvec4& color) const {
        r.evaluations.push_back(evaluate(where, weight, point, normal, r.materialSide,
                                         rules.vertexColor ? &color : nullptr, lights, rules,
                                         perLight, shadows ? shadows(point) : std::vector<Shadow>{}));
    }
    void perFragment(ProbeReport& r) const {
        const glm::dvec3& bc = hit.barycentric;
        const glm::dvec4 color = rules.vertexColor ? interpolate(bc, colorAt(t.vertices[0]),
                                                                 colorAt(t.vertices[1]),
                                                                 colorAt(t.vertices[2]))
                                                   : glm::dvec4(1.0);
        add(r, "surface point", 1.0, hit.point, r.normal, color);
    }
    void perVertex(ProbeReport& r) const {
        for (std::size_t c = 0; c < t.corners; ++c)
            add(r, "vertex " + std::to_string(t.vertices[c]), hit.barycentric[int(c)], t.eye[c],
                sign * safeNormalize(t.normal[c]), rules.vertexColor ? colorAt(t.vertices[c]) : glm::dvec4(1.0));
    }
    // GL_FLAT: the whole element takes the colour lit at its provoking (last) vertex.
    void provokingVertex(ProbeReport& r) const {
        const std::size_t last = t.corners - 1;
        const std::uint32_t v = t.vertices[last];
        add(r, "provoking vertex " + std::to_string(v), 1.0, t.eye[last],
            sign * safeNormalize(t.normal[last]), rules.vertexColor ? colorAt(v) : glm::dvec4(1.0));
    }
    // At the centroid with the face normal (a line's or a point's: the normalised mean of its
    // vertex normals), from the object-space data as the flat streams are built
    // (gpu/SceneBuffers.cpp, flatElement); COLOR_0 averaged.
    void faceCentroid(ProbeReport& r) const {
        glm::dvec3 p[3], sum(0.0), normals(0.0);
        glm::dvec4 colors(0.0);
        for (std::size_t c = 0; c < t.corners; ++c) {
            p[c] = vertices.position(t.vertices[c]);
            sum += p[c];
            normals += vertices.normal(t.vertices[c]);
            if (rules.vertexColor) colors += colorAt(t.vertices[c]);
        }
        const double k = double(t.corners);
        if (t.corners == 3) normals = glm::cross(p[1] - p[0], p[2] - p[0]);
        const double len = glm::length(normals);
        const glm::dvec3 face = (len > 0.0 && std::isfinite(len)) ? normals / len : glm::dvec3(0.0);
        const glm::dvec3 centroid = glm::dvec3(draw.viewFromModel * glm::dvec4(sum / k, 1.0));
        r.normal = sign * safeNormalize(draw.normalMatrix * face);
        const glm::dvec4 color = rules.vertexColor ? colors / k : glm::dvec4(1.0);
        const char* what[] = {"", "point", "line midpoint", "triangle centroid"};
        add(r, what[t.corners], 1.0, centroid, r.normal, color);
    }
    void evaluateAll(ProbeReport& r, frame::Program program) const {
        switch (program) {
        case frame::Program::Phong: perFragment(r); break;
        case frame::Program::Gouraud: perVertex(r); break;
        case frame::Program::GlFlat: provokingVertex(r); break;
        case frame::Program::Flat: faceCentroid(r); break;
        case frame::Program::Floor:
            // The floor's constant white is not the equation: there is nothing to evaluate.
            r.evaluations.push_back(ProbeEvaluation{"floor (constant white, unlit)", 1.0});
            r.evaluations.back().colour = glm::dvec3(1.0);
            break;
        }
    }
};

// The pixel's colour and alpha: its evaluations weighted, clamped as the frame clamps.
void sumEvaluations(ProbeReport& r, const DrawRules& rules) {
    glm::dvec3 colour(0.0);
    double alpha = 0.0;
    for (const ProbeEvaluation& e : r.evaluations) {
        colour += e.weight * e.colour;
        alpha += e.weight * e.alpha;
    }
    if (rules.fragmentClamp) colour = glm::clamp(colour, 0.0, 1.0);
    r.materialAlpha = alpha;
    r.colour = glm::dvec4(colour, rules.opaque ? 1.0 : alpha);
}

void describeSwitches(ProbeReport& r, const frame::Lighting& lit) {
    r.shading = lit.model.shading;
    r.specular = lit.model.specular;
    r.localViewer = lit.model.localViewer;
    r.twoSided = lit.model.twoSided.value_or(false);
    r.glCompat = lit.glCompat;
    r.clamped = lit.clamp != frame::Clamp::None;
}

} // namespace

ProbeReport PixelReference::explain(int x, int y, std::uint32_t drawId, std::uint32_t triangle,
                                    bool perLight) const {
    const frame::Lighting& lit = m_frame.lighting;
    ProbeReport r;
    r.x = x;
    r.y = y;
    describeSwitches(r, lit);
    std::size_t vi = 0;
    const frame::Draw* d = drawId == 0 ? nullptr : m_frame.draw(drawId - 1, &vi);
    if (!d) return r;
    const Primitive& prim = m_scene.meshes[d->mesh].primitives[d->primitive];
    if (triangle >= prim.elementCount()) return r;
    const frame::View& view = m_frame.views[vi];
    // The material as the scene gives it to the primitive (GL's limits applied by the frame).
    const std::size_t materialIndex =
        prim.material >= 0 ? std::size_t(prim.material) : m_scene.materials.size();
    const Material& mat = m_frame.materials[materialIndex];
    const DrawRules rules = rulesOf(mat, prim, lit);

    const Vertices vertices{prim, d->deformed ? &deformed(*d) : nullptr};
    const Triangle t = eyeTriangle(vertices, *d, triangle);
    glm::dvec3 origin, dir;
    pixelRay(view, m_imageHeight, x, y, origin, dir);
    const double top = double(m_imageHeight - view.y - view.height);
    const RayHit hit =
        t.corners == 3
            ? intersect(t, origin, dir)
            : intersectLineOrPoint(t, view.camera.clipFromView,
                                   glm::dvec4(view.x, top, view.width, view.height),
                                   glm::dvec2(x + 0.5, y + 0.5));

    r.hit = true;
    r.view = int(vi);
    r.node = int(d->node);
    r.nodeName = m_scene.nodes[d->node].name;
    r.mesh = int(d->mesh);
    r.primitive = int(d->primitive);
    r.topology = prim.topology;
    r.triangle = triangle;
    for (std::size_t c = 0; c < 3; ++c) r.vertices[c] = t.vertices[c];
    r.barycentric = hit.barycentric;
    r.position = hit.point;
    // A mirroring transform makes clockwise triangles the front ones (glTF's rule).
    // Lines and points are always front-facing (Vulkan and GL).
    r.backFacing = t.corners == 3 && (d->mirrored ? hit.counterClockwise : !hit.counterClockwise);
    r.twoSided = rules.twoSided;
    r.backMaterial = r.backFacing && rules.twoSided;
    const double sign = r.backMaterial ? -1.0 : 1.0;
    r.material = prim.material;
    r.materialName = mat.name;
    r.materialSide = r.backMaterial && mat.back ? *mat.back : mat.front;
    r.unlit = rules.settings.unlit;
    r.textured = rules.textured;
    bool lightSpecular = false;
    for (const EyeLight& l : view.lights) lightSpecular |= nonZero(l.specular);
    r.specularPresent = !r.unlit && lightSpecular && nonZero(r.materialSide.specular);
    r.normal = sign * safeNormalize(interpolate(hit.barycentric, t.normal[0], t.normal[1], t.normal[2]));

    RuleEvaluator evaluator{prim, vertices, *d, t, hit, rules, view.lights, perLight, sign, {}};
    if (m_frame.shadows.any())
        evaluator.shadows = [this, vi](const glm::dvec3& V) {
            return exactShadows(m_scene, m_frame, vi, V,
                                [this](const frame::Draw& other) -> const DeformedPrimitive& {
                                    return deformed(other);
                                });
        };
    evaluator.evaluateAll(r, lit.program);
    for (ProbeEvaluation& e : r.evaluations)
        for (ProbeLight& l : e.lights)
            if (l.occluderNode >= 0) l.occluderName = m_scene.nodes[std::size_t(l.occluderNode)].name;

    sumEvaluations(r, rules);
    return r;
}

ProbeReport probePixel(const Scene& scene, const frame::Frame& frame, const Image& image,
                       const std::vector<std::uint32_t>& ids, int x, int y) {
    const PixelReference reference(scene, frame, image.height);
    const std::size_t i = std::size_t(y) * std::size_t(image.width) + std::size_t(x);
    ProbeReport r = reference.explain(x, y, ids[i * 2], ids[i * 2 + 1]);
    const float* px = image.pixel(x, y);
    r.pixel = glm::dvec4(px[0], px[1], px[2], px[3]);
    return r;
}

} // namespace lantern::ref
