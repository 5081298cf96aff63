// The checks of limits.h's bounds that are not amounts of a transform
// (those are transforms.cpp's).
#include "anisoform/limits.h"

#include "anisoform/error.h"

namespace aniso {

void check_iteration_count(long long count, const std::string& what) {
  if (count < 1 || count > limits::kMaxIterations) {
    fail(ErrorCode::BadParameter, what + " must be an integer from 1 to " + std::to_string(limits::kMaxIterations) +
                                      ", got " + std::to_string(count));
  }
}

}  // namespace aniso
