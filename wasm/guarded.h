// What every embind entry point shares: guarded(), which turns any C++
// exception into a RETURNED JS Error carrying `code` (aniso::error_code_name,
// "out-of-memory" for std::bad_alloc and std::length_error, or "internal")
// and the C++ message, and copies of C++ arrays into JS-owned typed arrays.
//
// Why return rather than throw: throwing a JS exception from inside the
// module (TOOLCHAIN.md §1 option (a)) skips the epilogues of the frames it
// unwinds; measured, every error then leaks 32 bytes of the 5 MB shadow stack
// and one emval handle, so a long session would end in a stack overflow. The
// JS layer (js/anisoform-wasm.mjs) throws the returned Error.
#pragma once

#include <cstddef>
#include <new>
#include <stdexcept>
#include <string>
#include <type_traits>

#include <emscripten/val.h>

#include "anisoform/error.h"

namespace aniso::wasm {

// ANISO_WASM_MAXIMUM_MEMORY_GB is the -sMAXIMUM_MEMORY of the link
// (wasm/CMakeLists.txt), so the message names the limit actually in force.
#define ANISO_STRINGIFY2(x) #x
#define ANISO_STRINGIFY(x) ANISO_STRINGIFY2(x)
inline constexpr const char* kOutOfMemoryMessage =
    "out of memory: this needs more than the " ANISO_STRINGIFY(ANISO_WASM_MAXIMUM_MEMORY_GB)
    " GB of memory the module may use in the browser; nothing was changed "
    "(try a smaller mesh, or the native CLI)";

inline emscripten::val error_value(const char* code, const char* message) {
  emscripten::val error = emscripten::val::global("Error").new_(std::string(message));
  error.set("code", std::string(code));
  return error;
}

// The body's result as a JS value, or the Error it failed with.
template <typename Body>
emscripten::val guarded(Body&& body) {
  try {
    if constexpr (std::is_void_v<decltype(body())>) {
      body();
      return emscripten::val::undefined();
    } else {
      return emscripten::val(body());
    }
  } catch (const Error& error) {
    return error_value(error_code_name(error.code()), error.what());
  } catch (const std::length_error&) {
    // A container longer than 32-bit WASM can address: the same limit.
    return error_value("out-of-memory", kOutOfMemoryMessage);
  } catch (const std::bad_alloc&) {
    // Unwinding has freed what the call allocated, and the Session methods
    // change nothing until their work is done (session.h), so the session
    // stays as it was. The WASM memory itself never shrinks: it stays as
    // large as it grew, to be reused by the next calls.
    return error_value("out-of-memory", kOutOfMemoryMessage);
  } catch (const std::exception& error) {
    return error_value("internal", error.what());
  } catch (...) {
    return error_value("internal", "unknown C++ exception");
  }
}

// A JS-owned copy (the heap may move under a view).
template <typename T>
emscripten::val copy_to_js(const T* data, std::size_t count) {
  return emscripten::val(emscripten::typed_memory_view(count, data)).call<emscripten::val>("slice");
}

}  // namespace aniso::wasm
