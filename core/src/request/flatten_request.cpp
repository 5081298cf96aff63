// flatten_options (session_flatten.h): a SessionFlatten as the options of
// flatten() / Flattener::flatten.
#include "anisoform/session_flatten.h"

namespace aniso {

FlattenOptions flatten_options(const SessionFlatten& request) {
  FlattenOptions options;
  options.method = request.method;
  options.directions = request.directions;
  options.su = request.su;
  options.sv = request.sv;
  options.solver.max_iterations = request.max_iterations;
  options.solver.tolerance = request.tolerance;
  options.solver.refine = request.refine;
  return options;
}

}  // namespace aniso
