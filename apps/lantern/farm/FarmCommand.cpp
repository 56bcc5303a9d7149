// `lantern farm submit` and `lantern farm check`: a sequence rendered as a scheduler's job
// array (docs/farm.md). submit writes the job (sbatch script or Kubernetes manifest) and a
// submission record beside the outputs, submits it and, with --wait, follows it; check lists
// the frames missing or unreadable; submit --resume renders only those.
#include "common/CliSupport.h"
#include "common/Commands.h"
#include "farm/Farm.h"

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <map>
#include <set>

namespace lantern::cli {
namespace {

namespace fs = std::filesystem;
using farm::JobWork;
using farm::Submission;

struct SubmitArgs {
    std::string scheduler = "slurm";
    std::string frames;
    int tasks = 0;
    std::vector<std::string> outputs;
    std::string partition, time, mem, jobName, lantern, image, k8sNamespace, pvc;
    int cpusPerTask = 0, gpus = 0;
    std::vector<std::string> sbatchArgs, setup;
    bool wait = false, resume = false, noSubmit = false, hold = false;
};

struct CheckArgs {
    std::vector<std::string> outputs;
    std::string frames;
};

Error usage(const std::string& message, const std::string& object = {}) {
    return makeError(ErrorCode::Usage, message, object);
}

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

Result<void> checkOutputs(const std::vector<std::string>& outputs) {
    if (outputs.empty())
        return usage("name the output frames with -o, e.g. -o out/frame_####.exr", "--output");
    if (auto r = checkImagePaths(outputs, "--output"); !r) return r;
    for (const std::string& out : outputs) {
        if (!hasFramePattern(out))
            return makeError(ErrorCode::InvalidInput,
                             "a sequence needs '#' in the output name for the frame number (e.g. "
                             "out/frame_####.exr)",
                             "--output", out);
    }
    return {};
}

std::vector<std::string> absolutePatterns(const std::vector<std::string>& outputs) {
    std::vector<std::string> out;
    for (const std::string& o : outputs)
        out.push_back(fs::absolute(o).lexically_normal().string());
    return out;
}

std::vector<int> rangeFrames(const FrameRange& r) {
    std::vector<int> frames;
    for (int k = r.first;; ++k) {
        frames.push_back(k);
        if (k == r.last) break;
    }
    return frames;
}

// The frames of `frames` missing (or unreadable) in any output, each once.
std::vector<int> missingFrames(const std::vector<farm::MissingFrame>& missing) {
    std::set<int> frames;
    for (const auto& m : missing)
        frames.insert(m.frame);
    return {frames.begin(), frames.end()};
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

// Builds the submission from the command line, or for --resume from the record beside the
// outputs with what the command line overrides.
Result<Submission> makeSubmission(const SubmitArgs& a, const RenderPart& part,
                                  const CLI::App& cmd) {
    if (auto r = checkOutputs(a.outputs); !r) return std::move(r).error();
    const std::vector<std::string> outputs = absolutePatterns(a.outputs);
    Submission s;
    if (a.resume) {
        auto record = farm::readRecord(farm::recordPath(outputs.front()));
        if (!record) return std::move(record).error();
        s = std::move(*record);
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
    } else {
        if (part.scene.empty())
            return usage("farm submit needs a SCENE (glTF/GLB or builtin:NAME)");
        if (a.frames.empty()) return usage("farm submit needs --frames A-B", "--frames");
        if (a.tasks < 1)
            return usage("farm submit needs --tasks N (the job array's size)", "--tasks");
        auto r = parseFrameRange(a.frames);
        if (!r) return std::move(r).error();
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
        s.jobName = "lantern-" + farm::recordPath(outputs.front()).stem().string();
    }
    // Options given on this command line win over the record's.
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
    if (s.scheduler == "k8s" && s.image.empty())
        return usage("--scheduler k8s needs --image IMAGE (a container image holding lantern)",
                     "--image");
    if (auto r = checkOneLine(s); !r) return std::move(r).error();
    if (auto r = checkRenderLine(s); !r) return std::move(r).error();
    return s;
}

int printMissing(const std::vector<farm::MissingFrame>& missing) {
    for (const auto& m : missing)
        std::cout << m.path << ": " << (m.why.empty() ? "missing" : "unreadable (" + m.why + ")")
                  << "\n";
    return int(missingFrames(missing).size());
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
    const auto missing = farm::checkFrames(s.outputs, work.frames);
    const int count = printMissing(missing);
    std::fprintf(stderr, "lantern: job %s ended: %s; %zu of %zu frames present and readable\n",
                 id.c_str(), summary.c_str(), work.frames.size() - std::size_t(count),
                 work.frames.size());
    if (count == 0) return kOk;
    std::fprintf(
        stderr,
        "lantern: missing frames %s; render them with: lantern farm submit --resume -o %s\n",
        formatFrameList(missingFrames(missing)).c_str(),
        farm::shellQuote(s.outputs.front()).c_str());
    return kFailed;
}

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

    JobWork work;
    work.tasks = s.tasks;
    // Two jobs must not render the same frames: refuse while one of this sequence's is active
    // (for --resume, its frames are not missing, only not rendered yet).
    if (slurm && !a.noSubmit) {
        auto previous = a.resume ? Result<Submission>(s)
                                 : farm::readRecord(farm::recordPath(s.outputs.front()));
        if (previous) {
            std::vector<std::string> ids;
            for (const auto& j : previous->jobs)
                ids.push_back(j.id);
            auto active = farm::slurmActiveTasks(ids, previous->jobName);
            if (!active) return report(active.error());
            if (*active > 0)
                return report(
                    makeError(ErrorCode::InvalidInput,
                              std::to_string(*active) +
                                  " task(s) of this sequence are still pending or running: "
                                  "wait for them (or scancel them) first",
                              a.resume ? "--resume" : "--output"));
        }
    }
    if (a.resume) {
        const auto missing = farm::checkFrames(s.outputs, rangeFrames(s.range));
        work.frames = missingFrames(missing);
        if (work.frames.empty()) {
            std::fprintf(stderr,
                         "lantern: nothing to resume: all %d frames are present and readable\n",
                         s.range.count());
            return kOk;
        }
        for (const auto& m : missing)
            if (!m.why.empty())
                std::fprintf(stderr, "lantern: %s is unreadable: rendering it again\n",
                             m.path.c_str());
        work.wholeRange = false;
        work.tasks = cmd.count("--tasks") ? a.tasks : std::min(s.tasks, int(work.frames.size()));
        // The first job is the original submission; each resume gets its own script.
        work.script =
            farm::scriptPath(s.outputs.front(), s.scheduler, std::max(1, int(s.jobs.size())));
    } else {
        work.frames = rangeFrames(s.range);
        work.script = farm::scriptPath(s.outputs.front(), s.scheduler, 0);
        s.jobs.clear();
    }
    if (work.tasks > int(work.frames.size())) {
        std::fprintf(stderr, "lantern: %d tasks for %zu frames: using %zu tasks\n", work.tasks,
                     work.frames.size(), work.frames.size());
        work.tasks = int(work.frames.size());
    }

    // Every task writes into these folders; Slurm does not create the log folder either.
    std::error_code ec;
    for (const std::string& out : s.outputs)
        fs::create_directories(fs::path(out).parent_path(), ec);
    if (slurm) fs::create_directories(farm::logFolder(s.outputs.front()), ec);
    if (ec)
        return report(makeError(ErrorCode::IoError,
                                "cannot create the output folder: " + ec.message(), {},
                                s.outputs.front()));

    std::string text;
    if (slurm) {
        text = farm::slurmScript(s, work);
    } else {
        auto manifest = farm::k8sManifest(s, work);
        if (!manifest) return report(manifest.error());
        text = std::move(*manifest);
    }
    if (auto w = farm::writeTextFile(work.script, text); !w) return report(w.error());
    if (slurm)
        fs::permissions(work.script, fs::perms::owner_exec | fs::perms::group_exec,
                        fs::perm_options::add, ec);
    const std::string framesText =
        work.wholeRange ? std::to_string(s.range.first) + "-" + std::to_string(s.range.last)
                        : formatFrameList(work.frames);
    s.jobs.push_back({"", framesText, work.script.string()});
    if (auto w = farm::writeRecord(s); !w) return report(w.error());

    if (!slurm && s.pvc.empty())
        std::fprintf(stderr, "lantern: warning: without --pvc the pods write their frames inside "
                             "themselves, and they are lost when the pods end\n");
    if (!slurm || a.noSubmit) {
        std::cout << work.script.string() << "\n";
        std::fprintf(stderr, "lantern: wrote %s (%d tasks, frames %s)%s\n", work.script.c_str(),
                     work.tasks, framesText.c_str(),
                     slurm ? "; submit it with sbatch"
                           : "; apply it with kubectl apply -f (not tested here: docs/farm.md)");
        return kOk;
    }
    auto id = farm::slurmSubmit(work.script, a.hold);
    if (!id) return report(id.error());
    s.jobs.back().id = *id;
    if (auto w = farm::writeRecord(s); !w) return report(w.error());
    std::cout << *id << std::endl;
    std::fprintf(stderr, "lantern: submitted job %s: %d tasks, frames %s; script %s\n", id->c_str(),
                 work.tasks, framesText.c_str(), work.script.c_str());
    if (!a.wait) return kOk;
    auto states = farm::slurmFollow(*id, s, work);
    if (!states) return report(states.error());
    return reportFinished(*id, *states, s, work);
}

int runCheck(const CheckArgs& a) {
    if (auto r = checkOutputs(a.outputs); !r) return report(r.error());
    const std::vector<std::string> outputs = absolutePatterns(a.outputs);
    FrameRange range;
    if (!a.frames.empty()) {
        auto r = parseFrameRange(a.frames);
        if (!r) return report(r.error());
        range = *r;
    } else {
        auto record = farm::readRecord(farm::recordPath(outputs.front()));
        if (!record)
            return report(
                usage("give --frames A-B (there is no submission record to take it from: " +
                          record.error().describe() + ")",
                      "--frames"));
        range = record->range;
    }
    const auto missing = farm::checkFrames(outputs, rangeFrames(range));
    const int count = printMissing(missing);
    const std::string span = std::to_string(range.first) + "-" + std::to_string(range.last);
    if (count == 0) {
        std::printf("frames %s: all %d present and readable\n", span.c_str(), range.count());
        return kOk;
    }
    std::printf("frames %s: %d of %d present; missing %s\n", span.c_str(), range.count() - count,
                range.count(), formatFrameList(missingFrames(missing)).c_str());
    return kRefused;
}

} // namespace

Runner addFarmCommand(CLI::App& app) {
    CLI::App* farmCmd = app.add_subcommand(
        "farm", "Render a sequence on a cluster as a job array (Slurm, Kubernetes)");
    farmCmd->require_subcommand(1);

    auto s = std::make_shared<SubmitArgs>();
    CLI::App* submit =
        farmCmd->add_subcommand("submit", "Write and submit a job array rendering SCENE's frames; "
                                          "other options go to `lantern render`");
    submit->allow_extras(); // the scene and the render options: see splitRenderArguments
    submit->footer(
        "\nExample:\n  lantern farm submit scene.glb --frames 0-239 --tasks 16 -o "
        "/shared/shot/frame_####.exr \\\n      --width 1920 --height 1080 --partition gpu "
        "--gpus 1 --cpus-per-task 4 --wait\nSee docs/farm.md.");
    submit
        ->add_option("--scheduler", s->scheduler,
                     "slurm (sbatch job array) or k8s (writes an Indexed Job manifest)")
        ->capture_default_str();
    submit->add_option("--frames", s->frames, "Frames A-B inclusive");
    submit
        ->add_option("--tasks", s->tasks,
                     "Tasks in the array; task I renders frames k with k mod N == I")
        ->check(CLI::Range(1, 1000000));
    submit
        ->add_option("-o,--output", s->outputs,
                     "Output pattern (repeatable), e.g. out/frame_####.exr")
        ->allow_extra_args(false);
    submit->add_flag(
        "--wait", s->wait,
        "Follow the array to its end (tasks done, frames present), then check the frames");
    submit->add_flag(
        "--resume", s->resume,
        "Resubmit only the frames missing or unreadable, from the record beside the -o outputs");
    submit->add_flag("--no-submit", s->noSubmit, "Write the script and record without submitting");
    submit->add_flag("--hold", s->hold,
                     "Submit the array held (start it with scontrol release ID)");
    submit->add_option("--partition", s->partition, "Slurm partition (e.g. a GPU partition)");
    submit->add_option("--time", s->time, "Time limit per task (Slurm format: M, H:M:S, D-H:M...)");
    submit->add_option("--mem", s->mem, "Memory per task (Slurm format: 4000, 500M, 4G)");
    submit
        ->add_option("--cpus-per-task", s->cpusPerTask, "CPUs per task (also the encoder threads)")
        ->check(CLI::Range(1, 4096));
    submit
        ->add_option("--gpus", s->gpus,
                     "GPUs per task (Slurm --gres=gpu:G, Kubernetes nvidia.com/gpu)")
        ->check(CLI::Range(0, 64));
    submit
        ->add_option("--sbatch-arg", s->sbatchArgs,
                     "Extra #SBATCH argument (repeatable), e.g. --sbatch-arg=--qos=low")
        ->allow_extra_args(false);
    submit
        ->add_option("--setup", s->setup,
                     "Shell line run before the render in each task (repeatable), e.g. "
                     "'module load vulkan'")
        ->allow_extra_args(false);
    submit->add_option("--job-name", s->jobName,
                       "Job name (default lantern-NAME after the output pattern)");
    submit->add_option("--lantern", s->lantern,
                       "The lantern executable the tasks run (default: this one)");
    submit->add_option("--image", s->image, "k8s: container image holding lantern");
    submit->add_option("--namespace", s->k8sNamespace, "k8s: namespace");
    submit->add_option("--pvc", s->pvc,
                       "k8s: persistent volume claim mounted at the output folder");

    auto c = std::make_shared<CheckArgs>();
    CLI::App* check =
        farmCmd->add_subcommand("check", "List frames missing or unreadable; exit 1 if any");
    check->add_option("pattern", c->outputs, "Output pattern(s), e.g. out/frame_####.exr")
        ->required();
    check->add_option("--frames", c->frames, "Frames A-B (default: the submission record's)");

    return [s, c, submit, check]() {
        if (submit->parsed()) return runSubmit(*s, submit->remaining(), *submit);
        if (check->parsed()) return runCheck(*c);
        return -1;
    };
}

} // namespace lantern::cli
