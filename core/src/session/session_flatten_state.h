// What a Session keeps between flattenings (private to the core: session.cpp
// owns it, session_flatten.cpp uses it).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "anisoform/flatten.h"

namespace aniso {

struct SessionFlattenState {
  // Built on the session's current positions with `mask` (empty = the whole
  // mesh). It holds the factorization, so a flattening with other amounts,
  // directions or method reuses it. It is also the owner of the patch that
  // `last` refers to, which is why a selection change does not drop it: the
  // last pattern stays exportable; the next flatten with another mask builds
  // a new one.
  std::unique_ptr<Flattener> flattener;
  std::vector<char> mask;
  std::optional<FlattenResult> last;  // for Session::export_pattern
  std::string note;                   // the last result's scale-note text
  int retired_factorizations = 0;     // by flatteners already dropped

  int factorizations() const {
    return retired_factorizations + (flattener ? flattener->factorizations() : 0);
  }

  // The positions changed (load, edit, commit, undo): nothing built on the old
  // ones may be reused or exported. Never throws.
  void positions_changed() {
    if (flattener) retired_factorizations += flattener->factorizations();
    flattener.reset();
    mask.clear();
    last.reset();
    note.clear();
  }
};

}  // namespace aniso
