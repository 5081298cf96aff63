// Reading and writing triangle meshes: OBJ, OFF, PLY (ASCII and binary, either
// byte order), STL (ASCII and binary).
//
// Readers are strict and name what is wrong with its place in the file: a
// malformed number, a face that references a vertex that does not exist, a
// truncated binary body, an empty file. Polygon faces (quads, n-gons, concave
// ones too) are triangulated; STL triangle soups are welded by exact position.
// Non-finite coordinates are read as they are (check_mesh reports them).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "anisoform/mesh.h"

namespace aniso {

enum class MeshFormat { Obj, Off, Ply, Stl };

// Format from a file name's extension (case-insensitive); throws
// Error(BadParameter) naming the extension when it is not one of ours.
MeshFormat format_from_path(const std::string& path);
const char* format_name(MeshFormat format);
// How messages about a mesh read from `format` number its elements, for
// formats whose own numbers differ: problems of the mesh count vertices and
// faces from 0 (ROBUSTNESS.md), an OBJ's 'f' lines from 1. A clause to add
// after such a message; empty for OFF and PLY (which count from 0 too) and
// STL (no numbers of its own).
std::string element_numbering_note(MeshFormat format);

// What the reader did to turn the file into an indexed triangle mesh.
struct ReadReport {
  int polygons_triangulated = 0;   // faces with more than 3 corners
  int vertices_welded = 0;         // vertices merged away by welding (STL)
  int elements_skipped = 0;        // OBJ lines/points and other non-surface elements
  std::vector<std::string> notes;  // plain-words notes for the user
};

// A surface's texture coordinates, per triangle corner: an OBJ's `vt` list
// and, for every triangle of the mesh (the same rows as its F), which of them
// each corner uses. Corners, not vertices: a UV seam gives one vertex two.
// Empty when the file has none (or not for every face). The shape edits
// positions only, so an OBJ written with them keeps the file's texture
// mapping.
struct CornerTexture {
  Eigen::MatrixX2d uv;  // the coordinates, as in the file
  Triangles faces;      // #F by 3 rows of uv indices, or 0 rows: none
  bool empty() const { return faces.rows() == 0; }
};

// A PLY's vertex properties besides x, y, z (colours, quality, normals...),
// by name and declared type, one value per vertex. An edit moves positions
// only, so a PLY written with them carries them again; normals (nx, ny, nz)
// are computed again for the shape written.
struct VertexProperty {
  std::string name;
  std::string type;            // the PLY type as declared: "uchar", "float", ...
  std::vector<double> values;  // one per vertex (every PLY type is exact as a double)
};
using VertexProperties = std::vector<VertexProperty>;

// An OBJ's materials: its `mtllib` statements, and where each `usemtl`
// starts (the first triangle it applies to, in the mesh's F order).
struct ObjMaterials {
  std::vector<std::string> libraries;             // each mtllib statement's text, in order
  std::vector<std::pair<int, std::string>> runs;  // (first triangle, material name), ascending
  bool empty() const { return libraries.empty() && runs.empty(); }
};

// What a file carries besides positions and triangles, which an edit leaves
// as it is: written again in the same format (WriteOptions), so that a
// texture, a material or a scan's colours survive the edit.
struct SurfaceAttributes {
  CornerTexture texture;               // OBJ
  ObjMaterials materials;              // OBJ
  Eigen::MatrixX3d vertex_colors;      // OBJ: `v x y z r g b` on every vertex line (#V rows), or none
  VertexProperties vertex_properties;  // PLY
  // The file's header comments (attribution, licence...), in file order:
  // PLY `comment` and `obj_info` lines (their text after the keyword); the
  // whole-line `#` comments of an OBJ before its first statement and of an
  // OFF before its first vertex (comments further down describe the data,
  // e.g. "# 829 vertices", and would be stale after an edit). Kept as
  // keep_file_comment cleans them. Written into every format that has
  // comments (OBJ, OFF, PLY; in whichever the output is), after the line
  // saying anisoform wrote the file; binary STL's 80-byte header takes the
  // first when it fits, ASCII STL has only a solid name and takes none.
  std::vector<std::string> comments;
};

// At most this many comments are kept, each at most this many bytes (cut at
// a UTF-8 character boundary): a header is for attribution, not a payload.
constexpr std::size_t kMaxFileComments = 64;
constexpr std::size_t kMaxFileCommentBytes = 256;

// Adds `text` to `comments` as a header line can safely carry it: control
// characters (newlines, tabs, NUL, DEL...) become spaces, blanks at both
// ends go, long text is cut; nothing is added when it is empty, when
// kMaxFileComments are kept already, or when it is the line anisoform's own
// writers put first ("written by anisoform..."), which each output writes
// afresh (read and written again, it would pile up).
void keep_file_comment(std::vector<std::string>& comments, std::string_view text);

// The vertex colours in [0, 1], #V rows, whichever format carried them: an
// OBJ's `v x y z r g b`, or a PLY's red, green and blue properties (integer
// types scaled by their largest value); 0 rows when there are none.
Eigen::MatrixX3d vertex_colors(const SurfaceAttributes& attributes, int vertex_count);

// `attributes` as a file of `format` can carry them: the vertex colours of
// one format given to another that has a place for them (OBJ `v x y z r g
// b`; PLY red, green, blue as uchar when it has no properties of its own).
SurfaceAttributes attributes_for_format(const SurfaceAttributes& attributes, MeshFormat format, int vertex_count);

struct ReadResult {
  Mesh mesh;
  ReadReport report;
  SurfaceAttributes attributes;
};

// Reads from a file / from bytes in memory. Errors: Error(BadFile) with a
// message naming the file's problem, e.g.
//   "face 21 references vertex 840, but the file has 829 vertices (line 871)".
// Only regular files are read (read_regular_file: not a FIFO or /dev/zero),
// and a header never makes the reader allocate more than the bytes could
// hold: counts it declares beyond the file's (or buffer's) size are refused.
ReadResult read_mesh(const std::string& path);
ReadResult read_mesh_from_memory(const char* data, std::size_t size, MeshFormat format);

struct WriteOptions {
  bool binary = true;  // PLY and STL: binary (little endian) or ASCII
  // Written where the format has them: OBJ the texture (`vt`, `f v/vt`; its
  // faces must match the mesh's) and materials (`mtllib`, `usemtl`), PLY the
  // vertex properties (after x, y, z; one value per vertex each); OBJ, PLY and
  // OFF (as COFF) the vertex colours (attributes_for_format).
  const SurfaceAttributes* attributes = nullptr;
};

// Writes to a file (format from the extension; atomically, see
// write_file_atomically: a failed write leaves an existing file unchanged) /
// to bytes.
void write_mesh(const std::string& path, const Mesh& mesh, const WriteOptions& options = {});
std::string write_mesh_to_memory(const Mesh& mesh, MeshFormat format,
                                 const WriteOptions& options = {});

// OBJ with texture coordinates: 3D positions as `v`, uv (#V by 2) as `vt`,
// faces `f a/a b/b c/c`. Used for flattened patterns.
std::string write_obj_with_uv(const Mesh& mesh, const Eigen::MatrixX2d& uv);

}  // namespace aniso
