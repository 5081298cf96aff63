// A file's header comments (attribution, licence lines), kept on reading and
// written again by every writer with a place for them, so that a CC BY
// mesh keeps its attribution through an edit (it was dropped: a PLY's
// "derived ... (CC BY 3.0, ...)" came out as only "written by anisoform").
// The cleaning is here, once, for all formats: a comment becomes one line of
// another file's header, so it must not carry a newline (a PLY comment with
// one would end the header's line and break the file) or other control bytes.
#include <algorithm>
#include <string>
#include <string_view>
#include <vector>

#include "anisoform/mesh_io.h"
#include "io/io_common.h"

namespace aniso {

namespace {

constexpr std::string_view kOwnMarker = "written by anisoform";

bool is_control(unsigned char c) { return c < 0x20 || c == 0x7f; }

bool is_utf8_continuation(unsigned char c) { return (c & 0xC0) == 0x80; }

}  // namespace

void keep_file_comment(std::vector<std::string>& comments, std::string_view text) {
  if (comments.size() >= kMaxFileComments) return;
  std::string clean;
  clean.reserve(std::min(text.size(), kMaxFileCommentBytes + 4));
  for (const char c : text) clean += is_control(static_cast<unsigned char>(c)) ? ' ' : c;
  const std::size_t first = clean.find_first_not_of(' ');
  if (first == std::string::npos) return;
  clean.erase(0, first);
  if (clean.size() > kMaxFileCommentBytes) {
    // Cut before a character, not inside one: no half UTF-8 sequence.
    std::size_t cut = kMaxFileCommentBytes;
    while (cut > 0 && is_utf8_continuation(static_cast<unsigned char>(clean[cut]))) --cut;
    clean.resize(cut);
  }
  clean.erase(clean.find_last_not_of(' ') + 1);
  if (clean.empty()) return;
  if (clean.compare(0, kOwnMarker.size(), kOwnMarker) == 0) return;
  comments.push_back(std::move(clean));
}

namespace io {

void append_comment_lines(std::string& out, const SurfaceAttributes* attributes, const char* prefix) {
  out += prefix;
  out += kOwnMarker;
  out += '\n';
  if (!attributes) return;
  // Cleaned again: attributes may come from elsewhere than a reader.
  std::vector<std::string> safe;
  for (const std::string& comment : attributes->comments) keep_file_comment(safe, comment);
  for (const std::string& comment : safe) {
    out += prefix;
    out += comment;
    out += '\n';
  }
}

std::string first_comment_fitting(const SurfaceAttributes* attributes, std::size_t room) {
  if (!attributes) return {};
  std::vector<std::string> safe;
  for (const std::string& comment : attributes->comments) {
    keep_file_comment(safe, comment);
    if (!safe.empty()) break;
  }
  if (safe.empty() || safe.front().size() > room) return {};
  return safe.front();
}

}  // namespace io
}  // namespace aniso
