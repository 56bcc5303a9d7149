// InstallSupport.h: what the install tests share: installing a build tree into a fresh
// temporary prefix (then moving it, so nothing can point back at where it was installed), and
// configuring and building the apps/examples projects against that prefix alone, with the
// toolchain of the build under test (compiler, launcher, generator, sanitizer flags).
#pragma once

#include "TestSupport.h"

#include <filesystem>
#include <string>
#include <vector>

namespace lantern::test {

/// A temporary folder (under $TMPDIR or /tmp), removed when the test passed and kept (with a
/// note on stderr) when it failed.
class TempDir {
public:
    TempDir();
    ~TempDir();
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const std::filesystem::path& path() const { return m_path; }

private:
    std::filesystem::path m_path;
};

/// Runs `args`; on failure (or a non-zero exit) the returned text says what ran and what it
/// printed, for an assertion message. Empty: it succeeded.
std::string runStep(const std::vector<std::string>& args, const std::vector<std::string>& env = {},
                    double timeoutSeconds = 600.0, ProcessResult* result = nullptr);

/// `cmake --install buildDir` into `root`/staging, then renamed to `root`/prefix (returned):
/// the package must work wherever the prefix is moved. Empty path and `failure` on error.
std::filesystem::path installBuild(const std::filesystem::path& buildDir,
                                   const std::filesystem::path& root, std::string& failure);

/// Configures and builds apps/examples/`example` in `buildDir` with CMAKE_PREFIX_PATH =
/// `prefix` only (package registries off), and checks that Lantern came from the prefix.
/// Empty on success, else what failed.
std::string buildExample(const std::string& example, const std::filesystem::path& prefix,
                         const std::filesystem::path& buildDir);

/// The compile and link flags of the build under test that an executable linked against its
/// libLantern needs (the sanitizer flags in sanitizer builds), split into words.
std::vector<std::string> toolchainFlags();
/// The build's C++ compiler.
std::string cxxCompiler();

/// Configure arguments that reproduce the build's toolchain (generator, compiler, launcher,
/// flags) for another build of Lantern or of an example.
std::vector<std::string> toolchainArgs();

} // namespace lantern::test
