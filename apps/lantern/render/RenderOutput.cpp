// What `lantern render` prints and how it runs a sequence (render/RenderOutput.h).
#include "render/RenderOutput.h"

#include "common/CliSupport.h"

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <thread>
#include <unistd.h>
#include <vector>

namespace lantern::cli {
namespace {

std::string triple(const glm::dvec3& v) {
    std::ostringstream s;
    s << std::setprecision(6) << v.x << " " << v.y << " " << v.z;
    return s.str();
}

const char* lightTypeName(LightType t) {
    return t == LightType::Directional ? "directional" : t == LightType::Point ? "point" : "spot";
}

std::string clock(double seconds) {
    const long s = long(seconds + 0.5);
    char b[32];
    std::snprintf(b, sizeof b, "%ld:%02ld", s / 60, s % 60);
    return b;
}

// A progress bar on a terminal, one plain line per frame otherwise.
void showProgress(const SequenceProgress& p, bool terminal) {
    if (terminal) {
        const int width = 30;
        const int filled = p.total > 0 ? width * p.written / p.total : width;
        std::string bar(std::size_t(filled), '=');
        if (filled < width) bar += '>' + std::string(std::size_t(width - filled - 1), ' ');
        std::fprintf(stderr, "\r%5d/%d [%s] %.2f fps, %s left   ", p.written, p.total, bar.c_str(),
                     p.framesPerSecond, clock(p.secondsLeft).c_str());
        if (p.written == p.total) std::fputc('\n', stderr);
    } else {
        std::fprintf(stderr, "lantern: frame %d written (%d/%d, %.2f fps, %s left)\n", p.lastFrame,
                     p.written, p.total, p.framesPerSecond, clock(p.secondsLeft).c_str());
    }
    std::fflush(stderr);
}

double medianOf(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

} // namespace

void printProbe(std::ostream& out, const ProbeReport& r) {
    out << std::setprecision(6);
    out << "probe pixel " << r.x << "," << r.y << " (x from the left, y from the top)\n";
    if (!r.hit) {
        out << "  no surface: background " << triple(glm::dvec3(r.pixel)) << " alpha " << r.pixel.a
            << "\n";
        return;
    }
    out << "  view " << r.view << ", node " << r.node << " \"" << r.nodeName << "\", mesh "
        << r.mesh << " primitive " << r.primitive << ", ";
    if (r.topology == Topology::Points)
        out << "point " << r.triangle << " (vertex " << r.vertices[0] << ")\n";
    else if (r.topology == Topology::Lines)
        out << "line " << r.triangle << " (vertices " << r.vertices[0] << " " << r.vertices[1]
            << ", weights " << r.barycentric.x << " " << r.barycentric.y << ")\n";
    else
        out << "triangle " << r.triangle << " (vertices " << r.vertices[0] << " " << r.vertices[1]
            << " " << r.vertices[2] << ", barycentric " << triple(r.barycentric) << ")\n";
    out << "  surface point (eye space): " << triple(r.position) << "\n";
    out << "  normal (eye space, as lit): " << triple(r.normal) << "  "
        << (r.backFacing ? "back face" : "front face")
        << (r.backMaterial ? ", back material and negated normal (two-sided)" : "") << "\n";
    const MaterialSide& m = r.materialSide;
    out << "  material " << r.material << " \"" << r.materialName << "\""
        << (r.backMaterial ? " (back)" : "") << (r.unlit ? " unlit" : "") << ": ambient "
        << triple(m.ambient) << ", diffuse " << triple(glm::dvec3(m.diffuse)) << " alpha "
        << m.diffuse.a << ", specular " << triple(m.specular) << ", shininess " << m.shininess
        << ", emission " << triple(m.emission) << "\n";
    out << "  shading " << toString(r.shading) << (r.glCompat ? " (gl-compat)" : "")
        << ", specular " << (r.specularPresent ? toString(r.specular) : "none (not compiled in)")
        << ", " << (r.localViewer ? "local" : "distant") << " viewer, "
        << (r.twoSided ? "two-sided" : "one-sided") << (r.clamped ? ", clamped to [0,1]" : "")
        << "\n";
    if (r.textured)
        out << "  note: textures (base colour or maps) modulate this pixel; the probe evaluates "
               "the material without them\n";
    for (const ProbeEvaluation& e : r.evaluations) {
        out << "  evaluated at the " << e.where << " (weight " << e.weight << "): point "
            << triple(e.position) << ", normal " << triple(e.normal) << "\n";
        out << "    a_m " << triple(e.ambientM) << ", d_m " << triple(e.diffuseM) << "\n";
        out << "    emission e_m:          " << triple(e.emission) << "\n";
        out << "    global ambient a_m*A:  " << triple(e.globalAmbient) << "\n";
        for (std::size_t i = 0; i < e.lights.size(); ++i) {
            const ProbeLight& l = e.lights[i];
            out << "    light " << i << " \"" << l.name << "\" " << lightTypeName(l.type)
                << ": attenuation " << l.attenuation << ", spot " << l.spot << ", n.l " << l.nDotL
                << ", specular term " << l.specularTerm << "\n";
            out << "      ambient " << triple(l.ambient) << ", diffuse " << triple(l.diffuse)
                << ", specular " << triple(l.specular) << "\n";
            if (l.castsShadows)
                out << "      shadow: " << (l.visibility > 0.0 ? "lit" : "shadowed")
                    << (l.occluderNode >= 0 ? " by nodes[" + std::to_string(l.occluderNode) + "]" +
                                                  (l.occluderName.empty() ? std::string()
                                                                          : " \"" + l.occluderName + "\"")
                                            : std::string())
                    << " (exact shadow ray; visibility " << l.visibility << ")\n";
        }
        out << "    colour:                " << triple(e.colour) << " alpha " << e.alpha << "\n";
    }
    out << "  colour (reference):  " << triple(glm::dvec3(r.colour)) << " alpha " << r.colour.a
        << "\n";
    out << "  pixel (renderer):    " << triple(glm::dvec3(r.pixel)) << " alpha " << r.pixel.a
        << "\n";
}

int runSequence(Renderer& renderer, const PreparedScene& prepared, const RenderOptions& options,
                SequenceOptions seq) {
    const std::vector<std::string>& outputs = seq.outputs;
    const bool terminal = ::isatty(2);
    seq.progress = [terminal](const SequenceProgress& p) { showProgress(p, terminal); };
    installStopHandlers();
    seq.shouldStop = [] { return stopSignal() != 0; };
    auto result = renderer.renderSequence(prepared, options, seq);
    if (!result) return report(result.error());
    const SequenceReport& r = *result;
    for (int frame : r.framesWritten)
        for (const std::string& out : outputs)
            std::cout << expandFramePattern(out, frame) + "\n" << std::flush;  // whole lines
    const std::size_t total = sequenceFrames(seq).size();
    std::fprintf(
        stderr,
        "lantern: %zu of %zu frames written in %.2f s (%.2f fps); per frame (median): render "
        "%.1f ms (GPU %.1f ms), encode %.1f ms on %d threads; CPU %.1f s; at most %zu frames "
        "waiting\n",
        r.framesWritten.size(), total, r.wallSeconds,
        r.wallSeconds > 0 ? double(r.framesWritten.size()) / r.wallSeconds : 0.0,
        medianOf(r.renderMs), medianOf(r.gpuMs), medianOf(r.encodeMs),
        seq.encoderThreads > 0 ? seq.encoderThreads : int(std::thread::hardware_concurrency()),
        r.cpuSeconds, r.peakQueuedFrames);
    if (r.clampedValues > 0)
        std::fprintf(
            stderr,
            "lantern: warning: %llu values exceeded the half range and were clamped to 65504\n",
            (unsigned long long)r.clampedValues);
    if (r.stopped) {
        const int sig = stopSignal();
        std::fprintf(stderr, "lantern: stopped by %s; the frames written are complete\n",
                     sig == SIGTERM ? "SIGTERM" : "SIGINT");
        return 128 + (sig ? sig : SIGINT);
    }
    return kOk;
}

} // namespace lantern::cli
