#include "anisoform/error.h"

namespace aniso {

const char* error_code_name(ErrorCode code) {
  switch (code) {
    case ErrorCode::BadParameter: return "bad-parameter";
    case ErrorCode::BadMesh: return "bad-mesh";
    case ErrorCode::BadFile: return "bad-file";
    case ErrorCode::Numerical: return "numerical";
  }
  return "unknown";
}

}  // namespace aniso
