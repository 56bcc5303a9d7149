// The accuracy plot as SVG, written directly (no plotting dependency): per group of comparable
// rows, error against ms per frame on log-log axes, one curve per shading mode and sample
// count, the Pareto front drawn as a staircase with rings, and the 1e-3 acceptance line.
#include "bench/BenchAccuracy.h"
#include "bench/BenchHarness.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace lantern::cli {
namespace {

constexpr double kPanelW = 560, kPanelH = 380, kLeft = 72, kRight = 24, kTop = 44, kBottom = 52;
constexpr double kLegendH = 64;
constexpr double kErrorFloor = 1e-8; // log axes: a zero error is drawn here
constexpr double kAcceptance = 1e-3; // numerics.md 7.3: interior RMSE of a reference preset

const char* modeColour(ShadingMode m) {
    switch (m) {
    case ShadingMode::Flat:
        return "#d62728";
    case ShadingMode::Gouraud:
        return "#1f77b4";
    case ShadingMode::Phong:
        return "#2ca02c";
    }
    return "#000";
}

std::string escape(const std::string& s) {
    std::string out;
    for (char c : s) {
        if (c == '&')
            out += "&amp;";
        else if (c == '<')
            out += "&lt;";
        else if (c == '>')
            out += "&gt;";
        else
            out += c;
    }
    return out;
}

// A logarithmic axis over whole decades.
struct LogAxis {
    double lo = 0, hi = 1;   // decades (log10)
    double from = 0, to = 1; // pixels

    static LogAxis fit(double minValue, double maxValue, double from, double to) {
        LogAxis a;
        a.lo = std::floor(std::log10(minValue));
        a.hi = std::ceil(std::log10(maxValue));
        if (a.hi <= a.lo) a.hi = a.lo + 1;
        a.from = from;
        a.to = to;
        return a;
    }
    double at(double v) const { return from + (std::log10(v) - lo) / (hi - lo) * (to - from); }
};

std::string decadeLabel(double decade) {
    const double v = std::pow(10.0, decade);
    return decade >= 0 && decade < 5 ? num(v, "%g") : "1e" + num(decade, "%g");
}

class Svg {
public:
    std::ostringstream out;
    void text(double x, double y, const std::string& s, const char* anchor = "start", int size = 11,
              const char* extra = "") {
        out << "<text x='" << x << "' y='" << y << "' font-size='" << size << "' text-anchor='"
            << anchor << "' " << extra << ">" << escape(s) << "</text>\n";
    }
    void line(double x0, double y0, double x1, double y1, const char* stroke, double width = 1,
              const char* extra = "") {
        out << "<line x1='" << x0 << "' y1='" << y0 << "' x2='" << x1 << "' y2='" << y1
            << "' stroke='" << stroke << "' stroke-width='" << width << "' " << extra << "/>\n";
    }
    void marker(double x, double y, bool square, const char* colour) {
        if (square)
            out << "<rect x='" << x - 3.5 << "' y='" << y - 3.5 << "' width='7' height='7' fill='"
                << colour << "'/>\n";
        else
            out << "<circle cx='" << x << "' cy='" << y << "' r='3.5' fill='" << colour << "'/>\n";
    }
};

// The error plotted for a row: a zero or non-finite error sits on the floor of the log axis.
double plotError(const AccuracyRow* r, bool interior) {
    const double e = interior ? r->error.interior.rmse : r->error.whole.rmse;
    return std::isfinite(e) ? std::max(e, kErrorFloor) : kErrorFloor;
}

// The panel's frame, title, decade grid, axis labels and the acceptance line.
void axes(Svg& svg, double ox, double oy, const LogAxis& x, const LogAxis& y, bool interior,
          const std::string& title) {
    svg.out << "<rect x='" << x.from << "' y='" << y.to << "' width='" << x.to - x.from
            << "' height='" << y.from - y.to << "' fill='none' stroke='#444'/>\n";
    svg.text(ox + kPanelW / 2, oy + 22, title, "middle", 13, "font-weight='bold'");
    for (int pass = 0; pass < 2; ++pass) {
        const LogAxis& a = pass == 0 ? x : y;
        for (double d = a.lo; d <= a.hi; d += 1) {
            for (int k = 1; k < 10 && (k == 1 || d < a.hi); ++k) {
                const double p = a.at(k * std::pow(10.0, d));
                const bool major = k == 1;
                if (pass == 0) {
                    svg.line(p, y.to, p, y.from, major ? "#ccc" : "#eee");
                    if (major) svg.text(p, y.from + 16, decadeLabel(d), "middle");
                } else {
                    svg.line(x.from, p, x.to, p, major ? "#ccc" : "#eee");
                    if (major) svg.text(x.from - 6, p + 4, decadeLabel(d), "end");
                }
            }
        }
    }
    svg.text((x.from + x.to) / 2, y.from + 36, "ms per frame (median, log scale)", "middle");
    svg.text(ox + 16, (y.from + y.to) / 2, interior ? "interior RMSE" : "whole-image RMSE",
             "middle", 11,
             ("transform='rotate(-90 " + std::to_string(ox + 16) + " " +
              std::to_string((y.from + y.to) / 2) + ")'")
                 .c_str());
    const double acceptance = y.at(kAcceptance);
    svg.line(x.from, acceptance, x.to, acceptance, "#888", 1, "stroke-dasharray='6 4'");
    svg.text(x.to - 4, acceptance - 4, "1e-3", "end", 10, "fill='#666'");
}

// One curve per shading mode and sample count, in tessellation order.
void curves(Svg& svg, const LogAxis& x, const LogAxis& y,
            const std::vector<const AccuracyRow*>& rows, bool interior) {
    std::vector<std::pair<ShadingMode, int>> series;
    for (const AccuracyRow* r : rows)
        if (std::find(series.begin(), series.end(), std::pair{r->shading, r->msaa}) == series.end())
            series.push_back({r->shading, r->msaa});
    for (auto [mode, msaa] : series) {
        std::vector<const AccuracyRow*> pts;
        for (const AccuracyRow* r : rows)
            if (r->shading == mode && r->msaa == msaa) pts.push_back(r);
        std::sort(pts.begin(), pts.end(), [](const AccuracyRow* a, const AccuracyRow* b) {
            return a->segments < b->segments;
        });
        svg.out << "<polyline fill='none' stroke='" << modeColour(mode) << "' stroke-width='1.5' "
                << (msaa > 1 ? "stroke-dasharray='5 3' " : "") << "points='";
        for (const AccuracyRow* r : pts)
            svg.out << x.at(std::max(r->ms, 1e-3)) << ',' << y.at(plotError(r, interior)) << ' ';
        svg.out << "'/>\n";
        for (const AccuracyRow* r : pts) {
            const double px = x.at(std::max(r->ms, 1e-3)), py = y.at(plotError(r, interior));
            svg.marker(px, py, msaa > 1, modeColour(mode));
            svg.text(px + 5, py - 5, std::to_string(r->segments), "start", 8,
                     ("fill='" + std::string(modeColour(mode)) + "'").c_str());
        }
    }
}

// The Pareto front: a staircase through its points, each ringed.
void paretoFront(Svg& svg, const LogAxis& x, const LogAxis& y,
                 const std::vector<const AccuracyRow*>& rows, bool interior) {
    auto error = [&](const AccuracyRow* r) { return plotError(r, interior); };
    std::vector<const AccuracyRow*> front;
    for (const AccuracyRow* r : rows)
        if (interior ? r->paretoInterior : r->paretoWhole) front.push_back(r);
    std::sort(front.begin(), front.end(),
              [](const AccuracyRow* a, const AccuracyRow* b) { return a->ms < b->ms; });
    if (front.empty()) return;
    svg.out << "<polyline fill='none' stroke='#000' stroke-width='2' stroke-opacity='0.55' "
               "points='";
    for (std::size_t i = 0; i < front.size(); ++i) {
        const double px = x.at(std::max(front[i]->ms, 1e-3)), py = y.at(error(front[i]));
        if (i > 0) svg.out << px << ',' << y.at(error(front[i - 1])) << ' ';
        svg.out << px << ',' << py << ' ';
    }
    svg.out << "'/>\n";
    for (const AccuracyRow* r : front)
        svg.out << "<circle cx='" << x.at(std::max(r->ms, 1e-3)) << "' cy='" << y.at(error(r))
                << "' r='7' fill='none' stroke='#000' stroke-width='1.5'/>\n";
}

void panel(Svg& svg, double ox, double oy, const std::vector<const AccuracyRow*>& rows,
           bool interior, const std::string& title) {
    double msLo = 1e300, msHi = 0, eLo = kAcceptance, eHi = kAcceptance;
    for (const AccuracyRow* r : rows) {
        msLo = std::min(msLo, std::max(r->ms, 1e-3));
        msHi = std::max(msHi, std::max(r->ms, 1e-3));
        eLo = std::min(eLo, plotError(r, interior));
        eHi = std::max(eHi, plotError(r, interior));
    }
    const LogAxis x = LogAxis::fit(msLo, msHi, ox + kLeft, ox + kPanelW - kRight);
    const LogAxis y = LogAxis::fit(eLo, eHi, oy + kPanelH - kBottom, oy + kTop);
    axes(svg, ox, oy, x, y, interior, title);
    curves(svg, x, y, rows, interior);
    paretoFront(svg, x, y, rows, interior);
}

} // namespace

std::string accuracyPlotSvg(const std::vector<AccuracyRow>& rows) {
    std::vector<std::string> groups;
    for (const AccuracyRow& r : rows)
        if (std::find(groups.begin(), groups.end(), r.group()) == groups.end())
            groups.push_back(r.group());
    const double width = 2 * kPanelW, height = kLegendH + double(groups.size()) * kPanelH;
    Svg svg;
    svg.out << "<?xml version='1.0' encoding='UTF-8'?>\n"
            << "<svg xmlns='http://www.w3.org/2000/svg' width='" << width << "' height='" << height
            << "' viewBox='0 0 " << width << ' ' << height << "' font-family='sans-serif'>\n"
            << "<rect width='100%' height='100%' fill='white'/>\n";
    svg.text(16, 24, "lantern bench accuracy: error against the exact reference vs ms per frame",
             "start", 15, "font-weight='bold'");
    double lx = 16;
    for (ShadingMode m : {ShadingMode::Flat, ShadingMode::Gouraud, ShadingMode::Phong}) {
        svg.line(lx, 46, lx + 24, 46, modeColour(m), 2);
        svg.text(lx + 30, 50, toString(m));
        lx += 100;
    }
    svg.marker(lx + 6, 46, false, "#555");
    svg.text(lx + 16, 50, "1 sample (solid)");
    lx += 120;
    svg.marker(lx + 6, 46, true, "#555");
    svg.text(lx + 16, 50, "MSAA (dashed)");
    lx += 110;
    svg.out << "<circle cx='" << lx + 6
            << "' cy='46' r='7' fill='none' stroke='#000' stroke-width='1.5'/>\n";
    svg.text(lx + 18, 50, "Pareto front");
    lx += 100;
    svg.line(lx, 46, lx + 24, 46, "#888", 1, "stroke-dasharray='6 4'");
    svg.text(lx + 30, 50, "acceptance 1e-3; labels: segments / subdivisions");
    for (std::size_t g = 0; g < groups.size(); ++g) {
        std::vector<const AccuracyRow*> in;
        for (const AccuracyRow& r : rows)
            if (r.group() == groups[g]) in.push_back(&r);
        const double oy = kLegendH + double(g) * kPanelH;
        panel(svg, 0, oy, in, true, groups[g] + ": interior (shading)");
        panel(svg, kPanelW, oy, in, false, groups[g] + ": whole image");
    }
    svg.out << "</svg>\n";
    return svg.out.str();
}

} // namespace lantern::cli
