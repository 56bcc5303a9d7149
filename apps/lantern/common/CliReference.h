// CliReference.h: what the generated references of the command line share (docs/cli.md, the
// JSON definition, the man pages and the shell completions), read from its CLI11 definition.
#pragma once

#include <CLI/CLI.hpp>
#include <lantern/Result.h>

#include <string>
#include <vector>

namespace lantern::cli {

/// The options a reference lists: every one but --help.
std::vector<const CLI::Option*> listedOptions(const CLI::App& app);
/// "-o, --output", or a positional's name.
std::string optionNames(const CLI::Option& o);
bool isFlag(const CLI::Option& o);
bool isList(const CLI::Option& o);        ///< comma-separated values
bool isRepeatable(const CLI::Option& o);  ///< given several times

/// The names an option's value is one of, for completions (empty: any value).
std::vector<std::string> optionChoices(const CLI::Option& o);

/// "lantern-bench-accuracy": the man page's name of a command.
std::string manPageName(const CLI::App& app);
/// The command's man page (roff, section 1).
std::string manPage(const CLI::App& app);
/// Writes the man page of `root` and of every subcommand into the folder `dir` (NAME.1 each);
/// the paths written.
Result<std::vector<std::string>> writeManPages(const CLI::App& root, const std::string& dir);

/// The completion script for `shell` (bash, zsh or fish; else a usage error naming
/// --completion): subcommands, options, option values, scene files.
Result<std::string> completionScript(const CLI::App& root, const std::string& shell);

} // namespace lantern::cli
