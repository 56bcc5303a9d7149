// Suggest.h: what a mistyped command line meant: the nearest valid subcommand or option name
// ("did you mean render?"), found by edit distance over the CLI11 definition.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace lantern::cli {

/// Every subcommand of `app`, in the order they were added (parsed or not).
std::vector<const CLI::App*> subcommandsOf(const CLI::App& app);

/// "lantern bench accuracy": the names from the root to `app`.
std::string commandPath(const CLI::App& app);

/// Edits (insertions, deletions, substitutions and swaps of neighbours) from `a` to `b`.
std::size_t editDistance(std::string_view a, std::string_view b);

/// The name of `names` nearest to `typed` when it is near enough to be a typo (at most a third
/// of its letters, at least 2, or `typed` is the start of exactly one name).
std::optional<std::string> nearestName(std::string_view typed,
                                       const std::vector<std::string>& names);

/// After a failed parse of `args` (argv without the program): a one-sentence diagnosis of an
/// unknown subcommand or option with the nearest valid name, or nullopt when the error is
/// something else (a missing value, a value out of range).
std::optional<std::string> diagnoseUnknownName(const CLI::App& root,
                                               const std::vector<std::string>& args);

/// After a parse that succeeded: an option of a parsed (sub)command whose value is exactly the
/// name of one of that command's options ("--device --dry-run"). CLI11 takes whatever word
/// follows an option as its value, so the option meant there was swallowed (and a dry run
/// would render). Nullopt when there is none.
std::optional<std::string> diagnoseSwallowedOption(const CLI::App& root);

} // namespace lantern::cli
