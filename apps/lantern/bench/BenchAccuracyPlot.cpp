// The accuracy plot: benchmarks/plot_accuracy.py (matplotlib) draws accuracy.csv; this finds
// the script (installed beside the command, or in the source tree it was built from) and runs
// it when python3 has matplotlib, else says how to draw it later.
#include "bench/BenchAccuracy.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <spawn.h>
#include <sys/wait.h>
#include <vector>

extern char** environ;

namespace lantern::cli {
namespace {

namespace fs = std::filesystem;

// Runs argv[0] (searched on PATH) with its output on this process's; the exit status, or -1.
int spawnAndWait(const std::vector<std::string>& args) {
    std::vector<char*> argv;
    for (const std::string& a : args)
        argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    pid_t pid = 0;
    if (posix_spawnp(&pid, argv[0], nullptr, nullptr, argv.data(), environ) != 0) return -1;
    int status = 0;
    if (waitpid(pid, &status, 0) != pid) return -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

} // namespace

std::string plotScriptPath() {
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    const fs::path candidates[] = {
        exe.parent_path() / LANTERN_BIN_TO_DATA / "lantern" / "plot_accuracy.py",
        fs::path(LANTERN_SOURCE_PLOT_SCRIPT),
    };
    for (const fs::path& c : candidates) {
        // Each candidate with its own error code: a first one that cannot be looked at (a
        // component that is not a folder) must not hide the next.
        std::error_code cec;
        if (fs::is_regular_file(c, cec)) return fs::weakly_canonical(c, cec).string();
    }
    return "plot_accuracy.py";
}

PlotOutcome plotAccuracy(const std::string& csv, const std::vector<std::string>& outputs) {
    const std::string script = plotScriptPath();
    std::vector<std::string> command = {"python3", script, csv};
    for (const std::string& out : outputs) {
        command.push_back("-o");
        command.push_back(out);
    }
    std::string text;
    for (const std::string& word : command)
        text += (text.empty() ? "" : " ") + word;
    if (!fs::is_regular_file(script))
        return {false, "the plot script plot_accuracy.py was not found; it is in Lantern's "
                       "benchmarks/ folder: python3 benchmarks/plot_accuracy.py " + csv};
    // The first python3 that has matplotlib: $LANTERN_PYTHON, the one on PATH, Debian's (a
    // pyenv or virtualenv python3 first on PATH may lack Debian's python3-matplotlib).
    std::vector<std::string> pythons;
    if (const char* chosen = std::getenv("LANTERN_PYTHON"); chosen && *chosen)
        pythons.push_back(chosen);
    pythons.insert(pythons.end(), {"python3", "/usr/bin/python3"});
    const auto python = std::find_if(pythons.begin(), pythons.end(), [](const std::string& p) {
        return spawnAndWait({p, "-c", "import matplotlib"}) == 0;
    });
    if (python == pythons.end())
        return {false, "no plot: python3 with matplotlib (Debian: python3-matplotlib) is not "
                       "installed; once it is: " + text};
    command.front() = *python;
    text = *python + text.substr(std::string("python3").size());
    // The script prints the paths it wrote; a failure is its own message on stderr.
    if (spawnAndWait(command) != 0) return {false, "the plot failed: " + text};
    return {true, text};
}

} // namespace lantern::cli
