// `lantern farm` without a cluster: frame lists (what --resume renders) and `render
// --frame-list`, the sbatch script and the JSON record that `farm submit` writes, the
// Kubernetes manifest (parsed back with yaml-cpp, and each pod's command run here for its
// index), `farm check` on missing and damaged frames, and refused input.
#include "FarmTestSupport.h"

#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <lantern/Sequence.h>
#include <nlohmann/json.hpp>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

namespace {

using namespace lantern;
using lantern::test::runLantern;
using lantern::test::runProcess;
using lantern::test::testOutputDir;
using namespace lantern::test::farm;
namespace fs = std::filesystem;

TEST(FarmFrameLists, ParseFormatAndShard) {
    struct Row {
        const char* text;
        std::vector<int> frames;
        const char* formatted;
    };
    const Row rows[] = {
        {"3", {3}, "3"},
        {"1,5,9", {1, 5, 9}, "1,5,9"},
        {"4-6,1,5", {1, 4, 5, 6}, "1,4-6"}, // sorted, each frame once
        {"0-2,3", {0, 1, 2, 3}, "0-3"},     // adjacent runs merge
        {"7,7,7", {7}, "7"},
    };
    for (const Row& r : rows) {
        auto list = parseFrameList(r.text);
        ASSERT_TRUE(list) << r.text;
        EXPECT_EQ(*list, r.frames) << r.text;
        EXPECT_EQ(formatFrameList(*list), r.formatted) << r.text;
        EXPECT_EQ(*parseFrameList(formatFrameList(*list)), *list)
            << r.text << " does not round-trip";
    }
    for (const char* bad :
         {"", ",", "1,", ",1", "3-1", "a", "-1", "1--2", "1-2-3", "1;2", "0-99999999"})
        EXPECT_FALSE(parseFrameList(bad)) << bad;
    // A list is split by position, so the shards stay balanced whatever the frame numbers.
    const std::vector<int> list = {1, 4, 5, 6, 9};
    EXPECT_EQ(shardFrameList(list, {0, 2}), (std::vector<int>{1, 5, 9}));
    EXPECT_EQ(shardFrameList(list, {1, 2}), (std::vector<int>{4, 6}));
    for (int n = 1; n <= 7; ++n) {
        std::vector<int> all;
        for (int i = 0; i < n; ++i) {
            const auto part = shardFrameList(list, {i, n});
            EXPECT_LE(part.size(), list.size() / std::size_t(n) + 1);
            all.insert(all.end(), part.begin(), part.end());
        }
        std::sort(all.begin(), all.end());
        EXPECT_EQ(all, list) << n << " shards";
    }
}

class FarmRender : public lantern::test::GpuTest {};

TEST_F(FarmRender, FrameListShardsGiveTheRangeRendersBytes) {
    const auto dir = testOutputDir();
    renderReference(dir / "range", "0-5");
    fs::create_directories(dir / "list");
    for (const char* shard : {"0/2", "1/2"}) {
        const auto r =
            runLantern(concat({"render", "builtin:spheres-animated", "--frame-list", "1,4-5",
                               "--shard", shard, "-o", (dir / "list" / "f_##.exr").string()},
                              sampleRenderOptions()));
        ASSERT_EQ(r.exitCode, 0) << r.err;
    }
    EXPECT_EQ(filesEndingWith(dir / "list", ".exr"),
              (std::vector<std::string>{"f_01.exr", "f_04.exr", "f_05.exr"}));
    for (const char* n : {"f_01.exr", "f_04.exr", "f_05.exr"})
        EXPECT_TRUE(fileBytes(dir / "range" / n) == fileBytes(dir / "list" / n)) << n;
    auto r = runLantern({"render", "builtin:spheres-animated", "--frames", "0-3", "--frame-list",
                         "1", "-o", (dir / "x_#.exr").string()});
    EXPECT_EQ(r.exitCode, 2) << r.err;
    r = runLantern({"render", "builtin:spheres-animated", "--frame-list", "2-1", "-o",
                    (dir / "x_#.exr").string()});
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_NE(r.err.find("--frame-list"), std::string::npos) << r.err;
}

TEST(FarmSubmit, WritesAReadableScriptAndARecordBesideTheOutputs) {
    const auto dir = testOutputDir();
    const std::string pattern = (dir / "out" / "f_##.exr").string();
    const auto r = runLantern(
        concat(words("farm submit builtin:spheres-animated --frames 0-10 --tasks 4 -o " + pattern +
                     " --partition gpu --time 10:00 --mem 2G --cpus-per-task 2 --gpus 1"
                     " --sbatch-arg=--qos=low --no-submit --shading flat"),
               concat({"--setup", "module load vulkan"}, sampleRenderOptions())));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const fs::path script = dir / "out" / "f.sbatch";
    EXPECT_EQ(r.out, script.string() + "\n");
    const std::string text = fileBytes(script);
    for (const std::string& line : std::vector<std::string>{
             "#SBATCH --array=0-3\n", "#SBATCH --partition=gpu\n", "#SBATCH --time=10:00\n",
             "#SBATCH --mem=2G\n", "#SBATCH --cpus-per-task=2\n", "#SBATCH --gres=gpu:1\n",
             "#SBATCH --qos=low\n", "\nmodule load vulkan\n",
             " render builtin:spheres-animated \\\n", "--frames 0-10 \\\n", "--shading flat \\\n",
             "--width 64 \\\n", "--shard \"$SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT\"",
             "--encoder-threads \"${SLURM_CPUS_PER_TASK:-1}\"",
             "--output=" + (dir / "out" / "f-logs").string() + "/%A_%a.out\n"})
        EXPECT_NE(text.find(line), std::string::npos) << "no \"" << line << "\" in\n" << text;
    EXPECT_EQ(runProcess({"bash", "-n", script.string()}).exitCode, 0) << "not valid bash:\n"
                                                                       << text;
    EXPECT_TRUE(fs::is_directory(dir / "out" / "f-logs"))
        << "Slurm does not create the log folder itself";
    const std::string recordText = fileBytes(dir / "out" / "f.farm");
    const auto record = nlohmann::json::parse(recordText, nullptr, false);
    ASSERT_TRUE(record.is_object()) << "the record is not a JSON object:\n" << recordText;
    EXPECT_EQ(record.value("lantern-farm", 0), 2) << recordText;
    EXPECT_EQ(record["frames"], (nlohmann::json{{"first", 0}, {"last", 10}})) << recordText;
    EXPECT_EQ(record.value("tasks", 0), 4) << recordText;
    EXPECT_EQ(record["outputs"], nlohmann::json::array({pattern})) << recordText;
    const auto args = record["render-args"].get<std::vector<std::string>>();
    const std::vector<std::string> shading = {"--shading", "flat"};
    EXPECT_NE(std::search(args.begin(), args.end(), shading.begin(), shading.end()), args.end())
        << recordText;
    EXPECT_EQ(record["setup"], nlohmann::json::array({"module load vulkan"})) << recordText;
    EXPECT_EQ(record["jobs"], (nlohmann::json::array({{{"id", nullptr},
                                                       {"frames", "0-10"},
                                                       {"script", script.string()}}})))
        << recordText;

    // More tasks than frames: one frame per task.
    const auto few =
        runLantern({"farm", "submit", "builtin:spheres-animated", "--frames", "0-2", "--tasks", "8",
                    "-o", (dir / "few" / "g_#.exr").string(), "--no-submit"});
    ASSERT_EQ(few.exitCode, 0) << few.err;
    EXPECT_NE(fileBytes(dir / "few" / "g.sbatch").find("#SBATCH --array=0-2\n"), std::string::npos);
}

TEST(FarmSubmit, RefusesBadInputAndWritesNothing) {
    const auto dir = testOutputDir();
    const std::string out = (dir / "f_##.exr").string();
    const std::vector<std::string> base = {"farm",     "submit",     "builtin:spheres-animated",
                                           "--frames", "0-7",        "--tasks",
                                           "2",        "--no-submit"};
    struct Row {
        std::vector<std::string> args; // appended to `base` (whole command when base is false)
        bool withBase;
        int exitCode;
        const char* why;
    };
    const std::vector<Row> rows = {
        {{"-o", out, "--bogus"}, true, 2, "an option neither farm nor render knows"},
        {{"-o", out, "--shard", "0/2"}, true, 2, "the shard is the scheduler's to set"},
        {{"-o", out, "--frame-list", "1"}, true, 2, "so is the frame list"},
        {{"-o", out, "--views", "orbit:4"}, true, 2, "a batch is a plain job array, not a farm sequence"},
        {{}, true, 2, "no -o"},
        {{"-o", (dir / "f.exr").string()}, true, 1, "no '#' for the frame number"},
        {{"-o", (dir / "f_#.jpg").string()}, true, 1, "not .exr or .png"},
        {{"-o", out, "--width", "abc"}, true, 2, "render's parser refuses the value"},
        {{"-o", out, "--msaa", "3"}, true, 2, "render's check refuses the value"},
        {{"-o", out, "--width"}, true, 2, "a render option without its value"},
        {{"-o", out, "--scheduler", "pbs"}, true, 2, "unknown scheduler"},
        {{"-o", out, "--scheduler", "k8s"}, true, 2, "k8s needs --image"},
        {{"-o", out, "--wait"}, true, 2, "--wait with --no-submit"},
        {{"-o", out, "--setup", "a\nb"}, true, 2, "a line break would split the script's line"},
        {{"-o", out, "second-scene"}, true, 2, "two scenes"},
        {{"farm", "submit", "missing.gltf", "--frames", "0-7", "--tasks", "2", "-o", out},
         false,
         1,
         "no such scene file"},
        {{"farm", "submit", "builtin:spheres", "--frames", "7-2", "--tasks", "2", "-o", out},
         false,
         1,
         "backwards range"},
        {{"farm", "submit", "builtin:spheres", "--frames", "0-7", "-o", out},
         false,
         2,
         "no --tasks"},
        {{"farm", "submit", "builtin:spheres", "--frames", "0-7", "--tasks", "0", "-o", out},
         false,
         1,
         "zero tasks (a value out of its range is refused input)"},
        {{"farm", "submit", "--resume", "-o", out}, false, 1, "nothing was submitted to resume"},
        {{"farm", "check", out}, false, 2, "check without --frames or a record"},
    };
    for (const Row& row : rows) {
        const auto r = runLantern(row.withBase ? concat(base, row.args) : row.args);
        EXPECT_EQ(r.exitCode, row.exitCode) << row.why << "\n" << r.err;
        EXPECT_FALSE(r.err.empty()) << row.why << ": no message";
        EXPECT_TRUE(fs::is_empty(dir)) << row.why << ": wrote files";
    }
}

// Without Slurm's clients (or with a configuration that is not there) submit says so at once
// instead of hanging; the script stays, to be submitted by hand.
TEST(FarmSubmit, SaysWhenSlurmIsNotThere) {
    const auto dir = testOutputDir();
    const auto args = words("farm submit builtin:spheres --frames 0-3 --tasks 2 -o " +
                            (dir / "f_#.exr").string());
    struct Row {
        std::vector<std::string> environment;
        const char* expected;
    };
    const Row rows[] = {
        {{"PATH=/nonexistent"}, "sbatch not found"},
        {{"SLURM_CONF=/nonexistent/slurm.conf"}, "SLURM_CONF names /nonexistent/slurm.conf"},
    };
    for (const Row& row : rows) {
        const auto r = runLantern(args, row.environment);
        EXPECT_EQ(r.exitCode, 3) << r.err;
        EXPECT_NE(r.err.find(row.expected), std::string::npos) << r.err;
        EXPECT_TRUE(fs::exists(dir / "f.sbatch"));
    }
}

// The manifest parsed back with yaml-cpp: one Indexed Job with the resources, claim and
// completion index asked for; returns the script each pod runs.
std::string checkManifest(const fs::path& manifest, const fs::path& outputFolder) {
    std::vector<YAML::Node> docs;
    try {
        docs = YAML::LoadAllFromFile(manifest.string());
    } catch (const YAML::Exception& e) {
        ADD_FAILURE() << "not YAML: " << e.what() << "\n" << fileBytes(manifest);
        return {};
    }
    EXPECT_EQ(docs.size(), 1u) << fileBytes(manifest);
    if (docs.empty()) return {};
    const YAML::Node j = docs[0];
    EXPECT_EQ(j["apiVersion"].as<std::string>(""), "batch/v1");
    EXPECT_EQ(j["kind"].as<std::string>(""), "Job");
    EXPECT_EQ(j["metadata"]["namespace"].as<std::string>(""), "render");
    const YAML::Node s = j["spec"];
    EXPECT_EQ(s["completionMode"].as<std::string>(""), "Indexed");
    EXPECT_EQ(s["completions"].as<int>(0), 3);
    EXPECT_EQ(s["parallelism"].as<int>(0), 3);
    EXPECT_EQ(s["activeDeadlineSeconds"].as<int>(0), 5400);
    const YAML::Node p = s["template"]["spec"];
    EXPECT_EQ(p["restartPolicy"].as<std::string>(""), "Never");
    const YAML::Node c = p["containers"][0];
    EXPECT_EQ(c["image"].as<std::string>(""), "registry.example/lantern:1");
    EXPECT_EQ(c["command"].as<std::vector<std::string>>(std::vector<std::string>{}),
              (std::vector<std::string>{"/bin/sh", "-c"}));
    EXPECT_EQ(c["env"][0]["name"].as<std::string>(""), "JOB_COMPLETION_INDEX");
    EXPECT_NE(c["env"][0]["valueFrom"]["fieldRef"]["fieldPath"].as<std::string>("").find(
                  "job-completion-index"),
              std::string::npos);
    for (const char* kind : {"requests", "limits"}) {
        const YAML::Node r = c["resources"][kind];
        EXPECT_EQ(r.size(), 3u) << kind;
        EXPECT_EQ(r["memory"].as<std::string>(""), "2Gi") << kind;
        EXPECT_EQ(r["cpu"].as<std::string>(""), "2") << kind;
        EXPECT_EQ(r["cpu"].Tag(), "!") << kind << ": the CPU quantity is a quoted string";
        EXPECT_EQ(r["nvidia.com/gpu"].as<int>(0), 1) << kind;
    }
    EXPECT_EQ(c["volumeMounts"][0]["mountPath"].as<std::string>(""), outputFolder.string());
    EXPECT_EQ(p["volumes"][0]["persistentVolumeClaim"]["claimName"].as<std::string>(""), "frames");
    EXPECT_EQ(c["args"].size(), 1u);
    return c["args"][0].as<std::string>("");
}

TEST(FarmK8s, ManifestIsAnIndexedJobWhosePodsRenderTheirShard) {
    const auto dir = testOutputDir();
    const std::string pattern = (dir / "k" / "f_##.exr").string();
    const auto r = runLantern(concat(
        words("farm submit --scheduler k8s builtin:spheres-animated --frames 0-6 --tasks 3 -o " +
              pattern +
              " --image registry.example/lantern:1 --namespace render --pvc frames"
              " --time 1:30:00 --mem 2G --cpus-per-task 2 --gpus 1"),
        sampleRenderOptions()));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const fs::path manifest = dir / "k" / "f.k8s.yaml";
    ASSERT_EQ(r.out, manifest.string() + "\n");
    // Kubernetes itself cannot run here: check the manifest's structure, then run what each pod
    // would run, with its JOB_COMPLETION_INDEX.
    const std::string podScript = checkManifest(manifest, dir / "k");
    if (HasFatalFailure()) return;
    EXPECT_NE(podScript.find("--shard \"$JOB_COMPLETION_INDEX/3\""), std::string::npos)
        << podScript;
    EXPECT_NE(podScript.find("--encoder-threads 2"), std::string::npos) << podScript;

    if (!lantern::test::sharedRenderer())
        GTEST_SKIP() << "no Vulkan device: " << lantern::test::noDeviceReason();
    for (int index = 0; index < 3; ++index) {
        const auto pod =
            runProcess({"sh", "-c", podScript}, {"JOB_COMPLETION_INDEX=" + std::to_string(index)});
        ASSERT_EQ(pod.exitCode, 0) << "pod " << index << ": " << pod.err;
    }
    renderReference(dir / "reference", "0-6");
    expectSameFrames(dir / "reference", dir / "k");
}

// Frames written by the library (no device needed), some then removed or damaged.
TEST(FarmCheck, ReportsMissingAndUnreadableFrames) {
    const auto dir = testOutputDir();
    Image image(8, 4);
    for (std::size_t i = 0; i < image.rgba.size(); ++i)
        image.rgba[i] = float(i % 7) / 7.0f;
    for (int frame = 0; frame <= 5; ++frame) {
        ASSERT_TRUE(writeExr(expandFramePattern((dir / "a_##.exr").string(), frame), image));
        ASSERT_TRUE(writePng(expandFramePattern((dir / "b_##.png").string(), frame), image));
    }
    const std::string a = (dir / "a_##.exr").string(), b = (dir / "b_##.png").string();
    auto r = runLantern({"farm", "check", a, b, "--frames", "0-5"});
    EXPECT_EQ(r.exitCode, 0) << r.out << r.err;
    EXPECT_EQ(r.out, "frames 0-5: all 6 present and readable\n");

    struct Damage {
        const char* file;
        std::size_t keep; // bytes kept; 0 with remove: the file goes
        bool remove;
        const char* expected; // what check says about it
    };
    const Damage damage[] = {
        {"a_02.exr", 0, true, "missing"},
        {"a_04.exr", 100, false, "unreadable (OpenEXR cannot read it"}, // cut mid-file
        {"b_03.png", 0, false, "unreadable (shorter than a PNG signature)"},
        {"b_05.png", 40, false, "unreadable (truncated PNG"},
    };
    for (const Damage& d : damage) {
        const fs::path p = dir / d.file;
        if (d.remove) {
            fs::remove(p);
        } else {
            const std::string bytes = fileBytes(p).substr(0, d.keep);
            std::ofstream(p, std::ios::binary | std::ios::trunc) << bytes;
        }
    }
    // A writer killed mid-frame leaves only a temporary file, which is not a frame.
    std::ofstream(dir / "a_02.exr.tmp-12345") << "partial";
    r = runLantern({"farm", "check", a, b, "--frames", "0-5"});
    EXPECT_EQ(r.exitCode, 1) << r.out << r.err;
    for (const Damage& d : damage)
        EXPECT_NE(r.out.find((dir / d.file).string() + ": " + d.expected), std::string::npos)
            << d.file << " not reported as " << d.expected << ":\n"
            << r.out;
    EXPECT_NE(r.out.find("frames 0-5: 2 of 6 present; missing 2-5\n"), std::string::npos) << r.out;
    r = runLantern({"farm", "check", a, "--frames", "0-5"});
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.out.find("frames 0-5: 4 of 6 present; missing 2,4\n"), std::string::npos) << r.out;
}

} // namespace
