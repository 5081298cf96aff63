// Stanford PLY: reading ASCII and binary (either byte order) files with any
// element layout: the `vertex` element's x, y, z of any numeric type, the
// `face` element's `vertex_indices` (or `vertex_index`) list of any count and
// index types, and the vertex element's other scalar properties (colours,
// quality, normals: kept to be written again, mesh_io.h VertexProperties);
// every other property and element is skipped by its type.
// Writing: binary little endian (double coordinates, exact) or ASCII, with
// the kept vertex properties in their declared types.
#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>

#include <optional>

#include "anisoform/mesh_io.h"
#include "geometry/frames.h"
#include "io/io_common.h"

namespace aniso {
namespace io {

namespace {

// The most vertex properties besides x, y, z kept (in declaration order);
// more are read and dropped with a note. Each costs 8 bytes a vertex.
constexpr std::size_t kMaxKeptVertexProperties = 16;

enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };
enum class PlyEncoding { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::Float32;  // the item type, for a list
  std::string type_name = "float";  // as declared ("uchar", "uint8", ...)
  bool is_list = false;
  PlyType count_type = PlyType::UInt8;
};

struct PlyElement {
  std::string name;
  long long count = 0;
  std::vector<PlyProperty> properties;
};

struct PlyHeader {
  PlyEncoding encoding = PlyEncoding::Ascii;
  std::vector<PlyElement> elements;
  std::vector<std::string> comments;  // `comment` and `obj_info` lines' text, kept
  std::size_t body_offset = 0;  // first byte after "end_header\n"
  int body_first_line = 1;      // the file's line number there
};

bool is_integer_type(PlyType type) { return type != PlyType::Float32 && type != PlyType::Float64; }

std::size_t size_of(PlyType type) {
  switch (type) {
    case PlyType::Int8: case PlyType::UInt8: return 1;
    case PlyType::Int16: case PlyType::UInt16: return 2;
    case PlyType::Int32: case PlyType::UInt32: case PlyType::Float32: return 4;
    case PlyType::Float64: return 8;
  }
  return 1;
}

PlyType parse_type(std::string_view token, int line) {
  struct Named { std::string_view name; PlyType type; };
  static constexpr Named kTypes[] = {
      {"char", PlyType::Int8},     {"int8", PlyType::Int8},       {"uchar", PlyType::UInt8},
      {"uint8", PlyType::UInt8},   {"short", PlyType::Int16},     {"int16", PlyType::Int16},
      {"ushort", PlyType::UInt16}, {"uint16", PlyType::UInt16},   {"int", PlyType::Int32},
      {"int32", PlyType::Int32},   {"uint", PlyType::UInt32},     {"uint32", PlyType::UInt32},
      {"float", PlyType::Float32}, {"float32", PlyType::Float32}, {"double", PlyType::Float64},
      {"float64", PlyType::Float64}};
  for (const Named& named : kTypes) {
    if (token == named.name) return named.type;
  }
  fail_file("unknown PLY property type " + quoted(token) + " (header line " + std::to_string(line) + ")");
}

bool is_index_list(const PlyProperty& property) {
  return property.is_list && (property.name == "vertex_indices" || property.name == "vertex_index");
}

PlyHeader parse_header(const char* data, std::size_t size) {
  const std::string_view text(data, size);
  LineReader lines(text);
  std::string_view line;
  if (!lines.next(line) || line != "ply") fail_file("not a PLY file: it does not start with 'ply'");

  PlyHeader header;
  bool has_format = false;
  while (true) {
    if (!lines.next(line)) fail_file("the PLY header has no 'end_header' line");
    const int number = lines.line_number();
    const std::string at = " (header line " + std::to_string(number) + ")";
    std::string_view rest = line;
    const std::string_view keyword = next_token(rest);
    if (keyword == "end_header") break;
    if (keyword == "comment" || keyword == "obj_info") {
      keep_file_comment(header.comments, rest);
      continue;
    }
    if (keyword.empty()) continue;
    if (keyword == "format") {
      const std::string_view encoding = next_token(rest);
      if (encoding == "ascii") header.encoding = PlyEncoding::Ascii;
      else if (encoding == "binary_little_endian") header.encoding = PlyEncoding::BinaryLittleEndian;
      else if (encoding == "binary_big_endian") header.encoding = PlyEncoding::BinaryBigEndian;
      else fail_file("unknown PLY format " + quoted(encoding) + at);
      has_format = true;
    } else if (keyword == "element") {
      PlyElement element;
      element.name = std::string(next_token(rest));
      const std::string_view count = next_token(rest);
      if (element.name.empty() || !parse_integer(count, element.count) || element.count < 0) {
        fail_file("malformed PLY element line " + quoted(line) + at);
      }
      header.elements.push_back(std::move(element));
    } else if (keyword == "property") {
      if (header.elements.empty()) fail_file("a PLY property comes before any element" + at);
      PlyProperty property;
      std::string_view type = next_token(rest);
      if (type == "list") {
        property.is_list = true;
        property.count_type = parse_type(next_token(rest), number);
        if (!is_integer_type(property.count_type)) fail_file("a PLY list count must have an integer type" + at);
        type = next_token(rest);
      }
      property.type = parse_type(type, number);
      property.type_name = std::string(type);
      property.name = std::string(next_token(rest));
      if (property.name.empty()) fail_file("a PLY property has no name" + at);
      if (is_index_list(property) && !is_integer_type(property.type)) {
        fail_file("PLY face indices must have an integer type" + at);
      }
      header.elements.back().properties.push_back(std::move(property));
    } else {
      fail_file("unknown PLY header line " + quoted(line) + at);
    }
  }
  if (!has_format) fail_file("the PLY header has no 'format' line");
  // By length, not by pointer: when the header is the whole file, the rest
  // is an empty view whose data() may be null (fuzz/regressions/ply_header_only_no_newline).
  header.body_offset = text.size() - lines.rest().size();
  header.body_first_line = lines.line_number() + 1;
  return header;
}

// Values from a binary body, converted from the stored type and byte order.
class BinaryValues {
 public:
  BinaryValues(const char* begin, const char* end, bool little_endian)
      : p_(begin), end_(end), little_endian_(little_endian) {}

  // false when the body ends before the value.
  bool read(PlyType type, double& value) {
    const std::size_t size = size_of(type);
    if (static_cast<std::size_t>(end_ - p_) < size) return false;
    switch (type) {
      case PlyType::Int8: value = load_scalar<std::int8_t>(p_, little_endian_); break;
      case PlyType::UInt8: value = load_scalar<std::uint8_t>(p_, little_endian_); break;
      case PlyType::Int16: value = load_scalar<std::int16_t>(p_, little_endian_); break;
      case PlyType::UInt16: value = load_scalar<std::uint16_t>(p_, little_endian_); break;
      case PlyType::Int32: value = load_scalar<std::int32_t>(p_, little_endian_); break;
      case PlyType::UInt32: value = load_scalar<std::uint32_t>(p_, little_endian_); break;
      case PlyType::Float32: value = load_scalar<float>(p_, little_endian_); break;
      case PlyType::Float64: value = load_scalar<double>(p_, little_endian_); break;
    }
    p_ += size;
    return true;
  }
  bool read_integer(PlyType type, long long& value) {
    double stored = 0;  // every integer type is exact in a double
    if (!read(type, stored)) return false;
    value = static_cast<long long>(stored);
    return true;
  }
  bool skip(PlyType type, long long count) {
    const long long bytes = count * static_cast<long long>(size_of(type));
    if (end_ - p_ < bytes) return false;
    p_ += bytes;
    return true;
  }
  std::string where() const { return ""; }  // a binary body has no lines

 private:
  const char* p_;
  const char* end_;
  bool little_endian_;
};

// Values from an ASCII body: blank- or newline-separated tokens (lines end
// as LineReader's do), with the file's line numbers from `first_line`.
class AsciiValues {
 public:
  AsciiValues(std::string_view body, int first_line) : rest_(body), line_(first_line) {}

  bool read(PlyType, double& value) {
    const std::string_view token = next();
    if (token.empty()) return false;
    if (const char* problem = parse_coordinate(token, value)) fail_file(number_problem(token, problem) + where());
    return true;
  }
  bool read_integer(PlyType, long long& value) {
    const std::string_view token = next();
    if (token.empty()) return false;
    if (!parse_integer(token, value)) fail_file(quoted(token) + " is not an integer" + where());
    return true;
  }
  bool skip(PlyType type, long long count) {
    double unused;
    for (long long i = 0; i < count; ++i) {
      if (!read(type, unused)) return false;
    }
    return true;
  }

 private:
  std::string_view next() {
    std::size_t i = 0;
    while (i < rest_.size() && (is_blank(rest_[i]) || rest_[i] == '\n')) {
      const bool lone_cr = rest_[i] == '\r' && (i + 1 == rest_.size() || rest_[i + 1] != '\n');
      if (rest_[i] == '\n' || lone_cr) ++line_;
      ++i;
    }
    std::size_t end = i;
    while (end < rest_.size() && !is_blank(rest_[end]) && rest_[end] != '\n') ++end;
    const std::string_view token = rest_.substr(i, end - i);
    rest_.remove_prefix(end);
    return token;
  }

 public:
  // Where the value last read is, for messages.
  std::string where() const { return at_line(line_); }

 private:
  std::string_view rest_;
  int line_;
};

template <class Values>
class PlyBodyReader {
 public:
  PlyBodyReader(Values& values, PolygonMesh& polygons, long long num_vertices)
      : values_(values), polygons_(polygons), num_vertices_(num_vertices) {}

  void read_vertices(const PlyElement& element) {
    int axis_of[3] = {-1, -1, -1};  // property index of x, y, z
    for (std::size_t p = 0; p < element.properties.size(); ++p) {
      const PlyProperty& property = element.properties[p];
      const int axis = property.name == "x" ? 0 : property.name == "y" ? 1 : property.name == "z" ? 2 : -1;
      if (axis >= 0 && !property.is_list) axis_of[axis] = static_cast<int>(p);
    }
    if (axis_of[0] < 0 || axis_of[1] < 0 || axis_of[2] < 0) {
      fail_file("the PLY vertex element lacks an x, y or z property");
    }
    // The other scalar properties: which column each goes to (-1: not kept).
    std::vector<int> column_of(element.properties.size(), -1);
    for (std::size_t p = 0; p < element.properties.size(); ++p) {
      const PlyProperty& property = element.properties[p];
      const bool axis = static_cast<int>(p) == axis_of[0] || static_cast<int>(p) == axis_of[1] ||
                        static_cast<int>(p) == axis_of[2];
      if (axis || property.is_list) continue;
      if (kept.size() == kMaxKeptVertexProperties) {
        ++dropped_properties;
        continue;
      }
      column_of[p] = static_cast<int>(kept.size());
      kept.push_back({property.name, property.type_name, {}});
      // The count is the header's, checked against the body's size already.
      kept.back().values.reserve(static_cast<std::size_t>(element.count));
    }
    // A kept property with a non-finite value is dropped (below): no NaN or
    // inf reaches an output file. Positions keep theirs, for the mesh check
    // to name the vertex.
    std::vector<std::string> non_finite(kept.size());
    for (long long v = 0; v < element.count; ++v) {
      double xyz[3] = {0, 0, 0};
      for (std::size_t p = 0; p < element.properties.size(); ++p) {
        const PlyProperty& property = element.properties[p];
        bool complete;
        if (property.is_list) {
          complete = skip_list(property, "vertex", v);
        } else {
          double value = 0;
          complete = values_.read(property.type, value);
          for (int axis = 0; axis < 3; ++axis) {
            if (axis_of[axis] == static_cast<int>(p)) xyz[axis] = value;
          }
          if (complete && column_of[p] >= 0) {
            kept[column_of[p]].values.push_back(value);
            if (!std::isfinite(value) && non_finite[column_of[p]].empty()) {
              std::string text;
              append_number(text, value);
              non_finite[column_of[p]] = "vertex " + std::to_string(v) + " has " + text + values_.where();
            }
          }
        }
        if (!complete) fail_file(truncated_message(v, element.count, "vertices"));
      }
      polygons_.add_vertex(xyz[0], xyz[1], xyz[2]);
    }
    VertexProperties finite;
    for (std::size_t c = 0; c < kept.size(); ++c) {
      if (non_finite[c].empty()) {
        finite.push_back(std::move(kept[c]));
      } else {
        notes.push_back("vertex property '" + kept[c].name + "' ignored (" + non_finite[c] +
                        ", not a finite number)");
      }
    }
    kept = std::move(finite);
  }

  void read_faces(const PlyElement& element) {
    const auto index_list = std::find_if(element.properties.begin(), element.properties.end(), is_index_list);
    if (index_list == element.properties.end()) {
      fail_file("the PLY face element has no 'vertex_indices' list");
    }
    for (long long f = 0; f < element.count; ++f) {
      for (const PlyProperty& property : element.properties) {
        bool complete;
        if (&property == &*index_list) {
          complete = read_polygon(property, f);
        } else if (property.is_list) {
          complete = skip_list(property, "face", f);
        } else {
          complete = values_.skip(property.type, 1);
        }
        if (!complete) fail_file(truncated_message(f, element.count, "faces"));
      }
    }
  }

  // Returns how many items were skipped.
  long long skip_element(const PlyElement& element) {
    if (element.properties.empty()) return element.count;  // nothing stored per item
    for (long long i = 0; i < element.count; ++i) {
      for (const PlyProperty& property : element.properties) {
        const bool complete = property.is_list ? skip_list(property, element.name.c_str(), i)
                                               : values_.skip(property.type, 1);
        if (!complete) fail_file(truncated_message(i, element.count, "'" + element.name + "' elements"));
      }
    }
    return element.count;
  }

 private:
  // `kind` and the 0-based `item` name the element in messages ("face 30"):
  // from 0, as PLY numbers the vertices its faces reference.
  static std::string name(const char* kind, long long item) {
    return std::string(kind) + " " + std::to_string(item);
  }

  bool read_list_count(const PlyProperty& property, const char* kind, long long item, long long& count) {
    if (!values_.read_integer(property.count_type, count)) return false;
    if (count < 0) {
      fail_file(name(kind, item) + " has a negative list length " + std::to_string(count) + values_.where());
    }
    return true;
  }

  bool skip_list(const PlyProperty& property, const char* kind, long long item) {
    long long count = 0;
    return read_list_count(property, kind, item, count) && values_.skip(property.type, count);
  }

  bool read_polygon(const PlyProperty& property, long long face) {
    long long corners = 0;
    if (!read_list_count(property, "face", face, corners)) return false;
    if (corners < 3) {
      fail_file(name("face", face) + " has " + std::to_string(corners) + " corners; a face needs at least 3" +
                values_.where());
    }
    for (long long c = 0; c < corners; ++c) {
      long long index = 0;
      if (!values_.read_integer(property.type, index)) return false;
      if (index < 0 || index >= num_vertices_) {
        fail_file(name("face", face) + " references vertex " + std::to_string(index) + ", but the file has " +
                  std::to_string(num_vertices_) + " vertices (PLY numbers vertices and faces from 0)" +
                  values_.where());
      }
      polygons_.corners.push_back(static_cast<int>(index));
    }
    polygons_.end_polygon();
    return true;
  }

  Values& values_;
  PolygonMesh& polygons_;
  long long num_vertices_;

 public:
  VertexProperties kept;       // the vertex element's other scalar properties
  int dropped_properties = 0;   // beyond kMaxKeptVertexProperties
  std::vector<std::string> notes;  // properties dropped for a non-finite value
};

template <class Values>
ReadResult read_body(Values& values, const PlyHeader& header, std::size_t body_bytes) {
  const PlyElement* vertices = nullptr;
  const PlyElement* faces = nullptr;
  for (const PlyElement& element : header.elements) {
    if (element.name == "vertex" && !vertices) vertices = &element;
    else if (element.name == "face" && !faces) faces = &element;
  }
  if (!vertices) fail_file("the PLY file has no 'vertex' element");
  if (vertices->count > INT_MAX) fail_file("the PLY file declares more vertices than we can hold");

  PolygonMesh polygons;
  // Counts come from the file: reserve no more than the body could hold.
  const long long most_items = static_cast<long long>(body_bytes / 2) + 1;
  polygons.xyz.reserve(3 * static_cast<std::size_t>(std::min(vertices->count, most_items)));
  if (faces) {
    const auto face_items = static_cast<std::size_t>(std::min(faces->count, most_items));
    polygons.offsets.reserve(face_items + 1);
    polygons.corners.reserve(3 * face_items);
  }

  ReadReport report;
  PlyBodyReader<Values> reader(values, polygons, vertices->count);
  for (const PlyElement& element : header.elements) {
    if (&element == vertices) {
      reader.read_vertices(element);
    } else if (&element == faces) {
      reader.read_faces(element);
    } else {
      const long long skipped = reader.skip_element(element);
      note_skipped(report, static_cast<int>(std::min<long long>(skipped, INT_MAX)),
                   "'" + element.name + "' elements");
    }
  }
  for (std::string& note : reader.notes) report.notes.push_back(std::move(note));
  if (reader.dropped_properties > 0) {
    report.notes.push_back("kept the first " + std::to_string(kMaxKeptVertexProperties) +
                           " vertex properties besides x, y, z; dropped " +
                           std::to_string(reader.dropped_properties) + " more");
  }
  ReadResult result = assemble_mesh(polygons, std::move(report));
  result.attributes.vertex_properties = std::move(reader.kept);
  result.attributes.comments = header.comments;
  return result;
}

void append_header(std::string& out, const Mesh& mesh, const char* format, const char* coordinate_type,
                   const VertexProperties& properties, const SurfaceAttributes* attributes) {
  out += "ply\nformat ";
  out += format;
  out += " 1.0\n";
  append_comment_lines(out, attributes, "comment ");
  out += "element vertex ";
  out += std::to_string(mesh.V.rows());
  for (const char* axis : {"x", "y", "z"}) {
    out += "\nproperty ";
    out += coordinate_type;
    out += ' ';
    out += axis;
  }
  for (const VertexProperty& property : properties) {
    out += "\nproperty " + property.type + ' ' + property.name;
  }
  out += "\nelement face ";
  out += std::to_string(mesh.F.rows());
  out += "\nproperty list uchar int vertex_indices\nend_header\n";
}

long long saturating_add(long long a, long long b) { return a > LLONG_MAX - b ? LLONG_MAX : a + b; }
long long saturating_multiply(long long a, long long b) {
  return b != 0 && a > LLONG_MAX / b ? LLONG_MAX : a * b;
}

// The element counts are the header's promise: refuse those the body cannot
// hold before any is read. Binary: an item takes its scalar properties' sizes
// and each list's count (a list may be empty). ASCII: an item is at least one
// token per property.
void check_counts_against_body(const PlyHeader& header, std::size_t body_bytes) {
  long long needed = 0;
  long long text_tokens = 0;
  std::string declared = "element counts";
  for (const PlyElement& element : header.elements) {
    long long item_bytes = 0;
    for (const PlyProperty& property : element.properties) {
      item_bytes += static_cast<long long>(size_of(property.is_list ? property.count_type : property.type));
    }
    needed = saturating_add(needed, saturating_multiply(element.count, item_bytes));
    text_tokens = saturating_add(
        text_tokens, saturating_multiply(element.count, static_cast<long long>(element.properties.size())));
    declared += (&element == &header.elements.front() ? " " : ", ") + element.name + " " +
                std::to_string(element.count);
  }
  if (header.encoding == PlyEncoding::Ascii) needed = text_bytes_for(text_tokens);
  require_declared_bytes(needed, declared, body_bytes);
}

}  // namespace

ReadResult read_ply(const char* data, std::size_t size) {
  const PlyHeader header = parse_header(data, size);
  const char* body = data + header.body_offset;
  const std::size_t body_bytes = size - header.body_offset;
  check_counts_against_body(header, body_bytes);
  if (header.encoding == PlyEncoding::Ascii) {
    AsciiValues values(std::string_view(body, body_bytes), header.body_first_line);
    return read_body(values, header, body_bytes);
  }
  BinaryValues values(body, body + body_bytes, header.encoding == PlyEncoding::BinaryLittleEndian);
  return read_body(values, header, body_bytes);
}

namespace {

// The properties to write: given ones that fit the mesh (one value per
// vertex, a PLY type), with normals (nx, ny, nz) those of the shape written.
VertexProperties properties_to_write(const Mesh& mesh, const VertexProperties* given) {
  if (given == nullptr || given->empty()) return {};
  VertexProperties out = *given;
  std::optional<Positions> normals;
  for (VertexProperty& property : out) {
    if (property.values.size() != static_cast<std::size_t>(mesh.V.rows())) {
      fail(ErrorCode::BadParameter, "vertex property '" + property.name + "' has " +
                                        std::to_string(property.values.size()) + " values for " +
                                        std::to_string(mesh.V.rows()) + " vertices");
    }
    parse_type(property.type, 0);  // a PLY type, or Error naming it
    const int axis = property.name == "nx" ? 0 : property.name == "ny" ? 1 : property.name == "nz" ? 2 : -1;
    if (axis < 0) continue;
    if (!normals) normals = vertex_normals(mesh);
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) property.values[i] = (*normals)(i, axis);
  }
  return out;
}

void append_binary_value(std::string& out, PlyType type, double value) {
  switch (type) {
    case PlyType::Int8: append_little_endian<std::int8_t>(out, static_cast<std::int8_t>(value)); return;
    case PlyType::UInt8: append_little_endian<std::uint8_t>(out, static_cast<std::uint8_t>(value)); return;
    case PlyType::Int16: append_little_endian<std::int16_t>(out, static_cast<std::int16_t>(value)); return;
    case PlyType::UInt16: append_little_endian<std::uint16_t>(out, static_cast<std::uint16_t>(value)); return;
    case PlyType::Int32: append_little_endian<std::int32_t>(out, static_cast<std::int32_t>(value)); return;
    case PlyType::UInt32: append_little_endian<std::uint32_t>(out, static_cast<std::uint32_t>(value)); return;
    case PlyType::Float32: append_little_endian<float>(out, static_cast<float>(value)); return;
    case PlyType::Float64: append_little_endian<double>(out, value); return;
  }
}

}  // namespace

std::string write_ply(const Mesh& mesh, bool binary, const SurfaceAttributes* attributes) {
  const VertexProperties properties =
      properties_to_write(mesh, attributes ? &attributes->vertex_properties : nullptr);
  std::vector<PlyType> types;
  for (const VertexProperty& property : properties) types.push_back(parse_type(property.type, 0));
  std::string out;
  if (binary) {
    append_header(out, mesh, "binary_little_endian", "double", properties, attributes);
    out.reserve(out.size() + static_cast<std::size_t>(mesh.V.rows()) * (24 + 8 * properties.size()) +
                static_cast<std::size_t>(mesh.F.rows()) * 13);
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
      for (int k = 0; k < 3; ++k) append_little_endian<double>(out, mesh.V(i, k));
      for (std::size_t p = 0; p < properties.size(); ++p) append_binary_value(out, types[p], properties[p].values[i]);
    }
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
      append_little_endian<std::uint8_t>(out, 3);
      for (int k = 0; k < 3; ++k) append_little_endian<std::int32_t>(out, mesh.F(f, k));
    }
    return out;
  }
  append_header(out, mesh, "ascii", "double", properties, attributes);
  if (properties.empty()) {
    append_position_rows(out, mesh.V, "");
  } else {
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
      for (int k = 0; k < 3; ++k) {
        if (k > 0) out += ' ';
        append_number(out, mesh.V(i, k));
      }
      for (const VertexProperty& property : properties) {
        out += ' ';
        append_number(out, property.values[i]);
      }
      out += '\n';
    }
  }
  append_triangle_rows(out, mesh.F, "3", 0);
  return out;
}

}  // namespace io
}  // namespace aniso
