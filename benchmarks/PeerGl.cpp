// lantern_peer_gl: one scene and camera drawn by Lantern (Vulkan) and by fixed-function OpenGL
// through Mesa's OSMesa (glLight, glMaterial, glShadeModel, vertex buffers), interleaved in one
// process on the same CPU, each frame ending with its float RGBA pixels in host memory
// (Lantern: Renderer::render's Image, render() into a kept Image, and renderView's pixels read
// where the device left them; GL: glReadPixels into a float array). Prints the time per frame
// of each and the ratio Lantern / GL, and checks that the two pictures agree, so that the
// peer is known to draw the same thing (exit 1 if they do not). Built only when libosmesa6-dev
// is installed. docs/performance.md quotes it with the command.
//
//   lantern_peer_gl [--scene sphere|FILE|builtin:NAME] [--width 1920] [--height 1080]
//                   [--lights 1,8] [--shading gouraud,flat] [--rounds 5] [--frames 5]
//                   [--warmup 2] [--csv FILE]
//
// --lights N keeps the scene's first light (GL's headlight when it has none) and adds N - 1
// lights on a ring in front of it, point and spot in turn, each 1/N strong. GL has 8 lights, so
// N is at most 8. Lights with glTF falloff are drawn by GL with quadratic attenuation (a timing
// peer; the agreement check then reports the difference). Vertex colours and textures are not
// drawn by the GL side; lines and points are skipped by both.
#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/osmesa.h>

#include <lantern/Lantern.h>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

namespace {
using namespace lantern;
using Clock = std::chrono::steady_clock;

struct Args {
    std::string scene = "sphere";
    int width = 1920, height = 1080;
    std::vector<int> lights{1, 8};
    std::vector<std::string> shading{"gouraud", "flat"};
    int rounds = 5, frames = 5, warmup = 2;
    std::string csv;
};

// One sphere (64 x 32 segments) filling the middle of the picture, one directional light.
Scene sphereScene() {
    Scene s;
    s.sourcePath = "peer:sphere";
    Mesh mesh;
    mesh.name = "sphere";
    mesh.primitives.push_back(makeSphere(1.0, 64, 32));
    mesh.primitives[0].material = 0;
    s.meshes.push_back(mesh);
    Material m;
    m.name = "plastic";
    m.front.diffuse = {0.8, 0.3, 0.2, 1.0};
    m.front.specular = {0.6, 0.6, 0.6};
    m.front.shininess = 32.0;
    s.materials.push_back(m);
    Light key;
    key.name = "key";
    key.type = LightType::Directional;
    s.lights.push_back(key);
    Node sphere, light;
    sphere.name = "sphere";
    sphere.mesh = 0;
    light.name = "key";
    light.light = 0;
    light.rotation = glm::dquat(glm::dvec3(-0.6, 0.5, 0.0));
    s.nodes = {sphere, light};
    s.roots.push_back(SceneRoot{"peer", {0, 1}, std::nullopt});
    return s;
}

// `scene` with `count` lights: its first one (or GL's headlight as a directional light in
// world space along +Z), then point and spot lights in turn on a ring before the bounds.
Scene withLights(Scene s, int count) {
    const int root = s.defaultRoot;
    const Pose pose = evaluatePose(s, root, 0.0);
    const Bounds b = computeBounds(s, pose);
    Light first;
    first.type = LightType::Directional;
    glm::dmat4 firstMatrix(1.0);
    for (std::size_t i = 0; i < s.nodes.size(); ++i)
        if (pose.visible[i] && s.nodes[i].light >= 0) {
            first = s.lights[std::size_t(s.nodes[i].light)];
            firstMatrix = pose.worldFromNode[i];
            break;
        }
    for (Node& n : s.nodes) n.light = -1;
    s.lights.clear();
    auto add = [&](Light l, const glm::dmat4& m) {
        l.diffuse /= double(count);
        l.specular /= double(count);
        s.lights.push_back(l);
        Node n;
        n.name = l.name;
        n.light = int(s.lights.size()) - 1;
        n.matrix = m;
        s.nodes.push_back(n);
        s.roots[std::size_t(root)].nodes.push_back(int(s.nodes.size()) - 1);
    };
    add(first, firstMatrix);
    const glm::dvec3 c = b.empty() ? glm::dvec3(0.0) : b.center();
    const double r = b.empty() ? 1.0 : std::max(b.radius(), 1e-3);
    for (int i = 1; i < count; ++i) {
        Light l;
        l.name = "ring " + std::to_string(i);
        l.type = i % 2 ? LightType::Point : LightType::Spot;
        l.attenuation = {1.0, 0.0, 0.02 / (r * r)};
        l.spotCutoffDeg = 40.0;
        l.spotExponent = 8.0;
        const double a = 6.283185307179586 * double(i) / double(count);
        const glm::dvec3 p = c + r * glm::dvec3(1.2 * std::cos(a), 1.2 * std::sin(a), 1.5);
        // Looking at the centre: the node's -Z towards c.
        add(l, glm::inverse(glm::lookAt(p, c, glm::dvec3(0, 1, 0))));
    }
    return s;
}

// --- The OpenGL side ----------------------------------------------------------------------

struct GlDraw {
    GLuint vbo = 0, ibo = 0;
    GLsizei count = 0;
    bool indexed = false;
    std::size_t normalOffset = 0;
    glm::mat4 world{1.0f};
    int material = -1;
};

struct GlPeer {
    OSMesaContext ctx = nullptr;
    std::vector<float> target, pixels;
    std::vector<GlDraw> draws;
    int width = 0, height = 0;
    ~GlPeer() {
        if (ctx) OSMesaDestroyContext(ctx);
    }
};

void setMaterial(GLenum face, const MaterialSide& m) {
    const GLfloat a[4] = {float(m.ambient.r), float(m.ambient.g), float(m.ambient.b), 1.0f};
    const GLfloat d[4] = {float(m.diffuse.r), float(m.diffuse.g), float(m.diffuse.b), float(m.diffuse.a)};
    const GLfloat s[4] = {float(m.specular.r), float(m.specular.g), float(m.specular.b), 1.0f};
    const GLfloat e[4] = {float(m.emission.r), float(m.emission.g), float(m.emission.b), 1.0f};
    glMaterialfv(face, GL_AMBIENT, a);
    glMaterialfv(face, GL_DIFFUSE, d);
    glMaterialfv(face, GL_SPECULAR, s);
    glMaterialfv(face, GL_EMISSION, e);
    glMaterialf(face, GL_SHININESS, float(std::clamp(m.shininess, 0.0, 128.0)));
}

// Uploads every visible triangle primitive with normals into buffer objects.
bool uploadGl(GlPeer& gl, const Scene& scene, const Pose& pose) {
    for (std::size_t i = 0; i < scene.nodes.size(); ++i) {
        const Node& node = scene.nodes[i];
        if (!pose.visible[i] || node.mesh < 0) continue;
        for (const Primitive& p : scene.meshes[std::size_t(node.mesh)].primitives) {
            if (p.topology != Topology::Triangles || p.normals.empty()) continue;
            if (isDeformed(scene, int(i), p)) return false;
            GlDraw d;
            d.world = glm::mat4(pose.worldFromNode[i]);
            d.material = p.material;
            d.normalOffset = p.positions.size() * sizeof(glm::vec3);
            glGenBuffers(1, &d.vbo);
            glBindBuffer(GL_ARRAY_BUFFER, d.vbo);
            glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(2 * d.normalOffset), nullptr, GL_STATIC_DRAW);
            glBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(d.normalOffset), p.positions.data());
            glBufferSubData(GL_ARRAY_BUFFER, GLintptr(d.normalOffset), GLsizeiptr(d.normalOffset), p.normals.data());
            d.indexed = !p.indices.empty();
            d.count = GLsizei(d.indexed ? p.indices.size() : p.positions.size());
            if (d.indexed) {
                glGenBuffers(1, &d.ibo);
                glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, d.ibo);
                glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(p.indices.size() * 4), p.indices.data(), GL_STATIC_DRAW);
            }
            gl.draws.push_back(d);
        }
    }
    return true;
}

// GL's lights from the scene's, in eye space through viewFromWorld.
void setLights(const Scene& scene, const Pose& pose, const glm::dmat4& view) {
    glMatrixMode(GL_MODELVIEW);
    glLoadMatrixd(&view[0][0]);
    int n = 0;
    for (std::size_t i = 0; i < scene.nodes.size() && n < 8; ++i) {
        if (!pose.visible[i] || scene.nodes[i].light < 0) continue;
        const Light& l = scene.lights[std::size_t(scene.nodes[i].light)];
        const glm::dmat4& m = pose.worldFromNode[i];
        const GLenum id = GLenum(GL_LIGHT0 + n++);
        glEnable(id);
        const glm::vec4 a(glm::vec3(l.ambient), 1.0f), d(glm::vec3(l.diffuse), 1.0f), s(glm::vec3(l.specular), 1.0f);
        glLightfv(id, GL_AMBIENT, &a[0]);
        glLightfv(id, GL_DIFFUSE, &d[0]);
        glLightfv(id, GL_SPECULAR, &s[0]);
        const glm::vec4 pos = l.type == LightType::Directional ? glm::vec4(m * glm::dvec4(0, 0, 1, 0))
                                                               : glm::vec4(m * glm::dvec4(0, 0, 0, 1));
        glLightfv(id, GL_POSITION, &pos[0]);
        const bool glFalloff = l.falloff == LightFalloff::Gl;
        glLightf(id, GL_CONSTANT_ATTENUATION, glFalloff ? float(l.attenuation.x) : 0.0f);
        glLightf(id, GL_LINEAR_ATTENUATION, glFalloff ? float(l.attenuation.y) : 0.0f);
        glLightf(id, GL_QUADRATIC_ATTENUATION, glFalloff ? float(l.attenuation.z) : 1.0f);
        if (l.type == LightType::Spot) {
            const glm::vec3 dir(m * glm::dvec4(0, 0, -1, 0));
            glLightfv(id, GL_SPOT_DIRECTION, &dir[0]);
            glLightf(id, GL_SPOT_CUTOFF, float(glFalloff ? l.spotCutoffDeg : l.outerConeAngle * 57.29577951308232));
            glLightf(id, GL_SPOT_EXPONENT, float(std::min(l.spotExponent, 128.0)));
        }
    }
    if (n == 0) { // GL's default light 0: an eye-space headlight
        glLoadIdentity();
        glEnable(GL_LIGHT0);
    }
}

// Vulkan clip space (y down, reversed depth 1 at near .. 0 at far) to GL's (y up, -1 .. 1).
glm::dmat4 glClipFromVulkan(const glm::dmat4& clipFromView) {
    glm::dmat4 conv(1.0);
    conv[1][1] = -1.0;
    conv[2][2] = -2.0;
    conv[3][2] = 1.0;
    return conv * clipFromView;
}

// Draws one frame; `read` ends it with glReadPixels into gl.pixels, else with glFinish.
void drawGl(GlPeer& gl, const Scene& scene, const glm::dmat4& view, const glm::dmat4& proj, bool read) {
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glMatrixMode(GL_PROJECTION);
    glLoadMatrixd(&proj[0][0]);
    glMatrixMode(GL_MODELVIEW);
    int bound = -2;
    for (const GlDraw& d : gl.draws) {
        const glm::mat4 mv = glm::mat4(view) * d.world;
        glLoadMatrixf(&mv[0][0]);
        if (d.material != bound) {
            const Material def;
            const Material& m = d.material >= 0 ? scene.materials[std::size_t(d.material)] : def;
            setMaterial(GL_FRONT_AND_BACK, m.front);
            if (m.back) setMaterial(GL_BACK, *m.back);
            if (m.doubleSided) glDisable(GL_CULL_FACE); else glEnable(GL_CULL_FACE);
            bound = d.material;
        }
        glBindBuffer(GL_ARRAY_BUFFER, d.vbo);
        glVertexPointer(3, GL_FLOAT, 0, nullptr);
        glNormalPointer(GL_FLOAT, 0, reinterpret_cast<const void*>(d.normalOffset));
        if (d.indexed) {
            glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, d.ibo);
            glDrawElements(GL_TRIANGLES, d.count, GL_UNSIGNED_INT, nullptr);
        } else {
            glDrawArrays(GL_TRIANGLES, 0, d.count);
        }
    }
    if (read) glReadPixels(0, 0, gl.width, gl.height, GL_RGBA, GL_FLOAT, gl.pixels.data());
    else glFinish();
}

bool setUpGl(GlPeer& gl, int w, int h) {
    gl.ctx = OSMesaCreateContextExt(OSMESA_RGBA, 24, 0, 0, nullptr);
    gl.width = w;
    gl.height = h;
    gl.target.assign(std::size_t(w) * std::size_t(h) * 4, 0.0f);
    gl.pixels.assign(gl.target.size(), 0.0f);
    if (!gl.ctx || !OSMesaMakeCurrent(gl.ctx, gl.target.data(), GL_FLOAT, w, h)) return false;
    glViewport(0, 0, w, h);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glClearColor(0, 0, 0, 1);
    glEnable(GL_LIGHTING);
    glEnable(GL_NORMALIZE);
    glEnableClientState(GL_VERTEX_ARRAY);
    glEnableClientState(GL_NORMAL_ARRAY);
    glCullFace(GL_BACK);
    return true;
}

void setLightModel(const Scene& scene) {
    const SceneRoot& root = scene.roots[std::size_t(scene.defaultRoot)];
    const LightingModel lm = root.lighting.value_or(LightingModel{});
    const glm::vec4 ambient(glm::vec3(lm.globalAmbient), 1.0f);
    glLightModelfv(GL_LIGHT_MODEL_AMBIENT, &ambient[0]);
    glLightModeli(GL_LIGHT_MODEL_LOCAL_VIEWER, lm.localViewer ? 1 : 0);
    glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, lm.twoSided.value_or(false) ? 1 : 0);
}

// --- Timing -------------------------------------------------------------------------------

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

// Mean and largest absolute difference of RGB between Lantern's picture (top row first) and
// GL's (bottom row first).
struct Agreement {
    double mean = 0.0, worst = 0.0, lanternMean = 0.0, glMean = 0.0;
};
Agreement agreement(const Image& img, const std::vector<float>& gl) {
    Agreement r;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const float* a = img.pixel(x, y);
            const float* b = &gl[(std::size_t(img.height - 1 - y) * std::size_t(img.width) + std::size_t(x)) * 4];
            for (int c = 0; c < 3; ++c) {
                const double d = std::abs(double(a[c]) - double(b[c]));
                r.mean += d;
                r.worst = std::max(r.worst, d);
                r.lanternMean += a[c];
                r.glMean += b[c];
            }
        }
    const double n = 3.0 * double(img.pixelCount());
    r.mean /= n;
    r.lanternMean /= n;
    r.glMean /= n;
    return r;
}

struct Config {
    int lights;
    ShadingMode shading;
    std::shared_ptr<const Scene> scene;
    std::optional<PreparedScene> prepared;
    std::unique_ptr<GlPeer> gl;
    glm::dmat4 view{1.0}, proj{1.0};
    std::vector<double> lantern, lanternInto, lanternView, glRead, glDraw; // one median per round
    Agreement diff;
};

RenderOptions lanternOptions(const Args& a, const Config& c) {
    RenderOptions o;
    o.width = a.width;
    o.height = a.height;
    o.shading = c.shading;
    return o;
}

// Prepares configuration `c` on both sides, draws it once each, and checks that the view
// holds render()'s pixels. Returns 0 or the exit code.
int setUp(const Args& a, Renderer& renderer, Config& c) {
    auto prepared = renderer.prepare(c.scene);
    if (!prepared) return std::fprintf(stderr, "lantern_peer_gl: %s\n", prepared.error().describe().c_str()), 3;
    c.prepared.emplace(std::move(*prepared));
    c.gl = std::make_unique<GlPeer>();
    if (!setUpGl(*c.gl, a.width, a.height))
        return std::fprintf(stderr, "lantern_peer_gl: OSMesa gave no float RGBA context\n"), 3;
    const Pose pose = evaluatePose(*c.scene, -1, 0.0);
    if (!uploadGl(*c.gl, *c.scene, pose))
        return std::fprintf(stderr, "lantern_peer_gl: %s: skinned or morphing meshes are not drawn by the GL peer\n", a.scene.c_str()), 1;
    setLightModel(*c.scene);
    glShadeModel(c.shading == ShadingMode::Flat ? GL_FLAT : GL_SMOOTH);
    const RenderOptions o = lanternOptions(a, c);
    auto img = renderer.render(*c.prepared, o, 0.0);
    if (!img || !img->camera) return std::fprintf(stderr, "lantern_peer_gl: the first Lantern frame failed\n"), 3;
    c.view = img->camera->viewFromWorld;
    c.proj = glClipFromVulkan(img->camera->clipFromView);
    setLights(*c.scene, pose, c.view);
    drawGl(*c.gl, *c.scene, c.view, c.proj, true);
    c.diff = agreement(*img, c.gl->pixels);
    // The view reads the same pixels in place.
    auto view = renderer.renderView(*c.prepared, o, 0.0);
    if (!view || view->toImage().rgba != img->rgba)
        return std::fprintf(stderr, "lantern_peer_gl: renderView's pixels are not render()'s\n"), 3;
    return 0;
}

// One round of configuration `c`: Lantern three ways, GL with the read and without, each timed
// over `frames` frames after `warmup` untimed ones; the median frame of each is kept.
void timeRound(const Args& a, Renderer& renderer, Config& c) {
    const RenderOptions o = lanternOptions(a, c);
    auto time = [&](auto&& frame) {
        for (int i = 0; i < a.warmup; ++i) frame();
        std::vector<double> ms;
        for (int i = 0; i < a.frames; ++i) {
            const auto t0 = Clock::now();
            frame();
            ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
        }
        return median(ms);
    };
    c.lantern.push_back(time([&] {
        if (!renderer.render(*c.prepared, o, 0.0)) std::exit(3);
    }));
    // As GL reads into an array allocated once: render() into one Image kept.
    Image into;
    c.lanternInto.push_back(time([&] {
        if (!renderer.render(*c.prepared, o, 0.0, into)) std::exit(3);
    }));
    // The pixels where the device left them: a view of the mapped frame, no copy (one value is
    // read so that the frame is used).
    float used = 0.0f;
    c.lanternView.push_back(time([&] {
        auto view = renderer.renderView(*c.prepared, o, 0.0);
        if (!view) std::exit(3);
        used += view->row(a.height / 2)[a.width * 2];
    }));
    if (!std::isfinite(used)) std::exit(3);
    OSMesaMakeCurrent(c.gl->ctx, c.gl->target.data(), GL_FLOAT, a.width, a.height);
    c.glRead.push_back(time([&] { drawGl(*c.gl, *c.scene, c.view, c.proj, true); }));
    c.glDraw.push_back(time([&] { drawGl(*c.gl, *c.scene, c.view, c.proj, false); }));
}

// The table (and the CSV when asked); 1 when the Gouraud pictures do not agree.
int report(const Args& a, const std::vector<Config>& configs) {
    std::printf("lantern_peer_gl: %s, %dx%d, float RGBA in host memory; median of %d rounds' medians of %d frames\n\n",
                a.scene.c_str(), a.width, a.height, a.rounds, a.frames);
    std::printf("| shading | lights | GL ms (with glReadPixels) | GL ms (draw + glFinish) | Lantern ms (render()) | Lantern / GL | Lantern ms (render(into)) | into / GL | Lantern ms (renderView) | view / GL | mean RGB GL / Lantern | mean / max abs difference |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    std::ofstream csv;
    if (!a.csv.empty()) {
        csv.open(a.csv);
        csv << "scene,width,height,shading,lights,gl_read_ms,gl_draw_ms,lantern_ms,ratio,lantern_into_ms,into_ratio,lantern_view_ms,view_ratio,mean_abs_diff,max_abs_diff\n";
    }
    bool agree = true;
    for (const Config& c : configs) {
        const double l = median(c.lantern), li = median(c.lanternInto), lv = median(c.lanternView),
                     g = median(c.glRead), gd = median(c.glDraw);
        std::printf("| %s | %d | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.4f / %.4f | %.4f / %.3f |\n",
                    toString(c.shading), c.lights, g, gd, l, l / g, li, li / g, lv, lv / g, c.diff.glMean,
                    c.diff.lanternMean, c.diff.mean, c.diff.worst);
        if (csv)
            csv << a.scene << ',' << a.width << ',' << a.height << ',' << toString(c.shading) << ','
                << c.lights << ',' << g << ',' << gd << ',' << l << ',' << l / g << ',' << li << ','
                << li / g << ',' << lv << ',' << lv / g << ',' << c.diff.mean << ',' << c.diff.worst << '\n';
        // Gouraud is the same equation at the same vertices: the pictures must agree closely,
        // and show something (two black pictures would agree). Flat differs by definition (GL
        // lights the provoking vertex, Lantern the centroid).
        if (c.shading == ShadingMode::Gouraud && (c.diff.mean > 0.01 || c.diff.lanternMean < 0.005)) agree = false;
    }
    if (!agree) {
        std::fprintf(stderr, "lantern_peer_gl: the GL and Lantern gouraud pictures differ by more than 0.01 on average, "
                             "or are black: the peer does not draw the same scene\n");
        return 1;
    }
    return 0;
}

int run(const Args& a) {
    auto renderer = Renderer::create();
    if (!renderer) return std::fprintf(stderr, "lantern_peer_gl: %s\n", renderer.error().describe().c_str()), 3;
    Scene base;
    if (a.scene == "sphere") {
        base = sphereScene();
    } else {
        auto loaded = loadScene(a.scene);
        if (!loaded) return std::fprintf(stderr, "lantern_peer_gl: %s\n", loaded.error().describe().c_str()), 1;
        base = std::move(*loaded);
    }
    std::vector<Config> configs;
    for (int n : a.lights)
        for (const std::string& s : a.shading) {
            Config c;
            c.lights = n;
            c.shading = *parseShadingMode(s);
            c.scene = std::make_shared<const Scene>(withLights(base, n));
            configs.push_back(std::move(c));
        }
    for (Config& c : configs)
        if (const int code = setUp(a, *renderer, c); code != 0) return code;
    // Rounds: every configuration in turn.
    for (int round = 0; round < a.rounds; ++round)
        for (Config& c : configs) timeRound(a, *renderer, c);
    return report(a, configs);
}

} // namespace

int main(int argc, char** argv) {
    Args a;
    CLI::App app{"Lantern against fixed-function OpenGL (OSMesa) on the same scene, camera and CPU"};
    app.add_option("--scene", a.scene, "sphere (one sphere, one directional light), a glTF file or builtin:NAME");
    app.add_option("--width", a.width)->check(CLI::Range(1, 8192));
    app.add_option("--height", a.height)->check(CLI::Range(1, 8192));
    app.add_option("--lights", a.lights, "light counts (1 to 8: GL's limit)")->delimiter(',')->check(CLI::Range(1, 8));
    app.add_option("--shading", a.shading, "gouraud, flat")->delimiter(',')->check(CLI::IsMember({"gouraud", "flat"}));
    app.add_option("--rounds", a.rounds)->check(CLI::Range(1, 1000));
    app.add_option("--frames", a.frames)->check(CLI::Range(1, 1000));
    app.add_option("--warmup", a.warmup)->check(CLI::Range(0, 1000));
    app.add_option("--csv", a.csv, "also write the table as CSV");
    CLI11_PARSE(app, argc, argv);
    return run(a);
}
