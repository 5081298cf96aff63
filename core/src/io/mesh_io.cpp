// Format dispatch for reading and writing meshes, and the helpers the
// per-format readers (io_obj/io_off/io_ply/io_stl.cpp) share.
#include "anisoform/mesh_io.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <vector>

#include "anisoform/error.h"
#include "anisoform/file_io.h"
#include "anisoform/mesh_check.h"
#include "io/io_common.h"

namespace aniso {

namespace {

std::string lower_extension(const std::string& path) {
  const std::size_t slash = path.find_last_of("/\\");
  const std::size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return {};
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

// "an OBJ", "a PLY": the article as the format's name is read aloud.
const char* mesh_format_article(MeshFormat format) {
  return format == MeshFormat::Ply ? "a " : "an ";
}

}  // namespace

MeshFormat format_from_path(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == "obj") return MeshFormat::Obj;
  if (ext == "off") return MeshFormat::Off;
  if (ext == "ply") return MeshFormat::Ply;
  if (ext == "stl") return MeshFormat::Stl;
  if (ext == "glb" || ext == "gltf") {
    fail(ErrorCode::BadParameter,
         "'" + path + "': GLB/glTF files are read by the browser app only (three.js); "
         "the core reads .obj, .off, .ply and .stl");
  }
  if (ext.empty()) {
    fail(ErrorCode::BadParameter, "'" + path +
                                      "' has no file extension; expected .obj, .off, .ply or .stl");
  }
  fail(ErrorCode::BadParameter, "unknown mesh file extension '." + ext + "' of '" + path +
                                    "'; expected .obj, .off, .ply or .stl");
}

const char* format_name(MeshFormat format) {
  switch (format) {
    case MeshFormat::Obj: return "OBJ";
    case MeshFormat::Off: return "OFF";
    case MeshFormat::Ply: return "PLY";
    case MeshFormat::Stl: return "STL";
  }
  return "unknown";
}

std::string element_numbering_note(MeshFormat format) {
  if (format != MeshFormat::Obj) return {};
  return "vertices and faces are counted from 0 here: vertex 0 is the file's first 'v' line, face 0 its first triangle";
}

ReadResult read_mesh_from_memory(const char* data, std::size_t size, MeshFormat format) {
  if (size == 0) io::fail_file(std::string("file is empty (0 bytes): not ") +
                               mesh_format_article(format) + format_name(format) + " mesh");
  switch (format) {
    case MeshFormat::Obj: return io::read_obj(data, size);
    case MeshFormat::Off: return io::read_off(data, size);
    case MeshFormat::Ply: return io::read_ply(data, size);
    case MeshFormat::Stl: return io::read_stl(data, size);
  }
  fail(ErrorCode::BadParameter, "unknown mesh format");
}

ReadResult read_mesh(const std::string& path) {
  const MeshFormat format = format_from_path(path);
  const std::string data = read_regular_file(path);
  try {
    return read_mesh_from_memory(data.data(), data.size(), format);
  } catch (const Error& error) {
    // Name the file: the parsers only know bytes.
    throw Error(error.code(), "'" + path + "': " + error.what());
  }
}

std::string write_mesh_to_memory(const Mesh& mesh, MeshFormat format, const WriteOptions& options) {
  io::require_valid_indices(mesh);
  const SurfaceAttributes attributes =
      options.attributes ? attributes_for_format(*options.attributes, format, static_cast<int>(mesh.V.rows()))
                         : SurfaceAttributes{};
  switch (format) {
    case MeshFormat::Obj: return io::write_obj(mesh, &attributes);
    case MeshFormat::Off: return io::write_off(mesh, &attributes);
    case MeshFormat::Ply: return io::write_ply(mesh, options.binary, &attributes);
    case MeshFormat::Stl: return io::write_stl(mesh, options.binary, &attributes);
  }
  fail(ErrorCode::BadParameter, "unknown mesh format");
}

void write_mesh(const std::string& path, const Mesh& mesh, const WriteOptions& options) {
  write_file_atomically(path, write_mesh_to_memory(mesh, format_from_path(path), options));
}

// ------------------------------------------------------------------------
// Helpers shared by the format readers and writers (declared in io_common.h).

namespace io {

std::string quoted(std::string_view token) {
  constexpr std::size_t kMaxShown = 40;
  std::string out = "'";
  for (std::size_t i = 0; i < token.size() && i < kMaxShown; ++i) {
    const unsigned char c = static_cast<unsigned char>(token[i]);
    out += (c >= 0x20 && c < 0x7f) ? static_cast<char>(c) : '?';
  }
  if (token.size() > kMaxShown) out += "...";
  return out + "'";
}

void append_number(std::string& out, double value) {
  char buffer[32];
#if defined(__cpp_lib_to_chars)
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
#else
  // max_digits10 significant digits always read back to the same double.
  const int length = std::snprintf(buffer, sizeof buffer, "%.17g", value);
  out.append(buffer, static_cast<std::size_t>(length));
#endif
}

void append_position_rows(std::string& out, const Positions& V, const char* prefix) {
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    out += prefix;
    append_number(out, V(i, 0));
    out += ' ';
    append_number(out, V(i, 1));
    out += ' ';
    append_number(out, V(i, 2));
    out += '\n';
  }
}

void append_triangle_rows(std::string& out, const Triangles& F, const char* prefix, long long index_base) {
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    out += prefix;
    for (int k = 0; k < 3; ++k) {
      out += ' ';
      append_number(out, static_cast<long long>(F(f, k)) + index_base);
    }
    out += '\n';
  }
}

namespace {

void append_utf8(std::string& out, std::uint32_t code_point) {
  if (code_point < 0x80) {
    out += static_cast<char>(code_point);
  } else if (code_point < 0x800) {
    out += static_cast<char>(0xC0 | (code_point >> 6));
    out += static_cast<char>(0x80 | (code_point & 0x3F));
  } else if (code_point < 0x10000) {
    out += static_cast<char>(0xE0 | (code_point >> 12));
    out += static_cast<char>(0x80 | ((code_point >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (code_point & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (code_point >> 18));
    out += static_cast<char>(0x80 | ((code_point >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((code_point >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (code_point & 0x3F));
  }
}

std::string decode_utf16(const unsigned char* bytes, std::size_t size, bool little_endian) {
  if (size % 2 != 0) fail_file("file is UTF-16 encoded but has an odd number of bytes (truncated?)");
  auto unit_at = [&](std::size_t i) -> std::uint32_t {
    return little_endian ? (bytes[i] | (bytes[i + 1] << 8)) : ((bytes[i] << 8) | bytes[i + 1]);
  };
  std::string out;
  out.reserve(size / 2);
  for (std::size_t i = 0; i < size; i += 2) {
    std::uint32_t unit = unit_at(i);
    const bool high_surrogate = unit >= 0xD800 && unit < 0xDC00;
    if (high_surrogate && i + 3 < size) {
      const std::uint32_t low = unit_at(i + 2);
      if (low >= 0xDC00 && low < 0xE000) {
        unit = 0x10000 + ((unit - 0xD800) << 10) + (low - 0xDC00);
        i += 2;
      }
    }
    // A lone surrogate can only be in a comment or a name: keep the text readable.
    if (unit >= 0xD800 && unit < 0xE000) unit = '?';
    append_utf8(out, unit);
  }
  return out;
}

}  // namespace

std::string_view decode_text(const char* data, std::size_t size, std::string& storage,
                             ReadReport& report) {
  const auto* bytes = reinterpret_cast<const unsigned char*>(data);
  if (size >= 3 && bytes[0] == 0xEF && bytes[1] == 0xBB && bytes[2] == 0xBF) {
    return std::string_view(data + 3, size - 3);
  }
  const bool utf16_le = size >= 2 && bytes[0] == 0xFF && bytes[1] == 0xFE;
  const bool utf16_be = size >= 2 && bytes[0] == 0xFE && bytes[1] == 0xFF;
  if (!utf16_le && !utf16_be) return std::string_view(data, size);
  storage = decode_utf16(bytes + 2, size - 2, utf16_le);
  report.notes.push_back(std::string("the file is UTF-16 (") +
                         (utf16_le ? "little" : "big") +
                         " endian) encoded text; it was decoded (UTF-8 is the usual encoding)");
  return storage;
}

void reject_binary_text(std::string_view text, const char* format) {
  const std::size_t nul = text.find('\0');
  if (nul == std::string_view::npos) return;
  const auto line = 1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(nul), '\n');
  fail_file(std::string("the file holds binary data (a NUL byte on line ") + std::to_string(line) +
            "): it is not a text " + format + " file");
}

void require_valid_indices(const Mesh& mesh) {
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int index = mesh.F(f, k);
      if (index >= 0 && index < mesh.V.rows()) continue;
      fail(ErrorCode::BadMesh, "cannot write the mesh: face " + std::to_string(f) +
                                   " references vertex " + std::to_string(index) + ", but the mesh has " +
                                   std::to_string(mesh.V.rows()) + " vertices");
    }
  }
}

void require_declared_bytes(long long needed, const std::string& declared, std::size_t bytes) {
  if (needed <= static_cast<long long>(bytes)) return;
  fail_file("the header declares " + declared + ", which need at least " + std::to_string(needed) +
            " bytes, but only " + std::to_string(bytes) + " bytes follow it: the file is truncated or its "
            "header is wrong");
}

void note_skipped(ReadReport& report, int count, const std::string& what) {
  if (count == 0) return;
  report.elements_skipped += count;
  report.notes.push_back("skipped " + std::to_string(count) + " " + what);
}

ReadResult assemble_mesh(const PolygonMesh& polygons, ReadReport report) {
  ReadResult result;
  const int num_vertices = polygons.num_vertices();
  result.mesh.V = Eigen::Map<const Positions>(polygons.xyz.data(), num_vertices, 3);

  const int num_polygons = polygons.num_polygons();
  long long num_triangles = 0;
  for (int p = 0; p < num_polygons; ++p) num_triangles += polygons.offsets[p + 1] - polygons.offsets[p] - 2;
  result.mesh.F.resize(static_cast<Eigen::Index>(num_triangles), 3);

  CornerTexture& texture = result.attributes.texture;
  const bool textured = !polygons.corner_uv.empty();
  if (textured) {
    texture.uv = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>>(
        polygons.uv.data(), static_cast<Eigen::Index>(polygons.uv.size() / 2), 2);
    texture.faces.resize(result.mesh.F.rows(), 3);
  }
  result.attributes.materials.libraries = polygons.material_libraries;
  result.attributes.comments = polygons.comments;
  if (polygons.all_colored && num_vertices > 0 && polygons.colors.size() == 3 * static_cast<std::size_t>(num_vertices)) {
    result.attributes.vertex_colors =
        Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(polygons.colors.data(), num_vertices, 3);
  }
  std::size_t next_run = 0;  // the next material run, by its first polygon
  Eigen::Index row = 0;
  std::vector<int> polygon;
  // A textured polygon's (vertex, corner) pairs, by vertex then corner: a
  // triangle corner finds its texture coordinate by binary search, not by a
  // scan of the polygon (a 100k-corner polygon took 9.3 s, 400k over 120 s).
  std::vector<std::pair<int, int>> corner_of_vertex;
  for (int p = 0; p < num_polygons; ++p) {
    const int begin = polygons.offsets[p];
    const int end = polygons.offsets[p + 1];
    // A usemtl before polygon p starts at its first triangle (the last of
    // several before the same polygon wins, as in the file).
    for (; next_run < polygons.material_runs.size() && polygons.material_runs[next_run].first <= p; ++next_run) {
      auto& runs = result.attributes.materials.runs;
      if (!runs.empty() && runs.back().first == static_cast<int>(row)) runs.pop_back();
      runs.emplace_back(static_cast<int>(row), polygons.material_runs[next_run].second);
    }
    if (end - begin == 3) {
      if (textured) {
        texture.faces.row(row) << polygons.corner_uv[begin], polygons.corner_uv[begin + 1],
            polygons.corner_uv[begin + 2];
      }
      result.mesh.F.row(row++) << polygons.corners[begin], polygons.corners[begin + 1],
          polygons.corners[begin + 2];
      continue;
    }
    polygon.assign(polygons.corners.begin() + begin, polygons.corners.begin() + end);
    if (textured) {
      corner_of_vertex.clear();
      for (int c = 0; c < end - begin; ++c) corner_of_vertex.emplace_back(polygon[c], c);
      std::sort(corner_of_vertex.begin(), corner_of_vertex.end());
    }
    for (const auto& triangle : triangulate_polygon(result.mesh.V, polygon)) {
      if (textured) {
        // The triangle's corners are the polygon's vertices: each takes the
        // texture coordinate of its (first) corner in the polygon.
        for (int k = 0; k < 3; ++k) {
          const int corner = std::lower_bound(corner_of_vertex.begin(), corner_of_vertex.end(),
                                              std::make_pair(triangle[k], 0))->second;
          texture.faces(row, k) = polygons.corner_uv[begin + corner];
        }
      }
      result.mesh.F.row(row++) << triangle[0], triangle[1], triangle[2];
    }
    ++report.polygons_triangulated;
  }
  if (report.polygons_triangulated > 0) {
    report.notes.push_back("triangulated " + std::to_string(report.polygons_triangulated) +
                           " polygons with more than 3 corners");
  }
  result.report = std::move(report);
  return result;
}

}  // namespace io
}  // namespace aniso
