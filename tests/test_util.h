#pragma once
// Small helpers for tests that build files in code.
#include <cstdlib>
#include <functional>
#include <string>

#include "core/base/errors.h"
#include "core/io/mesh/mesh_import.h"

// SUBLIFT_ASAN: set by tests/CMakeLists.txt in sanitizer builds (whose test bodies are not
// instrumented themselves), or detected in a test compiled with ASan.
#if defined(SUBLIFT_ASAN)
#elif defined(__SANITIZE_ADDRESS__)  // gcc
#define SUBLIFT_ASAN 1
#elif defined(__has_feature)  // clang
#if __has_feature(address_sanitizer)
#define SUBLIFT_ASAN 1
#endif
#endif

namespace sublift::testing {

/// This test binary runs under AddressSanitizer (its quarantine holds freed memory, so memory
/// measurements skip; soak runs take fewer steps).
#ifdef SUBLIFT_ASAN
inline constexpr bool kAddressSanitizer = true;
#else
inline constexpr bool kAddressSanitizer = false;
#endif

/// Imports `bytes` as if read from `name`.
inline LoadedMesh load(const std::string& name, const std::string& bytes) {
  return import_surface_mesh_from_memory(name, bytes);
}

/// The warning whose text contains `needle`, or nullptr.
inline const ImportWarning* find_warning(const ImportReport& r, const std::string& needle) {
  for (const ImportWarning& w : r.warnings)
    if (w.what.find(needle) != std::string::npos) return &w;
  return nullptr;
}

/// The InputError message of importing `bytes`, or "" if it loads.
inline std::string load_error(const std::string& name, const std::string& bytes, std::size_t* line = nullptr) {
  try {
    load(name, bytes);
  } catch (const InputError& e) {
    if (line) *line = e.line();
    return e.what();
  }
  return "";
}

/// The message of the sublift::Error that `work` throws, or "" if it throws none.
inline std::string error_text(const std::function<void()>& work) {
  try {
    work();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

/// An environment variable set for one scope (child processes started inside inherit it).
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) { setenv(name, value, 1); }
  ~ScopedEnv() { unsetenv(name_); }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* name_;
};

}  // namespace sublift::testing
