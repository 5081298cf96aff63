// Anisoform's public API in one include. Start reading here.
//
// Where to begin, top down:
//  - session.h: one interactive modelling session (load a mesh, select, edit,
//    undo, flatten, export): what the browser app drives through WASM.
//  - deformer.h: the solver for one rest pose; deform_request.h: what a
//    deformation asks for (method, selection weights, direction source,
//    transform) and what it returns.
//  - flatten.h and pattern_export.h: garment-pattern flattening and its files.
// The layers below them, bottom up:
//  - mesh.h (the triangle mesh), error.h (every failure the user can cause),
//    limits.h (valid ranges), strict_number.h (the one number grammar);
//  - mesh_io.h, file_io.h (reading and writing), mesh_check.h (checks and repairs);
//  - laplacian.h (cotangent weights), transforms.h (the local transforms of
//    METHOD §3), direction_field.h and screen_direction.h (where directions
//    come from), selection.h (soft selections), distortion.h (the heat map).
// Everything under core/src is internal; core/README.md maps its folders.
#pragma once

#include "anisoform/error.h"
#include "anisoform/limits.h"
#include "anisoform/strict_number.h"
#include "anisoform/mesh.h"
#include "anisoform/file_io.h"
#include "anisoform/mesh_io.h"
#include "anisoform/mesh_check.h"
#include "anisoform/laplacian.h"
#include "anisoform/transforms.h"
#include "anisoform/direction_field.h"
#include "anisoform/screen_direction.h"
#include "anisoform/selection.h"
#include "anisoform/distortion.h"
#include "anisoform/deform_request.h"
#include "anisoform/deformer.h"
#include "anisoform/flatten.h"
#include "anisoform/pattern_export.h"
#include "anisoform/session_flatten.h"
#include "anisoform/session.h"
