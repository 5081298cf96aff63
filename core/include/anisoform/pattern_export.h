// Pattern files from a flattening: the outline(s) of every piece, its
// grainline and a scale note, in millimetres, as SVG (to view and print at 1:1)
// or DXF (for garment CAD and cutters).
//
// The core writes text into a string; writing it to a file is the caller's
// (the CLI writes it, the browser offers it as a download).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "anisoform/flatten.h"

namespace aniso {

// Which side of a piece a pattern shows, the one rule wherever a pattern is
// drawn: the piece as seen from the side its faces' normals point to (each
// face's corners run counter-clockwise in the plane; for a garment modelled
// with outward normals, the outside, the fabric's right side, faces up). The
// same patch with every face wound the other way gives the mirror image. The
// flattening keeps every piece so (scale_to_area turns a start map seen from
// the back over; a face wound against the rest of its piece is turned to
// agree with it, FlattenPatch::reoriented_faces); the SVG and DXF state it
// (this text), as do the CLI's output and the README.
inline constexpr const char* kPatternSide =
    "Face up: the side the mesh's face normals point to (the outside, for outward normals)";

struct PatternPiece {
  // Closed polylines in pattern coordinates (model units), one per boundary
  // loop of the piece, the first point not repeated at the end.
  std::vector<std::vector<Eigen::Vector2d>> outlines;
  Eigen::Vector2d grainline = Eigen::Vector2d::UnitX();  // unit direction in the plane
};

struct Pattern {
  std::vector<PatternPiece> pieces;  // one per patch component
  int outline_count() const;
};

// The pieces of a flattening: its boundary loops at result.uv, grouped by
// component, with the result's grainline per component.
Pattern make_pattern(const FlattenPatch& patch, const FlattenResult& result);

struct PatternExportOptions {
  double mm_per_unit = 1.0;  // millimetres per model unit (> 0)
  std::string note;          // appended to the scale note (e.g. the wanted stretch)
};

// SVG 1.1, width/height in mm and a viewBox in mm, so one user unit is one
// millimetre and printing at 100 % gives the real size. Per outline one
// <path class="outline">; per piece a grainline (<line class="grainline">
// with arrowhead lines); a 100 mm (or 10 mm) <line class="scale-bar"> and a
// <text class="scale-note"> in 4 mm type at any scale, one <tspan> per line
// (the scale, kPatternSide, then `note`), the sheet widened to hold the longest line; a <desc> says kPatternSide too.
// The y axis is flipped (SVG's points down), so the pattern is not mirrored. Throws Error(BadParameter) if mm_per_unit is not a
// positive finite number.
std::string write_pattern_svg(const Pattern& pattern, const PatternExportOptions& options);

// Under 1 mm across, a pattern is written with the decimals that keep four
// significant digits across it (3 at 1 mm and above), and this says so: "the
// pattern is 0.000148 mm across at 1 mm per model unit (written with 8
// decimals): check the millimetres per unit"; "" for a pattern of 1 mm or
// more. (Spothead at 1e-4 of its size, at 1 mm per unit, was written as
// "10.000 10.000" at every point, without a word.)
std::string pattern_size_warning(const Pattern& pattern, const PatternExportOptions& options);

// The one rule for a pattern's scale, wherever it is given (the writers
// below, the CLI's --mm-per-unit before it flattens): a finite number within
// limits.h [kMinMmPerUnit, kMaxMmPerUnit]; Error(BadParameter) "millimetres
// per unit must be a number from 0.001 to 1000000, got 1e+308" otherwise.
void validate_mm_per_unit(double mm_per_unit);

// ASCII DXF R12 (AC1009, the version garment CAD and cutters import; units
// millimetres, also stated as $INSUNITS 4): one closed POLYLINE (VERTEX ...
// SEQEND) per outline on layer OUTLINE, one LINE per piece on layer
// GRAINLINE, and the scale note and below it kPatternSide as 4 mm TEXT on
// layer NOTE (kPatternSide also as a 999 comment). Same errors as SVG.
std::string write_pattern_dxf(const Pattern& pattern, const PatternExportOptions& options);

}  // namespace aniso
