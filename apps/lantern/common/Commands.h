// Commands.h: the `lantern` subcommands. Each adds itself to the CLI11 app and returns the
// function that runs it after parsing; runCommandLine() builds the whole command and runs it.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

namespace lantern::cli {

using Runner = std::function<int()>;

Runner addRenderCommand(CLI::App& app);
Runner addInfoCommand(CLI::App& app);
Runner addBenchCommand(CLI::App& app);
Runner addViewCommand(CLI::App& app);
Runner addFarmCommand(CLI::App& app); // docs/farm.md
Runner addCompareCommand(CLI::App& app); // docs/testing-with-lantern.md
Runner addThumbnailCommand(CLI::App& app); // a freedesktop thumbnailer

/// `lantern help [COMMAND...] [--markdown|--json]`: the help of a command, or the reference of
/// the whole command line generated from its definition (docs/cli.md is its output).
Runner addHelpCommand(CLI::App& app);

/// The reference of the whole command line as markdown: docs/cli.md.
std::string cliMarkdown(const CLI::App& root);

/// The whole command line: every subcommand added to `app`, in the order docs/cli.md lists
/// them; returns their runners.
std::vector<Runner> addAllCommands(CLI::App& app);

/// Parses argv and runs the subcommand chosen: its exit status (docs/cli.md). A mistyped
/// subcommand or option gets the nearest valid name (exit 2).
int runCommandLine(int argc, char** argv);

} // namespace lantern::cli
