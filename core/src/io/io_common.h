// Private helpers shared by the format readers and writers in io_*.cpp.
//
// Text parsing works on std::string_view lines of an in-memory buffer: no
// allocation per line or token, so a 200k-vertex file parses in milliseconds.
// Numbers are parsed strictly (strict_number.h): a token must be a whole
// decimal number, nothing more ("3.1+e2" is rejected, not read as 3.1).
#pragma once

#include <charconv>
#include <climits>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "anisoform/error.h"
#include "anisoform/mesh_io.h"
#include "anisoform/strict_number.h"

namespace aniso::io {

// ---------------------------------------------------------------- errors

[[noreturn]] inline void fail_file(const std::string& message) {
  fail(ErrorCode::BadFile, message);
}

// A token quoted for an error message: printable, and short even when the
// file holds a megabyte without a line break.
std::string quoted(std::string_view token);

// " (line 12)", appended to messages about a text file's content.
inline std::string at_line(int line) { return " (line " + std::to_string(line) + ")"; }

// "the file is truncated: it ends after 900 of 1654 faces".
inline std::string truncated_message(long long done, long long total, const std::string& what) {
  return "the file is truncated: it ends after " + std::to_string(done) + " of " +
         std::to_string(total) + " " + what;
}

// ---------------------------------------------------------------- text

inline bool is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

// Yields the lines of a text buffer (without their ending) and their 1-based
// numbers. A line ends with "\n" (Unix), "\r\n" (Windows) or a lone "\r" (old
// Mac OS: an OBJ of such lines was one line, "'v' is not a number (line 1)").
// A last line without an ending is a line like any other.
class LineReader {
 public:
  explicit LineReader(std::string_view text) : rest_(text) {}

  bool next(std::string_view& line) {
    if (rest_.empty()) return false;
    const std::size_t end = rest_.find_first_of("\r\n");
    if (end == std::string_view::npos) {
      line = rest_;
      rest_ = {};
    } else {
      line = rest_.substr(0, end);
      const bool crlf = rest_[end] == '\r' && end + 1 < rest_.size() && rest_[end + 1] == '\n';
      rest_.remove_prefix(end + (crlf ? 2 : 1));
    }
    ++line_number_;
    return true;
  }
  int line_number() const { return line_number_; }  // of the line last returned
  std::string_view rest() const { return rest_; }     // text after that line

 private:
  std::string_view rest_;
  int line_number_ = 0;
};

// Removes and returns the next blank-separated token of `rest` (empty at the end).
inline std::string_view next_token(std::string_view& rest) {
  std::size_t begin = 0;
  while (begin < rest.size() && is_blank(rest[begin])) ++begin;
  std::size_t end = begin;
  while (end < rest.size() && !is_blank(rest[end])) ++end;
  const std::string_view token = rest.substr(begin, end - begin);
  rest.remove_prefix(end);
  return token;
}

// A number in a text mesh file: the strict grammar of strict_number.h, with
// nan/inf kept (check_mesh reports them per vertex). nullptr or the reason.
inline const char* parse_coordinate(std::string_view token, double& value) {
  return parse_strict_number(token, value, NonFiniteText::Keep);
}

// An integer in a text mesh file (strict_number.h); callers check the range.
inline bool parse_integer(std::string_view token, long long& value) {
  return parse_strict_integer(token, value) == nullptr;
}

// Refuses a header whose declared items (`declared`, in words: "829
// vertices and 1654 faces") take at least `needed` bytes when only `bytes`
// follow it, naming the counts and the size: no reader allocates or loops by
// a count the file cannot back.
void require_declared_bytes(long long needed, const std::string& declared, std::size_t bytes);

// The least bytes `items` text items (lines, tokens) take: one character each
// and a separator between them. Saturates instead of overflowing.
inline long long text_bytes_for(long long items) {
  if (items <= 0) return 0;
  return items > LLONG_MAX / 2 ? LLONG_MAX : 2 * items - 1;
}

// Appends the shortest text that reads back to exactly `value`.
void append_number(std::string& out, double value);
inline void append_number(std::string& out, long long value) {
  char buffer[24];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}

// Text rows of the ASCII writers: one "PREFIXx y z" line per vertex, and one
// "PREFIX a b c" line per triangle with indices + index_base (OBJ: prefix
// "v " / "f", base 1; OFF and ASCII PLY: prefix "" / "3", base 0).
void append_position_rows(std::string& out, const Positions& V, const char* prefix);
void append_triangle_rows(std::string& out, const Triangles& F, const char* prefix, long long index_base);

// The text of a file as UTF-8: skips a UTF-8 byte order mark, and decodes
// UTF-16 (little or big endian, recognised by its byte order mark) into
// `storage`, adding a note to `report`. Throws for a malformed UTF-16 body.
std::string_view decode_text(const char* data, std::size_t size, std::string& storage,
                             ReadReport& report);

// Throws when a text format holds a NUL byte: the file is binary, not text.
void reject_binary_text(std::string_view text, const char* format);

// ---------------------------------------------------------------- binary

inline bool host_is_little_endian() {
  const std::uint16_t probe = 1;
  unsigned char first = 0;
  std::memcpy(&first, &probe, 1);
  return first == 1;
}

// Reads a T stored at `p` in the given byte order (little endian when
// `little_endian`), whatever the host's order and alignment.
template <class T>
T load_scalar(const char* p, bool little_endian) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, p, sizeof(T));
  if (little_endian != host_is_little_endian()) {
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
  }
  T value;
  std::memcpy(&value, bytes, sizeof(T));
  return value;
}

// Appends a T in little endian order.
template <class T>
void append_little_endian(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if (!host_is_little_endian()) {
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
  }
  out.append(bytes, sizeof(T));
}

// ---------------------------------------------------------------- assembling

// What a polygon-based reader (OBJ, OFF, PLY) collects before triangulation.
// Corner indices are 0-based and already checked against the vertex count.
struct PolygonMesh {
  std::vector<double> xyz;           // 3 per vertex
  std::vector<int> corners;          // all polygons' corners, one after another
  std::vector<int> offsets{0};       // polygon i: corners[offsets[i], offsets[i+1])
  // Texture coordinates (OBJ): uv 2 per entry, and per corner its entry;
  // corner_uv stays empty unless every corner has one.
  std::vector<double> uv;
  std::vector<int> corner_uv;
  // OBJ vertex colours (r g b after x y z), 3 per vertex while every vertex has them.
  std::vector<double> colors;
  bool all_colored = true;
  // OBJ materials: mtllib statements, and (first polygon, name) per usemtl.
  std::vector<std::string> material_libraries;
  std::vector<std::pair<int, std::string>> material_runs;
  // The header's comments (OBJ, OFF: SurfaceAttributes::comments).
  std::vector<std::string> comments;

  int num_vertices() const { return static_cast<int>(xyz.size() / 3); }
  int num_polygons() const { return static_cast<int>(offsets.size()) - 1; }
  void add_vertex(double x, double y, double z) {
    xyz.push_back(x);
    xyz.push_back(y);
    xyz.push_back(z);
  }
  void end_polygon() { offsets.push_back(static_cast<int>(corners.size())); }
};

// Triangulates every polygon with more than 3 corners (triangulate_polygon)
// and counts them in report.polygons_triangulated.
ReadResult assemble_mesh(const PolygonMesh& polygons, ReadReport report);

// Elements a reader skipped, as a plain-words note, e.g. "skipped 6 line
// elements ('l')". Adds nothing when count is 0.
void note_skipped(ReadReport& report, int count, const std::string& what);

// Throws Error(BadMesh) naming the first face whose index is not a vertex:
// writers would otherwise read outside the positions.
void require_valid_indices(const Mesh& mesh);

// ---------------------------------------------------------------- comments

// The header's comment lines, each "PREFIX text\n" (OBJ and OFF "# ", PLY
// "comment "): first the line saying anisoform wrote the file, then the
// attributes' comments (file_comments.cpp: cleaned and capped again here).
void append_comment_lines(std::string& out, const SurfaceAttributes* attributes, const char* prefix);

// The first comment when it has at most `room` bytes, else "" (binary STL's
// header).
std::string first_comment_fitting(const SurfaceAttributes* attributes, std::size_t room);

// ---------------------------------------------------------------- formats

ReadResult read_obj(const char* data, std::size_t size);
ReadResult read_off(const char* data, std::size_t size);
ReadResult read_ply(const char* data, std::size_t size);
ReadResult read_stl(const char* data, std::size_t size);

std::string write_obj(const Mesh& mesh, const SurfaceAttributes* attributes = nullptr);
std::string write_off(const Mesh& mesh, const SurfaceAttributes* attributes = nullptr);
std::string write_ply(const Mesh& mesh, bool binary, const SurfaceAttributes* attributes = nullptr);
std::string write_stl(const Mesh& mesh, bool binary, const SurfaceAttributes* attributes = nullptr);

}  // namespace aniso::io
