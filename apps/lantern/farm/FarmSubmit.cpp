// `lantern farm submit`: a sequence rendered as a scheduler's job array (docs/farm.md). Builds
// the submission from the command line (or, with --resume, from the record beside the
// outputs), writes the job (sbatch script or Kubernetes manifest) and the record, submits it
// and, with --wait, follows it to its end; --resume renders only the frames missing.
#include "common/CliSupport.h"
#include "common/Commands.h"
#include "farm/FarmCommand.h"

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <map>

namespace lantern::cli::farm {
namespace {

namespace fs = std::filesystem;

// The arguments farm did not recognise are the scene and `lantern render` options, passed to
// every task verbatim. Which of them take a value is read from the render command itself, so
// every render option works here without being listed twice.
struct RenderPart {
    std::string scene;
    std::vector<std::string> args;
};

// The `lantern render` command's own parser, with the runner that owns the variables its
// options write into (a parse after the runner is gone writes into freed memory).
struct RenderParser {
    CLI::App app;
    Runner runner = addRenderCommand(app);
};

Result<RenderPart> splitRenderArguments(const std::vector<std::string>& extras) {
    RenderParser parser;
    const CLI::App* render = parser.app.get_subcommand("render");
    RenderPart part;
    for (std::size_t i = 0; i < extras.size(); ++i) {
        const std::string& arg = extras[i];
        const bool option = arg.size() > 1 && arg[0] == '-';
        if (!option) {
            if (!part.scene.empty())
                return usage("unexpected argument \"" + arg + "\" (the scene is \"" + part.scene +
                             "\")");
            part.scene = arg;
            continue;
        }
        const std::string name = arg.substr(0, arg.find('='));
        if (name == "--shard" || name == "--frame-list")
            return usage("farm submit sets " + name + " for each task itself", name);
        if (name == "--views" || name == "--list" || name == "--overwrite")
            return usage("farm submit renders sequences; run a batch as a plain job array "
                         "with --shard (docs/farm.md)",
                         name);
        const CLI::Option* opt = render->get_option_no_throw(name);
        if (!opt)
            return usage("unknown option " + name +
                             " (farm submit takes its own options and those of `lantern render`)",
                         name);
        part.args.push_back(arg);
        if (arg.find('=') == std::string::npos && opt->get_items_expected_max() > 0) {
            if (i + 1 >= extras.size()) return usage(name + " needs a value", name);
            part.args.push_back(extras[++i]);
        }
    }
    return part;
}

// Checks the tasks' command line with the render command's own parser before anything is
// queued, so a typo fails here rather than in every task.
Result<void> checkRenderLine(const Submission& s) {
    std::vector<std::string> line = {
        "render",   s.scene,
        "--frames", std::to_string(s.range.first) + "-" + std::to_string(s.range.last),
        "--shard",  "0/1"};
    for (const std::string& out : s.outputs)
        line.insert(line.end(), {"-o", out});
    line.insert(line.end(), s.renderArgs.begin(), s.renderArgs.end());
    std::reverse(line.begin(), line.end()); // CLI11 takes the arguments last first
    RenderParser parser;
    try {
        parser.app.parse(line);
    } catch (const CLI::ParseError& e) {
        return usage(std::string("the render options: ") + e.what());
    }
    return {};
}

std::string selfPath() {
    std::error_code ec;
    const fs::path self = fs::read_symlink("/proc/self/exe", ec);
    return ec ? std::string("lantern") : self.string();
}

// A line of the record or script must stay one line.
Result<void> checkOneLine(const Submission& s) {
    std::vector<const std::string*> all = {&s.scene,     &s.lantern,      &s.jobName,
                                           &s.partition, &s.time,         &s.mem,
                                           &s.image,     &s.k8sNamespace, &s.pvc};
    for (const auto* list : {&s.outputs, &s.renderArgs, &s.setup, &s.sbatchArgs})
        for (const std::string& v : *list)
            all.push_back(&v);
    for (const std::string* v : all)
        if (v->find_first_of("\n\r") != std::string::npos)
            return usage("arguments may not contain line breaks: \"" + *v + "\"");
    return {};
}

// --resume: the record beside the outputs, which this command line may not contradict.
Result<Submission> resumedSubmission(const SubmitArgs& a, const RenderPart& part,
                                     const std::vector<std::string>& outputs) {
    auto record = readRecord(recordPath(outputs.front()));
    if (!record) return std::move(record).error();
    Submission s = std::move(*record);
    if (outputs != s.outputs)
        return usage("-o differs from the original submission's outputs", "--output");
    if (!a.frames.empty()) {
        auto r = parseFrameRange(a.frames);
        if (!r) return std::move(r).error();
        if (r->first != s.range.first || r->last != s.range.last)
            return usage("--frames differs from the original submission's " +
                             std::to_string(s.range.first) + "-" + std::to_string(s.range.last),
                         "--frames");
    }
    if (!part.scene.empty()) {
        const std::string scene = part.scene.rfind("builtin:", 0) == 0
                                      ? part.scene
                                      : fs::absolute(part.scene).lexically_normal().string();
        if (scene != s.scene)
            return usage("the scene differs from the original submission's " + s.scene);
    }
    if (!part.args.empty() && part.args != s.renderArgs)
        return usage("the render options differ from the original submission's; resume renders "
                     "the missing frames exactly as the others were");
    return s;
}

// A new submission: the scene (absolute; every task must reach it), frames and tasks.
Result<Submission> newSubmission(const SubmitArgs& a, const RenderPart& part,
                                 const std::vector<std::string>& outputs) {
    if (part.scene.empty()) return usage("farm submit needs a SCENE (a scene file or builtin:NAME)");
    if (a.frames.empty()) return usage("farm submit needs --frames A-B", "--frames");
    if (a.tasks < 1) return usage("farm submit needs --tasks N (the job array's size)", "--tasks");
    auto r = parseFrameRange(a.frames);
    if (!r) return std::move(r).error();
    Submission s;
    s.range = *r;
    s.scene = part.scene;
    if (s.scene.rfind("builtin:", 0) != 0) {
        std::error_code ec;
        if (!fs::is_regular_file(s.scene, ec))
            return makeError(ErrorCode::InvalidInput,
                             "no such scene file (every task must reach it: use "
                             "shared storage)",
                             {}, s.scene);
        s.scene = fs::absolute(s.scene).lexically_normal().string();
    }
    s.outputs = outputs;
    s.renderArgs = part.args;
    s.tasks = a.tasks;
    s.lantern = selfPath();
    s.jobName = "lantern-" + recordPath(outputs.front()).stem().string();
    return s;
}

// Options given on this command line win over the record's.
void applyGivenOptions(Submission& s, const SubmitArgs& a, const CLI::App& cmd) {
    auto given = [&](const char* name) { return cmd.count(name) > 0; };
    if (given("--scheduler")) s.scheduler = a.scheduler;
    if (given("--tasks") && !a.resume) s.tasks = a.tasks;
    if (given("--lantern")) s.lantern = a.lantern;
    if (given("--job-name")) s.jobName = a.jobName;
    if (given("--partition")) s.partition = a.partition;
    if (given("--time")) s.time = a.time;
    if (given("--mem")) s.mem = a.mem;
    if (given("--cpus-per-task")) s.cpusPerTask = a.cpusPerTask;
    if (given("--gpus")) s.gpus = a.gpus;
    if (given("--sbatch-arg")) s.sbatchArgs = a.sbatchArgs;
    if (given("--setup")) s.setup = a.setup;
    if (given("--image")) s.image = a.image;
    if (given("--namespace")) s.k8sNamespace = a.k8sNamespace;
    if (given("--pvc")) s.pvc = a.pvc;
}

// Builds the submission from the command line, or for --resume from the record beside the
// outputs with what the command line overrides.
Result<Submission> makeSubmission(const SubmitArgs& a, const RenderPart& part,
                                  const CLI::App& cmd) {
    if (auto r = checkOutputs(a.outputs); !r) return std::move(r).error();
    const std::vector<std::string> outputs = absolutePatterns(a.outputs);
    auto made = a.resume ? resumedSubmission(a, part, outputs) : newSubmission(a, part, outputs);
    if (!made) return made;
    Submission s = std::move(*made);
    applyGivenOptions(s, a, cmd);
    if (s.scheduler == "k8s" && s.image.empty())
        return usage("--scheduler k8s needs --image IMAGE (a container image holding lantern)",
                     "--image");
    if (auto r = checkOneLine(s); !r) return std::move(r).error();
    if (auto r = checkRenderLine(s); !r) return std::move(r).error();
    return s;
}

// Two jobs must not render the same frames: refuse while one of this sequence's is active
// (for --resume, its frames are not missing, only not rendered yet).
Result<void> refuseWhileActive(const SubmitArgs& a, const Submission& s) {
    auto previous = a.resume ? Result<Submission>(s) : readRecord(recordPath(s.outputs.front()));
    if (!previous) return {};
    std::vector<std::string> ids;
    for (const auto& j : previous->jobs)
        ids.push_back(j.id);
    auto active = slurmActiveTasks(ids, previous->jobName);
    if (!active) return std::move(active).error();
    if (*active > 0)
        return makeError(ErrorCode::InvalidInput,
                         std::to_string(*active) +
                             " task(s) of this sequence are still pending or running: "
                             "wait for them (or scancel them) first",
                         a.resume ? "--resume" : "--output");
    return {};
}

// The job's frames, tasks and script: the whole range, or for --resume the frames missing or
// unreadable (none: nothing to do). A new submission forgets the record's jobs.
JobWork planWork(const SubmitArgs& a, Submission& s, const CLI::App& cmd) {
    JobWork work;
    work.tasks = s.tasks;
    if (a.resume) {
        const auto missing = checkFrames(s.outputs, rangeFrames(s.range));
        work.frames = missingFrames(missing);
        if (work.frames.empty()) return work;
        for (const auto& m : missing)
            if (!m.why.empty())
                std::fprintf(stderr, "lantern: %s is unreadable: rendering it again\n",
                             m.path.c_str());
        work.wholeRange = false;
        work.tasks = cmd.count("--tasks") ? a.tasks : std::min(s.tasks, int(work.frames.size()));
        // The first job is the original submission; each resume gets its own script.
        work.script = scriptPath(s.outputs.front(), s.scheduler, std::max(1, int(s.jobs.size())));
    } else {
        work.frames = rangeFrames(s.range);
        work.script = scriptPath(s.outputs.front(), s.scheduler, 0);
        s.jobs.clear();
    }
    if (work.tasks > int(work.frames.size())) {
        std::fprintf(stderr, "lantern: %d tasks for %zu frames: using %zu tasks\n", work.tasks,
                     work.frames.size(), work.frames.size());
        work.tasks = int(work.frames.size());
    }
    return work;
}

// Writes the job's script (or manifest) and the record with the job added; returns the
// frames it renders as the record says them.
Result<std::string> writeJob(Submission& s, const JobWork& work) {
    const bool slurm = s.scheduler == "slurm";
    // Every task writes into these folders; Slurm does not create the log folder either.
    std::error_code ec;
    for (const std::string& out : s.outputs)
        fs::create_directories(fs::path(out).parent_path(), ec);
    if (slurm) fs::create_directories(logFolder(s.outputs.front()), ec);
    if (ec)
        return makeError(ErrorCode::IoError, "cannot create the output folder: " + ec.message(), {},
                         s.outputs.front());
    std::string text;
    if (slurm) {
        text = slurmScript(s, work);
    } else {
        auto manifest = k8sManifest(s, work);
        if (!manifest) return std::move(manifest).error();
        text = std::move(*manifest);
    }
    LANTERN_TRY(writeTextFile(work.script, text));
    if (slurm)
        fs::permissions(work.script, fs::perms::owner_exec | fs::perms::group_exec,
                        fs::perm_options::add, ec);
    const std::string framesText =
        work.wholeRange ? std::to_string(s.range.first) + "-" + std::to_string(s.range.last)
                        : formatFrameList(work.frames);
    s.jobs.push_back({"", framesText, work.script.string()});
    LANTERN_TRY(writeRecord(s));
    return framesText;
}

// After --wait: which tasks did not complete, and whether every frame is there.
int reportFinished(const std::string& id, const std::vector<std::string>& states,
                   const Submission& s, const JobWork& work) {
    std::map<std::string, std::vector<int>> byState;
    for (std::size_t i = 0; i < states.size(); ++i)
        byState[states[i]].push_back(int(i));
    std::string summary;
    for (const auto& [state, tasks] : byState) {
        summary += (summary.empty() ? "" : ", ") + std::to_string(tasks.size()) + " " + state;
        if (state != "COMPLETED") summary += " (task " + formatFrameList(tasks) + ")";
    }
    const auto missing = checkFrames(s.outputs, work.frames);
    const int count = printMissing(missing);
    std::fprintf(stderr, "lantern: job %s ended: %s; %zu of %zu frames present and readable\n",
                 id.c_str(), summary.c_str(), work.frames.size() - std::size_t(count),
                 work.frames.size());
    if (count == 0) return kOk;
    std::fprintf(
        stderr,
        "lantern: missing frames %s; render them with: lantern farm submit --resume -o %s\n",
        formatFrameList(missingFrames(missing)).c_str(), shellQuote(s.outputs.front()).c_str());
    return kFailed;
}

// Submits the written job with sbatch, records its id and, with --wait, follows it.
int submitAndFollow(const SubmitArgs& a, Submission& s, const JobWork& work,
                    const std::string& framesText) {
    auto id = slurmSubmit(work.script, a.hold);
    if (!id) return report(id.error());
    s.jobs.back().id = *id;
    if (auto w = writeRecord(s); !w) return report(w.error());
    std::cout << *id << std::endl;
    std::fprintf(stderr, "lantern: submitted job %s: %d tasks, frames %s; script %s\n", id->c_str(),
                 work.tasks, framesText.c_str(), work.script.c_str());
    if (!a.wait) return kOk;
    auto states = slurmFollow(*id, s, work);
    if (!states) return report(states.error());
    return reportFinished(*id, *states, s, work);
}

} // namespace

int runSubmit(const SubmitArgs& a, const std::vector<std::string>& extras, const CLI::App& cmd) {
    auto part = splitRenderArguments(extras);
    if (!part) return report(part.error());
    if (a.scheduler != "slurm" && a.scheduler != "k8s")
        return report(
            usage("unknown scheduler \"" + a.scheduler + "\" (slurm, k8s)", "--scheduler"));
    auto made = makeSubmission(a, *part, cmd);
    if (!made) return report(made.error());
    Submission s = std::move(*made);
    const bool slurm = s.scheduler == "slurm";
    if ((a.wait || a.hold) && (!slurm || a.noSubmit))
        return report(usage(
            "--wait and --hold are for a Slurm job that farm submits (not with --no-submit or k8s)",
            a.wait ? "--wait" : "--hold"));
    if (a.wait && a.hold)
        return report(usage("a held job would never end: --hold or --wait", "--wait"));
    if (slurm && !a.noSubmit)
        if (auto r = refuseWhileActive(a, s); !r) return report(r.error());
    const JobWork work = planWork(a, s, cmd);
    if (work.frames.empty()) {
        std::fprintf(stderr, "lantern: nothing to resume: all %d frames are present and readable\n",
                     s.range.count());
        return kOk;
    }
    auto framesText = writeJob(s, work);
    if (!framesText) return report(framesText.error());
    if (!slurm && s.pvc.empty())
        std::fprintf(stderr, "lantern: warning: without --pvc the pods write their frames inside "
                             "themselves, and they are lost when the pods end\n");
    if (!slurm || a.noSubmit) {
        std::cout << work.script.string() << "\n";
        std::fprintf(stderr, "lantern: wrote %s (%d tasks, frames %s)%s\n", work.script.c_str(),
                     work.tasks, framesText->c_str(),
                     slurm ? "; submit it with sbatch"
                           : "; apply it with kubectl apply -f (not tested here: docs/farm.md)");
        return kOk;
    }
    return submitAndFollow(a, s, work, *framesText);
}

} // namespace lantern::cli::farm
