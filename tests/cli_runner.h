// Runs the real `anisoform` binary for the CLI-contract tests: stdout and
// stderr sent to files (no pipe can fill up and block the child), stdin from
// /dev/null, and a deadline, so that a hang is a failure and not a stuck suite.
#pragma once

#include <string>
#include <vector>

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

}  // namespace aniso::test
