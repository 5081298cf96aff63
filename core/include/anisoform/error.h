// Errors raised by the core. Every failure the user can cause (a bad file, a
// bad parameter, a numerical breakdown) is an aniso::Error with a code that the
// CLI maps to its exit status and the WASM layer maps to a JS Error code, and a
// message that names the element at fault ("face 21 references vertex 840 ...").
#pragma once

#include <stdexcept>
#include <string>

namespace aniso {

enum class ErrorCode {
  BadParameter,  // a parameter or option is out of range or malformed (CLI exit 2)
  BadMesh,       // the input mesh cannot be used as it is (CLI exit 3)
  BadFile,       // a file cannot be read or parsed (CLI exit 3)
  Numerical,     // a factorization or solve failed (CLI exit 3: the mesh is the cause)
};

// Short stable name of a code, used as the JS Error's `code` and in JSON.
const char* error_code_name(ErrorCode code);

class Error : public std::runtime_error {
 public:
  Error(ErrorCode code, const std::string& message)
      : std::runtime_error(message), code_(code) {}
  ErrorCode code() const { return code_; }

 private:
  ErrorCode code_;
};

[[noreturn]] inline void fail(ErrorCode code, const std::string& message) {
  throw Error(code, message);
}

}  // namespace aniso
