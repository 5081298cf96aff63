// Whole-file reading and atomic writing (file_io.h): only regular files are
// read, and a write either replaces the file completely or leaves it as it was.
#include <catch2/catch.hpp>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>

#include <filesystem>
#include <fstream>
#include <string>

#include "anisoform/error.h"
#include "anisoform/file_io.h"
#include "test_support.h"

namespace fs = std::filesystem;
using aniso::test::error_message_of;

namespace {

// A fresh directory of its own in the test temp dir, removed at the end.
class ScratchDirectory {
 public:
  explicit ScratchDirectory(const std::string& name)
      : path_(std::string(aniso::test::kScratchDir) + "/file_io_" + std::to_string(::getpid()) + "_" + name) {
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~ScratchDirectory() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  std::string file(const std::string& name) const { return path_ + "/" + name; }
  // The names of the files in the directory.
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(path_)) names.push_back(entry.path().filename().string());
    return names;
  }

 private:
  std::string path_;
};

}  // namespace

TEST_CASE("file io: a write replaces the file whole and leaves no temporary file", "[file_io]") {
  ScratchDirectory dir("replace");
  const std::string path = dir.file("out.txt");
  aniso::write_file_atomically(path, "first version, rather long\n");
  REQUIRE(::chmod(path.c_str(), 0640) == 0);
  aniso::write_file_atomically(path, "second\n");
  CHECK(aniso::test::slurp(path) == "second\n");
  CHECK(dir.entries() == std::vector<std::string>{"out.txt"});
  struct stat info {};
  REQUIRE(::stat(path.c_str(), &info) == 0);
  CHECK((info.st_mode & 0777) == 0640);  // an existing file keeps its permissions
}

TEST_CASE("file io: a write through a symlink replaces the target and keeps the link", "[file_io]") {
  ScratchDirectory dir("symlink");
  aniso::write_file_atomically(dir.file("target.txt"), "old\n");
  fs::create_symlink("target.txt", dir.file("link.txt"));
  aniso::write_file_atomically(dir.file("link.txt"), "new\n");
  CHECK(fs::is_symlink(dir.file("link.txt")));
  CHECK(aniso::test::slurp(dir.file("target.txt")) == "new\n");
}

TEST_CASE("file io: a write that cannot happen names the file and changes nothing", "[file_io]") {
  ScratchDirectory dir("refused");
  const auto bad_file = aniso::ErrorCode::BadFile;
  CHECK_THAT(error_message_of([&] { aniso::write_file_atomically(dir.file("missing/out.txt"), "x"); }, bad_file),
             Catch::StartsWith("could not write " + dir.file("missing/out.txt") + ": No such file or directory"));
  fs::create_directory(dir.file("sub"));
  CHECK_THAT(error_message_of([&] { aniso::write_file_atomically(dir.file("sub"), "x"); }, bad_file),
             Catch::Contains("could not write " + dir.file("sub") + ": it is a directory"));
  REQUIRE(::mkfifo(dir.file("pipe").c_str(), 0600) == 0);
  CHECK_THAT(error_message_of([&] { aniso::write_file_atomically(dir.file("pipe"), "x"); }, bad_file),
             Catch::Contains("it is not a regular file (a FIFO)"));
  CHECK(fs::is_fifo(dir.file("pipe")));
  CHECK(dir.entries().size() == 2);  // sub and pipe: no temporary file left
}

TEST_CASE("file io: only regular files are read, without blocking or reading forever", "[file_io]") {
  ScratchDirectory dir("read");
  const auto code = aniso::ErrorCode::BadFile;
  aniso::write_file_atomically(dir.file("plain.txt"), std::string("a\0b", 3));
  CHECK(aniso::read_regular_file(dir.file("plain.txt")) == std::string("a\0b", 3));

  CHECK(error_message_of([&] { aniso::read_regular_file(dir.file("none.txt")); }, code) ==
        "cannot open " + dir.file("none.txt") + ": no such file");
  fs::create_directory(dir.file("sub"));
  CHECK(error_message_of([&] { aniso::read_regular_file(dir.file("sub")); }, code) ==
        dir.file("sub") + " is a directory, not a regular file");
  REQUIRE(::mkfifo(dir.file("pipe.obj").c_str(), 0600) == 0);  // no writer: opening would block
  CHECK(error_message_of([&] { aniso::read_regular_file(dir.file("pipe.obj")); }, code) ==
        dir.file("pipe.obj") + " is not a regular file (a FIFO)");
  fs::create_symlink("/dev/zero", dir.file("zero.obj"));  // endless bytes
  CHECK(error_message_of([&] { aniso::read_regular_file(dir.file("zero.obj")); }, code) ==
        dir.file("zero.obj") + " is not a regular file (a character device)");
  // Files named by options are parameters: the caller picks the code.
  CHECK(error_message_of([&] { aniso::read_regular_file(dir.file("sub"), aniso::ErrorCode::BadParameter); },
                   aniso::ErrorCode::BadParameter) == dir.file("sub") + " is a directory, not a regular file");
}

// SIGTERM or SIGINT while the bytes went out (a job manager's timeout, a
// Ctrl+C during a slow write) left the hidden ".NAME.tmp-PID-N" beside OUT.
// A child writes 192 MB; the signal comes once its temporary file is there.
TEST_CASE("file io: SIGTERM or SIGINT during a write removes the temporary file, and still ends the process",
          "[file_io]") {
  for (const int signal : {SIGTERM, SIGINT}) {
    ScratchDirectory dir("signal_" + std::to_string(signal));
    const std::string path = dir.file("out.bin");
    const pid_t child = ::fork();
    REQUIRE(child >= 0);
    if (child == 0) {
      ::signal(SIGINT, SIG_DFL);  // as a shell's foreground job has it
      ::signal(SIGTERM, SIG_DFL);
      try {
        aniso::write_file_atomically(path, std::string(std::size_t{192} << 20, 'x'));
      } catch (...) {
      }
      ::_exit(0);
    }
    bool seen = false;
    for (int wait = 0; wait < 20000 && !seen; ++wait) {
      for (const std::string& name : dir.entries()) seen = seen || name.rfind(".out.bin.tmp-", 0) == 0;
      if (!seen) ::usleep(500);
    }
    ::kill(child, signal);
    int status = 0;
    REQUIRE(::waitpid(child, &status, 0) == child);
    INFO("signal " << signal);
    REQUIRE(seen);
    if (WIFEXITED(status)) {
      WARN("the write ended before the signal came: nothing to check");
      continue;
    }
    CHECK(WIFSIGNALED(status));
    CHECK(WTERMSIG(status) == signal);  // ended by the signal, as its parent expects
    const std::vector<std::string> left = dir.entries();
    INFO("left: " << (left.empty() ? std::string("nothing") : left.front()));
    CHECK(left.empty());  // no temporary file, no partial out.bin
  }
}
