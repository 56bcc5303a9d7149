// The Kubernetes back end of `lantern farm`: an Indexed Job manifest whose pod I renders
// shard JOB_COMPLETION_INDEX/N. Written only: nothing here talks to a cluster, and it has not
// been run on one (docs/farm.md says so).
#include "farm/Farm.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdio>
#include <sstream>

namespace lantern::cli::farm {
namespace {

// A YAML double-quoted scalar (JSON escapes are valid YAML).
std::string q(const std::string& s) {
    std::string out = "\"";
    for (char c : s) {
        if (c == '"' || c == '\\') {
            out += '\\';
            out += c;
        } else if (c == '\n') {
            out += "\\n";
        } else if (static_cast<unsigned char>(c) < 0x20) {
            char b[8];
            std::snprintf(b, sizeof b, "\\x%02x", c);
            out += b;
        } else {
            out += c;
        }
    }
    return out + "\"";
}

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

// The Job itself down to the container's command.
Result<void> jobSpec(std::ostringstream& o, const Submission& s, const JobWork& work) {
    const std::string n = std::to_string(work.tasks);
    o << "apiVersion: batch/v1\n"
      << "kind: Job\n"
      << "metadata:\n"
      << "  name: " << q(dnsLabel(s.jobName)) << "\n";
    if (!s.k8sNamespace.empty()) o << "  namespace: " << q(s.k8sNamespace) << "\n";
    o << "  labels:\n"
      << "    app.kubernetes.io/name: lantern\n"
      << "spec:\n"
      << "  completionMode: Indexed\n"
      << "  completions: " << n << "\n"
      << "  parallelism: " << n << "\n"
      << "  # A failed pod is retried with the same index; this many retries over the whole job.\n"
      << "  backoffLimit: " << std::max(3, work.tasks) << "\n";
    if (!s.time.empty()) {
        auto seconds = slurmTimeSeconds(s.time);
        if (!seconds) return std::move(seconds).error();
        o << "  activeDeadlineSeconds: " << *seconds << "\n";
    }
    o << "  template:\n"
      << "    metadata:\n"
      << "      labels:\n"
      << "        app.kubernetes.io/name: lantern\n"
      << "    spec:\n"
      << "      restartPolicy: Never\n"
      << "      containers:\n"
      << "        - name: lantern\n"
      << "          image: " << q(s.image) << "\n"
      << "          env:\n"
      << "            # Set by the control plane since Kubernetes 1.22; spelled out for older "
         "ones.\n"
      << "            - name: JOB_COMPLETION_INDEX\n"
      << "              valueFrom:\n"
      << "                fieldRef:\n"
      << "                  fieldPath: "
      << q("metadata.annotations['batch.kubernetes.io/job-completion-index']") << "\n"
      << "          command: [\"/bin/sh\", \"-c\"]\n"
      << "          args:\n"
      << "            - " << q(podScript(s, work)) << "\n";
    return {};
}

// The container's resources (memory, CPUs, GPUs) and the claim the frames go to.
Result<void> resourcesAndVolumes(std::ostringstream& o, const Submission& s) {
    if (!s.mem.empty() || s.cpusPerTask > 0 || s.gpus > 0) {
        std::string mem;
        if (!s.mem.empty()) {
            auto m = k8sMemory(s.mem);
            if (!m) return std::move(m).error();
            mem = *m;
        }
        o << "          resources:\n";
        for (const char* kind : {"requests", "limits"}) {
            o << "            " << kind << ":\n";
            if (!mem.empty()) o << "              memory: " << q(mem) << "\n";
            if (s.cpusPerTask > 0)
                o << "              cpu: " << q(std::to_string(s.cpusPerTask)) << "\n";
            if (s.gpus > 0) o << "              nvidia.com/gpu: " << s.gpus << "\n";
        }
    }
    if (!s.pvc.empty()) {
        o << "          volumeMounts:\n"
          << "            - name: frames\n"
          << "              mountPath: "
          << q(std::filesystem::path(s.outputs.front()).parent_path().string()) << "\n"
          << "      volumes:\n"
          << "        - name: frames\n"
          << "          persistentVolumeClaim:\n"
          << "            claimName: " << q(s.pvc) << "\n";
    }
    return {};
}

} // namespace

Result<std::string> k8sManifest(const Submission& s, const JobWork& work) {
    std::ostringstream o;
    manifestHeader(o, s, work);
    LANTERN_TRY(jobSpec(o, s, work));
    LANTERN_TRY(resourcesAndVolumes(o, s));
    return o.str();
}

} // namespace lantern::cli::farm
