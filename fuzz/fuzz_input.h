#pragma once
// Shared by the fuzz targets (docs/fuzzing.md). A reader may refuse an input only with a
// sublift::Error, the clean "bad input" path the CLI and the modeler report; any other exception
// escapes LLVMFuzzerTestOneInput and aborts, so libFuzzer records it as a crasher.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/base/errors.h"

namespace sublift::fuzz {

inline std::string bytes_of(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

/// Runs `read`; an Error is a clean refusal, everything else propagates.
template <class Read>
void expect_clean(Read&& read) {
  try {
    read();
  } catch (const Error&) {
  }
}

/// Writes `bytes` to `name` inside a private folder made once per process (readers that take a
/// path only; the folder is also the glTF sandbox, so nothing outside it can be read). Returns
/// the file's path.
std::string write_private_file(const std::string& name, const std::string& bytes);

}  // namespace sublift::fuzz
