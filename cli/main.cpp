// Entry point of the `anisoform` command-line tool: parses the command line
// with CLI11, runs the chosen subcommand, and maps every failure to the exit
// statuses of the contract (commands.h). Nothing escapes main: scripts rely on
// a status, never a signal.
#include <csignal>
#include <cstdlib>  // defines __GLIBC__ on glibc
#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include <CLI/CLI.hpp>

#include "cli_common.h"
#include "commands.h"

namespace {

int parse_and_run(int argc, char** argv) {
  CLI::App app{"Anisotropic mesh deformation (Colaianni et al. 2017): local shape control "
               "by anisotropic scale, shear, rotation and twist.",
               "anisoform"};
  app.require_subcommand(1);
  app.footer(
      "Results are one JSON object on stdout; messages go to stderr (warnings too,\n"
      "each also in the JSON's warnings).\n"
      "Exit status: 0 success, 2 bad command line or parameter (including an\n"
      "unknown-format OUT or one in a missing or unwritable directory), 3 bad or unreadable input\n"
      "mesh, or OUT could not be written (an existing OUT is then left unchanged).");

  aniso::cli::Action action;
  aniso::cli::register_info(app, action);
  aniso::cli::register_deform(app, action);
  aniso::cli::register_flatten(app, action);
  aniso::cli::register_replay(app, action);

  // A first word that names no command: CLI11 took it for a stray argument
  // and said "A subcommand is required".
  if (argc > 1 && argv[1][0] != '-') {
    const std::string word = argv[1];
    std::string names;
    bool known = false;
    for (const CLI::App* command : app.get_subcommands([](CLI::App*) { return true; })) {
      known = known || command->get_name() == word;
      names += (names.empty() ? "" : ", ") + command->get_name();
    }
    if (!known) {
      aniso::cli::report_error("", "unknown command '" + word + "' (the commands are " + names +
                                       "; see anisoform --help)");
      return aniso::cli::kExitBadUsage;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help is a ParseError whose exit code is 0 (app.exit prints the help on
    // stdout); CLI11 gives other errors codes of its own, all of which are a
    // bad command line under our contract, reported as every other error is
    // ("anisoform deform: error: ..."; CLI11's own lines had no prefix).
    if (e.get_exit_code() == 0) return app.exit(e) == 0 ? aniso::cli::kExitSuccess : aniso::cli::kExitBadUsage;
    const std::vector<CLI::App*> parsed = app.get_subcommands();
    const std::string command = parsed.empty() ? "" : parsed.back()->get_name();
    aniso::cli::report_error(command, std::string(e.what()) + " (see anisoform " +
                                          (command.empty() ? "" : command + " ") + "--help)");
    return aniso::cli::kExitBadUsage;
  }
  return action ? action() : aniso::cli::kExitBadUsage;
}

}  // namespace

int main(int argc, char** argv) {
#if defined(__GLIBC__)
  // Keep freed memory in the process instead of handing it back to the
  // system: the flattening's Newton iterations factor a matrix of the same
  // size every step, and with glibc's defaults every factor's buffers were
  // fresh pages (page faults and zeroing were half of the bunny's time:
  // 120 iterations 28.1 s -> 13.3 s). TOOLCHAIN.md §7 sets the same for
  // the benchmarks.
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
#endif
#if defined(SIGXFSZ)
  // A write past the file size limit (ulimit -f) fails with EFBIG, reported
  // as any failed write (exit 3, the temporary file removed, an existing
  // OUT untouched), instead of the signal killing the process mid-write.
  std::signal(SIGXFSZ, SIG_IGN);
#endif
  return aniso::cli::run_reporting_errors("", [&] { return parse_and_run(argc, argv); });
}
