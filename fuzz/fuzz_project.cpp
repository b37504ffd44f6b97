// libFuzzer target: the .sublift project reader (header, coefficients, input order, extras).
#include "core/io/project/project_io.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes = sublift::fuzz::bytes_of(data, size);
  sublift::ProjectExtras extras;
  sublift::fuzz::expect_clean([&] { sublift::read_project_from_memory("fuzz.sublift", bytes, &extras); });
  return 0;
}
