// Reading and writing whole files, the one way every file of the core and the
// CLI is read or written.
//
// Reading refuses what is not a regular file (a directory, a FIFO, a device
// such as /dev/zero, a socket) before any byte is read: those would block or
// be read until memory runs out. A regular file is read up to the size it had
// when opened, so nothing read is larger than the file.
//
// Writing never leaves a partial file behind: the bytes go to a temporary
// file in the same directory, which is flushed to disk and then renamed over
// the path. On any failure (disk full, file-size limit, no permission) the
// temporary file is removed and an existing file at the path is unchanged,
// byte for byte; so writing a mesh over its own input is safe.
#pragma once

#include <string>
#include <string_view>

#include "anisoform/error.h"

namespace aniso {

// The whole content of the regular file at `path` (symlinks followed).
// Throws Error(code) with one of these messages:
//   "cannot open PATH: no such file", "PATH is a directory, not a regular file",
//   "PATH is not a regular file (a FIFO)", "cannot read PATH: <reason>".
std::string read_regular_file(const std::string& path, ErrorCode code = ErrorCode::BadFile);

// Replaces the file at `path` with `bytes` atomically (see above); a symlink
// at `path` is followed and its target replaced. An existing file keeps its
// permissions. Throws Error(BadFile, "could not write PATH: <reason>").
// "could not write PATH: <reason>" ends "(an existing PATH is left
// unchanged)" when there is one. Natively, SIGTERM, SIGINT and SIGHUP during
// the write (when their disposition is the default) remove the temporary
// file before the process ends by the signal as it would have.
void write_file_atomically(const std::string& path, std::string_view bytes);

// Whether write_file_atomically could create its temporary file next to
// `path`: creates one and removes it again. 0 when it could, else the errno
// (EACCES in a directory without write permission, EROFS, ENOENT...), so
// that a host refuses an unwritable place before the work whose result it is.
int temporary_file_error_next_to(const std::string& path);

}  // namespace aniso
