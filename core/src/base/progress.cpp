#include "anisoform/progress.h"

namespace aniso {

const char* progress_stage_name(ProgressStage stage) {
  switch (stage) {
    case ProgressStage::Load: return "load";
    case ProgressStage::Factorize: return "factorize";
    case ProgressStage::Solve: return "solve";
    case ProgressStage::Flatten: return "flatten";
  }
  return "unknown";
}

}  // namespace aniso
