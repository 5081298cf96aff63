// The valid ranges of user-given amounts and of mesh coordinates: the one
// place these numbers live. Core validation (transforms.cpp validate, the
// deformer's request check, the flatten targets, the mesh check) enforces them;
// out of range is Error(BadParameter) naming the field, or Error(BadMesh)
// naming the vertex. See docs/ROBUSTNESS.md for the reasoning in full.
//
// Why these bounds: every amount here becomes a factor of the per-element
// target matrices T. Factors in [1/100, 100] keep T's condition number below
// 1e4, so the solves stay accurate to ~1e-12 and the deformed positions stay
// within 100 times the mesh's extent; beyond that the "deformation" is a
// typing mistake (1e300 overflowed to inf and printed null).
#pragma once

#include <string>

namespace aniso {
namespace limits {

// Scales along, across and along the normal (deform su, sv, sn) and the
// wanted stretches of flattening (su, sv): within [kMinScale, kMaxScale].
constexpr double kMinScale = 0.01;
constexpr double kMaxScale = 100.0;

// Shear h (the off-diagonal of the local map): |h| <= kMaxShear, so the
// sheared map's factors stay within the scale range.
constexpr double kMaxShear = 100.0;

// Rotation angle in degrees: |angle| <= kMaxRotateDegrees (ten turns). An
// angle of 1e16 degrees has no digit left below one turn.
constexpr double kMaxRotateDegrees = 3600.0;

// Twist: the rate is in degrees per unit of mesh length, so its sensible range
// depends on the mesh. The bound is on the whole twist across the mesh:
// |rate| * bounding-box diagonal <= kMaxTwistDegrees (one hundred turns).
constexpr double kMaxTwistDegrees = 36000.0;

// ARAP's move (the handles' offset): |offset| <= kMaxMoveDiagonals bounding-box
// diagonals, as the scales keep a deformed mesh within a hundred mesh sizes.
// Beyond, it is a typing mistake: a move of 1e300 wrote coordinates that the
// readers refuse (kMaxCoordinate) and left a session that could not flatten.
constexpr double kMaxMoveDiagonals = 100.0;

// Mesh coordinates: |x| <= kMaxCoordinate. The square of any coordinate
// difference (up to 2e150) and sums of three such squares stay finite, so edge
// lengths, bounding boxes and the normalisation to unit size (deformer.cpp)
// are exact enough; the solvers then work in that unit frame, so within this
// range the result does not depend on the mesh's units.
constexpr double kMaxCoordinate = 1e150;

// AnARAP's coupled rotations' alpha (DeformRequest::rotation_coupling, the
// CLI's --rotation-coupling, an op's rotationCoupling): how strongly a
// region's rotation is kept against the rest bending. The result settles
// at both ends of this range (the plane turned 10 degrees: the energy moves
// by under 1 % from 1e-4 down to 1e-8 and from 1e4 up to 1e200); beyond it, the
// coupling terms swamp the energy (1e308 made it non-finite, exit 3).
constexpr double kMinRotationCoupling = 1e-4;
constexpr double kMaxRotationCoupling = 1e4;

// Iterations of one solve: a deformation's maxIterations and the paper's
// rotation scheme's rotationSteps (each a full solve), a flattening's
// maxIterations. The solvers stop at their tolerance long before (a 200k
// mesh commits in 50; the open bunny's flattening with its refinement takes
// 332), so the bound only stops a typing mistake or a crafted document with
// tolerance 0 from holding the solver for hours: 10000 iterations of a 200k
// mesh are about ten minutes natively.
constexpr int kMaxIterations = 10000;
// A pattern file's scale, millimetres per model unit: a micrometre to a
// kilometre. Beyond, the outlines are zeros to the file's micrometre
// precision, or no cutter's size.
constexpr double kMinMmPerUnit = 1e-3;
constexpr double kMaxMmPerUnit = 1e6;

}  // namespace limits

// Error(BadParameter) "WHAT must be an integer from 1 to 10000, got COUNT"
// unless 1 <= count <= limits::kMaxIterations.
void check_iteration_count(long long count, const std::string& what);

}  // namespace aniso
