// Batches and sequences over several processes (`lantern render --processes N`): the same
// command line run N times, each run told by LANTERN_BATCH_WORKER=J/N to take the jobs (or
// frames) at positions k with k mod N == J (within its own --shard, when one was given), each
// with its own renderer and device, so that N renderers are in flight. The first process waits for them, passes SIGINT
// and SIGTERM on (each stops between two jobs) and exits with the worst of their codes.
#include "render/Batch.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <spawn.h>
#include <string>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

extern char** environ;

namespace lantern::cli {
namespace {

constexpr const char* kWorkerVariable = "LANTERN_BATCH_WORKER";

volatile std::sig_atomic_t g_signal = 0;

extern "C" void rememberSignal(int sig) { g_signal = sig; }

// Starts worker `index` of `count`: this program, these arguments, the worker variable added.
Result<pid_t> startWorker(const std::string& program, const std::vector<std::string>& args,
                          int index, int count) {
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    std::vector<std::string> env;
    for (char** e = environ; *e; ++e)
        if (std::string(*e).rfind(std::string(kWorkerVariable) + "=", 0) != 0) env.emplace_back(*e);
    env.push_back(std::string(kWorkerVariable) + "=" + std::to_string(index) + "/" +
                  std::to_string(count));
    std::vector<char*> envp;
    for (std::string& e : env) envp.push_back(e.data());
    envp.push_back(nullptr);
    pid_t pid = 0;
    if (const int err = posix_spawn(&pid, program.c_str(), nullptr, nullptr, argv.data(), envp.data());
        err != 0)
        return makeError(ErrorCode::IoError,
                         "cannot start batch process " + std::to_string(index) + ": " +
                             std::strerror(err),
                         "--processes");
    return pid;
}

// A worker's exit as this process reports it: its code, or 128 + the signal that ended it.
int exitCodeOf(int status) {
    if (WIFEXITED(status)) return WEXITSTATUS(status);
    if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
    return kFailed;
}

// Waits for every worker, passing SIGINT and SIGTERM on; the worst exit code (a signal's
// 128 + N above kFailed above kUsage above kRefused above kOk).
int waitForWorkers(std::vector<pid_t> pids) {
    struct sigaction sa {};
    sa.sa_handler = rememberSignal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = 0;  // no SA_RESTART: waitpid returns to pass the signal on
    sigaction(SIGINT, &sa, nullptr);
    sigaction(SIGTERM, &sa, nullptr);
    int worst = kOk, passed = 0;
    while (!pids.empty()) {
        int status = 0;
        const pid_t pid = waitpid(-1, &status, 0);
        if (pid < 0 && errno == EINTR) {
            if (g_signal != 0 && g_signal != passed)
                for (pid_t p : pids) kill(p, g_signal);
            passed = g_signal;
            continue;
        }
        if (pid < 0) break;  // ECHILD: none left
        const auto it = std::find(pids.begin(), pids.end(), pid);
        if (it == pids.end()) continue;
        pids.erase(it);
        const int code = exitCodeOf(status);
        const bool rankSignal = code > kFailed, rankWorst = worst > kFailed;
        if (rankSignal != rankWorst ? rankSignal : code > worst) worst = code;
    }
    return worst;
}

} // namespace

int processCount(int asked) {
    if (std::getenv(kWorkerVariable)) return 1;
    return asked > 0 ? asked : int(std::max(1u, std::thread::hardware_concurrency()));
}

Result<std::optional<Shard>> workerShard(std::optional<Shard> outer) {
    const char* worker = std::getenv(kWorkerVariable);
    if (!worker) return outer;
    auto mine = parseShard(worker);
    if (!mine)
        return makeError(ErrorCode::Usage, std::string("must be J/N, not \"") + worker + "\"",
                         kWorkerVariable);
    const Shard o = outer.value_or(Shard{});
    return std::optional<Shard>(Shard{o.index + o.count * mine->index, o.count * mine->count});
}

int runProcesses(int count) {
    char self[4096];
    const ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
    if (n <= 0)
        return report(makeError(ErrorCode::IoError, "cannot find this program (/proc/self/exe)",
                                "--processes"));
    self[n] = '\0';
    const std::vector<std::string> args = processArguments();
    const auto start = std::chrono::steady_clock::now();
    std::fflush(stdout);
    std::vector<pid_t> pids;
    for (int j = 0; j < count; ++j) {
        auto pid = startWorker(self, args, j, count);
        if (!pid) {
            for (pid_t p : pids) kill(p, SIGTERM);
            waitForWorkers(pids);
            return report(pid.error());
        }
        pids.push_back(*pid);
    }
    const int code = waitForWorkers(pids);
    std::fprintf(stderr, "lantern: %d processes done in %.2f s, exit code %d\n",
                 count,
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                 code);
    return code;
}

} // namespace lantern::cli
