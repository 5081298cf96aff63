// Whole-file reading and atomic writing (file_io.h), with POSIX calls: they
// report why something failed (errno) where iostreams only say that it did,
// and they open a FIFO without blocking.
#include "anisoform/file_io.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace aniso {

namespace {

// What a stat mode is, for "PATH is not a regular file (a FIFO)".
const char* non_regular_kind(mode_t mode) {
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a file";
}

[[noreturn]] void fail_not_regular(const std::string& path, mode_t mode, ErrorCode code) {
  if (S_ISDIR(mode)) fail(code, path + " is a directory, not a regular file");
  fail(code, path + " is not a regular file (" + non_regular_kind(mode) + ")");
}

// Closes a descriptor when the scope ends (also when a failure throws).
class FileDescriptor {
 public:
  explicit FileDescriptor(int fd) : fd_(fd) {}
  ~FileDescriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  int get() const { return fd_; }
  // Closes now and returns close's result (a deferred write error shows here).
  int close_now() {
    const int result = ::close(fd_);
    fd_ = -1;
    return result;
  }

 private:
  int fd_;
};

// Writes all of `bytes`, resuming after short writes and signals; false with
// errno set on failure (EFBIG beyond a file-size limit, ENOSPC on a full disk).
bool write_all(int fd, std::string_view bytes) {
  while (!bytes.empty()) {
    const ssize_t written = ::write(fd, bytes.data(), bytes.size());
    if (written < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    bytes.remove_prefix(static_cast<std::size_t>(written));
  }
  return true;
}

// The temporary file of the write in progress, removed by the handler of a
// signal that ends the process (SIGTERM from a job manager, SIGINT from
// Ctrl+C, SIGHUP from a closed terminal): it was left behind as a hidden
// ".NAME.tmp-PID-N" beside OUT. The handler does only async-signal-safe
// things: unlink the path (a fixed buffer, filled before it is armed), put
// the default disposition back and raise the signal again, so the process
// still ends by it, as its parent expects. A signal whose disposition is not
// the default (ignored, or the host's own handler) is left alone.
#if defined(__EMSCRIPTEN__)
class TemporaryRemovedOnSignal {  // no signals in the browser
 public:
  void arm(const std::string&) const {}
  void disarm() const {}
};
#else
class TemporaryRemovedOnSignal {
 public:
  TemporaryRemovedOnSignal() {
    struct sigaction removing {};
    removing.sa_handler = remove_and_reraise;
    sigemptyset(&removing.sa_mask);
    for (std::size_t k = 0; k < kSignals.size(); ++k) {
      struct sigaction before {};
      if (::sigaction(kSignals[k], nullptr, &before) != 0 || before.sa_handler != SIG_DFL) continue;
      installed_[k] = ::sigaction(kSignals[k], &removing, &previous_[k]) == 0;
    }
  }
  ~TemporaryRemovedOnSignal() {
    armed_ = 0;
    for (std::size_t k = 0; k < kSignals.size(); ++k) {
      if (installed_[k]) ::sigaction(kSignals[k], &previous_[k], nullptr);
    }
  }
  TemporaryRemovedOnSignal(const TemporaryRemovedOnSignal&) = delete;
  TemporaryRemovedOnSignal& operator=(const TemporaryRemovedOnSignal&) = delete;

  // From now on a signal removes `temporary`: armed before the file is
  // created, so that no signal between its creation and the arming misses it
  // (a path too long for the buffer is not armed: the temporary then stays,
  // as before).
  void arm(const std::string& temporary) const {
    armed_ = 0;
    if (temporary.size() >= sizeof path_) return;
    std::memcpy(path_, temporary.c_str(), temporary.size() + 1);
    armed_ = 1;
  }
  void disarm() const { armed_ = 0; }

 private:
  static constexpr std::array<int, 3> kSignals{SIGTERM, SIGINT, SIGHUP};

  static void remove_and_reraise(int signal) {
    if (armed_) ::unlink(path_);
    ::signal(signal, SIG_DFL);
    ::raise(signal);
  }

  static inline char path_[4096];
  static inline volatile std::sig_atomic_t armed_ = 0;
  std::array<struct sigaction, 3> previous_{};
  std::array<bool, 3> installed_{};
};
#endif

// A new file next to `target`, created exclusively (never someone else's):
// ".NAME.tmp-PID-N" in the same directory, so the rename stays on one file
// system and is atomic. Sets `temporary` and returns the descriptor, or -1.
// With `on_signal`, each name is armed before it is created.
int create_temporary_next_to(const std::string& target, std::string& temporary,
                             const TemporaryRemovedOnSignal* on_signal = nullptr) {
  static std::atomic<unsigned> counter{0};
  const std::size_t slash = target.find_last_of('/');
  const std::string directory = slash == std::string::npos ? "" : target.substr(0, slash + 1);
  const std::string name = slash == std::string::npos ? target : target.substr(slash + 1);
  const std::string stem = directory + "." + name + ".tmp-" + std::to_string(::getpid()) + "-";
  for (int attempt = 0; attempt < 100; ++attempt) {
    temporary = stem + std::to_string(counter++);
    if (on_signal) on_signal->arm(temporary);
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0) return fd;
    if (on_signal) on_signal->disarm();  // not ours
    if (errno != EEXIST) return fd;
  }
  return -1;
}

// The file a symlink finally points to (the path itself otherwise, and for a
// dangling link, which the rename then replaces).
std::string resolve_symlink(const std::string& path) {
  struct stat link {};
  if (::lstat(path.c_str(), &link) != 0 || !S_ISLNK(link.st_mode)) return path;
  char* resolved = ::realpath(path.c_str(), nullptr);
  if (!resolved) return path;
  std::string target(resolved);
  std::free(resolved);
  return target;
}

}  // namespace

int temporary_file_error_next_to(const std::string& path) {
  std::string temporary;
  const int fd = create_temporary_next_to(resolve_symlink(path), temporary);
  if (fd < 0) return errno != 0 ? errno : EEXIST;
  ::close(fd);
  ::unlink(temporary.c_str());
  return 0;
}

std::string read_regular_file(const std::string& path, ErrorCode code) {
  struct stat info {};
  // stat first: a FIFO or a device is refused before it is opened at all.
  if (::stat(path.c_str(), &info) != 0) {
    if (errno == ENOENT || errno == ENOTDIR) fail(code, "cannot open " + path + ": no such file");
    fail(code, "cannot open " + path + ": " + std::strerror(errno));
  }
  if (!S_ISREG(info.st_mode)) fail_not_regular(path, info.st_mode, code);
  // O_NONBLOCK: should the path have become a FIFO since the stat, opening it
  // must not wait for a writer; fstat then refuses it.
  FileDescriptor file(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC));
  if (file.get() < 0) fail(code, "cannot open " + path + ": " + std::strerror(errno));
  if (::fstat(file.get(), &info) != 0) fail(code, "cannot read " + path + ": " + std::strerror(errno));
  if (!S_ISREG(info.st_mode)) fail_not_regular(path, info.st_mode, code);

  // No more than the size at open: a file that grows while we read cannot
  // make us read (and allocate) without end.
  std::string data(static_cast<std::size_t>(info.st_size), '\0');
  std::size_t filled = 0;
  while (filled < data.size()) {
    const ssize_t got = ::read(file.get(), &data[filled], data.size() - filled);
    if (got < 0) {
      if (errno == EINTR || errno == EAGAIN) continue;
      fail(code, "cannot read " + path + ": " + std::strerror(errno));
    }
    if (got == 0) break;  // shrunk since the fstat
    filled += static_cast<std::size_t>(got);
  }
  data.resize(filled);
  return data;
}

void write_file_atomically(const std::string& path, std::string_view bytes) {
  // A symlink keeps pointing where it did: replace its target, not the link.
  const std::string target = resolve_symlink(path);
  struct stat existing {};
  const bool exists = ::stat(target.c_str(), &existing) == 0;
  // "An existing PATH is left unchanged" only where there is one (it was
  // said of a new file in an unwritable directory too).
  const auto fail_write = [&path, exists](const std::string& reason) {
    fail(ErrorCode::BadFile, "could not write " + path + ": " + reason +
                                 (exists ? " (an existing " + path + " is left unchanged)" : std::string()));
  };
  if (exists && !S_ISREG(existing.st_mode)) {
    fail_write(S_ISDIR(existing.st_mode) ? std::string("it is a directory")
                                         : std::string("it is not a regular file (") +
                                               non_regular_kind(existing.st_mode) + ")");
  }

  const TemporaryRemovedOnSignal on_signal;
  std::string temporary;
  FileDescriptor file(create_temporary_next_to(target, temporary, &on_signal));
  if (file.get() < 0) fail_write(std::strerror(errno));
  const auto fail_and_remove = [&](int error) {
    if (file.get() >= 0) file.close_now();
    ::unlink(temporary.c_str());
    fail_write(std::strerror(error));
  };
  if (exists) ::fchmod(file.get(), existing.st_mode & 07777);  // best effort
  if (!write_all(file.get(), bytes)) fail_and_remove(errno);
  // fsync: file systems that allocate late report a full disk only here (or
  // at close), and the rename must not publish data still in flight.
  if (::fsync(file.get()) != 0 && errno != EINVAL && errno != EROFS) fail_and_remove(errno);
  if (file.close_now() != 0) fail_and_remove(errno);
  if (std::rename(temporary.c_str(), target.c_str()) != 0) fail_and_remove(errno);
}

}  // namespace aniso
