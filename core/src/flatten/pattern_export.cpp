// SVG and DXF pattern files (pattern_export.h).
#include "anisoform/pattern_export.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "anisoform/error.h"
#include "anisoform/limits.h"

namespace aniso {

namespace {

struct Segment {
  Eigen::Vector2d from, to;
};

struct Box {
  Eigen::Vector2d min = Eigen::Vector2d::Constant(HUGE_VAL);
  Eigen::Vector2d max = Eigen::Vector2d::Constant(-HUGE_VAL);
  void add(const Eigen::Vector2d& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  bool empty() const { return !(min.x() <= max.x()); }
};

void require_scale(const PatternExportOptions& options) { validate_mm_per_unit(options.mm_per_unit); }

}  // namespace

void validate_mm_per_unit(double mm_per_unit) {
  if (mm_per_unit >= limits::kMinMmPerUnit && mm_per_unit <= limits::kMaxMmPerUnit) return;
  // %.15g: 0.001 and 1000000 as written, not 1e-03 and 1e+06. The value
  // given: %g, with more digits when six do not show it (1000000.1).
  char given[40];
  for (int digits = 6; digits <= 17; ++digits) {
    std::snprintf(given, sizeof given, "%.*g", digits, mm_per_unit);
    if (!std::isfinite(mm_per_unit) || std::strtod(given, nullptr) == mm_per_unit) break;
  }
  char text[160];
  std::snprintf(text, sizeof text, "millimetres per unit must be a number from %.15g to %.15g, got %s",
                limits::kMinMmPerUnit, limits::kMaxMmPerUnit, given);
  fail(ErrorCode::BadParameter, text);
}

namespace {

// Millimetres to three decimals (micrometres): plenty for a cutter, and
// independent of the C++ locale. Room for any double's digits (DBL_MAX
// has 309): a coordinate is never cut short. A pattern's coordinates take
// pattern_decimals.
std::string number(double value, int decimals = 3) {
  char text[400];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

// The decimals that keep four significant digits across a pattern under 1 mm
// (three at 1 mm and above: micrometres). A pattern 0.0001 mm across was
// written as "10.000 10.000" at every point: a dot.
int pattern_decimals(const Box& box) {
  const double extent = std::max(box.max.x() - box.min.x(), box.max.y() - box.min.y());
  int decimals = 3;
  for (double e = extent; e > 0.0 && e < 1.0 && decimals < 17; e *= 10.0) ++decimals;
  return decimals;
}

Box piece_box(const PatternPiece& piece, double scale) {
  Box box;
  for (const auto& outline : piece.outlines) {
    for (const Eigen::Vector2d& p : outline) box.add(scale * p);
  }
  return box;
}

Box pattern_box(const Pattern& pattern, double scale) {
  Box box;
  for (const PatternPiece& piece : pattern.pieces) {
    const Box b = piece_box(piece, scale);
    if (b.empty()) continue;
    box.add(b.min);
    box.add(b.max);
  }
  if (box.empty()) box.add(Eigen::Vector2d::Zero());
  return box;
}

// The grainline in mm: through the middle of the piece's box, along its
// direction, over the middle 60 % of the piece's extent along it.
Segment grainline_segment(const PatternPiece& piece, double scale) {
  const Box box = piece_box(piece, scale);
  const Eigen::Vector2d center =
      box.empty() ? Eigen::Vector2d(Eigen::Vector2d::Zero()) : Eigen::Vector2d(0.5 * (box.min + box.max));
  const Eigen::Vector2d d = piece.grainline.normalized();
  double lo = 0.0, hi = 0.0;
  for (const auto& outline : piece.outlines) {
    for (const Eigen::Vector2d& p : outline) {
      const double along = (scale * p - center).dot(d);
      lo = std::min(lo, along);
      hi = std::max(hi, along);
    }
  }
  const double margin = 0.2 * (hi - lo);
  return {center + (lo + margin) * d, center + (hi - margin) * d};
}

std::string printable_ascii(const std::string& text) {
  std::string clean;
  for (char c : text) clean += (c >= 32 && c < 127) ? c : ' ';
  return clean;
}

std::string scale_heading(const PatternExportOptions& options) {
  return "Anisoform pattern - outlines in mm, 1 model unit = " + number(options.mm_per_unit) + " mm";
}

// The scale note in plain ASCII on one line (DXF TEXT takes no line breaks).
std::string scale_note(const PatternExportOptions& options) {
  std::string note = scale_heading(options);
  if (!options.note.empty()) note += " - " + options.note;
  return printable_ascii(note);
}

// The SVG's note: a fixed 4 mm type whatever the pattern's size (a piece of a
// few millimetres must not shrink or clip it), in lines of its own, and a
// sheet wide enough for the longest line (0.6 em per character bounds the
// width of a sans-serif ASCII line).
constexpr double kNoteFontMm = 4.0;
// The DXF note's baseline below the pattern's lowest point.
constexpr double kNoteGapMm = 10.0;
constexpr double kNoteLineMm = 5.0;
double note_width_mm(const std::string& line) { return 0.6 * kNoteFontMm * static_cast<double>(line.size()); }

std::string xml_escaped(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

// A scale bar long enough to measure against and no longer than the pattern.
double scale_bar_length(double pattern_width) { return pattern_width >= 100.0 ? 100.0 : 10.0; }

}  // namespace

int Pattern::outline_count() const {
  int count = 0;
  for (const PatternPiece& piece : pieces) count += static_cast<int>(piece.outlines.size());
  return count;
}

Pattern make_pattern(const FlattenPatch& patch, const FlattenResult& result) {
  Pattern pattern;
  pattern.pieces.resize(patch.num_components);
  for (std::size_t l = 0; l < patch.boundary_loops.size(); ++l) {
    std::vector<Eigen::Vector2d> outline;
    for (int vertex : patch.boundary_loops[l]) outline.emplace_back(result.uv.row(vertex).transpose());
    pattern.pieces[patch.loop_component[l]].outlines.push_back(std::move(outline));
  }
  for (int c = 0; c < patch.num_components && c < static_cast<int>(result.grainline.size()); ++c) {
    pattern.pieces[c].grainline = result.grainline[c];
  }
  return pattern;
}

std::string pattern_size_warning(const Pattern& pattern, const PatternExportOptions& options) {
  require_scale(options);
  const Box box = pattern_box(pattern, options.mm_per_unit);
  const double extent = std::max(box.max.x() - box.min.x(), box.max.y() - box.min.y());
  if (!(extent < 1.0)) return "";
  char text[160];
  std::snprintf(text, sizeof text, "the pattern is %.3g mm across at %.6g mm per model unit", extent,
                options.mm_per_unit);
  return std::string(text) + " (written with " + std::to_string(pattern_decimals(box)) +
         " decimals): check the millimetres per unit";
}

std::string write_pattern_svg(const Pattern& pattern, const PatternExportOptions& options) {
  require_scale(options);
  const double scale = options.mm_per_unit;
  const Box box = pattern_box(pattern, scale);
  const double bar = scale_bar_length(box.max.x() - box.min.x());
  std::vector<std::string> note_lines{printable_ascii(scale_heading(options) + " - scale bar " + number(bar) + " mm"),
                                      kPatternSide};
  if (!options.note.empty()) note_lines.push_back(printable_ascii(options.note));
  double note_width = 0.0;
  for (const std::string& text : note_lines) note_width = std::max(note_width, note_width_mm(text));
  // The scale bar 8 mm below the pattern, the note's first baseline 14 mm below it.
  const double margin = 10.0;
  const double footer = 20.0 + kNoteLineMm * static_cast<double>(note_lines.size() - 1);
  const double width = std::max(box.max.x() - box.min.x(), note_width) + 2.0 * margin;
  const double height = box.max.y() - box.min.y() + 2.0 * margin + footer;
  // Pattern mm to SVG user units (mm), y pointing down.
  const int decimals = pattern_decimals(box);
  const auto x = [&](double u) { return number(u - box.min.x() + margin, decimals); };
  const auto y = [&](double v) { return number(box.max.y() - v + margin, decimals); };
  const auto line = [&](const char* cls, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return "<line class=\"" + std::string(cls) + "\" x1=\"" + x(a.x()) + "\" y1=\"" + y(a.y()) +
           "\" x2=\"" + x(b.x()) + "\" y2=\"" + y(b.y()) + "\"/>\n";
  };

  std::ostringstream svg;
  svg << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" << number(width)
      << "mm\" height=\"" << number(height) << "mm\" viewBox=\"0 0 " << number(width) << " "
      << number(height) << "\">\n"
      << "<title>Anisoform pattern</title>\n"
      << "<desc>" << xml_escaped(kPatternSide) << "</desc>\n"
      << "<style>.outline{fill:none;stroke:#000;stroke-width:0.3}"
         ".grainline{stroke:#c00;stroke-width:0.3}.scale-bar{stroke:#000;stroke-width:0.5}"
         ".scale-note{font-family:sans-serif;font-size:" << number(kNoteFontMm) << "px}</style>\n";
  for (std::size_t p = 0; p < pattern.pieces.size(); ++p) {
    const PatternPiece& piece = pattern.pieces[p];
    svg << "<g class=\"piece\" id=\"piece-" << p << "\">\n";
    for (const auto& outline : piece.outlines) {
      svg << "<path class=\"outline\" d=\"";
      for (std::size_t k = 0; k < outline.size(); ++k) {
        const Eigen::Vector2d q = scale * outline[k];
        svg << (k == 0 ? "M" : " L") << x(q.x()) << " " << y(q.y());
      }
      svg << " Z\"/>\n";
    }
    const Segment grain = grainline_segment(piece, scale);
    svg << line("grainline", grain.from, grain.to);
    // Arrowheads at both ends: a grainline is a line, not a direction.
    const Eigen::Vector2d d = (grain.to - grain.from).normalized();
    const double head = std::min(3.0, 0.25 * (grain.to - grain.from).norm());
    const Eigen::Vector2d side(-d.y(), d.x());
    const Eigen::Vector2d tips[2] = {grain.to, grain.from};
    const Eigen::Vector2d backwards[2] = {-d, d};
    for (int end = 0; end < 2; ++end) {
      svg << line("grainline", tips[end], tips[end] + head * (backwards[end] + 0.5 * side));
      svg << line("grainline", tips[end], tips[end] + head * (backwards[end] - 0.5 * side));
    }
    svg << "</g>\n";
  }
  const Eigen::Vector2d bar_start(box.min.x(), box.min.y() - 8.0);
  svg << line("scale-bar", bar_start, bar_start + Eigen::Vector2d(bar, 0.0));
  svg << "<text class=\"scale-note\" x=\"" << x(box.min.x()) << "\" y=\"" << y(box.min.y() - 14.0) << "\">";
  for (std::size_t k = 0; k < note_lines.size(); ++k) {
    svg << "<tspan x=\"" << x(box.min.x()) << "\" dy=\"" << number(k == 0 ? 0.0 : kNoteLineMm) << "\">"
        << xml_escaped(note_lines[k]) << "</tspan>";
  }
  svg << "</text>\n";
  svg << "</svg>\n";
  return svg.str();
}

std::string write_pattern_dxf(const Pattern& pattern, const PatternExportOptions& options) {
  require_scale(options);
  const double scale = options.mm_per_unit;
  const Box box = pattern_box(pattern, scale);
  std::ostringstream dxf;
  const auto group = [&dxf](int code, const std::string& value) {
    dxf << code << "\n" << value << "\n";
  };
  const int decimals = pattern_decimals(box);
  const auto point = [&](int code, const Eigen::Vector2d& p) {
    group(code, number(p.x(), decimals));
    group(code + 10, number(p.y(), decimals));
    group(code + 20, number(0.0));
  };

  group(999, "Anisoform pattern, units: millimetres");
  group(999, kPatternSide);
  group(0, "SECTION");
  group(2, "HEADER");
  group(9, "$ACADVER");
  group(1, "AC1009");
  group(9, "$INSUNITS");
  group(70, "4");
  // The extents hold the note too: its baseline kNoteGapMm below the
  // pattern, its width at most a type height per character.
  const std::string note = scale_note(options);
  const Eigen::Vector2d note_at(box.min.x(), box.min.y() - kNoteGapMm);
  // kPatternSide's line below the note.
  const Eigen::Vector2d side_at(note_at.x(), note_at.y() - kNoteLineMm);
  group(9, "$EXTMIN");
  point(10, Eigen::Vector2d(box.min.x(), side_at.y()));
  group(9, "$EXTMAX");
  const std::size_t longest = std::max(note.size(), std::string(kPatternSide).size());
  point(10, Eigen::Vector2d(std::max(box.max.x(), note_at.x() + kNoteFontMm * static_cast<double>(longest)),
                            box.max.y()));
  group(0, "ENDSEC");

  group(0, "SECTION");
  group(2, "ENTITIES");
  for (const PatternPiece& piece : pattern.pieces) {
    for (const auto& outline : piece.outlines) {
      group(0, "POLYLINE");
      group(8, "OUTLINE");
      group(66, "1");  // vertices follow
      point(10, Eigen::Vector2d::Zero());
      group(70, "1");  // closed
      for (const Eigen::Vector2d& p : outline) {
        group(0, "VERTEX");
        group(8, "OUTLINE");
        point(10, scale * p);
      }
      group(0, "SEQEND");
      group(8, "OUTLINE");
    }
    const Segment grain = grainline_segment(piece, scale);
    group(0, "LINE");
    group(8, "GRAINLINE");
    point(10, grain.from);
    point(11, grain.to);
  }
  group(0, "TEXT");
  group(8, "NOTE");
  point(10, note_at);
  group(40, number(kNoteFontMm));
  group(1, note);
  group(0, "TEXT");
  group(8, "NOTE");
  point(10, side_at);
  group(40, number(kNoteFontMm));
  group(1, kPatternSide);
  group(0, "ENDSEC");
  group(0, "EOF");
  return dxf.str();
}

}  // namespace aniso
