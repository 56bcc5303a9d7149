// The reference ray caster: exact spheres and planes in double precision, the renderer's own
// camera resolution and light placement, and the lighting equation of reference/Lighting
// (the shaders' twin) at every sample, with blended layers composited in exact depth order and
// (when asked) exact shadow rays. Ground truth for the accuracy benchmark.
#include "frame/Frame.h"
#include "reference/Lighting.h"
#include "reference/SurfaceTexture.h"
#include "reference/Torus.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <lantern/Reference.h>
#include <limits>
#include <string>
#include <thread>

namespace lantern {

AnalyticShape AnalyticShape::sphere(int mesh, double radius) {
    return AnalyticShape{mesh, AnalyticKind::Sphere, radius, 2.0};
}

AnalyticShape AnalyticShape::plane(int mesh, double size) {
    return AnalyticShape{mesh, AnalyticKind::Plane, 1.0, size};
}

AnalyticShape AnalyticShape::torus(int mesh, double ringRadius, double tubeRadius) {
    return AnalyticShape{mesh, AnalyticKind::Torus, ringRadius, tubeRadius};
}

Primitive tessellate(const AnalyticShape& shape, int segments) {
    if (shape.kind == AnalyticKind::Plane) return makePlane(shape.size, std::max(segments, 1));
    segments = std::max(segments, 3);
    if (shape.kind == AnalyticKind::Torus)
        return ref::makeTorus(shape.radius, shape.size, segments, std::max(3, segments / 2));
    return makeSphere(shape.radius, segments, std::max(2, segments / 2));
}

namespace {

constexpr double kNoHit = std::numeric_limits<double>::infinity();

// One placed analytic surface: the shape, where it is, and how it is drawn.
struct Surface {
    AnalyticShape shape;
    glm::dmat4 modelFromView{1.0};
    glm::dmat3 normalFromModel{1.0}; // eye-space normals, up to length (normalMatrix())
    const Material* material = nullptr;
    const Texture* texture = nullptr; // the base colour's, sampled nearest; null: none
};

struct Ray {
    glm::dvec3 origin{0.0};    // on the near plane, eye space
    glm::dvec3 direction{0.0}; // not normalised: t = 1 reaches the mid-depth plane
};

struct Hit {
    double t = kNoHit;
    int surface = -1;
    glm::dvec3 point{0.0};  // eye space
    glm::dvec3 normal{0.0}; // unit, eye space, the surface's outward (front) side
    bool front = true;
    glm::dvec4 texel{1.0};  // the base-colour texel there (linear; white without a texture)
};

// Both roots of |o + t d|^2 = r^2 in ascending order (NaN-free); false without real roots.
bool sphereRoots(const glm::dvec3& o, const glm::dvec3& d, double r, double roots[2]) {
    const double a = glm::dot(d, d), b = glm::dot(o, d), c = glm::dot(o, o) - r * r;
    const double disc = b * b - a * c;
    if (!(disc >= 0.0) || !(a > 0.0)) return false;
    // The stable pair: q never cancels, t1 = q / a and t2 = c / q.
    const double q = -(b + std::copysign(std::sqrt(disc), b));
    if (q == 0.0) {
        roots[0] = roots[1] = 0.0;
        return true;
    }
    roots[0] = q / a;
    roots[1] = c / q;
    if (roots[0] > roots[1]) std::swap(roots[0], roots[1]);
    return true;
}

// The roots of a ray (model-space origin o, direction d) with a surface: up to 2 (4 for a
// torus) of them.
int surfaceRoots(const AnalyticShape& shape, const glm::dvec3& o, const glm::dvec3& d, double ts[4]) {
    if (shape.kind == AnalyticKind::Sphere) return sphereRoots(o, d, shape.radius, ts) ? 2 : 0;
    if (shape.kind == AnalyticKind::Torus) return ref::torusRoots(shape.radius, shape.size, o, d, ts);
    if (d.z == 0.0) return 0;
    ts[0] = -o.z / d.z;
    const glm::dvec3 p = o + ts[0] * d;
    const double h = 0.5 * shape.size;
    return std::abs(p.x) <= h && std::abs(p.y) <= h ? 1 : 0;
}

// What a hit lets through of what lies behind it: a blended material its 1 - alpha, a masked
// one where the mask cuts it away, an opaque one nothing (alpha: the side's times the texel's).
double transmittance(const Material& mat, const MaterialSide& side, double texelAlpha) {
    const double alpha = side.diffuse.a * texelAlpha;
    if (mat.alphaMode == AlphaMode::Blend) return 1.0 - std::clamp(alpha, 0.0, 1.0);
    if (mat.alphaMode == AlphaMode::Mask && alpha < mat.alphaCutoff) return 1.0;
    return 0.0;
}

// The base-colour texel at model point p of surface s (white without a texture).
glm::dvec4 texelAt(const Surface& s, const glm::dvec3& p) {
    if (!s.texture) return glm::dvec4(1.0);
    const glm::dvec3 uv = s.material->baseColorUvTransform * glm::dvec3(ref::analyticUv(s.shape, p), 1.0);
    return ref::sampleNearest(*s.texture, glm::dvec2(uv));
}

class Caster {
public:
    Caster(std::vector<Surface> surfaces, const frame::ViewCamera& camera,
           std::vector<ref::EyeLight> lights, const ref::Settings& settings,
           const RenderOptions& options, bool shadows)
        : m_surfaces(std::move(surfaces)), m_lights(std::move(lights)), m_settings(settings),
          m_options(options), m_clipFromView(camera.clipFromView),
          m_viewFromClip(glm::inverse(camera.clipFromView)),
          m_nearDepth(options.depth == DepthMode::ReversedZ ? 1.0 : 0.0), m_shadows(shadows) {}

    // The ray through framebuffer point (fx, fy): x from the left, y from the top, in pixels.
    Ray rayAt(double fx, double fy) const {
        const double x = 2.0 * fx / m_options.width - 1.0, y = 2.0 * fy / m_options.height - 1.0;
        const glm::dvec4 a = m_viewFromClip * glm::dvec4(x, y, m_nearDepth, 1.0);
        const glm::dvec4 b = m_viewFromClip * glm::dvec4(x, y, 0.5, 1.0);
        Ray r;
        r.origin = glm::dvec3(a) / a.w;
        r.direction = glm::dvec3(b) / b.w - r.origin;
        return r;
    }

    // Every surface the rasteriser would keep along the ray (in front of the near plane, before
    // the far plane, not culled, not cut away by the alpha mask), nearest first, up to the
    // nearest opaque one: the layers a blended pixel composites.
    void trace(const Ray& ray, std::vector<Hit>& hits) const {
        hits.clear();
        for (std::size_t i = 0; i < m_surfaces.size(); ++i) {
            const Surface& s = m_surfaces[i];
            const glm::dvec3 o(s.modelFromView * glm::dvec4(ray.origin, 1.0));
            const glm::dvec3 d(s.modelFromView * glm::dvec4(ray.direction, 0.0));
            double ts[4];
            const int count = surfaceRoots(s.shape, o, d, ts);
            for (int k = 0; k < count; ++k) {
                Hit h;
                if (ts[k] >= 0.0 && drawn(s, o + ts[k] * d, ray, ts[k], int(i), h)) hits.push_back(h);
            }
        }
        std::sort(hits.begin(), hits.end(), [](const Hit& a, const Hit& b) {
            return a.t != b.t ? a.t < b.t : a.surface < b.surface;
        });
        const auto opaque = std::find_if(hits.begin(), hits.end(), [&](const Hit& h) {
            return m_surfaces[std::size_t(h.surface)].material->alphaMode != AlphaMode::Blend;
        });
        if (opaque != hits.end()) hits.erase(opaque + 1, hits.end());
    }

    // Premultiplied RGBA of a sample: its layers composited front to back over the background,
    // as blending them far to near in exact depth order would (colour = alpha c + (1 - alpha)
    // behind; alpha = alpha + (1 - alpha) behind).
    glm::dvec4 shade(const std::vector<Hit>& hits) const {
        glm::dvec3 colour(0.0);
        double alpha = 0.0, through = 1.0;
        for (const Hit& h : hits) {
            const glm::dvec4 c = shadeLayer(h);
            colour += (through * c.a) * glm::dvec3(c);
            alpha += through * c.a;
            through *= 1.0 - c.a;
            if (!(through > 0.0)) break;
        }
        const glm::dvec4 background(m_options.background);
        return glm::dvec4(colour + through * glm::dvec3(background), alpha + through * background.a);
    }

    void setLighting(const frame::Lighting& lighting) { m_lighting = lighting; }

private:
    // One layer's straight colour and alpha (1 unless blended).
    glm::dvec4 shadeLayer(const Hit& hit) const {
        const Material& mat = *m_surfaces[std::size_t(hit.surface)].material;
        const bool useBack = frame::twoSidedLighting(m_lighting, mat) && !hit.front;
        const MaterialSide& side = mat.side(useBack);
        ref::Settings st = m_settings;
        st.unlit = mat.unlit;
        const glm::dvec3 n = useBack ? -hit.normal : hit.normal;
        std::vector<double> visible;
        bool anyShadow = false;
        for (const ref::EyeLight& light : m_lights) {
            const bool casts = m_shadows || light.castShadows;
            visible.push_back(casts ? visibility(hit.point, light, hit.surface) : 1.0);
            anyShadow |= casts;
        }
        const ref::LightSums sums = ref::evaluateLighting(hit.point, n, side, m_lights, st, nullptr,
                                                          anyShadow ? &visible : nullptr);
        const ref::MaterialColours mc = ref::materialColours(side, nullptr, false);
        const ref::SplitColour split =
            ref::splitColour(sums, mc.ambient, mc.diffuse, mat.ambientFollowsDiffuse, false);
        glm::dvec3 c = split.base + glm::dvec3(hit.texel) * split.textured;
        if (m_options.clamp)
            for (int k = 0; k < 3; ++k)
                if (std::isfinite(c[k])) c[k] = std::clamp(c[k], 0.0, 1.0);
        return glm::dvec4(c, mat.alphaMode == AlphaMode::Blend ? std::clamp(mc.alpha * hit.texel.a, 0.0, 1.0) : 1.0);
    }

    // The share of `light` that reaches eye-space point p on surface `self`: the mean over its
    // shadow rays (one, or a light disc's: ref::shadowRays) of what every surface between
    // them lets through (transmittance), both faces of each counted. The point's own surface
    // is skipped within a millionth of its extent of the point.
    double visibility(const glm::dvec3& p, const ref::EyeLight& light, int self) const {
        const std::vector<ref::ShadowRay> rays = ref::shadowRays(light, p, m_options.shadows);
        double sum = 0.0;
        for (const ref::ShadowRay& ray : rays) sum += through(p, ray, self);
        return sum / double(rays.size());
    }

    double through(const glm::dvec3& p, const ref::ShadowRay& ray, int self) const {
        const glm::dvec3& dir = ray.dir;
        double share = 1.0;
        for (std::size_t i = 0; i < m_surfaces.size() && share > 0.0; ++i) {
            const Surface& s = m_surfaces[i];
            const glm::dvec3 o(s.modelFromView * glm::dvec4(p, 1.0));
            const glm::dvec3 d(s.modelFromView * glm::dvec4(dir, 0.0));
            const double extent = s.shape.kind == AnalyticKind::Plane ? s.shape.size : s.shape.radius;
            const double tMin = int(i) == self ? 1e-6 * extent / std::max(glm::length(d), 1e-300) : 0.0;
            double ts[4];
            const int count = surfaceRoots(s.shape, o, d, ts);
            for (int k = 0; k < count; ++k) {
                if (!(ts[k] > tMin && ts[k] < ray.tMax)) continue;
                const glm::dvec3 model = o + ts[k] * d;
                const bool front = glm::dot(s.normalFromModel * modelNormal(s, model), dir) < 0.0;
                const Material& mat = *s.material;
                share *= transmittance(mat, mat.side(frame::twoSidedLighting(m_lighting, mat) && !front),
                                       texelAt(s, model).a);
            }
        }
        return share;
    }

    static glm::dvec3 modelNormal(const Surface& s, const glm::dvec3& p) {
        if (s.shape.kind == AnalyticKind::Torus) return ref::torusNormal(s.shape.radius, p);
        return s.shape.kind == AnalyticKind::Sphere ? p / s.shape.radius : glm::dvec3(0, 0, 1);
    }

    // Whether the rasteriser draws surface s at model point p (t along the ray), and the hit.
    bool drawn(const Surface& s, const glm::dvec3& p, const Ray& ray, double t, int index,
               Hit& hit) const {
        const glm::dvec3 eye = ray.origin + t * ray.direction;
        const glm::dvec4 clip = m_clipFromView * glm::dvec4(eye, 1.0);
        if (!(clip.w > 0.0)) return false;
        const double depth = clip.z / clip.w;
        if (depth < 0.0 || depth > 1.0) return false;
        const glm::dvec3 n = ref::safeNormalize(s.normalFromModel * modelNormal(s, p));
        const bool front = glm::dot(n, ray.direction) < 0.0;
        const Material& mat = *s.material;
        if (!front && !mat.doubleSided) return false; // back-face culling
        const glm::dvec4 texel = texelAt(s, p);
        if (mat.alphaMode == AlphaMode::Mask &&
            mat.side(frame::twoSidedLighting(m_lighting, mat) && !front).diffuse.a * texel.a < mat.alphaCutoff)
            return false;
        hit = Hit{t, index, eye, n, front, texel};
        return true;
    }

    std::vector<Surface> m_surfaces;
    std::vector<ref::EyeLight> m_lights;
    ref::Settings m_settings;
    RenderOptions m_options;
    glm::dmat4 m_clipFromView, m_viewFromClip;
    double m_nearDepth;
    bool m_shadows;
    frame::Lighting m_lighting;
};

Error refuse(ErrorCode code, std::string message, std::string object) {
    return makeError(code, std::move(message), std::move(object));
}

Result<void> checkOptions(const Scene& scene, const RenderOptions& o, double time,
                          const ReferenceOptions& r) {
    if (o.width < 1 || o.height < 1 || double(o.width) * double(o.height) > double(1 << 28))
        return refuse(ErrorCode::InvalidInput,
                      "image size " + std::to_string(o.width) + "x" + std::to_string(o.height) +
                          " is empty or larger than 2^28 pixels",
                      "--width/--height");
    if (!std::isfinite(time))
        return refuse(ErrorCode::InvalidInput, "time must be a finite number", "--time");
    if (r.boxSamples < 1 || r.boxSamples > 64)
        return refuse(ErrorCode::InvalidInput,
                      "box samples per axis " + std::to_string(r.boxSamples) + " is not in 1..64",
                      "ReferenceOptions::boxSamples");
    if (r.edgeProbes < 2 || r.edgeProbes > 64)
        return refuse(ErrorCode::InvalidInput,
                      "edge probes per axis " + std::to_string(r.edgeProbes) + " is not in 2..64",
                      "ReferenceOptions::edgeProbes");
    if (!o.views.empty())
        return refuse(
            ErrorCode::Unsupported,
            "the reference renders one full-image view; RenderOptions::views is not empty",
            "views");
    if (o.glCompat)
        return refuse(ErrorCode::Unsupported,
                      "GL compatibility changes how the rasteriser interpolates; the reference "
                      "evaluates the scene contract's equation exactly",
                      "--gl-compat");
    if (o.root < -1 || o.root >= int(scene.roots.size()))
        return refuse(ErrorCode::InvalidInput,
                      "scene " + std::to_string(o.root) + " does not exist (the file has " +
                          std::to_string(scene.roots.size()) + " scenes)",
                      "--scene");
    for (std::size_t i = 0; i < r.shapes.size(); ++i) {
        const AnalyticShape& s = r.shapes[i];
        const std::string object = "ReferenceOptions::shapes[" + std::to_string(i) + "]";
        if (s.mesh < 0 || s.mesh >= int(scene.meshes.size()))
            return refuse(ErrorCode::InvalidInput,
                          "mesh " + std::to_string(s.mesh) + " does not exist (the scene has " +
                              std::to_string(scene.meshes.size()) + " meshes)",
                          object);
        const double extent = s.kind == AnalyticKind::Plane ? s.size : s.radius;
        if (!(extent > 0.0) || !std::isfinite(extent))
            return refuse(ErrorCode::InvalidInput,
                          std::string(s.kind == AnalyticKind::Plane ? "size" : "radius") +
                              " must be a finite number > 0",
                          object);
        if (s.kind == AnalyticKind::Torus && !(s.size > 0.0 && s.size < s.radius))
            return refuse(ErrorCode::InvalidInput,
                          "a torus's tube radius (size) must be > 0 and less than its ring radius",
                          object);
        for (std::size_t j = 0; j < i; ++j)
            if (r.shapes[j].mesh == s.mesh)
                return refuse(ErrorCode::InvalidInput,
                              "mesh " + std::to_string(s.mesh) + " is described twice", object);
        if (scene.meshes[s.mesh].primitives.size() != 1)
            return refuse(ErrorCode::InvalidInput,
                          "an analytic mesh has exactly one primitive; mesh " +
                              std::to_string(s.mesh) + " has " +
                              std::to_string(scene.meshes[s.mesh].primitives.size()),
                          object);
    }
    return {};
}

// The analytic surface each visible node with a mesh draws, placed in eye space. Refuses a mesh
// without an analytic description, what the reference does not model, and singular transforms.
Result<std::vector<Surface>> placeSurfaces(const Scene& scene, const Pose& pose,
                                           const glm::dmat4& viewFromWorld,
                                           const std::vector<AnalyticShape>& shapes) {
    static const Material kDefaultMaterial;
    std::vector<Surface> surfaces;
    for (std::size_t ni = 0; ni < scene.nodes.size(); ++ni) {
        const Node& node = scene.nodes[ni];
        if (!pose.visible[ni] || node.mesh < 0) continue;
        const auto shape = std::find_if(shapes.begin(), shapes.end(), [&](const AnalyticShape& s) {
            return s.mesh == node.mesh;
        });
        const std::string object = "nodes[" + std::to_string(ni) + "]";
        if (shape == shapes.end())
            return refuse(ErrorCode::InvalidInput,
                          "draws mesh " + std::to_string(node.mesh) +
                              ", which has no analytic description (the reference ray-casts only "
                              "the spheres and planes listed in ReferenceOptions::shapes)",
                          object);
        const Primitive& prim = scene.meshes[node.mesh].primitives[0];
        if (isDeformed(scene, int(ni), prim))
            return refuse(ErrorCode::Unsupported,
                          "a skinned or morphing mesh is not an analytic surface (the pixel "
                          "reference covers deformed meshes)",
                          object);
        const Material& mat =
            prim.material >= 0 ? scene.materials[prim.material] : kDefaultMaterial;
        const std::string matObject = "materials[" + std::to_string(prim.material) + "]";
        const Texture* texture = mat.baseColorTexture >= 0 ? &scene.textures[mat.baseColorTexture] : nullptr;
        if (texture && (!texture->nearest || shape->kind == AnalyticKind::Torus))
            return refuse(ErrorCode::Unsupported,
                          "the reference samples base-colour textures nearest, on spheres and "
                          "planes only",
                          matObject);
        Surface s;
        s.texture = texture;
        s.shape = *shape;
        const glm::dmat4 viewFromModel = viewFromWorld * pose.worldFromNode[ni];
        s.modelFromView = glm::inverse(viewFromModel);
        s.normalFromModel = normalMatrix(viewFromModel);
        if (!std::isfinite(s.modelFromView[0][0]) || s.normalFromModel == glm::dmat3(0.0))
            return refuse(ErrorCode::InvalidInput,
                          "the node's transform is singular: the surface has no inside", object);
        s.material = &mat;
        surfaces.push_back(s);
    }
    return surfaces;
}

// The surfaces a ray meets, in order (-1: none): what the edge probes compare.
std::vector<int> layers(const std::vector<Hit>& hits) {
    std::vector<int> ids;
    for (const Hit& h : hits) ids.push_back(h.surface);
    if (ids.empty()) ids.push_back(-1);
    return ids;
}

// One pixel: the centre sample, the average of N x N box samples, and whether K x K probes
// across the pixel (its edges included) all meet the same surfaces in the same order.
void renderPixel(const Caster& caster, int x, int y, int N, int K, ReferenceImage& out) {
    std::vector<Hit> hits;
    caster.trace(caster.rayAt(x + 0.5, y + 0.5), hits);
    const glm::dvec4 centre = caster.shade(hits);
    glm::dvec4 sum(0.0);
    for (int j = 0; j < N; ++j)
        for (int i = 0; i < N; ++i) {
            caster.trace(caster.rayAt(x + (i + 0.5) / N, y + (j + 0.5) / N), hits);
            sum += caster.shade(hits);
        }
    std::vector<int> first;
    bool same = true;
    for (int j = 0; j < K && same; ++j)
        for (int i = 0; i < K && same; ++i) {
            caster.trace(caster.rayAt(x + double(i) / (K - 1), y + double(j) / (K - 1)), hits);
            std::vector<int> ids = layers(hits);
            if (first.empty()) first = std::move(ids);
            else same = ids == first;
        }
    const glm::dvec4 box = sum / double(N * N);
    float* pc = out.centre.pixel(x, y);
    float* pb = out.box.pixel(x, y);
    for (int k = 0; k < 4; ++k) {
        pc[k] = float(centre[k]);
        pb[k] = float(box[k]);
    }
    out.interior[std::size_t(y) * out.centre.width + x] = same && first[0] >= 0 ? 1 : 0;
}

// Calls renderRow(y) for rows 0..rows-1 on `threads` threads (this one among them), each thread
// taking the next row not yet taken.
void forEachRow(int rows, int threads, const std::function<void(int)>& renderRow) {
    std::atomic<int> nextRow{0};
    auto worker = [&] {
        for (int y = nextRow++; y < rows; y = nextRow++)
            renderRow(y);
    };
    std::vector<std::thread> pool;
    for (int t = 1; t < threads; ++t)
        pool.emplace_back(worker);
    worker();
    for (std::thread& t : pool)
        t.join();
}

} // namespace

Result<ReferenceImage> raycastReference(const Scene& scene, const RenderOptions& options,
                                        double time, const ReferenceOptions& reference) {
    LANTERN_TRY(scene.validate());
    LANTERN_TRY(checkOptions(scene, options, time, reference));
    const int root = options.root < 0 ? scene.defaultRoot : options.root;
    const Pose pose = evaluatePose(scene, root, time);
    auto camera = frame::resolveCamera(scene, pose, options.camera,
                                       double(options.width) / double(options.height),
                                       options.depth, "camera");
    if (!camera) return std::move(camera).error();
    const frame::Lighting lit = frame::resolveLighting(scene, root, options);
    auto surfaces = placeSurfaces(scene, pose, camera->viewFromWorld, reference.shapes);
    if (!surfaces) return std::move(surfaces).error();

    ref::Settings settings;
    settings.globalAmbient = lit.model.globalAmbient;
    settings.localViewer = lit.model.localViewer;
    settings.specular = lit.model.specular;
    Caster caster(std::move(*surfaces), *camera,
                  frame::placeLights(scene, pose, camera->viewFromWorld, false), settings, options,
                  reference.shadows || options.shadows.all);
    caster.setLighting(lit);

    const int W = options.width, H = options.height;
    const int N = reference.boxSamples, K = reference.edgeProbes;
    ReferenceImage out;
    out.centre = Image(W, H);
    out.box = Image(W, H);
    out.interior.assign(std::size_t(W) * std::size_t(H), 0);
    out.rays = std::size_t(W) * std::size_t(H) * std::size_t(1 + N * N + K * K);

    int threads = reference.threads > 0 ? reference.threads
                                        : int(std::max(1u, std::thread::hardware_concurrency()));
    threads = std::min(threads, H);
    forEachRow(H, threads, [&](int y) {
        for (int x = 0; x < W; ++x)
            renderPixel(caster, x, y, N, K, out);
    });
    return out;
}

} // namespace lantern
