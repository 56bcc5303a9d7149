// `lantern farm`: a sequence rendered as a scheduler's job array (docs/farm.md). Its options,
// `farm check` (the frames missing or unreadable; exit 1 if any) and what submit and check
// share; `farm submit` itself is in FarmSubmit.cpp.
#include "farm/FarmCommand.h"

#include "common/CliSupport.h"
#include "common/Commands.h"

#include <cstdio>
#include <iostream>
#include <set>

namespace lantern::cli::farm {

namespace fs = std::filesystem;

Error usage(const std::string& message, const std::string& object) {
    return makeError(ErrorCode::Usage, message, object);
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

std::vector<int> missingFrames(const std::vector<MissingFrame>& missing) {
    std::set<int> frames;
    for (const auto& m : missing)
        frames.insert(m.frame);
    return {frames.begin(), frames.end()};
}

int printMissing(const std::vector<MissingFrame>& missing) {
    for (const auto& m : missing)
        std::cout << m.path << ": " << (m.why.empty() ? "missing" : "unreadable (" + m.why + ")")
                  << "\n";
    return int(missingFrames(missing).size());
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
        auto record = readRecord(recordPath(outputs.front()));
        if (!record)
            return report(
                usage("give --frames A-B (there is no submission record to take it from: " +
                          record.error().describe() + ")",
                      "--frames"));
        range = record->range;
    }
    const auto missing = checkFrames(outputs, rangeFrames(range));
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

namespace {

CLI::App* addSubmitCommand(CLI::App& farmCmd, SubmitArgs& s) {
    CLI::App* submit =
        farmCmd.add_subcommand("submit", "Write and submit a job array rendering SCENE's frames; "
                                         "other options go to `lantern render`");
    submit->allow_extras(); // the scene and the render options: see splitRenderArguments
    submit->footer(
        "\nExample:\n  lantern farm submit scene.glb --frames 0-239 --tasks 16 -o "
        "/shared/shot/frame_####.exr \\\n      --width 1920 --height 1080 --partition gpu "
        "--gpus 1 --cpus-per-task 4 --wait\nSee docs/farm.md.");
    submit
        ->add_option("--scheduler", s.scheduler,
                     "slurm (sbatch job array) or k8s (writes an Indexed Job manifest)")
        ->capture_default_str();
    submit->add_option("--frames", s.frames, "Frames A-B inclusive");
    submit
        ->add_option("--tasks", s.tasks,
                     "Tasks in the array; task I renders frames k with k mod N == I")
        ->check(CLI::Range(1, 1000000));
    submit
        ->add_option("-o,--output", s.outputs,
                     "Output pattern (repeatable), e.g. out/frame_####.exr")
        ->allow_extra_args(false);
    submit->add_flag(
        "--wait", s.wait,
        "Follow the array to its end (tasks done, frames present), then check the frames");
    submit->add_flag(
        "--resume", s.resume,
        "Resubmit only the frames missing or unreadable, from the record beside the -o outputs");
    submit->add_flag("--no-submit", s.noSubmit, "Write the script and record without submitting");
    submit->add_flag("--hold", s.hold, "Submit the array held (start it with scontrol release ID)");
    submit->add_option("--partition", s.partition, "Slurm partition (e.g. a GPU partition)");
    submit->add_option("--time", s.time, "Time limit per task (Slurm format: M, H:M:S, D-H:M...)");
    submit->add_option("--mem", s.mem, "Memory per task (Slurm format: 4000, 500M, 4G)");
    submit->add_option("--cpus-per-task", s.cpusPerTask, "CPUs per task (also the encoder threads)")
        ->check(CLI::Range(1, 4096));
    submit
        ->add_option("--gpus", s.gpus,
                     "GPUs per task (Slurm --gres=gpu:G, Kubernetes nvidia.com/gpu)")
        ->check(CLI::Range(0, 64));
    submit
        ->add_option("--sbatch-arg", s.sbatchArgs,
                     "Extra #SBATCH argument (repeatable), e.g. --sbatch-arg=--qos=low")
        ->allow_extra_args(false);
    submit
        ->add_option("--setup", s.setup,
                     "Shell line run before the render in each task (repeatable), e.g. "
                     "'module load vulkan'")
        ->allow_extra_args(false);
    submit->add_option("--job-name", s.jobName,
                       "Job name (default lantern-NAME after the output pattern)");
    submit->add_option("--lantern", s.lantern,
                       "The lantern executable the tasks run (default: this one)");
    submit->add_option("--image", s.image, "k8s: container image holding lantern");
    submit->add_option("--namespace", s.k8sNamespace, "k8s: namespace");
    submit->add_option("--pvc", s.pvc, "k8s: persistent volume claim mounted at the output folder");
    return submit;
}

CLI::App* addCheckCommand(CLI::App& farmCmd, CheckArgs& c) {
    CLI::App* check =
        farmCmd.add_subcommand("check", "List frames missing or unreadable; exit 1 if any");
    check->add_option("pattern", c.outputs, "Output pattern(s), e.g. out/frame_####.exr")
        ->required();
    check->add_option("--frames", c.frames, "Frames A-B (default: the submission record's)");
    return check;
}

} // namespace
} // namespace lantern::cli::farm

namespace lantern::cli {

Runner addFarmCommand(CLI::App& app) {
    CLI::App* farmCmd = app.add_subcommand(
        "farm", "Render a sequence on a cluster as a job array (Slurm, Kubernetes)");
    farmCmd->require_subcommand(1);
    auto s = std::make_shared<farm::SubmitArgs>();
    CLI::App* submit = farm::addSubmitCommand(*farmCmd, *s);
    auto c = std::make_shared<farm::CheckArgs>();
    CLI::App* check = farm::addCheckCommand(*farmCmd, *c);
    return [s, c, submit, check]() {
        if (submit->parsed()) return farm::runSubmit(*s, submit->remaining(), *submit);
        if (check->parsed()) return farm::runCheck(*c);
        return -1;
    };
}

} // namespace lantern::cli
