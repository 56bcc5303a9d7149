// Install tests' support: temporary prefixes, running build steps, building the examples
// against an installed Lantern with the toolchain of the build under test.
#include "InstallSupport.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <unistd.h>

namespace fs = std::filesystem;

namespace lantern::test {
namespace {

std::vector<std::string> words(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream s(text);
    for (std::string w; s >> w;) out.push_back(w);
    return out;
}

std::string joined(const std::vector<std::string>& args) {
    std::string s;
    for (const std::string& a : args) s += (s.empty() ? "" : " ") + a;
    return s;
}

} // namespace

TempDir::TempDir() {
    const char* tmp = std::getenv("TMPDIR");
    std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/lantern-install-XXXXXX";
    if (mkdtemp(pattern.data())) m_path = pattern;
}

TempDir::~TempDir() {
    if (m_path.empty()) return;
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    if (info && info->result()->Failed()) {
        std::cerr << "note: kept " << m_path << " for inspection\n";
        return;
    }
    std::error_code ec;
    fs::remove_all(m_path, ec);
}

std::string runStep(const std::vector<std::string>& args, const std::vector<std::string>& env,
                    double timeoutSeconds, ProcessResult* result) {
    const ProcessResult r = runProcess(args, env, timeoutSeconds);
    if (result) *result = r;
    if (r.exitCode == 0) return {};
    return "`" + joined(args) + "` exited with " + std::to_string(r.exitCode) + "\nstdout:\n" +
           r.out + "\nstderr:\n" + r.err;
}

fs::path installBuild(const fs::path& buildDir, const fs::path& root, std::string& failure) {
    const fs::path staging = root / "staging", prefix = root / "prefix";
    failure = runStep({LANTERN_INSTALL_CMAKE, "--install", buildDir.string(), "--prefix",
                       staging.string()});
    if (!failure.empty()) return {};
    std::error_code ec;
    fs::rename(staging, prefix, ec);
    if (ec) {
        failure = "cannot move the installed prefix: " + ec.message();
        return {};
    }
    return prefix;
}

std::vector<std::string> toolchainFlags() { return words(LANTERN_INSTALL_FLAGS); }

std::string cxxCompiler() { return LANTERN_INSTALL_CXX; }

std::vector<std::string> toolchainArgs() {
    std::vector<std::string> args = {"-G", LANTERN_INSTALL_GENERATOR,
                                     "-DCMAKE_CXX_COMPILER=" + std::string(LANTERN_INSTALL_CXX),
                                     "-DCMAKE_C_COMPILER=" + std::string(LANTERN_INSTALL_CC)};
    const std::string launcher = LANTERN_INSTALL_LAUNCHER;
    if (!launcher.empty())
        args.insert(args.end(), {"-DCMAKE_CXX_COMPILER_LAUNCHER=" + launcher,
                                 "-DCMAKE_C_COMPILER_LAUNCHER=" + launcher});
    const std::string flags = LANTERN_INSTALL_FLAGS;
    if (!flags.empty())
        args.insert(args.end(), {"-DCMAKE_CXX_FLAGS=" + flags, "-DCMAKE_EXE_LINKER_FLAGS=" + flags,
                                 "-DCMAKE_SHARED_LINKER_FLAGS=" + flags});
    return args;
}

std::string buildExample(const std::string& example, const fs::path& prefix,
                         const fs::path& buildDir) {
    std::vector<std::string> configure = {
        LANTERN_INSTALL_CMAKE,
        "-S",
        (sourceDir() / "apps" / "examples" / example).string(),
        "-B",
        buildDir.string(),
        "-DCMAKE_BUILD_TYPE=" + std::string(LANTERN_INSTALL_BUILD_TYPE),
        "-DCMAKE_PREFIX_PATH=" + prefix.string(),
        // Only the prefix: no package registry may lead back to a build tree.
        "-DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF",
    };
    const auto tool = toolchainArgs();
    configure.insert(configure.end(), tool.begin(), tool.end());
    // CMAKE_PREFIX_PATH in the environment could name a build tree: it names the prefix too.
    const std::vector<std::string> env = {"CMAKE_PREFIX_PATH=" + prefix.string()};
    if (auto f = runStep(configure, env); !f.empty()) return f;

    // find_package must have found the installed package.
    std::ifstream cache(buildDir / "CMakeCache.txt");
    std::string line, found;
    while (std::getline(cache, line))
        if (line.rfind("Lantern_DIR:", 0) == 0) found = line.substr(line.find('=') + 1);
    const fs::path expected = prefix / LANTERN_INSTALL_LIBDIR / "cmake" / "Lantern";
    if (fs::weakly_canonical(found) != fs::weakly_canonical(expected))
        return "the " + example + " example found Lantern in \"" + found + "\", not in " +
               expected.string();

    return runStep({LANTERN_INSTALL_CMAKE, "--build", buildDir.string()}, env);
}

} // namespace lantern::test
