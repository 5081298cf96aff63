// Pattern files (pattern_export.h): the SVG is well-formed XML with one outline
// per boundary loop, sized in millimetres; the DXF has a valid group-code
// structure with one closed POLYLINE per boundary loop.
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "anisoform/error.h"
#include "anisoform/flatten.h"
#include "anisoform/pattern_export.h"
#include "test_support.h"

namespace {

using namespace aniso;

using aniso::test::count_of;
using aniso::test::kPi;

// A flat annulus (two boundary loops) in the plane z = 0, radii 1 and 2.
Mesh annulus(double x_offset) {
  const int around = 32, across = 4;
  Mesh mesh;
  mesh.V.resize(around * (across + 1), 3);
  for (int j = 0; j <= across; ++j) {
    for (int i = 0; i < around; ++i) {
      const double radius = 1.0 + double(j) / across, angle = 2.0 * kPi * i / around;
      mesh.V.row(j * around + i) << x_offset + radius * std::cos(angle), radius * std::sin(angle), 0.0;
    }
  }
  mesh.F.resize(2 * around * across, 3);
  int t = 0;
  for (int j = 0; j < across; ++j) {
    for (int i = 0; i < around; ++i) {
      const int a = j * around + i, b = j * around + (i + 1) % around;
      const int c = a + around, d = b + around;
      mesh.F.row(t++) << a, b, d;
      mesh.F.row(t++) << a, d, c;
    }
  }
  return mesh;
}

// Two annuli side by side: 2 pieces, 4 outlines.
Mesh two_annuli() {
  const Mesh left = annulus(0.0), right = annulus(10.0);
  Mesh both;
  both.V.resize(left.num_vertices() * 2, 3);
  both.V << left.V, right.V;
  both.F.resize(left.num_triangles() * 2, 3);
  both.F << left.F, (right.F.array() + left.num_vertices()).matrix();
  return both;
}

// A small XML well-formedness scan: every element opened is closed in order,
// attributes are quoted, and there is exactly one root. Enough for the subset
// the writer uses (no CDATA, no comments).
bool well_formed_xml(const std::string& text, std::string& problem) {
  std::vector<std::string> open;
  int roots = 0;
  std::size_t at = 0;
  while ((at = text.find('<', at)) != std::string::npos) {
    const std::size_t end = text.find('>', at);
    if (end == std::string::npos) {
      problem = "unterminated tag";
      return false;
    }
    const std::string tag = text.substr(at + 1, end - at - 1);
    at = end + 1;
    if (tag.empty()) {
      problem = "empty tag";
      return false;
    }
    if (tag[0] == '?') continue;  // the XML declaration
    if (count_of(tag, "\"") % 2 != 0) {
      problem = "unbalanced quotes in <" + tag + ">";
      return false;
    }
    if (tag[0] == '/') {
      if (open.empty() || open.back() != tag.substr(1)) {
        problem = "</" + tag.substr(1) + "> closes nothing open";
        return false;
      }
      open.pop_back();
      continue;
    }
    const std::string name = tag.substr(0, tag.find_first_of(" \t\n/"));
    if (open.empty()) ++roots;
    if (tag.back() != '/') open.push_back(name);
  }
  if (!open.empty()) {
    problem = "<" + open.back() + "> never closed";
    return false;
  }
  if (roots != 1) {
    problem = std::to_string(roots) + " root elements";
    return false;
  }
  return true;
}

// DXF as (code, value) pairs; false if a code line is not an integer.
bool dxf_pairs(const std::string& text, std::vector<std::pair<int, std::string>>& pairs) {
  std::istringstream in(text);
  std::string code, value;
  while (std::getline(in, code)) {
    if (!std::getline(in, value)) return false;
    try {
      std::size_t used = 0;
      const int number = std::stoi(code, &used);
      if (used != code.size()) return false;
      pairs.emplace_back(number, value);
    } catch (const std::exception&) {
      return false;
    }
  }
  return true;
}

FlattenOutput flattened(const Mesh& mesh) { return flatten(mesh, {}, FlattenOptions{}); }

}  // namespace

TEST_CASE("pattern: the SVG is well-formed with one outline per boundary loop", "[pattern]") {
  const Mesh mesh = two_annuli();
  const FlattenOutput out = flattened(mesh);
  const Pattern pattern = make_pattern(out.patch, out.result);
  REQUIRE(pattern.pieces.size() == 2);
  REQUIRE(pattern.outline_count() == 4);
  PatternExportOptions options;
  options.note = "su <0.8> & \"sv\" 1";  // must be escaped
  const std::string svg = write_pattern_svg(pattern, options);
  std::string problem;
  CHECK(well_formed_xml(svg, problem));
  INFO(problem);
  CHECK(count_of(svg, "<path ") == 4);
  CHECK(count_of(svg, "<polyline") == 0);
  CHECK(count_of(svg, "class=\"grainline\"") == 2 * 5);  // a line and four arrowhead strokes per piece
  CHECK(count_of(svg, "class=\"scale-note\"") == 1);
  CHECK(svg.find("&lt;0.8&gt; &amp; &quot;sv&quot;") != std::string::npos);
}

TEST_CASE("pattern: SVG sizes are millimetres at the given scale", "[pattern]") {
  const Mesh plane = test::load("open/plane.off");
  const FlattenOutput out = flattened(plane);
  const Pattern pattern = make_pattern(out.patch, out.result);
  double width_units = 0.0;
  {
    Eigen::RowVector2d lo = out.result.uv.colwise().minCoeff(), hi = out.result.uv.colwise().maxCoeff();
    width_units = hi.x() - lo.x();
  }
  PatternExportOptions options;
  options.mm_per_unit = 1000.0;
  const std::string svg = write_pattern_svg(pattern, options);
  const std::size_t at = svg.find("width=\"");
  REQUIRE(at != std::string::npos);
  const double width_mm = std::stod(svg.substr(at + 7));
  CHECK(width_mm == Approx(width_units * 1000.0 + 20.0).margin(0.01));  // plus 10 mm margins
  CHECK(svg.find("1 model unit = 1000.000 mm") != std::string::npos);

  options.mm_per_unit = 0.0;
  CHECK_THROWS_AS(write_pattern_svg(pattern, options), Error);
  CHECK_THROWS_AS(write_pattern_dxf(pattern, options), Error);
}

TEST_CASE("pattern: the DXF has valid sections and one closed POLYLINE per boundary loop",
          "[pattern]") {
  const Mesh mesh = two_annuli();
  const FlattenOutput out = flattened(mesh);
  const Pattern pattern = make_pattern(out.patch, out.result);
  const std::string dxf = write_pattern_dxf(pattern, PatternExportOptions{});
  std::vector<std::pair<int, std::string>> pairs;
  REQUIRE(dxf_pairs(dxf, pairs));
  REQUIRE(!pairs.empty());
  CHECK(pairs.back() == std::make_pair(0, std::string("EOF")));

  int sections = 0, polylines = 0, closed = 0, vertices = 0, seqends = 0, lines = 0;
  bool in_section = false, in_polyline = false;
  std::vector<std::string> section_names;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const auto& [code, value] = pairs[k];
    if (code != 0) continue;
    if (value == "SECTION") {
      CHECK_FALSE(in_section);
      in_section = true;
      ++sections;
      REQUIRE(k + 1 < pairs.size());
      CHECK(pairs[k + 1].first == 2);
      section_names.push_back(pairs[k + 1].second);
    } else if (value == "ENDSEC") {
      CHECK(in_section);
      CHECK_FALSE(in_polyline);
      in_section = false;
    } else if (value == "POLYLINE") {
      CHECK(in_section);
      in_polyline = true;
      ++polylines;
      for (std::size_t j = k + 1; j < pairs.size() && pairs[j].first != 0; ++j) {
        if (pairs[j].first == 70 && (std::stoi(pairs[j].second) & 1)) ++closed;
      }
    } else if (value == "VERTEX") {
      CHECK(in_polyline);
      ++vertices;
    } else if (value == "SEQEND") {
      CHECK(in_polyline);
      in_polyline = false;
      ++seqends;
    } else if (value == "LINE") {
      ++lines;
    }
  }
  CHECK_FALSE(in_section);
  CHECK(sections == 2);
  CHECK(section_names == std::vector<std::string>{"HEADER", "ENTITIES"});
  CHECK(polylines == 4);
  CHECK(closed == 4);
  CHECK(seqends == 4);
  CHECK(lines == 2);  // one grainline per piece
  int loop_vertices = 0;
  for (const auto& loop : out.patch.boundary_loops) loop_vertices += static_cast<int>(loop.size());
  CHECK(vertices == loop_vertices);
  CHECK(dxf.find("$INSUNITS\n70\n4\n") != std::string::npos);  // millimetres
}

TEST_CASE("pattern: the real torso panel gives one outline in SVG and DXF", "[pattern]") {
  const Mesh torso = test::load("open/human_woman_torso_front_patch.obj");
  const FlattenOutput out = flattened(torso);
  const Pattern pattern = make_pattern(out.patch, out.result);
  PatternExportOptions options;
  options.mm_per_unit = 1000.0;  // the body is in metres
  const std::string svg = write_pattern_svg(pattern, options);
  const std::string dxf = write_pattern_dxf(pattern, options);
  std::string problem;
  CHECK(well_formed_xml(svg, problem));
  CHECK(count_of(svg, "<path ") == 1);
  CHECK(count_of(dxf, "\nPOLYLINE\n") == 1);
}

TEST_CASE("pattern: a piece of a few millimetres keeps its note whole and 4 mm high", "[pattern]") {
  const Mesh torso = test::load("open/human_woman_torso_front_patch.obj");
  const FlattenOutput out = flattened(torso);
  const Pattern pattern = make_pattern(out.patch, out.result);
  PatternExportOptions options;
  options.mm_per_unit = 10.0;  // metres read as centimetres: a piece of about 4 mm
  options.note = "anisotropic, su 0.8 sv 1, direction global:0,1,0; grainline = mean compression direction";
  const std::string svg = write_pattern_svg(pattern, options);
  std::string problem;
  CHECK(well_formed_xml(svg, problem));
  INFO(problem);
  CHECK(svg.find(".scale-note{font-family:sans-serif;font-size:4.000px}") != std::string::npos);
  CHECK(count_of(svg, "<tspan ") == 3);  // the scale, the side shown (kPatternSide), the note
  // The sheet holds the longest note line at 0.6 em (2.4 mm) per character, plus the margins.
  const double width_mm = std::stod(svg.substr(svg.find("width=\"") + 7));
  CHECK(width_mm >= 2.4 * static_cast<double>(options.note.size()) + 20.0);
  CHECK(width_mm < 2.4 * static_cast<double>(options.note.size()) + 20.1);
}

TEST_CASE("pattern: a DXF's extents hold every entity, the note below the pattern too", "[pattern]") {
  const Mesh torso = test::load("open/human_woman_torso_front_patch.obj");
  const FlattenOutput out = flattened(torso);
  PatternExportOptions options;
  options.mm_per_unit = 1000.0;
  options.note = "anisotropic, su 0.8 sv 1, direction global:0,1,0; grainline = mean compression direction";
  const std::string dxf = write_pattern_dxf(make_pattern(out.patch, out.result), options);
  // The file as (group code, value) pairs.
  std::vector<std::pair<int, std::string>> pairs;
  std::istringstream in(dxf);
  for (std::string code, value; std::getline(in, code) && std::getline(in, value);) pairs.emplace_back(std::stoi(code), value);
  const auto header_point = [&](const std::string& name) {
    for (std::size_t i = 0; i + 2 < pairs.size(); ++i) {
      if (pairs[i].first == 9 && pairs[i].second == name) {
        return Eigen::Vector2d(std::stod(pairs[i + 1].second), std::stod(pairs[i + 2].second));
      }
    }
    FAIL("no " << name);
    return Eigen::Vector2d();
  };
  const Eigen::Vector2d low = header_point("$EXTMIN"), high = header_point("$EXTMAX");
  int points = 0;
  for (std::size_t i = 0; i + 1 < pairs.size(); ++i) {
    if (pairs[i].first != 10 && pairs[i].first != 11) continue;
    if (i > 0 && pairs[i - 1].first == 9) continue;  // the header's own
    const Eigen::Vector2d p(std::stod(pairs[i].second), std::stod(pairs[i + 1].second));
    if (p.isZero() && pairs[i - 1].first == 66) continue;  // a POLYLINE's dummy point
    ++points;
    CHECK((p.array() >= low.array() - 1e-9).all());
    CHECK((p.array() <= high.array() + 1e-9).all());
  }
  CHECK(points > 50);  // the outline (about 90 points), the grainline, the note
  // The note's baseline is inside, below the pattern.
  CHECK(low.y() < 0.0);
}
