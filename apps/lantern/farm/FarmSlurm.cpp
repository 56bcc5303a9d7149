// The Slurm back end of `lantern farm`: the sbatch script of a job array, submission with
// sbatch, and following the array's tasks with squeue.
#include "farm/Farm.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <map>
#include <poll.h>
#include <signal.h>
#include <sstream>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

namespace lantern::cli::farm {
namespace {

struct Output {
    int exitCode = -1;
    std::string out, err;
};

// Runs a Slurm client (found on PATH) and collects what it prints; kills it after `timeout`.
Result<Output> runTool(const std::vector<std::string>& args, double timeoutSeconds = 120.0) {
    // Slurm's clients retry a missing configuration for a minute before failing.
    if (const char* conf = std::getenv("SLURM_CONF");
        conf && *conf && !std::filesystem::exists(conf))
        return makeError(ErrorCode::Unsupported,
                         std::string("SLURM_CONF names ") + conf + ", which does not exist",
                         "SLURM_CONF");
    int outPipe[2], errPipe[2];
    if (pipe2(outPipe, O_CLOEXEC) != 0)
        return makeError(ErrorCode::IoError, "pipe: " + std::string(std::strerror(errno)));
    if (pipe2(errPipe, O_CLOEXEC) != 0) {
        close(outPipe[0]);
        close(outPipe[1]);
        return makeError(ErrorCode::IoError, "pipe: " + std::string(std::strerror(errno)));
    }
    std::vector<char*> argv;
    for (const std::string& a : args)
        argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    const pid_t pid = fork();
    if (pid == 0) {
        dup2(outPipe[1], 1);
        dup2(errPipe[1], 2);
        const int devnull = open("/dev/null", O_RDONLY);
        if (devnull >= 0) dup2(devnull, 0);
        execvp(argv[0], argv.data());
        std::fprintf(stderr, "%s", std::strerror(errno));
        _exit(127);
    }
    close(outPipe[1]);
    close(errPipe[1]);
    if (pid < 0) {
        close(outPipe[0]);
        close(errPipe[0]);
        return makeError(ErrorCode::IoError, "fork: " + std::string(std::strerror(errno)));
    }
    Output result;
    pollfd fds[2] = {{outPipe[0], POLLIN, 0}, {errPipe[0], POLLIN, 0}};
    const auto deadline =
        std::chrono::steady_clock::now() + std::chrono::duration<double>(timeoutSeconds);
    bool killed = false;
    char buf[4096];
    for (int open = 2; open > 0;) {
        if (!killed && std::chrono::steady_clock::now() > deadline) {
            kill(pid, SIGKILL);
            killed = true;
        }
        if (poll(fds, 2, 200) <= 0) continue;
        for (pollfd& p : fds) {
            if (p.fd < 0 || !(p.revents & (POLLIN | POLLHUP | POLLERR))) continue;
            const ssize_t n = read(p.fd, buf, sizeof buf);
            if (n > 0) {
                (&p == &fds[0] ? result.out : result.err).append(buf, std::size_t(n));
            } else {
                close(p.fd);
                p.fd = -1;
                --open;
            }
        }
    }
    int status = 0;
    waitpid(pid, &status, 0);
    result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    if (result.exitCode == 127 && result.out.empty())
        return makeError(ErrorCode::Unsupported,
                         args[0] + " not found (" + result.err +
                             "): is this a Slurm login node with the Slurm client tools on PATH? "
                             "(--no-submit writes the script without submitting it)",
                         "--scheduler");
    if (killed)
        return makeError(ErrorCode::IoError, args[0] + " did not answer in " +
                                                 std::to_string(int(timeoutSeconds)) +
                                                 " s (is slurmctld up?)");
    return result;
}

std::string firstLine(const std::string& text) {
    std::string line = text.substr(0, text.find('\n'));
    return line.empty() ? "(no message)" : line;
}

bool finalState(const std::string& state) {
    for (const char* s : {"COMPLETED", "FAILED", "CANCELLED", "TIMEOUT", "NODE_FAIL", "PREEMPTED",
                          "OUT_OF_MEMORY", "BOOT_FAIL", "DEADLINE", "SPECIAL_EXIT", "REVOKED"})
        if (state.rfind(s, 0) == 0) return true; // "CANCELLED by 0" starts with CANCELLED
    return false;
}

// squeue's view of a job's tasks: array index -> state. Tasks the controller no longer lists
// (cancelled while pending, or purged after MinJobAge) are absent.
struct TaskStates {
    bool known = true; // false: squeue says the job id is not (or no longer) valid
    std::map<int, std::string> states;
};

// Only tasks named `jobName` count: a controller that lost its state reuses job ids.
Result<TaskStates> queryTasks(const std::string& id, bool allStates, const std::string& jobName) {
    std::vector<std::string> args = {"squeue", "--noheader", "--array", "--jobs",
                                     id,       "--format",   "%K|%T|%j"};
    if (allStates) args.insert(args.end(), {"--states", "all"});
    auto r = runTool(args);
    if (!r) return std::move(r).error();
    TaskStates t;
    if (r->exitCode != 0) {
        if (r->err.find("Invalid job id") != std::string::npos) {
            t.known = false;
            return t;
        }
        return makeError(ErrorCode::IoError, "squeue failed: " + firstLine(r->err), "job " + id);
    }
    std::istringstream in(r->out);
    for (std::string line; std::getline(in, line);) {
        const auto bar1 = line.find('|'), bar2 = line.find('|', bar1 + 1);
        if (bar2 == std::string::npos || line.substr(bar2 + 1) != jobName) continue;
        int index = 0;
        // A job submitted without --array shows "N/A"; count it as task 0.
        if (std::sscanf(line.c_str(), "%d", &index) != 1) index = 0;
        t.states[index] = line.substr(bar1 + 1, bar2 - bar1 - 1);
    }
    return t;
}

std::string clock(double seconds) {
    const long s = long(seconds + 0.5);
    char b[32];
    std::snprintf(b, sizeof b, "%ld:%02ld", s / 60, s % 60);
    return b;
}

} // namespace

std::string slurmScript(const Submission& s, const JobWork& work) {
    std::ostringstream o;
    const std::string what =
        work.wholeRange
            ? "frames " + std::to_string(s.range.first) + "-" + std::to_string(s.range.last)
            : "the frames " + formatFrameList(work.frames) + " (missing from an earlier run)";
    const std::string n = std::to_string(work.tasks);
    o << "#!/bin/bash\n"
      << "# Lantern render job written by `lantern farm submit`: " << what << "\n"
      << "# of " << s.scene << "\n"
      << "# as a Slurm job array of " << n << " tasks. Task I renders "
      << (work.wholeRange ? "the frames k with k mod " + n + " == I"
                          : "the frames at positions p of that list with p mod " + n + " == I")
      << ",\n# and every frame's bytes are the same whichever task renders it.\n"
      << "#\n# Edit freely and resubmit with:  sbatch " << shellQuote(work.script.string()) << "\n"
      << "# (the shard is I/N with N the array's size: keep --array=0-(N-1) whole; to redo single\n"
      << "# frames use `lantern farm submit --resume`, which renders only the missing ones).\n"
      << "# Missing or unreadable frames:  lantern farm check " << shellQuote(s.outputs.front())
      << "\n";
    o << "#SBATCH --job-name=" << s.jobName << "\n"
      << "#SBATCH --array=0-" << work.tasks - 1 << "\n"
      << "#SBATCH --ntasks=1\n"
      << "#SBATCH --output=" << logFolder(s.outputs.front()).string() << "/%A_%a.out\n";
    if (s.cpusPerTask > 0) o << "#SBATCH --cpus-per-task=" << s.cpusPerTask << "\n";
    if (!s.partition.empty()) o << "#SBATCH --partition=" << s.partition << "\n";
    if (!s.time.empty()) o << "#SBATCH --time=" << s.time << "\n";
    if (!s.mem.empty()) o << "#SBATCH --mem=" << s.mem << "\n";
    if (s.gpus > 0) o << "#SBATCH --gres=gpu:" << s.gpus << "\n";
    for (const std::string& a : s.sbatchArgs)
        o << "#SBATCH " << a << "\n";
    o << "set -eu\n";
    for (const std::string& line : s.setup)
        o << line << "\n";
    // One option per line, so the command reads (and edits) easily.
    o << "exec";
    const std::vector<std::string> words = renderCommand(s, work);
    for (std::size_t i = 0; i < words.size(); ++i)
        o << (i > 2 && words[i].size() > 1 && words[i][0] == '-' ? " \\\n    " : " ")
          << shellQuote(words[i]);
    o << " \\\n    --shard \"$SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT\"";
    // Encode on the CPUs Slurm gave the task, not on every core of the node.
    if (!hasRenderOption(s, "--encoder-threads"))
        o << " --encoder-threads \"${SLURM_CPUS_PER_TASK:-1}\"";
    o << "\n";
    return o.str();
}

Result<std::string> slurmSubmit(const std::filesystem::path& script, bool hold) {
    std::vector<std::string> args = {"sbatch", "--parsable"};
    if (hold) args.push_back("--hold");
    args.push_back(script.string());
    auto r = runTool(args);
    if (!r) return std::move(r).error();
    if (r->exitCode != 0)
        return makeError(ErrorCode::IoError, "sbatch refused the job: " + firstLine(r->err), {},
                         script.string());
    // --parsable prints "ID" or "ID;CLUSTER".
    std::string id = r->out.substr(0, r->out.find_first_of(";\n"));
    if (id.empty() || id.find_first_not_of("0123456789") != std::string::npos)
        return makeError(ErrorCode::IoError,
                         "sbatch printed no job id: " + firstLine(r->out + r->err), {},
                         script.string());
    return id;
}

Result<int> slurmActiveTasks(const std::vector<std::string>& ids, const std::string& jobName) {
    int active = 0;
    for (const std::string& id : ids) {
        if (id.empty()) continue;
        auto t = queryTasks(id, false, jobName);
        if (!t) return std::move(t).error();
        for (const auto& [task, state] : t->states)
            active += !finalState(state);
    }
    return active;
}

Result<std::vector<std::string>> slurmFollow(const std::string& id, const Submission& s,
                                             const JobWork& work) {
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    const bool terminal = ::isatty(2);
    const int frames = int(work.frames.size());
    std::string last;
    int failures = 0;
    std::fprintf(stderr,
                 "lantern: following job %s (Ctrl-C stops following; the job keeps running)\n",
                 id.c_str());
    for (;;) {
        auto t = queryTasks(id, true, s.jobName);
        if (!t) {
            // The controller may be briefly busy; give up after about half a minute.
            if (++failures > 60) return std::move(t).error();
            std::this_thread::sleep_for(std::chrono::milliseconds(500));
            continue;
        }
        failures = 0;
        int done = 0, running = 0, pending = 0, failed = 0;
        for (int task = 0; task < work.tasks; ++task) {
            const auto it = t->states.find(task);
            if (!t->known || it == t->states.end()) {
                ++done; // no longer listed: cancelled while pending, or long finished
                failed += t->known;
                continue;
            }
            const std::string& state = it->second;
            if (finalState(state)) {
                ++done;
                failed += state != "COMPLETED";
            } else if (state == "RUNNING" || state == "COMPLETING") {
                ++running;
            } else {
                ++pending;
            }
        }
        const int present = countPresent(s.outputs, work.frames);
        const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
        const std::string notCompleted =
            failed ? ", " + std::to_string(failed) + " not completed" : "";
        char line[256];
        std::snprintf(line, sizeof line,
                      "job %s: %d/%d tasks done (%d running, %d pending%s), %d/%d frames present",
                      id.c_str(), done, work.tasks, running, pending, notCompleted.c_str(), present,
                      frames);
        const bool finished = done == work.tasks;
        if (terminal) {
            std::fprintf(stderr, "\rlantern: %s, %s   %s", line, clock(elapsed).c_str(),
                         finished ? "\n" : "");
        } else if (line != last || finished) {
            std::fprintf(stderr, "lantern: %s, %s\n", line, clock(elapsed).c_str());
        }
        std::fflush(stderr);
        last = line;
        if (finished) {
            std::vector<std::string> states(std::size_t(work.tasks), "GONE");
            for (const auto& [task, state] : t->states)
                if (task >= 0 && task < work.tasks) states[std::size_t(task)] = state;
            return states;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(500));
    }
}

} // namespace lantern::cli::farm
