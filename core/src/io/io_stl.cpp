// STL, ASCII and binary. A binary file is recognised by its size (84 + 50 n
// bytes for n triangles), not by its first word: many binary exporters start
// the 80-byte header with "solid" too. STL stores every triangle's corners
// separately; the reader welds them by exact position into an indexed mesh and
// keeps every triangle, including those welding leaves with a repeated corner
// (check_mesh reports them).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include <Eigen/Geometry>

#include "anisoform/mesh_check.h"
#include "anisoform/mesh_io.h"
#include "io/io_common.h"

namespace aniso {
namespace io {

namespace {

constexpr std::size_t kHeaderBytes = 80;
constexpr std::size_t kPreambleBytes = 84;   // header + triangle count
constexpr std::size_t kTriangleBytes = 50;   // normal, 3 corners, attribute

// An ASCII STL keyword, in any case: exporters write `SOLID`, `FACET`,
// `VERTEX` too (as many readers take them, so do we; such a file was read as
// binary and refused as "truncated: its header declares 774909216
// triangles").
bool is_keyword(std::string_view token, std::string_view keyword) {
  if (token.size() != keyword.size()) return false;
  for (std::size_t k = 0; k < token.size(); ++k) {
    const char c = token[k];
    if ((c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c) != keyword[k]) return false;
  }
  return true;
}

// ASCII STL starts with "solid" (any case) and its first bytes are all text;
// a binary header may start with "solid" but is followed by binary floats.
bool looks_like_ascii(const char* data, std::size_t size) {
  std::size_t i = 0;
  while (i < size && (is_blank(data[i]) || data[i] == '\n')) ++i;
  if (!is_keyword(std::string_view(data + i, std::min<std::size_t>(5, size - i)), "solid")) return false;
  const std::size_t probe = std::min<std::size_t>(size, 512);
  for (std::size_t k = 0; k < probe; ++k) {
    const unsigned char c = static_cast<unsigned char>(data[k]);
    if (c < 0x20 && c != '\n' && !is_blank(static_cast<char>(c))) return false;
  }
  return true;
}

// Corner positions, three per triangle, in file order.
using Soup = std::vector<double>;

Soup read_binary_soup(const char* data, std::size_t size, ReadReport& report) {
  if (size < kPreambleBytes) {
    fail_file("the file is too short for a binary STL (" + std::to_string(size) +
              " bytes; the header alone takes 84) and is not ASCII STL (it does not start with 'solid')");
  }
  const std::uint32_t count = load_scalar<std::uint32_t>(data + kHeaderBytes, true);
  const unsigned long long expected = kPreambleBytes + static_cast<unsigned long long>(count) * kTriangleBytes;
  if (size < expected) {
    fail_file("the binary STL is truncated: its header declares " + std::to_string(count) +
              " triangles, which take " + std::to_string(expected) + " bytes, but the file has " +
              std::to_string(size) + " bytes (it ends after " +
              std::to_string((size - kPreambleBytes) / kTriangleBytes) + " complete triangles)");
  }
  if (size > expected) {
    report.notes.push_back("ignored " + std::to_string(size - expected) +
                           " bytes after the last of the " + std::to_string(count) +
                           " triangles the header declares");
  }
  Soup soup(static_cast<std::size_t>(count) * 9);
  const char* record = data + kPreambleBytes;
  for (std::size_t t = 0; t < count; ++t, record += kTriangleBytes) {
    const char* corner = record + 12;  // after the stored normal, which we recompute when needed
    for (std::size_t k = 0; k < 9; ++k) soup[9 * t + k] = load_scalar<float>(corner + 4 * k, true);
  }
  return soup;
}

// Tokens of an ASCII STL with the line each came from.
class StlTokens {
 public:
  explicit StlTokens(std::string_view text) : lines_(text) {}
  std::string_view next() {
    std::string_view token = next_token(line_rest_);
    while (token.empty() && lines_.next(line_rest_)) token = next_token(line_rest_);
    return token;
  }
  void skip_rest_of_line() { line_rest_ = {}; }
  int line() const { return lines_.line_number(); }

 private:
  LineReader lines_;
  std::string_view line_rest_;
};

class AsciiStlParser {
 public:
  explicit AsciiStlParser(std::string_view text) : tokens_(text) {}

  Soup parse(ReadReport& report) {
    expect("solid");
    tokens_.skip_rest_of_line();  // the solid's name
    while (true) {
      const std::string_view token = tokens_.next();
      if (token.empty()) {
        report.notes.push_back("the ASCII STL has no closing 'endsolid' line");
        break;
      }
      if (is_keyword(token, "facet")) {
        read_facet();
      } else if (is_keyword(token, "endsolid")) {
        tokens_.skip_rest_of_line();
        const std::string_view after = tokens_.next();
        if (after.empty()) break;
        if (!is_keyword(after, "solid")) unexpected(after, "'solid' or the end of the file");
        tokens_.skip_rest_of_line();  // a further solid: its facets join the same mesh
      } else {
        unexpected(token, "'facet' or 'endsolid'");
      }
    }
    return std::move(soup_);
  }

 private:
  [[noreturn]] void unexpected(std::string_view token, const std::string& wanted) const {
    if (token.empty()) {
      fail_file("the file is truncated: it ends inside facet " + std::to_string(facets_ + 1) +
                at_line(tokens_.line()));
    }
    fail_file("expected " + wanted + " but found " + quoted(token) + at_line(tokens_.line()));
  }
  void expect(std::string_view keyword) {
    const std::string_view token = tokens_.next();
    if (!is_keyword(token, keyword)) unexpected(token, "'" + std::string(keyword) + "'");
  }
  double number() {
    const std::string_view token = tokens_.next();
    double value = 0;
    if (token.empty()) unexpected(token, "a number");
    if (const char* problem = parse_coordinate(token, value)) {
      fail_file(number_problem(token, problem) + at_line(tokens_.line()));
    }
    return value;
  }
  void read_facet() {
    expect("normal");
    for (int k = 0; k < 3; ++k) number();  // recomputed from the corners when needed
    expect("outer");
    expect("loop");
    for (int corner = 0; corner < 3; ++corner) {
      expect("vertex");
      for (int k = 0; k < 3; ++k) soup_.push_back(number());
    }
    const std::string_view token = tokens_.next();
    if (is_keyword(token, "vertex")) {
      fail_file("facet " + std::to_string(facets_ + 1) + " has more than 3 vertices" +
                at_line(tokens_.line()) + "; STL facets are triangles");
    }
    if (!is_keyword(token, "endloop")) unexpected(token, "'endloop'");
    expect("endfacet");
    ++facets_;
  }

  StlTokens tokens_;
  Soup soup_;
  int facets_ = 0;
};

ReadResult weld_soup(const Soup& soup, ReadReport report) {
  const Eigen::Index corners = static_cast<Eigen::Index>(soup.size() / 3);
  Mesh unwelded;
  unwelded.V = Eigen::Map<const Positions>(soup.data(), corners, 3);
  unwelded.F.resize(corners / 3, 3);
  for (Eigen::Index c = 0; c < corners; ++c) unwelded.F(c / 3, c % 3) = static_cast<int>(c);

  std::vector<int> old_to_new;
  const Mesh welded = weld_vertices(unwelded, 0.0, &old_to_new);
  ReadResult result;
  result.mesh.V = welded.V;
  // All triangles are kept (weld_vertices drops collapsed ones): the file holds them.
  result.mesh.F.resize(unwelded.F.rows(), 3);
  int collapsed = 0;
  for (Eigen::Index t = 0; t < unwelded.F.rows(); ++t) {
    for (int k = 0; k < 3; ++k) result.mesh.F(t, k) = old_to_new[static_cast<std::size_t>(unwelded.F(t, k))];
    const auto& f = result.mesh.F;
    if (f(t, 0) == f(t, 1) || f(t, 1) == f(t, 2) || f(t, 2) == f(t, 0)) ++collapsed;
  }
  report.vertices_welded = static_cast<int>(corners - welded.V.rows());
  if (report.vertices_welded > 0) {
    report.notes.push_back("welded " + std::to_string(report.vertices_welded) +
                           " duplicate corners by exact position (STL stores every triangle's "
                           "corners separately)");
  }
  if (collapsed > 0) {
    report.notes.push_back(std::to_string(collapsed) +
                           " triangles have two corners at the same position");
  }
  result.report = std::move(report);
  return result;
}

void append_facet_normal(std::string& out, const Eigen::Vector3d& n, bool binary) {
  if (binary) {
    for (int k = 0; k < 3; ++k) append_little_endian<float>(out, static_cast<float>(n[k]));
    return;
  }
  out += "  facet normal ";
  for (int k = 0; k < 3; ++k) {
    append_number(out, n[k]);
    out += k < 2 ? ' ' : '\n';
  }
}

Eigen::Vector3d unit_normal(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const double length = n.norm();
  return length > 0 && std::isfinite(length) ? Eigen::Vector3d(n / length) : Eigen::Vector3d::Zero();
}

// Binary STL stores 32-bit floats. A larger coordinate would be written as
// inf; and a mesh small for its distance from the origin loses its shape:
// 32-bit floats near 1e6 are 0.0625 apart, so corners closer than that become
// one point, which a reader welds (spot scaled by 1e-4 and moved by 1e6 was
// written without a word and read back as 1 vertex). Refused when a face's
// two distinct corners would become one, naming the face, the spacing and the
// way out: what is written then keeps every edge (a mesh read from binary
// STL writes back exactly). ASCII STL and the other formats write doubles.
constexpr const char* kWriteDoublesInstead =
    "write ASCII STL (the CLI's --ascii), OBJ, OFF or PLY instead, which keep 64-bit coordinates";

std::string short_number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", value);
  return text;
}

void require_float32_keeps(const Mesh& mesh) {
  double largest_used = 0.0;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const Eigen::Index v = mesh.F(f, k);
      const double largest = mesh.V.row(v).cwiseAbs().maxCoeff();
      largest_used = std::max(largest_used, largest);
      if (largest <= std::numeric_limits<float>::max()) continue;
      char text[32];
      std::snprintf(text, sizeof text, "%g", largest);
      fail(ErrorCode::BadMesh, "vertex " + std::to_string(v) + " has a coordinate of magnitude " + text +
                                   ", beyond the 32-bit floats of binary STL (at most 3.4e38); " +
                                   kWriteDoublesInstead);
    }
  }
  long long collapsed = 0;
  Eigen::Index first_face = -1;
  int first_a = 0, first_b = 0;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    bool lost = false;
    for (int k = 0; k < 3 && !lost; ++k) {
      const int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3);
      if (mesh.V.row(a) == mesh.V.row(b)) continue;  // one point already: kept as it is
      if (mesh.V.row(a).cast<float>() != mesh.V.row(b).cast<float>()) continue;
      lost = true;
      if (first_face < 0) {
        first_face = f;
        first_a = a;
        first_b = b;
      }
    }
    collapsed += lost ? 1 : 0;
  }
  if (collapsed == 0) return;
  const float at = static_cast<float>(largest_used);
  const double spacing = static_cast<double>(std::nextafter(at, std::numeric_limits<float>::infinity())) - at;
  fail(ErrorCode::BadMesh,
       "binary STL stores 32-bit floats, which cannot keep this mesh's shape: near its largest coordinate, " +
           short_number(largest_used) + ", they are " + short_number(spacing) + " apart, and vertices " +
           std::to_string(first_a) + " and " + std::to_string(first_b) + " of face " + std::to_string(first_face) +
           ", " + short_number((mesh.V.row(first_a) - mesh.V.row(first_b)).norm()) +
           " apart, would become one point (" + std::to_string(collapsed) + " of " +
           std::to_string(mesh.F.rows()) + " faces would lose a corner); " + kWriteDoublesInstead);
}

}  // namespace

ReadResult read_stl(const char* data, std::size_t size) {
  ReadReport report;
  Soup soup;
  const bool size_says_binary =
      size >= kPreambleBytes &&
      size == kPreambleBytes + static_cast<unsigned long long>(load_scalar<std::uint32_t>(data + kHeaderBytes, true)) *
                                   kTriangleBytes;
  if (!size_says_binary && looks_like_ascii(data, size)) {
    const std::string_view text(data, size);
    reject_binary_text(text, "ASCII STL");
    soup = AsciiStlParser(text).parse(report);
  } else {
    soup = read_binary_soup(data, size, report);
  }
  return weld_soup(soup, std::move(report));
}

std::string write_stl(const Mesh& mesh, bool binary, const SurfaceAttributes* attributes) {
  std::string out;
  if (binary) require_float32_keeps(mesh);
  if (binary) {
    // The header must not start with "solid": some readers take that for ASCII.
    // Then the file's first comment, when it fits whole (a cut attribution
    // would misquote it); ASCII STL has only a solid name, no comment.
    std::string header = "binary STL written by anisoform";
    const std::string first = first_comment_fitting(attributes, kHeaderBytes - header.size() - 2);
    if (!first.empty()) header += "; " + first;
    header.resize(kHeaderBytes, ' ');
    out = header;
    append_little_endian<std::uint32_t>(out, static_cast<std::uint32_t>(mesh.F.rows()));
    out.reserve(kPreambleBytes + static_cast<std::size_t>(mesh.F.rows()) * kTriangleBytes);
  } else {
    out = "solid anisoform\n";
  }
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const Eigen::Vector3d corner[3] = {mesh.V.row(mesh.F(f, 0)).transpose(),
                                       mesh.V.row(mesh.F(f, 1)).transpose(),
                                       mesh.V.row(mesh.F(f, 2)).transpose()};
    append_facet_normal(out, unit_normal(corner[0], corner[1], corner[2]), binary);
    if (!binary) out += "    outer loop\n";
    for (const Eigen::Vector3d& p : corner) {
      if (binary) {
        for (int k = 0; k < 3; ++k) append_little_endian<float>(out, static_cast<float>(p[k]));
        continue;
      }
      out += "      vertex ";
      for (int k = 0; k < 3; ++k) {
        append_number(out, p[k]);
        out += k < 2 ? ' ' : '\n';
      }
    }
    if (binary) {
      append_little_endian<std::uint16_t>(out, 0);  // attribute byte count
    } else {
      out += "    endloop\n  endfacet\n";
    }
  }
  if (!binary) out += "endsolid anisoform\n";
  return out;
}

}  // namespace io
}  // namespace aniso
