// aniso::test::run_cli: posix_spawn with redirected streams and a deadline.
#include "cli_runner.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include <catch2/catch.hpp>

#include "test_support.h"

extern char** environ;

namespace aniso::test {

namespace {

// Every file temp_path handed out, removed when the test process ends.
class TempFiles {
 public:
  ~TempFiles() {
    std::error_code ignored;
    for (const std::string& path : paths_) std::filesystem::remove(path, ignored);
  }
  void add(const std::string& path) { paths_.push_back(path); }

 private:
  std::vector<std::string> paths_;
};

}  // namespace

// A path in the test temp dir that no other test process uses (ctest may run
// the test cases in parallel).
std::string temp_path(const std::string& name) {
  static TempFiles files;
  static std::atomic<int> counter{0};
  const std::string path = std::string(aniso::test::kScratchDir) + "/cli_" + std::to_string(getpid()) +
                           "_" + std::to_string(counter++) + "_" + name;
  files.add(path);
  return path;
}

namespace {

// Runs `command` (program first) with stdout and stderr sent to files (no pipe
// can fill up and block the child), stdin from /dev/null, and a deadline: a
// hang is a failure.
CliRun run_program(std::vector<std::string> command, int timeout_seconds) {
  const std::string out_path = temp_path("stdout.txt");
  const std::string err_path = temp_path("stderr.txt");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, 2, err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);

  std::vector<char*> argv;
  for (std::string& arg : command) argv.push_back(arg.data());
  argv.push_back(nullptr);

  CliRun run;
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  REQUIRE(spawned == 0);

  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(timeout_seconds);
  int status = 0;
  while (waitpid(pid, &status, WNOHANG) == 0) {
    if (std::chrono::steady_clock::now() > deadline) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      run.timed_out = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  run.signaled = WIFSIGNALED(status);
  if (WIFEXITED(status)) run.exit_status = WEXITSTATUS(status);
  run.out = slurp(out_path);
  run.err = slurp(err_path);
  return run;
}

}  // namespace

CliRun run_cli(const std::vector<std::string>& args, int timeout_seconds) {
  std::vector<std::string> command{aniso::test::kCliPath};
  command.insert(command.end(), args.begin(), args.end());
  return run_program(std::move(command), timeout_seconds);
}

CliRun run_cli_under(const std::vector<std::string>& wrapper, const std::vector<std::string>& args,
                     int timeout_seconds) {
  std::vector<std::string> command = wrapper;
  command.push_back(aniso::test::kCliPath);
  command.insert(command.end(), args.begin(), args.end());
  return run_program(std::move(command), timeout_seconds);
}

CliRun run_cli_after_shell(const std::string& setup, const std::vector<std::string>& args,
                           int timeout_seconds) {
  // The arguments reach the CLI as "$@": no quoting of paths in the script.
  std::vector<std::string> command{"/bin/sh", "-c", setup + "; exec \"$0\" \"$@\"", aniso::test::kCliPath};
  command.insert(command.end(), args.begin(), args.end());
  return run_program(std::move(command), timeout_seconds);
}

std::string describe(const std::vector<std::string>& args, const CliRun& run) {
  std::string text = "anisoform";
  for (const std::string& arg : args) text += " " + arg;
  return text + "\n  exit " + std::to_string(run.exit_status) + (run.signaled ? " (signal)" : "") +
         (run.timed_out ? " (timed out)" : "") + "\n  stdout: " + run.out + "\n  stderr: " + run.err;
}

nlohmann::json stdout_json(const CliRun& run) {
  REQUIRE(!run.out.empty());
  REQUIRE(run.out.back() == '\n');
  REQUIRE(run.out.find('\n') == run.out.size() - 1);
  const nlohmann::json result = nlohmann::json::parse(run.out);
  REQUIRE(result.is_object());
  return result;
}

CliRun run_expecting(const std::vector<std::string>& args, int expected_exit) {
  const CliRun run = run_cli(args);
  INFO(describe(args, run));
  REQUIRE_FALSE(run.signaled);
  REQUIRE_FALSE(run.timed_out);
  REQUIRE(run.exit_status == expected_exit);
  return run;
}

std::string write_temp_text(const std::string& name, const std::string& text) {
  const std::string path = temp_path(name);
  std::ofstream(path) << text;
  return path;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace aniso::test
