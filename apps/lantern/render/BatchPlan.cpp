// The plan of a batch (Batch.h): which scenes (paths, globs, list files), the output names
// each job writes, and the refusal of a plan whose jobs would write the same file.
#include "render/Batch.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <glob.h>
#include <map>
#include <string_view>
#include <unordered_map>
#include <sys/stat.h>

namespace lantern::cli {
namespace fs = std::filesystem;

namespace {

bool isBuiltin(const std::string& arg) {
    return arg.rfind("builtin:", 0) == 0;
}

std::string lower(std::string s) {
    for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

bool isSceneFile(const std::string& path) {
    static const std::vector<std::string> extensions = sceneFileExtensions();
    const std::string ext = lower(fs::path(path).extension().string());
    return std::find(extensions.begin(), extensions.end(), ext) != extensions.end();
}

BatchScene sceneFor(const std::string& path) {
    BatchScene s;
    s.path = path;
    s.stem = isBuiltin(path) ? path.substr(8) : fs::path(path).stem().string();
    return s;
}

// True when `inner` (a real path) is `folder` (a real path) or lies below it.
bool isInside(const fs::path& inner, const fs::path& folder) {
    auto f = folder.begin(), i = inner.begin();
    for (; f != folder.end(); ++f, ++i)
        if (i == inner.end() || *i != *f) return false;
    return true;
}

// The real path of `path` (every link followed; for a missing file, of what exists of it).
fs::path realPath(const fs::path& path) {
    std::error_code ec;
    fs::path real = fs::weakly_canonical(path, ec);
    return ec ? path.lexically_normal() : real;
}

// Whether `path` lies inside `folder` or one of the allowed folders, once every link is
// followed: the rule the loader keeps for a scene's URIs (docs/robustness.md).
bool confined(const fs::path& path, const fs::path& folder,
              const std::vector<fs::path>& allowed) {
    const fs::path real = realPath(path);
    if (isInside(real, realPath(folder))) return true;
    return std::any_of(allowed.begin(), allowed.end(),
                       [&](const fs::path& a) { return isInside(real, realPath(a)); });
}

Error outside(const std::string& path, const std::string& folder, const std::string& source) {
    return makeError(ErrorCode::InvalidInput,
                     "leads outside " + folder + " (a symbolic link, an absolute path or ..); "
                     "--allow-folder admits another folder",
                     source, path);
}

// The folder part of a glob before its first wildcard ("scenes/a*/x.glb" -> "scenes").
fs::path globBase(const std::string& pattern) {
    const std::size_t wild = pattern.find_first_of("*?[");
    const std::size_t slash = pattern.rfind('/', wild);
    if (slash == std::string::npos) return ".";
    return slash == 0 ? fs::path("/") : fs::path(pattern.substr(0, slash));
}

// A glob's scene files (every format loadScene reads), sorted by their bytes; a match whose real path leaves the
// glob's folder fails at its turn.
Result<std::vector<BatchScene>> expandGlob(const std::string& pattern,
                                           const std::vector<fs::path>& allowed) {
    glob_t g{};
    const int rc = ::glob(pattern.c_str(), GLOB_MARK, nullptr, &g);
    std::vector<std::string> matches;
    if (rc == 0)
        for (std::size_t i = 0; i < g.gl_pathc; ++i) {
            const std::string m = g.gl_pathv[i];
            if (!m.empty() && m.back() != '/' && isSceneFile(m)) matches.push_back(m);
        }
    ::globfree(&g);
    if (rc != 0 && rc != GLOB_NOMATCH)
        return makeError(ErrorCode::IoError, "the pattern could not be expanded", "scene", pattern);
    if (matches.empty())
        return makeError(ErrorCode::Usage, "the pattern matches no scene file (.gltf, .glb, .obj, .ply, .stl, .off)", "scene",
                         pattern);
    std::sort(matches.begin(), matches.end());
    const fs::path base = globBase(pattern);
    std::vector<BatchScene> scenes;
    for (const std::string& m : matches) {
        BatchScene s = sceneFor(m);
        if (!confined(m, base, allowed)) s.problem = outside(m, base.string(), pattern);
        scenes.push_back(std::move(s));
    }
    return scenes;
}

// The text of a list file: a regular file of at most maxBytes. A list that is missing or
// cannot be read is refused input (exit 1), as a scene file is, not a renderer failure.
Result<std::string> readListFile(const std::string& list, std::uint64_t maxBytes) {
    struct stat st {};
    if (::stat(list.c_str(), &st) != 0)
        return makeError(ErrorCode::InvalidInput,
                         std::string("cannot read the list: ") + std::strerror(errno), "--list",
                         list);
    if (!S_ISREG(st.st_mode))
        return makeError(ErrorCode::InvalidInput, "the list is not a regular file", "--list", list);
    if (std::uint64_t(st.st_size) > maxBytes)
        return makeError(ErrorCode::InvalidInput,
                         "the list is larger than --max-size (" + std::to_string(maxBytes) +
                             " bytes)",
                         "--list", list);
    std::ifstream in(list, std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!in && !in.eof())
        return makeError(ErrorCode::InvalidInput, "cannot read the list", "--list", list);
    return text;
}

// A list file: one path per line, relative to the list's folder (blank lines and lines
// starting with '#' are skipped). As for a scene's URIs, ".." is refused unless --allow-folder
// is given, and the real path (links followed) must lie inside the list's folder or an allowed
// one; an absolute path is accepted where it lies there.
Result<std::vector<BatchScene>> expandList(const std::string& list,
                                           const std::vector<fs::path>& allowed,
                                           std::uint64_t maxBytes) {
    auto text = readListFile(list, maxBytes);
    if (!text) return std::move(text).error();
    const fs::path folder = fs::path(list).parent_path().empty() ? fs::path(".")
                                                                 : fs::path(list).parent_path();
    std::vector<BatchScene> scenes;
    std::size_t start = 0, lineNo = 0;
    while (start < text->size()) {
        std::size_t end = text->find('\n', start);
        if (end == std::string::npos) end = text->size();
        std::string line = text->substr(start, end - start);
        start = end + 1;
        ++lineNo;
        while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back()))) line.pop_back();
        const std::size_t first = line.find_first_not_of(" \t");
        if (first == std::string::npos || line[first] == '#') continue;
        line = line.substr(first);
        if (isBuiltin(line)) {
            scenes.push_back(sceneFor(line));
            continue;
        }
        const fs::path entry(line);
        const bool parent = std::any_of(entry.begin(), entry.end(),
                                        [](const fs::path& c) { return c == ".."; });
        BatchScene s = sceneFor(entry.is_absolute() ? line : (folder / entry).string());
        const std::string where = list + ":" + std::to_string(lineNo);
        if ((parent && allowed.empty()) || !confined(s.path, folder, allowed))
            s.problem = outside(s.path, folder.string(), where);
        scenes.push_back(std::move(s));
    }
    if (scenes.empty())
        return makeError(ErrorCode::Usage, "the list names no scene", "--list", list);
    return scenes;
}

// `i` zero-padded to the width of the largest index below `count` (names sort in order).
std::string padded(std::size_t i, std::size_t count) {
    const std::string s = std::to_string(i);
    const std::size_t width = std::to_string(count > 0 ? count - 1 : 0).size();
    return std::string(width - std::min(width, s.size()), '0') + s;
}

} // namespace

void BatchCliArgs::add(CLI::App& app) {
    app.add_option("--list", lists,
                   "A file naming scenes, one path per line relative to its folder (blank lines "
                   "and # comments skipped); repeatable; @FILE as a scene is the same");
    app.add_option("--views", views,
                   "Render every scene from these views, comma-separated: orbit:N (N views "
                   "around +Y, 30 degrees up), turntable:N (level), view names (three-quarter, "
                   "front, back, left, right, top, bottom, iso) or a .json pose file");
    app.add_option("--processes", processes,
                   "In a batch, renderers in flight: the jobs split by position over N "
                   "processes, each with its own device (0: one per core); paths are printed as "
                   "each process writes them")
        ->capture_default_str()
        ->check(CLI::Range(0, 256));
    app.add_flag("--overwrite", overwrite,
                 "In a batch, render jobs whose outputs exist already (default: skip them)");
}

Result<void> checkBatchOptions(const BatchCliArgs& batch, const CameraOptions& c,
                               const char* single) {
    if (single)
        return makeError(ErrorCode::Usage,
                         "concerns one picture: it cannot be combined with a batch (several "
                         "scenes, a glob, a list, --views or an output template)",
                         single);
    const bool chosen = !c.cameras.empty() || c.defaultCamera || !c.lookAt.empty() ||
                        !c.perspective.empty() || !c.ortho.empty() || !c.frustum.empty() ||
                        !c.viewports.empty() || !c.layout.empty() || !c.view.empty();
    if (!batch.views.empty() && chosen)
        return makeError(ErrorCode::Usage,
                         "--views chooses the cameras: --camera, --default-camera, --look-at, "
                         "--view, the projections, --viewport and --layout cannot be combined "
                         "with it",
                         "--views");
    return {};
}

Result<std::vector<BatchFrame>> batchFrames(const std::string& range, const std::string& list,
                                            double fps, std::optional<int> frame, double time) {
    std::vector<int> numbers;
    if (!list.empty()) {
        auto l = parseFrameList(list);
        if (!l) return std::move(l).error();
        numbers = *l;
    } else if (!range.empty()) {
        auto f = parseFrameRange(range);
        if (!f) return std::move(f).error();
        numbers = shardFrames(*f, Shard{});
    }
    std::vector<BatchFrame> frames;
    for (int n : numbers) frames.push_back({n, double(n) / fps});
    if (frames.empty())
        frames.push_back(frame ? BatchFrame{*frame, double(*frame) / fps}
                               : BatchFrame{int(std::round(time * fps)), time});
    return frames;
}

bool isGlob(const std::string& arg) {
    if (isBuiltin(arg) || arg.find_first_of("*?[") == std::string::npos) return false;
    std::error_code ec;
    return !fs::exists(arg, ec);
}

bool wantsBatch(const std::vector<std::string>& scenes, const std::vector<std::string>& lists,
                const std::string& views, const std::vector<std::string>& outputs) {
    if (scenes.size() > 1 || !lists.empty() || !views.empty()) return true;
    for (const std::string& s : scenes)
        if ((!s.empty() && s[0] == '@') || isGlob(s)) return true;
    return std::any_of(outputs.begin(), outputs.end(),
                       [](const std::string& o) { return o.find('{') != std::string::npos; });
}

Result<std::vector<BatchScene>> expandScenes(const std::vector<std::string>& args,
                                             const std::vector<std::string>& lists,
                                             const std::vector<fs::path>& allowed,
                                             std::uint64_t maxBytes) {
    std::vector<BatchScene> scenes;
    auto append = [&](Result<std::vector<BatchScene>> more) -> Result<void> {
        if (!more) return std::move(more).error();
        for (BatchScene& s : *more) scenes.push_back(std::move(s));
        return {};
    };
    for (const std::string& arg : args) {
        if (!arg.empty() && arg[0] == '@')
            LANTERN_TRY(append(expandList(arg.substr(1), allowed, maxBytes)));
        else if (isGlob(arg))
            LANTERN_TRY(append(expandGlob(arg, allowed)));
        else
            scenes.push_back(sceneFor(arg));
    }
    for (const std::string& list : lists) LANTERN_TRY(append(expandList(list, allowed, maxBytes)));
    return scenes;
}

Result<std::string> expandOutputTemplate(const std::string& pattern, const TemplateValues& v) {
    // '#' runs are expanded in the template's own text only: a '#' in a file or view name
    // stays as it is.
    std::string out, literal;
    for (std::size_t i = 0; i < pattern.size();) {
        if (pattern[i] != '{') {
            literal += pattern[i++];
            continue;
        }
        const std::size_t close = pattern.find('}', i);
        const std::string_view name = std::string_view(pattern).substr(
            i, close == std::string::npos ? std::string::npos : close - i + 1);
        const std::string frame = name == "{frame}" ? std::to_string(v.frame) : std::string();
        const std::string* value = name == "{scene}"   ? &v.scene
                                   : name == "{index}" ? &v.index
                                   : name == "{view}"  ? &v.view
                                   : name == "{frame}" ? &frame
                                                       : nullptr;
        if (!value)
            return makeError(ErrorCode::Usage,
                             "unknown placeholder " + std::string(name) + " in \"" + pattern +
                                 "\" (known: {scene}, {index}, {view}, {frame})",
                             "--output");
        out += expandFramePattern(literal, v.frame);
        out += *value;
        literal.clear();
        i = close + 1;
    }
    return out + expandFramePattern(literal, v.frame);
}

namespace {

// The file an output names, for telling two outputs apart: the path made lexically normal
// ("a//b" and "a/./b" are "a/b"). Most names are normal already, and building a path costs
// a batch of a million jobs a second, so only a name with "//", a "." component or a
// trailing '/' is rebuilt.
std::string outputKey(const std::string& out) {
    const bool plain = !out.empty() && out.front() != '.' && out.back() != '/' &&
                       out.find("//") == std::string::npos && out.find("/.") == std::string::npos;
    return plain ? out : fs::path(out).lexically_normal().string();
}

} // namespace

Result<std::vector<BatchJob>> planJobs(const std::vector<BatchScene>& scenes,
                                       const std::vector<BatchView>& views,
                                       const std::vector<BatchFrame>& frames,
                                       const std::vector<std::string>& outputs) {
    // Counted before anything is planned: a plan is held whole (to refuse two jobs writing
    // one file before anything renders), so its size is bounded.
    std::uint64_t total = 0;
    if (__builtin_mul_overflow(std::uint64_t(scenes.size()), std::uint64_t(views.size()), &total) ||
        __builtin_mul_overflow(total, std::uint64_t(frames.size()), &total) ||
        total > kMaxBatchJobs)
        return makeError(ErrorCode::InvalidInput,
                         "the batch has " + std::to_string(scenes.size()) + " scenes x " +
                             std::to_string(views.size()) + " views x " +
                             std::to_string(frames.size()) + " frames, more than " +
                             std::to_string(kMaxBatchJobs) +
                             " jobs; split it into several batches (a list per batch, or fewer "
                             "frames)",
                         "");
    std::vector<BatchJob> jobs;
    jobs.reserve(std::size_t(total));
    // Each output file and the job that writes it: two jobs (or two outputs of one) writing
    // the same file would overwrite each other, so the plan is refused before anything renders.
    std::unordered_map<std::string, std::size_t> writer;
    writer.reserve(std::size_t(total * outputs.size()));
    for (std::size_t s = 0; s < scenes.size(); ++s) {
        const std::string index = padded(s, scenes.size());
        for (std::size_t v = 0; v < views.size(); ++v)
            for (std::size_t f = 0; f < frames.size(); ++f) {
                BatchJob job{s, v, f, {}};
                job.outputs.reserve(outputs.size());
                for (const std::string& pattern : outputs) {
                    auto out = expandOutputTemplate(
                        pattern, {scenes[s].stem, index, views[v].name, frames[f].number});
                    if (!out) return std::move(out).error();
                    if (auto [it, fresh] = writer.emplace(outputKey(*out), jobs.size()); !fresh) {
                        const BatchJob& other = jobs.size() > it->second ? jobs[it->second] : job;
                        return makeError(
                            ErrorCode::Usage,
                            "the batch would write " + *out + " twice (" +
                                scenes[other.scene].path + " view " + views[other.view].name +
                                " and " + scenes[s].path + " view " + views[v].name +
                                "); put {scene} (or {index}), {view} and {frame} in the output name",
                            "--output");
                    }
                    job.outputs.push_back(std::move(*out));
                }
                jobs.push_back(std::move(job));
            }
    }
    return jobs;
}

} // namespace lantern::cli
