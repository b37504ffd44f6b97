// libFuzzer target: the OpenVolumeMesh ASCII .ovm reader and the complex built from what it read
// (read_shape, the path of every command and of the modeler's open).
#include "core/io/lattice/shape_io.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes = sublift::fuzz::bytes_of(data, size);
  sublift::fuzz::expect_clean([&] { sublift::read_shape_from_memory("fuzz.ovm", bytes); });
  return 0;
}
