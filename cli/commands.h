// The subcommands of the `anisoform` command-line tool. Each registers itself
// on the CLI11 app and, when chosen, runs and returns the process exit status:
//   0 success, 2 bad command line or parameter, 3 bad input mesh (or a
//   numerical failure the mesh causes). Errors go to stderr, results to stdout
//   as one JSON object.
#pragma once

#include <functional>

#include <CLI/CLI.hpp>

namespace aniso::cli {

// Set by the chosen subcommand's callback; main() runs it after parsing.
using Action = std::function<int()>;

void register_info(CLI::App& app, Action& action);
void register_deform(CLI::App& app, Action& action);
void register_flatten(CLI::App& app, Action& action);
void register_replay(CLI::App& app, Action& action);  // cmd_replay.cpp

}  // namespace aniso::cli
