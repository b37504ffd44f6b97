// libFuzzer target: the glTF (.gltf) model importer behind the folder sandbox. import_model
// takes a path, so the input is written to a private temp folder, which is also its sandbox.
#include "core/io/model/model.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = sublift::fuzz::write_private_file("model.gltf", sublift::fuzz::bytes_of(data, size));
  sublift::fuzz::expect_clean([&] { sublift::import_model(path); });
  return 0;
}
