// Runs the real `anisoform` binary for the CLI-contract tests: stdout and
// stderr sent to files (no pipe can fill up and block the child), stdin from
// /dev/null, and a deadline, so that a hang is a failure and not a stuck suite.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace aniso::test {

struct CliRun {
  int exit_status = -1;  // -1 when the process did not exit normally
  bool signaled = false;
  bool timed_out = false;
  std::string out;
  std::string err;
};

// A path in the test temp dir that no other test process uses (ctest runs
// test cases in parallel), removed when the test process ends.
std::string temp_path(const std::string& name);

CliRun run_cli(const std::vector<std::string>& args, int timeout_seconds = 60);

// Runs the CLI from /bin/sh after the shell commands `setup` (e.g. "trap ''
// XFSZ; ulimit -f 8": limits and signal dispositions the CLI inherits).
CliRun run_cli_after_shell(const std::string& setup, const std::vector<std::string>& args,
                           int timeout_seconds = 60);

// Runs the CLI as the last part of `wrapper`'s command line (e.g. setpriv
// dropping a capability: what the CLI cannot do then, it must report).
CliRun run_cli_under(const std::vector<std::string>& wrapper, const std::vector<std::string>& args,
                     int timeout_seconds = 60);

// The command line and what it did, for INFO messages.
std::string describe(const std::vector<std::string>& args, const CliRun& run);

// Runs the CLI and requires that it exits with `expected_exit` (no signal, no hang).
CliRun run_expecting(const std::vector<std::string>& args, int expected_exit);

// Stdout must be exactly one JSON object on one line; returns it.
nlohmann::json stdout_json(const CliRun& run);

// Writes `text` to a new temp_path(name) and returns the path.
std::string write_temp_text(const std::string& name, const std::string& text);

bool contains(const std::string& text, const std::string& part);

}  // namespace aniso::test
