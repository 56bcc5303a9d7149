// The Kubernetes back end of `lantern farm`: an Indexed Job manifest whose pod I renders
// shard JOB_COMPLETION_INDEX/N, emitted with yaml-cpp (quoting and escaping are its job).
// Written only: nothing here talks to a cluster, and it has not been run on one (docs/farm.md
// says so).
#include "farm/Farm.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <sstream>
#include <yaml-cpp/yaml.h>

namespace lantern::cli::farm {
namespace {

// Slurm's --time forms: M, M:S, H:M:S, D-H, D-H:M, D-H:M:S.
Result<long> slurmTimeSeconds(const std::string& text) {
    long days = 0;
    std::string rest = text;
    if (const auto dash = text.find('-'); dash != std::string::npos) {
        const auto r = std::from_chars(text.data(), text.data() + dash, days);
        if (r.ec != std::errc() || r.ptr != text.data() + dash)
            rest.clear();
        else
            rest = text.substr(dash + 1);
    }
    std::vector<long> parts;
    std::istringstream in(rest);
    for (std::string p; std::getline(in, p, ':');) {
        long v = -1;
        const auto r = std::from_chars(p.data(), p.data() + p.size(), v);
        if (p.empty() || r.ec != std::errc() || r.ptr != p.data() + p.size() || v < 0)
            return makeError(ErrorCode::InvalidInput,
                             "\"" + text +
                                 "\" is not a Slurm time (M, M:S, H:M:S, D-H, D-H:M, D-H:M:S)",
                             "--time");
        parts.push_back(v);
    }
    const bool withDays = text.find('-') != std::string::npos;
    if (parts.empty() || parts.size() > 3)
        return makeError(ErrorCode::InvalidInput, "\"" + text + "\" is not a Slurm time", "--time");
    long seconds = 0;
    if (withDays) { // D-H[:M[:S]]
        const long unit[3] = {3600, 60, 1};
        for (std::size_t i = 0; i < parts.size(); ++i)
            seconds += parts[i] * unit[i];
        seconds += days * 86400;
    } else if (parts.size() == 1) {
        seconds = parts[0] * 60;
    } else if (parts.size() == 2) {
        seconds = parts[0] * 60 + parts[1];
    } else {
        seconds = parts[0] * 3600 + parts[1] * 60 + parts[2];
    }
    if (seconds <= 0)
        return makeError(ErrorCode::InvalidInput, "the time limit must be positive", "--time");
    return seconds;
}

// Slurm's --mem (a number with an optional K, M, G or T suffix, megabytes by default) as a
// Kubernetes quantity.
Result<std::string> k8sMemory(const std::string& text) {
    std::size_t digits = 0;
    while (digits < text.size() && std::isdigit(static_cast<unsigned char>(text[digits])))
        ++digits;
    const std::string suffix = text.substr(digits);
    static const std::pair<const char*, const char*> units[] = {
        {"", "Mi"}, {"K", "Ki"}, {"M", "Mi"}, {"G", "Gi"}, {"T", "Ti"}};
    for (const auto& [slurm, k8s] : units)
        if (digits > 0 && suffix == slurm) return text.substr(0, digits) + k8s;
    return makeError(ErrorCode::InvalidInput,
                     "\"" + text + "\" is not a memory size like 4000, 500M or 4G", "--mem");
}

// A DNS label for the Job's name: lower case letters, digits and '-'; pods are named
// NAME-INDEX-XXXXX, which must stay within 63 characters.
std::string dnsLabel(const std::string& name) {
    std::string out;
    for (char c : name) {
        const char l = char(std::tolower(static_cast<unsigned char>(c)));
        out += std::isalnum(static_cast<unsigned char>(l)) ? l : '-';
    }
    out = out.substr(0, 40);
    while (!out.empty() && out.back() == '-')
        out.pop_back();
    while (!out.empty() && out.front() == '-')
        out.erase(out.begin());
    return out.empty() ? "lantern" : out;
}

// What `sh -c` runs in each pod: the setup lines, then the task's `lantern render`.
std::string podScript(const Submission& s, const JobWork& work) {
    std::ostringstream script;
    for (const std::string& line : s.setup)
        script << line << "\n";
    script << "exec";
    for (const std::string& word : renderCommand(s, work))
        script << " " << shellQuote(word);
    script << " --shard \"$JOB_COMPLETION_INDEX/" << work.tasks << "\"";
    if (!hasRenderOption(s, "--encoder-threads") && s.cpusPerTask > 0)
        script << " --encoder-threads " << s.cpusPerTask;
    return script.str();
}

// The comment heading the manifest: what it renders, that it was never run on a cluster, and
// how to submit and check it.
void manifestHeader(std::ostringstream& o, const Submission& s, const JobWork& work) {
    const std::string n = std::to_string(work.tasks);
    const std::string what =
        work.wholeRange
            ? "frames " + std::to_string(s.range.first) + "-" + std::to_string(s.range.last)
            : "the frames " + formatFrameList(work.frames) + " (missing from an earlier run)";
    o << "# Lantern render job written by `lantern farm submit --scheduler k8s`: " << what << "\n"
      << "# of " << s.scene << "\n"
      << "# as a Kubernetes Indexed Job of " << n
      << " pods. Pod I renders shard JOB_COMPLETION_INDEX/" << n << ".\n"
      << "#\n"
      << "# NOT RUN ON A CLUSTER: Lantern's tests have no Kubernetes; the Slurm path is the\n"
      << "# one tested (docs/farm.md). The image must hold a Vulkan driver and\n"
      << "#   " << s.lantern << "\n"
      << "# and the scene must be at the same path inside the pod. The frames go to "
      << (s.pvc.empty() ? "the pod's\n# own filesystem and are LOST when it ends, unless the image "
                          "mounts shared storage\n# there (use --pvc CLAIM).\n"
                        : "the claim " + s.pvc + ", mounted at the output folder.\n")
      << "# Submit with:  kubectl apply -f " << work.script.string() << "\n"
      << "# Then:         lantern farm check " << s.outputs.front()
      << "   (on a machine that mounts the claim)\n";
}

// The pod's one container: image, the completion index, the command and its resources.
Result<void> container(YAML::Emitter& y, const Submission& s, const JobWork& work) {
    y << YAML::BeginMap << YAML::Key << "name" << YAML::Value << "lantern";
    y << YAML::Key << "image" << YAML::Value << s.image;
    y << YAML::Key << "env" << YAML::Value << YAML::BeginSeq << YAML::BeginMap;
    y << YAML::Comment("set by the control plane since Kubernetes 1.22; spelled out for older ones");
    y << YAML::Key << "name" << YAML::Value << "JOB_COMPLETION_INDEX";
    y << YAML::Key << "valueFrom" << YAML::Value << YAML::BeginMap << YAML::Key << "fieldRef"
      << YAML::Value << YAML::BeginMap << YAML::Key << "fieldPath" << YAML::Value
      << "metadata.annotations['batch.kubernetes.io/job-completion-index']" << YAML::EndMap
      << YAML::EndMap;
    y << YAML::EndMap << YAML::EndSeq;
    y << YAML::Key << "command" << YAML::Value << YAML::Flow << YAML::BeginSeq << "/bin/sh"
      << "-c" << YAML::EndSeq;
    y << YAML::Key << "args" << YAML::Value << YAML::BeginSeq << YAML::Literal
      << podScript(s, work) << YAML::EndSeq;
    if (!s.mem.empty() || s.cpusPerTask > 0 || s.gpus > 0) {
        std::string mem;
        if (!s.mem.empty()) {
            auto m = k8sMemory(s.mem);
            if (!m) return std::move(m).error();
            mem = *m;
        }
        y << YAML::Key << "resources" << YAML::Value << YAML::BeginMap;
        for (const char* kind : {"requests", "limits"}) {
            y << YAML::Key << kind << YAML::Value << YAML::BeginMap;
            if (!mem.empty()) y << YAML::Key << "memory" << YAML::Value << mem;
            // A quantity: a string for CPUs, an integer for the extended GPU resource.
            if (s.cpusPerTask > 0)
                y << YAML::Key << "cpu" << YAML::Value << YAML::DoubleQuoted
                  << std::to_string(s.cpusPerTask);
            if (s.gpus > 0) y << YAML::Key << "nvidia.com/gpu" << YAML::Value << s.gpus;
            y << YAML::EndMap;
        }
        y << YAML::EndMap;
    }
    if (!s.pvc.empty())
        y << YAML::Key << "volumeMounts" << YAML::Value << YAML::BeginSeq << YAML::BeginMap
          << YAML::Key << "name" << YAML::Value << "frames" << YAML::Key << "mountPath"
          << YAML::Value << std::filesystem::path(s.outputs.front()).parent_path().string()
          << YAML::EndMap << YAML::EndSeq;
    y << YAML::EndMap;
    return {};
}

// The Job: its name and labels, the indexed completions, the time limit and the pod template.
Result<void> jobSpec(YAML::Emitter& y, const Submission& s, const JobWork& work) {
    y << YAML::BeginMap;
    y << YAML::Key << "apiVersion" << YAML::Value << "batch/v1";
    y << YAML::Key << "kind" << YAML::Value << "Job";
    y << YAML::Key << "metadata" << YAML::Value << YAML::BeginMap;
    y << YAML::Key << "name" << YAML::Value << dnsLabel(s.jobName);
    if (!s.k8sNamespace.empty()) y << YAML::Key << "namespace" << YAML::Value << s.k8sNamespace;
    y << YAML::Key << "labels" << YAML::Value << YAML::BeginMap << YAML::Key
      << "app.kubernetes.io/name" << YAML::Value << "lantern" << YAML::EndMap;
    y << YAML::EndMap;
    y << YAML::Key << "spec" << YAML::Value << YAML::BeginMap;
    y << YAML::Key << "completionMode" << YAML::Value << "Indexed";
    y << YAML::Key << "completions" << YAML::Value << work.tasks;
    y << YAML::Key << "parallelism" << YAML::Value << work.tasks;
    y << YAML::Key << "backoffLimit" << YAML::Value << std::max(3, work.tasks);
    y << YAML::Comment("a failed pod is retried with the same index; this many retries in all");
    if (!s.time.empty()) {
        auto seconds = slurmTimeSeconds(s.time);
        if (!seconds) return std::move(seconds).error();
        y << YAML::Key << "activeDeadlineSeconds" << YAML::Value << *seconds;
    }
    y << YAML::Key << "template" << YAML::Value << YAML::BeginMap;
    y << YAML::Key << "metadata" << YAML::Value << YAML::BeginMap << YAML::Key << "labels"
      << YAML::Value << YAML::BeginMap << YAML::Key << "app.kubernetes.io/name" << YAML::Value
      << "lantern" << YAML::EndMap << YAML::EndMap;
    y << YAML::Key << "spec" << YAML::Value << YAML::BeginMap;
    y << YAML::Key << "restartPolicy" << YAML::Value << "Never";
    y << YAML::Key << "containers" << YAML::Value << YAML::BeginSeq;
    LANTERN_TRY(container(y, s, work));
    y << YAML::EndSeq;
    if (!s.pvc.empty())
        y << YAML::Key << "volumes" << YAML::Value << YAML::BeginSeq << YAML::BeginMap << YAML::Key
          << "name" << YAML::Value << "frames" << YAML::Key << "persistentVolumeClaim"
          << YAML::Value << YAML::BeginMap << YAML::Key << "claimName" << YAML::Value << s.pvc
          << YAML::EndMap << YAML::EndMap << YAML::EndSeq;
    y << YAML::EndMap << YAML::EndMap << YAML::EndMap << YAML::EndMap;
    return {};
}

} // namespace

Result<std::string> k8sManifest(const Submission& s, const JobWork& work) {
    std::ostringstream o;
    manifestHeader(o, s, work);
    YAML::Emitter y;
    y.SetIndent(2);
    LANTERN_TRY(jobSpec(y, s, work));
    if (!y.good())
        return makeError(ErrorCode::Internal, "yaml-cpp could not emit the manifest: " +
                                                  y.GetLastError());
    o << y.c_str() << "\n";
    return o.str();
}

} // namespace lantern::cli::farm
