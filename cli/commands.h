// The subcommands of the `anisoform` command-line tool. Each registers itself
// on the CLI11 app and, when chosen, runs and returns the process exit status:
//   0 success, 2 bad command line or parameter, 3 bad input mesh (or a
//   numerical failure the mesh causes). Errors go to stderr, results to stdout
//   as one JSON object.
#pragma once

#include <functional>
#include <memory>

#include <CLI/CLI.hpp>

#include "cli_common.h"

namespace aniso::cli {

// Set by the chosen subcommand's callback; main() runs it after parsing.
using Action = std::function<int()>;

// When `command` is the subcommand chosen, `action` becomes: refuse empty
// option values, then run(*args), every error reported by the command's
// name with its exit status (run_reporting_errors).
template <typename Arguments, typename Run>
void run_when_chosen(CLI::App* command, std::shared_ptr<Arguments> args, Action& action, Run run) {
  command->callback([command, args, &action, run] {
    action = [command, args, run] {
      return run_reporting_errors(command->get_name(), [&] {
        refuse_empty_values(*command);
        return run(*args);
      });
    };
  });
}

void register_info(CLI::App& app, Action& action);
void register_deform(CLI::App& app, Action& action);
void register_flatten(CLI::App& app, Action& action);
void register_replay(CLI::App& app, Action& action);  // cmd_replay.cpp

}  // namespace aniso::cli
