// TextFile.h: a text file written as every output of the command is: whole or not at all
// (a temporary beside it, created exclusively and never through a symbolic link, renamed into
// place). The farm's records and scripts, the benchmarks' reports and `render --report` use it.
#pragma once

#include <lantern/Result.h>

#include <filesystem>
#include <string>

namespace lantern::cli {

Result<void> writeTextFile(const std::filesystem::path& path, const std::string& text);

} // namespace lantern::cli
