#pragma once
/// @file suggest.hpp
/// Answers to a mistyped command line: the command or option names nearest to what was typed, by
/// the Damerau–Levenshtein (optimal string alignment) distance, and the one-line message `main`
/// prints instead of CLI11's ("did you mean `map`?").

#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

namespace sonarmap::cli {

/// The optimal string alignment distance between `a` and `b`: insertions, deletions,
/// substitutions and swaps of two neighbouring characters each count one (Damerau 1964).
std::size_t editDistance(std::string_view a, std::string_view b);

/// The names of `candidates` nearest to `typed`, at most a third of its length away (at least 1,
/// at most 3 edits), nearest first and in `candidates`' order among equals; empty when none is
/// that near. A candidate that starts with `typed` (an abbreviation) counts as near.
std::vector<std::string> nearestNames(std::string_view typed, const std::vector<std::string>& candidates);

/// The one-line message for a parse error of `app` on `args` (argv without the program's name):
/// an unknown command or option named with its nearest names and the usage line
/// ("unknown command `mapp`: did you mean `map`? Usage: sonarmap COMMAND ..."), else CLI11's
/// `error` as it is.
std::string parseErrorMessage(CLI::App& app, const std::vector<std::string>& args, const CLI::ParseError& error);

}  // namespace sonarmap::cli
