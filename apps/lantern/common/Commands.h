// Commands.h: the `lantern` subcommands. Each adds itself to the CLI11 app and returns the
// function that runs it after parsing.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>

namespace lantern::cli {

using Runner = std::function<int()>;

Runner addRenderCommand(CLI::App& app);
Runner addInfoCommand(CLI::App& app);
Runner addBenchCommand(CLI::App& app);
Runner addViewCommand(CLI::App& app);
Runner addFarmCommand(CLI::App& app); // docs/farm.md
Runner addCompareCommand(CLI::App& app); // docs/testing-with-lantern.md

} // namespace lantern::cli
