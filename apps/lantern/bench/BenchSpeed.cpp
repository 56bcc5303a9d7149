// `lantern bench speed`: where the frame time goes, every time also given as a multiple of the
// floor (a trivial shader over the same geometry and pixels, FeatureMode::Floor). Three
// sections, each timed in interleaved rounds: shading modes on a scene (the teapot grid by
// default), specialised against all-features pipelines; 1 to 256 lights; and 1e3 to 1e7
// triangles (the S1 sphere tessellated ever finer, so the pixels stay the same).
#include "bench/BenchAccuracy.h"
#include "bench/BenchHarness.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>
#include <tuple>

namespace lantern::cli {
namespace {

struct SpeedArgs {
    std::string scene = "builtin:default";
    int width = 1280, height = 720;
    int msaa = 1;
    std::vector<std::string> sections{"modes", "lights", "triangles"};
    std::vector<std::string> shading{"flat", "gouraud", "phong"};
    std::vector<int> lights{1, 2, 4, 8, 16, 32, 64, 128, 256};
    std::vector<double> triangles{1e3, 1e4, 1e5, 1e6, 1e7};
    bool shadows = false;        ///< --shadows: the lights section also with every light casting
    int shadowResolution = 1024; ///< --shadow-resolution
    TimingOptions timing;
    DeviceOptions device;
    CLI::Option *widthOption = nullptr, *heightOption = nullptr, *lightsOption = nullptr,
                *trianglesOption = nullptr;
};

void applyQuick(SpeedArgs& a) {
    if (!a.timing.quick) return;
    if (!a.widthOption->count()) a.width = 640;
    if (!a.heightOption->count()) a.height = 360;
    if (!a.lightsOption->count()) a.lights = {1, 8, 64};
    if (!a.trianglesOption->count()) a.triangles = {1e3, 1e4, 1e5};
    a.timing.applyQuick(2, 3);
}

// One measured configuration of a section.
struct SpeedRow {
    std::string section, scene, shading, features;
    std::size_t lights = 0, triangles = 0;
    int width = 0, height = 0, msaa = 1;
    std::size_t config = 0; // index into the section's TimedConfigs
    std::size_t floor = 0;  // the floor configuration of the same geometry and pixels
};

std::size_t drawnTriangles(const Scene& scene) {
    const Pose pose = evaluatePose(scene, -1, 0.0);
    std::size_t n = 0;
    for (std::size_t i = 0; i < scene.nodes.size(); ++i)
        if (pose.visible[i] && scene.nodes[i].mesh >= 0)
            for (const Primitive& p : scene.meshes[scene.nodes[i].mesh].primitives)
                n += p.triangleCount();
    return n;
}

std::size_t drawnLights(const Scene& scene) {
    const Pose pose = evaluatePose(scene, -1, 0.0);
    std::size_t n = 0;
    for (std::size_t i = 0; i < scene.nodes.size(); ++i)
        if (pose.visible[i] && scene.nodes[i].light >= 0) ++n;
    return std::max<std::size_t>(n, 1); // GL's light 0 when there is none
}

// `scene` with exactly `count` lights: its first light where it was (or GL's headlight as a
// directional light), then point lights on a ring in front of the scene's bounds, each
// 1/count strong so the picture keeps its brightness.
Scene withLights(const Scene& scene, int count) {
    Scene s = scene;
    const int root = s.defaultRoot;
    const Pose pose = evaluatePose(s, root, 0.0);
    const Bounds b = computeBounds(s, pose);
    Light first;
    first.name = "key";
    first.type = LightType::Directional;
    glm::dmat4 firstMatrix(1.0);
    for (std::size_t i = 0; i < s.nodes.size(); ++i)
        if (pose.visible[i] && s.nodes[i].light >= 0) {
            first = s.lights[s.nodes[i].light];
            firstMatrix = pose.worldFromNode[i];
            break;
        }
    for (Node& n : s.nodes)
        n.light = -1;
    s.lights.clear();
    auto add = [&](const Light& l, const glm::dmat4& matrix) {
        s.lights.push_back(l);
        Node n;
        n.name = l.name;
        n.light = int(s.lights.size()) - 1;
        n.matrix = matrix;
        s.nodes.push_back(n);
        s.roots[root].nodes.push_back(int(s.nodes.size()) - 1);
    };
    add(first, firstMatrix);
    const glm::dvec3 c = b.empty() ? glm::dvec3(0.0) : b.center();
    const double r = b.empty() ? 1.0 : std::max(b.radius(), 1e-3);
    for (int i = 1; i < count; ++i) {
        Light l;
        l.name = "point " + std::to_string(i);
        l.type = LightType::Point;
        l.diffuse = l.specular = glm::dvec3(1.0 / count);
        const double angle = 6.283185307179586 * double(i) / double(count);
        glm::dmat4 m(1.0);
        m[3] = glm::dvec4(
            c + glm::dvec3(0.8 * r * std::cos(angle), 0.8 * r * std::sin(angle), 0.5 * r), 1.0);
        add(l, m);
    }
    return s;
}

// Sphere segments whose triangle count 2 s (s / 2 - 1) is nearest to `triangles`.
int segmentsFor(double triangles) {
    int s = int(std::lround(1.0 + std::sqrt(1.0 + triangles)));
    return std::max(4, s + (s % 2));
}

struct Section {
    std::vector<std::shared_ptr<const Scene>> scenes;
    std::vector<std::unique_ptr<PreparedScene>> prepared; // stable: configs point at them
    std::vector<TimedConfig> configs;
    std::vector<SpeedRow> rows;
};

class SpeedBench {
public:
    SpeedBench(SpeedArgs& a, Renderer& r, std::vector<ShadingMode> modes)
        : m_a(a), m_renderer(r), m_modes(std::move(modes)) {}

    Result<std::size_t> prepare(Section& s, Scene scene) {
        auto shared = std::make_shared<const Scene>(std::move(scene));
        auto p = m_renderer.prepare(shared);
        if (!p) return std::move(p).error();
        s.scenes.push_back(shared);
        s.prepared.push_back(std::make_unique<PreparedScene>(*p));
        return s.prepared.size() - 1;
    }

    // Adds a configuration; its floor index is filled in by the caller.
    SpeedRow& add(Section& s, std::size_t scene, const std::string& sceneName,
                  const std::string& section, std::optional<ShadingMode> mode,
                  FeatureMode features, bool shadows = false) {
        TimedConfig c;
        c.options.width = m_a.width;
        c.options.height = m_a.height;
        c.options.msaa = m_a.msaa;
        c.options.shading = mode;
        c.options.features = features;
        c.options.shadows.all = shadows;
        c.options.shadows.resolution = m_a.shadowResolution;
        SpeedRow row;
        row.section = section;
        row.scene = sceneName;
        row.shading = features == FeatureMode::Floor ? "floor" : mode ? toString(*mode) : "scene";
        row.features = features == FeatureMode::AllFeatures ? "all-features"
                       : features == FeatureMode::Floor     ? "floor"
                       : shadows                            ? "specialised+shadows"
                                                            : "specialised";
        row.lights = drawnLights(*s.scenes[scene]);
        row.triangles = drawnTriangles(*s.scenes[scene]);
        row.width = m_a.width;
        row.height = m_a.height;
        row.msaa = m_a.msaa;
        row.config = s.configs.size();
        c.label = section + ": " + row.shading + " " + row.features + ", " +
                  std::to_string(row.lights) + " lights, " + std::to_string(row.triangles) +
                  " triangles";
        c.scene = s.prepared[scene].get();
        s.configs.push_back(std::move(c));
        s.rows.push_back(row);
        return s.rows.back();
    }

    Result<Section> modes(const Scene& scene) {
        Section s;
        auto i = prepare(s, scene);
        if (!i) return std::move(i).error();
        const std::size_t floor =
            add(s, *i, m_a.scene, "modes", std::nullopt, FeatureMode::Floor).config;
        s.rows.back().floor = floor;
        for (ShadingMode m : m_modes)
            for (FeatureMode f : {FeatureMode::Specialised, FeatureMode::AllFeatures})
                add(s, *i, m_a.scene, "modes", m, f).floor = floor;
        return s;
    }

    Result<Section> lights(const Scene& scene) {
        Section s;
        std::size_t floor = 0;
        for (int n : m_a.lights) {
            auto i = prepare(s, withLights(scene, n));
            if (!i) return std::move(i).error();
            if (n == m_a.lights.front()) {
                floor = add(s, *i, m_a.scene, "lights", std::nullopt, FeatureMode::Floor).config;
                s.rows.back().floor = floor;
            }
            for (ShadingMode m : m_modes) {
                add(s, *i, m_a.scene, "lights", m, FeatureMode::Specialised).floor = floor;
                if (m_a.shadows)
                    add(s, *i, m_a.scene, "lights", m, FeatureMode::Specialised, true).floor = floor;
            }
        }
        return s;
    }

    Result<Section> triangles() {
        Section s;
        for (double t : m_a.triangles) {
            auto i = prepare(s, makeBenchScene("sphere", 128.0, segmentsFor(t)).scene);
            if (!i) return std::move(i).error();
            const std::size_t floor =
                add(s, *i, "bench:sphere", "triangles", std::nullopt, FeatureMode::Floor).config;
            s.rows.back().floor = floor;
            for (ShadingMode m : m_modes)
                add(s, *i, "bench:sphere", "triangles", m, FeatureMode::Specialised).floor = floor;
        }
        return s;
    }

private:
    SpeedArgs& m_a;
    Renderer& m_renderer;
    std::vector<ShadingMode> m_modes;
};

std::string csvHeader() {
    return "section,scene,width,height,shading,features,lights,triangles,msaa,ms_per_frame,ms_min,"
           "ms_wall,ms_round_spread,first_frame_ms,pipelines_compiled,floor_ms,x_floor\n";
}

const SpeedRow* find(const Section& s, const std::string& shading, const std::string& features,
                     std::size_t lights, std::size_t triangles) {
    for (const SpeedRow& r : s.rows)
        if (r.shading == shading && r.features == features && r.lights == lights &&
            r.triangles == triangles)
            return &r;
    return nullptr;
}

std::string cell(const Section& s, const SpeedRow* r) {
    if (!r) return "-";
    const double ms = s.configs[r->config].ms(), floor = s.configs[r->floor].ms();
    return num(ms, "%.2f") + " (" + num(ms / floor, "%.1f") + "x)";
}

void sectionMarkdown(std::ostringstream& md, const Section& s, const std::string& name,
                     const std::vector<ShadingMode>& modes) {
    if (s.rows.empty()) return;
    const SpeedRow& first = s.rows.front();
    const std::string size = std::to_string(first.width) + "x" + std::to_string(first.height) +
                             (first.msaa > 1 ? ", " + std::to_string(first.msaa) + "x MSAA" : "");
    if (name == "modes") {
        md << "## Shading modes, specialised and all-features (" << first.scene << ", " << size
           << ", " << first.triangles << " triangles, " << first.lights << " lights)\n\n"
           << "ms per frame (multiple of the floor). Floor: " << cell(s, &first) << ".\n\n"
           << "| shading | specialised | all-features | all-features / specialised "
              "|\n|---|---|---|---|\n";
        for (ShadingMode m : modes) {
            const SpeedRow* sp = find(s, toString(m), "specialised", first.lights, first.triangles);
            const SpeedRow* all =
                find(s, toString(m), "all-features", first.lights, first.triangles);
            md << "| " << toString(m) << " | " << cell(s, sp) << " | " << cell(s, all) << " | "
               << (sp && all ? num(s.configs[all->config].ms() / s.configs[sp->config].ms(), "%.2f")
                             : "-")
               << " |\n";
        }
    } else {
        const bool lights = name == "lights";
        md << "## " << (lights ? "Lights" : "Triangles") << " (" << first.scene << ", " << size
           << ")\n\n"
           << "ms per frame (multiple of the floor of the same geometry and pixels).\n\n| "
           << (lights ? "lights" : "triangles") << " | floor |";
        const bool shadows = lights && find(s, toString(modes.front()), "specialised+shadows",
                                            first.lights, first.triangles);
        for (ShadingMode m : modes)
            md << ' ' << toString(m) << " |";
        if (shadows)
            for (ShadingMode m : modes) md << ' ' << toString(m) << " + shadows (x unshadowed) |";
        md << (lights ? "" : " phong Mtri/s |") << "\n|---|---|";
        for (std::size_t i = 0; i < modes.size() * (shadows ? 2 : 1); ++i)
            md << "---|";
        md << (lights ? "" : "---|") << "\n";
        for (const SpeedRow& r : s.rows) {
            if (r.shading != toString(modes.front()) || r.features != "specialised") continue;
            md << "| " << (lights ? r.lights : r.triangles) << " | "
               << num(s.configs[r.floor].ms(), "%.2f") << " |";
            const SpeedRow* phong = nullptr;
            for (ShadingMode m : modes) {
                const SpeedRow* x = find(s, toString(m), "specialised", r.lights, r.triangles);
                if (m == ShadingMode::Phong) phong = x;
                md << ' ' << cell(s, x) << " |";
            }
            for (ShadingMode m : shadows ? modes : std::vector<ShadingMode>{}) {
                const SpeedRow* x = find(s, toString(m), "specialised", r.lights, r.triangles);
                const SpeedRow* y = find(s, toString(m), "specialised+shadows", r.lights, r.triangles);
                md << ' ' << cell(s, y) << " ("
                   << (x && y ? num(s.configs[y->config].ms() / s.configs[x->config].ms(), "%.2f") : "-")
                   << "x) |";
            }
            if (!lights)
                md << ' '
                   << (phong ? num(double(r.triangles) / s.configs[phong->config].ms() / 1000.0,
                                   "%.1f")
                             : "-")
                   << " |";
            md << "\n";
        }
    }
    md << "\n";
}

int run(SpeedArgs& a) {
    applyQuick(a);
    auto modes = parseShadingList(a.shading, "--shading");
    if (!modes) return report(modes.error());
    for (const std::string& s : a.sections)
        if (s != "modes" && s != "lights" && s != "triangles")
            return report(makeError(ErrorCode::InvalidInput,
                                    "\"" + s + "\" is not a section (modes, lights, triangles)",
                                    "--sections"));
    if (auto r = checkRange(a.lights, 1, 4096, "--lights"); !r) return report(r.error());
    for (double t : a.triangles)
        if (!(t >= 100.0 && t <= 1e8))
            return report(makeError(ErrorCode::InvalidInput, "triangle counts must be in 100..1e8",
                                    "--triangles"));
    if (a.width < 1 || a.height < 1 || a.width > 16384 || a.height > 16384)
        return report(makeError(ErrorCode::InvalidInput, "image sides must be in 1..16384",
                                "--width/--height"));
    if (auto f = makeOutputFolder(a.timing.output); !f) return report(f.error());
    auto loaded = loadScene(a.scene);
    if (!loaded) return report(loaded.error());
    const ColdShaderCache coldCache; // before the device: first frames pay the whole JIT
    auto renderer = Renderer::create(a.device.desc());
    if (!renderer) return report(renderer.error());
    if (auto r = checkMsaa(a.msaa, renderer->device()); !r) return report(r.error());

    SpeedBench bench(a, *renderer, *modes);
    std::ostringstream md;
    md << "# Where the frame time goes: `lantern bench speed`\n\n"
       << "Machine: " << machineDescription(*renderer) << ".\n\nReproduce: `" << commandLine()
       << "`\n\n";
    std::string csv = csvHeader();
    bool gpuClock = true;
    std::vector<double> spreads;
    for (const std::string& name :
         {std::string("modes"), std::string("lights"), std::string("triangles")}) {
        if (std::find(a.sections.begin(), a.sections.end(), name) == a.sections.end()) continue;
        auto section = name == "modes"    ? bench.modes(*loaded)
                       : name == "lights" ? bench.lights(*loaded)
                                          : bench.triangles();
        if (!section) return report(section.error());
        if (!a.timing.quiet)
            std::fprintf(stderr, "section %s: %zu configurations\n", name.c_str(),
                         section->configs.size());
        bool clock = true;
        if (auto t =
                timeInterleaved(*renderer, section->configs, a.timing.plan, a.timing.quiet, &clock);
            !t)
            return report(t.error());
        gpuClock = gpuClock && clock;
        for (const TimedConfig& c : section->configs)
            spreads.push_back(c.roundSpread());
        for (const SpeedRow& r : section->rows) {
            const TimedConfig& c = section->configs[r.config];
            const double floor = section->configs[r.floor].ms();
            std::ostringstream line;
            line << r.section << ',' << r.scene << ',' << r.width << ',' << r.height << ','
                 << r.shading << ',' << r.features << ',' << r.lights << ',' << r.triangles << ','
                 << r.msaa << ',' << num(c.ms()) << ',' << num(c.minMs()) << ',' << num(c.msWall())
                 << ',' << num(c.roundSpread(), "%.3f") << ',' << num(c.firstFrameMs) << ','
                 << c.pipelinesCreated << ',' << num(floor) << ',' << num(c.ms() / floor) << '\n';
            csv += line.str();
        }
        sectionMarkdown(md, *section, name, *modes);
    }
    md << "Frame time: "
       << (gpuClock ? "the render pass on the device's timestamps" : "render() wall time")
       << ", median of " << a.timing.plan.rounds << " rounds' medians of " << a.timing.plan.frames
       << " frames after " << a.timing.plan.warmup
       << " warm-up frames; within a section every configuration is interleaved with "
       << "the others in each round. The floor draws the same geometry over the same pixels with a "
       << "constant-colour shader (FeatureMode::Floor). " << spreadSentence(spreads) << "\n";
    const std::filesystem::path dir(a.timing.output);
    for (auto [file, text] : {std::pair{"speed.csv", csv}, std::pair{"speed.md", md.str()}})
        if (auto w = writeTextFile((dir / file).string(), text); !w) return report(w.error());
    if (!a.timing.quiet) std::fputs(md.str().c_str(), stdout);
    std::printf("wrote %s and %s\n", (dir / "speed.csv").c_str(), (dir / "speed.md").c_str());
    return kOk;
}

} // namespace

Runner addSpeedBench(CLI::App& bench) {
    auto a = std::make_shared<SpeedArgs>();
    CLI::App* cmd = bench.add_subcommand(
        "speed",
        "Frame times as multiples of a trivial-shader floor: shading modes (specialised and "
        "all-features), 1 to 256 lights, 1e3 to 1e7 triangles");
    cmd->add_option("scene", a->scene, "Scene of the modes and lights sections")
        ->capture_default_str();
    std::tie(a->widthOption, a->heightOption) = addSizeOptions(*cmd, a->width, a->height);
    cmd->add_option("--msaa", a->msaa, help::kMsaa)
        ->capture_default_str()
        ->check(CLI::IsMember({1, 2, 4, 8}));
    cmd->add_option("--sections", a->sections, "modes, lights, triangles")
        ->delimiter(',')
        ->capture_default_str();
    cmd->add_option("--shading", a->shading, help::kShadingList)
        ->delimiter(',')
        ->capture_default_str();
    a->lightsOption = cmd->add_option("--lights", a->lights, "Light counts")
                          ->delimiter(',')
                          ->capture_default_str();
    a->trianglesOption =
        cmd->add_option("--triangles", a->triangles, "Triangle counts (approximate)")
            ->delimiter(',')
            ->capture_default_str();
    cmd->add_flag("--shadows", a->shadows,
                  "The lights section also with every light casting shadows, side by side");
    cmd->add_option("--shadow-resolution", a->shadowResolution,
                    "Texels per side of each shadow map (--shadows)")
        ->capture_default_str()
        ->check(CLI::Range(16, 16384));
    a->timing.output = "bench-speed";
    a->timing.add(*cmd,
                  "Reduced run: 640x360, lights 1,8,64, up to 1e5 triangles, 2 rounds of 3 frames",
                  "Folder for speed.csv and speed.md");
    a->device.add(*cmd);
    return [a, cmd]() { return cmd->parsed() ? run(*a) : -1; };
}

} // namespace lantern::cli
