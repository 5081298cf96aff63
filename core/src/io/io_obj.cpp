// Wavefront OBJ: reading `v`, `vt` and `f` (all corner forms, negative
// relative indices, polygons) and the materials (`mtllib`, `usemtl`),
// skipping everything else; writing positions and faces, optionally with
// texture coordinates and the materials. Texture coordinates are
// kept only when every face corner has a valid one; otherwise they are
// dropped with a note and the mesh reads as before (they never made a file
// unreadable).
#include <algorithm>
#include <climits>
#include <cmath>
#include <limits>

#include "anisoform/mesh_io.h"
#include "io/io_common.h"

namespace aniso {
namespace io {

namespace {

// Statements that carry no surface geometry we use: attributes, grouping,
// materials, free-form surface data. They are ignored without a note.
bool is_ignored_statement(std::string_view keyword) {
  static constexpr std::string_view kIgnored[] = {
      "vn",   "vp",    "o",      "g",    "s",
      "usemap", "maplib", "lod", "shadow_obj", "trace_obj", "bevel", "c_interp", "d_interp",
      "cstype", "deg", "bmat", "step", "parm", "trim", "hole", "scrv",
      "sp",   "end",   "con",   "mg",     "ctech", "stech", "call", "csh"};
  for (std::string_view ignored : kIgnored) {
    if (keyword == ignored) return true;
  }
  return false;
}

// Non-surface elements: points, lines and free-form curves/surfaces.
bool is_skipped_element(std::string_view keyword) {
  return keyword == "p" || keyword == "l" || keyword == "curv" || keyword == "curv2" ||
         keyword == "surf";
}

class ObjParser {
 public:
  ReadResult parse(std::string_view text, ReadReport report) {
    LineReader lines(text);
    std::string_view line;
    while (lines.next(line)) {
      line_ = lines.line_number();
      std::string_view rest = line;
      const std::string_view keyword = next_token(rest);
      if (keyword.empty()) continue;
      if (keyword[0] == '#') {
        // The leading block is the file's header (attribution, licence).
        if (!seen_statement_) keep_file_comment(polygons_.comments, line.substr(line.find('#') + 1));
        continue;
      }
      seen_statement_ = true;
      if (keyword == "v") {
        parse_vertex(rest);
      } else if (keyword == "vt") {
        parse_texture_coordinate(rest);
      } else if (keyword == "mtllib") {
        if (const std::string_view text = statement_text(rest); !text.empty()) {
          polygons_.material_libraries.emplace_back(text);
        }
      } else if (keyword == "usemtl") {
        if (const std::string_view name = statement_text(rest); !name.empty()) {
          polygons_.material_runs.emplace_back(polygons_.num_polygons(), std::string(name));
        }
      } else if (keyword == "f" || keyword == "fo") {
        parse_face(rest);
      } else if (is_skipped_element(keyword)) {
        ++skipped_elements_;
      } else if (!is_ignored_statement(keyword)) {
        if (unknown_statements_++ == 0) first_unknown_ = std::string(keyword);
      }
    }
    check_indices();
    check_texture(report);
    if (!colors_dropped_.empty()) {
      report.notes.push_back("vertex colours ignored (" + colors_dropped_ + ")");
    }
    note_skipped(report, skipped_elements_, "point, line or curve elements (p, l, curv, surf)");
    if (unknown_statements_ > 0) {
      report.notes.push_back("ignored " + std::to_string(unknown_statements_) +
                             " lines with unknown statements, the first being " +
                             quoted(first_unknown_));
    }
    return assemble_mesh(polygons_, std::move(report));
  }

 private:
  void parse_vertex(std::string_view rest) {
    double xyz[3];
    for (double& value : xyz) {
      const std::string_view token = next_token(rest);
      if (token.empty()) fail_file("a vertex has fewer than 3 coordinates" + at_line(line_));
      if (const char* problem = parse_coordinate(token, value)) {
        fail_file(number_problem(token, problem) + at_line(line_));
      }
    }
    // Optional w, or r g b [a] vertex colours: checked to be numbers; r g b
    // kept when every vertex has exactly them (then written again).
    int extra = 0;
    double values[4];
    for (std::string_view token = next_token(rest); !token.empty(); token = next_token(rest)) {
      if (token[0] == '#') break;
      if (extra == 4) fail_file("a vertex has more than 7 values" + at_line(line_));
      if (const char* problem = parse_coordinate(token, values[extra])) {
        fail_file(number_problem(token, problem) + at_line(line_));
      }
      ++extra;
    }
    if (extra == 3 && polygons_.all_colored && colors_dropped_.empty() &&
        !(std::isfinite(values[0]) && std::isfinite(values[1]) && std::isfinite(values[2]))) {
      // Dropped with a note, as a malformed texture coordinate is: no NaN or
      // inf reaches an output file. (A non-finite position is kept, for the
      // mesh check to name the vertex.)
      colors_dropped_ = "vertex " + std::to_string(polygons_.num_vertices()) + " has a colour value that is not a "
                        "finite number" + at_line(line_);
    }
    if (extra == 3 && polygons_.all_colored && colors_dropped_.empty()) {
      polygons_.colors.insert(polygons_.colors.end(), values, values + 3);
    } else {
      polygons_.all_colored = false;
      polygons_.colors.clear();
    }
    polygons_.add_vertex(xyz[0], xyz[1], xyz[2]);
  }

  // A statement's text after its keyword, blanks and a trailing comment cut.
  static std::string_view statement_text(std::string_view rest) {
    const std::size_t comment = rest.find('#');
    if (comment != std::string_view::npos) rest = rest.substr(0, comment);
    const std::size_t first = rest.find_first_not_of(" \t\r");
    if (first == std::string_view::npos) return {};
    return rest.substr(first, rest.find_last_not_of(" \t\r") - first + 1);
  }

  // "vt u [v [w]]": u and v kept (v defaults to 0), w unused. A malformed
  // one drops the texture, not the mesh.
  void parse_texture_coordinate(std::string_view rest) {
    double uv[2] = {0.0, 0.0};
    int count = 0;
    for (std::string_view token = next_token(rest); !token.empty(); token = next_token(rest)) {
      if (token[0] == '#') break;
      double value;
      if (parse_coordinate(token, value) != nullptr || !std::isfinite(value) || count == 3) {
        drop_texture("the texture coordinate" + at_line(line_) + " is malformed");
        return;
      }
      if (count < 2) uv[count] = value;
      ++count;
    }
    if (count == 0) drop_texture("the texture coordinate" + at_line(line_) + " has no value");
    polygons_.uv.push_back(uv[0]);
    polygons_.uv.push_back(uv[1]);
  }

  void drop_texture(const std::string& why) {
    if (texture_dropped_.empty()) texture_dropped_ = why;
  }

  // Every corner has a texture coordinate in range, or the texture goes.
  void check_texture(ReadReport& report) {
    const long long count = static_cast<long long>(polygons_.uv.size() / 2);
    if (texture_dropped_.empty() && corners_with_uv_ > 0 && corners_with_uv_ < polygons_.corners.size()) {
      drop_texture("some face corners have none");
    }
    for (std::size_t c = 0; texture_dropped_.empty() && c < polygons_.corner_uv.size(); ++c) {
      if (polygons_.corner_uv[c] < 0 || polygons_.corner_uv[c] >= count) {
        drop_texture("a face corner names texture coordinate " + std::to_string(polygons_.corner_uv[c] + 1) +
                     ", but the file has " + std::to_string(count));
      }
    }
    if (!texture_dropped_.empty()) {
      if (corners_with_uv_ > 0 || count > 0) {
        report.notes.push_back("texture coordinates ignored (" + texture_dropped_ + ")");
      }
      polygons_.uv.clear();
      polygons_.corner_uv.clear();
    } else if (corners_with_uv_ == 0) {
      polygons_.corner_uv.clear();
    }
  }

  // "v", "v/vt", "v//vn" or "v/vt/vn": returns the vertex index as written,
  // and the texture coordinate's in `uv` (0 when the corner has none).
  long long parse_corner(std::string_view token, long long& uv_index) const {
    const std::size_t slash = token.find('/');
    const std::string_view vertex = token.substr(0, slash);
    long long index = 0;
    if (!parse_integer(vertex, index)) {
      fail_file("face " + std::to_string(face_number()) + " has a malformed corner " +
                quoted(token) + at_line(line_));
    }
    if (slash != std::string_view::npos) {
      std::string_view attributes = token.substr(slash + 1);  // "vt", "vt/vn" or "/vn"
      const std::size_t second = attributes.find('/');
      const std::string_view uv = attributes.substr(0, second);
      const std::string_view normal =
          second == std::string_view::npos ? std::string_view() : attributes.substr(second + 1);
      long long unused;
      uv_index = 0;
      const bool uv_ok = uv.empty() ? second != std::string_view::npos : parse_integer(uv, uv_index);
      const bool normal_ok = second == std::string_view::npos || parse_integer(normal, unused);
      if (!uv_ok || !normal_ok) {
        fail_file("face " + std::to_string(face_number()) + " has a malformed corner " +
                  quoted(token) + at_line(line_));
      }
    }
    return index;
  }

  void parse_face(std::string_view rest) {
    const long long vertices_so_far = polygons_.num_vertices();
    const long long uv_so_far = static_cast<long long>(polygons_.uv.size() / 2);
    int corners = 0;
    for (std::string_view token = next_token(rest); !token.empty(); token = next_token(rest)) {
      if (token[0] == '#') break;
      long long uv_index = 0;
      const long long index = parse_corner(token, uv_index);
      if (uv_index != 0) {
        ++corners_with_uv_;
        // 1-based, or negative: relative to the coordinates read so far.
        const long long zero_based_uv = uv_index > 0 ? uv_index - 1 : uv_so_far + uv_index;
        polygons_.corner_uv.resize(polygons_.corners.size(), -1);
        polygons_.corner_uv.push_back(
            static_cast<int>(std::clamp<long long>(zero_based_uv, -1, std::numeric_limits<int>::max())));
      }
      long long zero_based = 0;
      if (index > 0) {
        // Checked against the final vertex count in check_indices(): OBJ lets a
        // face come before the vertices it uses.
        if (index > INT_MAX) {
          fail_file("face " + std::to_string(face_number()) + " references vertex " +
                    std::to_string(index) + ", more than any file can hold" + at_line(line_));
        }
        zero_based = index - 1;
      } else if (index < 0) {
        zero_based = vertices_so_far + index;  // -1 is the vertex defined last
        if (zero_based < 0) {
          zero_based = invalid_corner("uses relative index " + std::to_string(index) + ", but only " +
                                      std::to_string(vertices_so_far) + " vertices precede it");
        }
      } else {
        zero_based = invalid_corner("references vertex 0, but OBJ vertex numbers start at 1");
      }
      polygons_.corners.push_back(static_cast<int>(zero_based));
      ++corners;
    }
    if (corners < 3) {
      fail_file("face " + std::to_string(face_number()) + " has " + std::to_string(corners) +
                " corners; a face needs at least 3" + at_line(line_));
    }
    polygons_.end_polygon();
    face_lines_.push_back(line_);
  }

  // Errors are reported for the first bad face in file order, and whether a
  // positive index is in range is known only at the end: so a corner that is
  // wrong already when read is remembered, and marked -1, until then.
  int invalid_corner(const std::string& problem) {
    if (first_invalid_face_ < 0) {
      first_invalid_face_ = polygons_.num_polygons();
      first_invalid_message_ = "face " + std::to_string(face_number()) + " " + problem + at_line(line_);
    }
    return -1;
  }

  void check_indices() const {
    const int num_vertices = polygons_.num_vertices();
    for (int face = 0; face < polygons_.num_polygons(); ++face) {
      if (face == first_invalid_face_) fail_file(first_invalid_message_);
      for (int c = polygons_.offsets[face]; c < polygons_.offsets[face + 1]; ++c) {
        if (polygons_.corners[c] < num_vertices) continue;
        fail_file("face " + std::to_string(face + 1) + " references vertex " +
                  std::to_string(polygons_.corners[c] + 1) + ", but the file has " +
                  std::to_string(num_vertices) + " vertices" + at_line(face_lines_[face]));
      }
    }
  }

  int face_number() const { return polygons_.num_polygons() + 1; }  // 1-based, of the face being read

  PolygonMesh polygons_;
  bool seen_statement_ = false;  // past the leading comment block
  std::size_t corners_with_uv_ = 0;
  std::string texture_dropped_;  // why the texture coordinates are not kept ("" while they are)
  std::string colors_dropped_;   // why the vertex colours are not kept, when one was not finite
  std::vector<int> face_lines_;
  int line_ = 0;
  int skipped_elements_ = 0;
  int unknown_statements_ = 0;
  std::string first_unknown_;
  int first_invalid_face_ = -1;  // 0-based
  std::string first_invalid_message_;
};

}  // namespace

ReadResult read_obj(const char* data, std::size_t size) {
  ReadReport report;
  std::string decoded;
  const std::string_view text = decode_text(data, size, decoded, report);
  reject_binary_text(text, "OBJ");
  return ObjParser().parse(text, std::move(report));
}

namespace {

void append_uv_rows(std::string& out, const Eigen::MatrixX2d& uv) {
  for (Eigen::Index i = 0; i < uv.rows(); ++i) {
    out += "vt ";
    append_number(out, uv(i, 0));
    out += ' ';
    append_number(out, uv(i, 1));
    out += '\n';
  }
}

// The faces, 1-based: "f v/vt v/vt v/vt" with `uv_faces`, else "f v v v";
// each material run's "usemtl NAME" before its first triangle.
void append_faces(std::string& out, const Triangles& F, const Triangles* uv_faces,
                  const std::vector<std::pair<int, std::string>>& runs) {
  std::size_t run = 0;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    for (; run < runs.size() && runs[run].first <= f; ++run) out += "usemtl " + runs[run].second + '\n';
    out += 'f';
    for (int k = 0; k < 3; ++k) {
      out += ' ';
      append_number(out, static_cast<long long>(F(f, k)) + 1);
      if (uv_faces) {
        out += '/';
        append_number(out, static_cast<long long>((*uv_faces)(f, k)) + 1);
      }
    }
    out += '\n';
  }
}

}  // namespace

std::string write_obj(const Mesh& mesh, const SurfaceAttributes* attributes) {
  const CornerTexture* texture = attributes ? &attributes->texture : nullptr;
  const bool textured = texture != nullptr && !texture->empty();
  if (textured) {
    if (texture->faces.rows() != mesh.F.rows()) {
      fail(ErrorCode::BadParameter, "texture coordinates for " + std::to_string(texture->faces.rows()) +
                                        " triangles, but the mesh has " + std::to_string(mesh.F.rows()));
    }
    for (Eigen::Index f = 0; f < texture->faces.rows(); ++f) {
      for (int k = 0; k < 3; ++k) {
        const int index = texture->faces(f, k);
        if (index < 0 || index >= texture->uv.rows()) {
          fail(ErrorCode::BadParameter, "triangle " + std::to_string(f) + " names texture coordinate " +
                                            std::to_string(index) + ", but there are " +
                                            std::to_string(texture->uv.rows()));
        }
      }
    }
  }
  static const ObjMaterials kNone;
  const ObjMaterials& materials = attributes ? attributes->materials : kNone;
  std::string out;
  append_comment_lines(out, attributes, "# ");
  out.reserve(static_cast<std::size_t>(mesh.V.rows()) * 40 + static_cast<std::size_t>(mesh.F.rows()) * 24);
  for (const std::string& library : materials.libraries) out += "mtllib " + library + '\n';
  if (attributes && attributes->vertex_colors.rows() == mesh.V.rows() && mesh.V.rows() > 0) {
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {  // "v x y z r g b"
      out += 'v';
      for (int k = 0; k < 6; ++k) {
        out += ' ';
        append_number(out, k < 3 ? mesh.V(i, k) : attributes->vertex_colors(i, k - 3));
      }
      out += '\n';
    }
  } else {
    append_position_rows(out, mesh.V, "v ");
  }
  if (textured) append_uv_rows(out, texture->uv);
  append_faces(out, mesh.F, textured ? &texture->faces : nullptr, materials.runs);
  return out;
}

}  // namespace io

std::string write_obj_with_uv(const Mesh& mesh, const Eigen::MatrixX2d& uv) {
  if (uv.rows() != mesh.V.rows()) {
    fail(ErrorCode::BadParameter, "write_obj_with_uv: " + std::to_string(uv.rows()) +
                                      " uv rows for " + std::to_string(mesh.V.rows()) +
                                      " vertices; they must match");
  }
  io::require_valid_indices(mesh);
  std::string out = "# written by anisoform: positions and their flattened uv\n";
  io::append_position_rows(out, mesh.V, "v ");
  io::append_uv_rows(out, uv);
  io::append_faces(out, mesh.F, &mesh.F, {});
  return out;
}

}  // namespace aniso
