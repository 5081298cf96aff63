// Object File Format (OFF, ASCII): reading the OFF/COFF/NOFF/STOFF family
// (a COFF's per-vertex colours are kept, as an OBJ's are; normals, texture
// coordinates and face colours are skipped) and writing OFF, or COFF when
// the mesh has vertex colours.
#include <algorithm>
#include <cmath>

#include "anisoform/mesh_io.h"
#include "io/io_common.h"

namespace aniso {
namespace io {

namespace {

// Yields the lines that hold data: comments ('#' to the end of a line) and
// blank lines are dropped; the whole-line comments are kept in `comments`
// until the first vertex line (stop_keeping_comments).
class OffLines {
 public:
  explicit OffLines(std::string_view text, std::vector<std::string>& comments)
      : lines_(text), comments_(&comments) {}
  void stop_keeping_comments() { comments_ = nullptr; }
  bool next(std::string_view& line) {
    while (lines_.next(line)) {
      const std::size_t hash = line.find('#');
      if (comments_ && hash != std::string_view::npos && line.find_first_not_of(" \t") == hash) {
        keep_file_comment(*comments_, line.substr(hash + 1));
      }
      line = line.substr(0, hash);
      std::string_view probe = line;
      if (!next_token(probe).empty()) return true;
    }
    return false;
  }
  int line_number() const { return lines_.line_number(); }
  std::size_t bytes_left() const { return lines_.rest().size(); }

 private:
  LineReader lines_;
  std::vector<std::string>* comments_;
};

// "OFF" with optional prefixes: ST (texture coordinates), C (colour),
// N (normal). "4OFF"/"nOFF" (other dimensions) and binary OFF are not ours.
void check_header_keyword(std::string_view keyword, std::string_view rest) {
  static constexpr std::string_view kAccepted[] = {"OFF",    "COFF",    "NOFF",    "CNOFF",
                                                   "NCOFF",  "STOFF",   "STCOFF",  "STNOFF",
                                                   "STCNOFF", "STNCOFF"};
  for (std::string_view accepted : kAccepted) {
    if (keyword != accepted) continue;
    std::string_view probe = rest;
    if (next_token(probe) == "BINARY") fail_file("binary OFF files are not supported; use ASCII OFF");
    return;
  }
  if (keyword.size() >= 3 && keyword.substr(keyword.size() - 3) == "OFF") {
    fail_file("unsupported OFF variant " + quoted(keyword) +
              " (only 3D OFF, COFF, NOFF and STOFF are read)");
  }
  fail_file("not an OFF file: it starts with " + quoted(keyword) + " instead of 'OFF'");
}

long long parse_count(std::string_view token, const char* what, int line) {
  long long count = 0;
  if (token.empty()) fail_file(std::string("the header has no ") + what + " count" + at_line(line));
  if (!parse_integer(token, count) || count < 0 || count > INT32_MAX) {
    fail_file(std::string("the ") + what + " count " + quoted(token) + " is not a valid count" +
              at_line(line));
  }
  return count;
}

// The colour after a COFF vertex's coordinates (and normal): three or four
// numbers; anything else (a colour-map index, none) leaves the mesh without
// colours, as one OBJ vertex without them does.
void read_vertex_color(std::string_view line, bool has_normals, PolygonMesh& polygons) {
  if (has_normals) {
    for (int k = 0; k < 3; ++k) next_token(line);
  }
  double rgb[3];
  for (double& value : rgb) {
    const std::string_view token = next_token(line);
    if (!polygons.all_colored || token.empty() || parse_coordinate(token, value) || !(value >= 0.0)) {
      polygons.all_colored = false;
      polygons.colors.clear();
      return;
    }
  }
  polygons.colors.insert(polygons.colors.end(), rgb, rgb + 3);
}

// COFF colours are integers to 255 or fractions to 1 (the spec's): any value
// above 1 says the file counts to 255.
void finish_colors(PolygonMesh& polygons) {
  if (!polygons.all_colored || polygons.colors.empty()) {
    polygons.colors.clear();
    return;
  }
  if (*std::max_element(polygons.colors.begin(), polygons.colors.end()) <= 1.0) return;
  for (double& value : polygons.colors) value = std::min(value / 255.0, 1.0);
}

}  // namespace

ReadResult read_off(const char* data, std::size_t size) {
  ReadReport report;
  std::string decoded;
  const std::string_view text = decode_text(data, size, decoded, report);
  reject_binary_text(text, "OFF");
  PolygonMesh polygons;
  OffLines lines(text, polygons.comments);
  std::string_view line;

  if (!lines.next(line)) fail_file("the file has no OFF header (only blank lines and comments)");
  std::string_view rest = line;
  const std::string_view keyword = next_token(rest);
  check_header_keyword(keyword, rest);
  // A vertex line: x y z, then [nx ny nz] (N), then [r g b [a]] (C), then [s t] (ST).
  const bool has_normals = keyword.find('N') != std::string_view::npos;
  const bool has_colors = keyword.find('C') != std::string_view::npos;
  // The counts may follow the keyword on the same line ("OFF 8 6 0").
  {
    std::string_view probe = rest;
    if (next_token(probe).empty() && !lines.next(rest)) fail_file("the file ends after the OFF header");
  }
  const int counts_line = lines.line_number();
  const long long num_vertices = parse_count(next_token(rest), "vertex", counts_line);
  const long long num_faces = parse_count(next_token(rest), "face", counts_line);

  // The counts come from the file: refuse those its bytes cannot hold before
  // anything is allocated or looped over. Each vertex and face is a line of
  // at least one character and a newline (a truncated file that passes this
  // is reported where it ends, which says more).
  require_declared_bytes(text_bytes_for(num_vertices + num_faces),
                         std::to_string(num_vertices) + " vertices and " + std::to_string(num_faces) + " faces",
                         lines.bytes_left());
  // Reserve no more than the bytes could hold: a vertex line takes 6 at least.
  polygons.xyz.reserve(3 * static_cast<std::size_t>(std::min<long long>(num_vertices, size / 6)));
  polygons.offsets.reserve(static_cast<std::size_t>(std::min<long long>(num_faces, size / 6)) + 1);

  for (long long v = 0; v < num_vertices; ++v) {
    if (!lines.next(line)) fail_file(truncated_message(v, num_vertices, "vertices"));
    lines.stop_keeping_comments();  // the header's comments are read; those below describe the data
    double xyz[3];
    for (double& value : xyz) {
      const std::string_view token = next_token(line);
      if (token.empty()) {
        fail_file("vertex " + std::to_string(v) + " has fewer than 3 coordinates" +
                  at_line(lines.line_number()));
      }
      if (const char* problem = parse_coordinate(token, value)) {
        fail_file(number_problem(token, problem) + at_line(lines.line_number()));
      }
    }
    if (has_colors) read_vertex_color(line, has_normals, polygons);
    polygons.add_vertex(xyz[0], xyz[1], xyz[2]);
  }
  finish_colors(polygons);

  for (long long f = 0; f < num_faces; ++f) {
    if (!lines.next(line)) fail_file(truncated_message(f, num_faces, "faces"));
    const int line_number = lines.line_number();
    // From 0, as OFF numbers the vertices its faces reference.
    const std::string face = "face " + std::to_string(f);
    long long corners = 0;
    const std::string_view count_token = next_token(line);
    if (!parse_integer(count_token, corners) || corners < 3 || corners > INT32_MAX) {
      fail_file(face + " has corner count " + quoted(count_token) +
                "; a face needs at least 3 corners" + at_line(line_number));
    }
    for (long long c = 0; c < corners; ++c) {
      const std::string_view token = next_token(line);
      long long index = 0;
      if (token.empty()) {
        fail_file(face + " lists " + std::to_string(corners) + " corners but gives only " +
                  std::to_string(c) + at_line(line_number));
      }
      if (!parse_integer(token, index)) {
        fail_file(face + " has a malformed vertex index " + quoted(token) + at_line(line_number));
      }
      if (index < 0 || index >= num_vertices) {
        fail_file(face + " references vertex " + std::to_string(index) + ", but the file has " +
                  std::to_string(num_vertices) + " vertices (OFF numbers vertices and faces from 0)" +
                  at_line(line_number));
      }
      polygons.corners.push_back(static_cast<int>(index));
    }
    polygons.end_polygon();  // anything after the corners is a face colour
  }
  return assemble_mesh(polygons, std::move(report));
}

namespace {

// COFF: each vertex's colour after its position, as integers to 255 (what
// most readers of COFF expect), alpha full.
std::string write_coff(const Mesh& mesh, const Eigen::MatrixX3d& colors, const SurfaceAttributes* attributes) {
  std::string out = "COFF\n";
  append_comment_lines(out, attributes, "# ");
  append_number(out, static_cast<long long>(mesh.V.rows()));
  out += ' ';
  append_number(out, static_cast<long long>(mesh.F.rows()));
  out += " 0\n";
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
    for (int k = 0; k < 3; ++k) {
      append_number(out, mesh.V(i, k));
      out += ' ';
    }
    for (int k = 0; k < 3; ++k) {
      append_number(out, static_cast<long long>(std::lround(std::clamp(colors(i, k), 0.0, 1.0) * 255.0)));
      out += ' ';
    }
    out += "255\n";
  }
  append_triangle_rows(out, mesh.F, "3", 0);
  return out;
}

}  // namespace

std::string write_off(const Mesh& mesh, const SurfaceAttributes* attributes) {
  const Eigen::MatrixX3d colors =
      attributes ? vertex_colors(*attributes, static_cast<int>(mesh.V.rows())) : Eigen::MatrixX3d();
  if (colors.rows() > 0) return write_coff(mesh, colors, attributes);
  // The comments after the keyword: readers look for "OFF" on the first line.
  std::string out = "OFF\n";
  append_comment_lines(out, attributes, "# ");
  out.reserve(static_cast<std::size_t>(mesh.V.rows()) * 40 + static_cast<std::size_t>(mesh.F.rows()) * 24);
  append_number(out, static_cast<long long>(mesh.V.rows()));
  out += ' ';
  append_number(out, static_cast<long long>(mesh.F.rows()));
  out += " 0\n";
  append_position_rows(out, mesh.V, "");
  append_triangle_rows(out, mesh.F, "3", 0);
  return out;
}

}  // namespace io
}  // namespace aniso
