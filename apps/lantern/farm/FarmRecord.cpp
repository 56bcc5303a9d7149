// The farm's files: where a submission's record, scripts and logs go, the record itself (a
// JSON document beside the outputs, through nlohmann_json), and which frames exist and can be
// read.
#include "farm/Farm.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <mutex>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>
#include <fcntl.h>
#include <random>
#include <sys/random.h>
#include <unistd.h>

namespace lantern::cli::farm {
namespace fs = std::filesystem;

namespace {

// "out/frame_####.exr" -> "out/frame": the pattern's name without '#' runs or extension, and
// without the separators that were next to the frame number.
fs::path baseOf(const std::string& pattern) {
    const fs::path p(pattern);
    std::string stem = p.stem().string();
    stem.erase(std::remove(stem.begin(), stem.end(), '#'), stem.end());
    while (!stem.empty() && std::strchr("_-. ", stem.back()))
        stem.pop_back();
    while (!stem.empty() && std::strchr("_-. ", stem.front()))
        stem.erase(stem.begin());
    if (stem.empty()) stem = "frames";
    return p.parent_path() / stem;
}

constexpr const char* kRecordAbout = "Submission record of `lantern farm submit`: what `lantern "
                                     "farm check` and `lantern farm submit --resume` read";
constexpr int kRecordVersion = 2; // 1 was a line-per-value text file (lantern 0.1)

// A PNG is complete when it starts with the signature and ends with the IEND chunk (the
// writer renames a finished file into place, so anything else is damage).
std::string pngProblem(const fs::path& path) {
    std::ifstream f(path, std::ios::binary);
    char head[8] = {}, tail[12] = {};
    if (!f.read(head, 8)) return "shorter than a PNG signature";
    if (std::memcmp(head, "\x89PNG\r\n\x1a\n", 8) != 0) return "not a PNG (bad signature)";
    f.seekg(-12, std::ios::end);
    if (!f.read(tail, 12) || std::memcmp(tail + 4, "IEND", 4) != 0)
        return "truncated PNG (no IEND chunk)";
    return {};
}

} // namespace

fs::path recordPath(const std::string& pattern) {
    return baseOf(pattern).string() + ".farm";
}

fs::path scriptPath(const std::string& pattern, const std::string& scheduler, int resume) {
    std::string name = baseOf(pattern).string();
    if (resume > 0) name += ".resume-" + std::to_string(resume);
    return name + (scheduler == "k8s" ? ".k8s.yaml" : ".sbatch");
}

fs::path logFolder(const std::string& pattern) {
    return baseOf(pattern).string() + "-logs";
}

std::string shellQuote(const std::string& word) {
    const bool plain = !word.empty() && std::all_of(word.begin(), word.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || std::strchr("@%_+=:,./-", c);
    });
    if (plain) return word;
    std::string out = "'";
    for (char c : word)
        out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}


namespace {

using Json = nlohmann::ordered_json;

// The record's plain fields, in the order they are written: text, lists and counts.
struct TextField {
    const char* key;
    std::string Submission::*member;
};
struct ListField {
    const char* key;
    std::vector<std::string> Submission::*member;
};
struct CountField {
    const char* key;
    int Submission::*member;
};
constexpr TextField kTextFields[] = {{"scheduler", &Submission::scheduler},
                                     {"lantern", &Submission::lantern},
                                     {"scene", &Submission::scene},
                                     {"job-name", &Submission::jobName},
                                     {"partition", &Submission::partition},
                                     {"time", &Submission::time},
                                     {"mem", &Submission::mem},
                                     {"image", &Submission::image},
                                     {"namespace", &Submission::k8sNamespace},
                                     {"pvc", &Submission::pvc}};
constexpr ListField kListFields[] = {{"outputs", &Submission::outputs},
                                     {"render-args", &Submission::renderArgs},
                                     {"setup", &Submission::setup},
                                     {"sbatch-args", &Submission::sbatchArgs}};
constexpr CountField kCountFields[] = {{"tasks", &Submission::tasks},
                                       {"cpus-per-task", &Submission::cpusPerTask},
                                       {"gpus", &Submission::gpus}};

// The record's fields from its JSON (nlohmann's type errors name what was expected).
Submission fromJson(const Json& j) {
    Submission s;
    for (const auto& f : kTextFields)
        s.*f.member = j.value(f.key, std::string());
    for (const auto& f : kListFields)
        s.*f.member = j.value(f.key, std::vector<std::string>());
    for (const auto& f : kCountFields)
        s.*f.member = j.value(f.key, f.member == &Submission::tasks ? 1 : 0);
    const Json& frames = j.at("frames");
    s.range = FrameRange{frames.at("first").get<int>(), frames.at("last").get<int>()};
    for (const Json& job : j.value("jobs", Json::array()))
        s.jobs.push_back({job.at("id").is_null() ? "" : job.at("id").get<std::string>(),
                          job.at("frames").get<std::string>(), job.at("script").get<std::string>()});
    return s;
}

} // namespace

Result<void> writeRecord(const Submission& s) {
    Json j;
    j["about"] = kRecordAbout;
    j["lantern-farm"] = kRecordVersion;
    j["frames"] = {{"first", s.range.first}, {"last", s.range.last}};
    for (const auto& f : kTextFields)
        j[f.key] = s.*f.member;
    for (const auto& f : kCountFields)
        j[f.key] = s.*f.member;
    for (const auto& f : kListFields)
        j[f.key] = s.*f.member;
    j["jobs"] = Json::array();
    for (const auto& job : s.jobs)
        j["jobs"].push_back({{"id", job.id.empty() ? Json() : Json(job.id)},
                             {"frames", job.frames},
                             {"script", job.script}});
    return writeTextFile(recordPath(s.outputs.front()), j.dump(2) + "\n");
}

Result<Submission> readRecord(const fs::path& path) {
    std::ifstream f(path);
    if (!f)
        return makeError(ErrorCode::InvalidInput,
                         "no submission record here (was the sequence submitted with `lantern farm "
                         "submit` and this -o?)",
                         {}, path.string());
    auto bad = [&](const std::string& why) {
        return makeError(ErrorCode::InvalidInput, why, {}, path.string());
    };
    const Json j = Json::parse(f, nullptr, false);
    if (j.is_discarded() || !j.is_object())
        return bad("not a lantern farm record (not a JSON object; a record of the older text "
                   "format, version 1, is not read: submit again with --no-submit)");
    if (j.value("lantern-farm", 0) != kRecordVersion)
        return bad("record version " + j.value("lantern-farm", Json()).dump() +
                   " is not one this lantern reads (" + std::to_string(kRecordVersion) + ")");
    Submission s;
    try {
        s = fromJson(j);
    } catch (const Json::exception& e) {
        return bad(std::string("malformed record: ") + e.what());
    }
    if (s.range.first < 0 || s.range.last < s.range.first)
        return bad("frames must be a range A-B with 0 <= A <= B");
    if (s.tasks < 1) return bad("tasks must be at least 1");
    if (s.outputs.empty() || s.scene.empty() || s.lantern.empty())
        return bad("incomplete record: it needs lantern, scene and outputs");
    for (const auto& job : s.jobs)
        if (job.frames.empty()) return bad("a job needs its frames");
    return s;
}

std::vector<MissingFrame> checkFrames(const std::vector<std::string>& outputs,
                                      const std::vector<int>& frames) {
    struct Item {
        int frame;
        std::string path;
    };
    std::vector<Item> items;
    for (const std::string& out : outputs)
        for (int frame : frames)
            items.push_back({frame, expandFramePattern(out, frame)});
    std::vector<std::string> problems(items.size());
    std::vector<char> absent(items.size(), 0);
    std::atomic<std::size_t> next{0};
    auto work = [&] {
        for (std::size_t i; (i = next.fetch_add(1)) < items.size();) {
            const fs::path path = items[i].path;
            std::error_code ec;
            if (!fs::is_regular_file(path, ec)) {
                absent[i] = 1;
                continue;
            }
            const std::string ext = path.extension().string();
            if (ext == ".exr") {
                if (auto image = readExr(path); !image)
                    problems[i] = "OpenEXR cannot read it: " + image.error().message;
            } else if (ext == ".png") {
                problems[i] = pngProblem(path);
            }
        }
    };
    const unsigned threads = std::clamp(std::thread::hardware_concurrency(), 1u, 16u);
    std::vector<std::thread> pool;
    for (unsigned t = 1; t < threads; ++t)
        pool.emplace_back(work);
    work();
    for (auto& t : pool)
        t.join();
    std::vector<MissingFrame> missing;
    for (std::size_t i = 0; i < items.size(); ++i)
        if (absent[i] || !problems[i].empty())
            missing.push_back({items[i].frame, items[i].path, problems[i]});
    std::stable_sort(
        missing.begin(), missing.end(),
        [](const MissingFrame& a, const MissingFrame& b) { return a.frame < b.frame; });
    return missing;
}

int countPresent(const std::vector<std::string>& outputs, const std::vector<int>& frames) {
    int present = 0;
    for (int frame : frames) {
        bool all = true;
        for (const std::string& out : outputs) {
            std::error_code ec;
            all = all && fs::is_regular_file(expandFramePattern(out, frame), ec);
        }
        present += all;
    }
    return present;
}

std::vector<std::string> renderCommand(const Submission& s, const JobWork& work) {
    std::vector<std::string> words = {s.lantern, "render", s.scene};
    if (work.wholeRange) {
        words.push_back("--frames");
        words.push_back(std::to_string(s.range.first) + "-" + std::to_string(s.range.last));
    } else {
        words.push_back("--frame-list");
        words.push_back(formatFrameList(work.frames));
    }
    for (const std::string& out : s.outputs) {
        words.push_back("-o");
        words.push_back(out);
    }
    words.insert(words.end(), s.renderArgs.begin(), s.renderArgs.end());
    return words;
}

bool hasRenderOption(const Submission& s, const std::string& option) {
    return std::any_of(s.renderArgs.begin(), s.renderArgs.end(), [&](const std::string& a) {
        return a == option || a.rfind(option + "=", 0) == 0;
    });
}

} // namespace lantern::cli::farm
