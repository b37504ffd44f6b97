// libFuzzer target: the binary glTF (.glb) model importer behind the folder sandbox, and the
// animation sampler on the same file. Both take a path, so the input is written to a private
// temp folder, which is also its sandbox.
#include "core/io/model/animation.h"
#include "core/io/model/model.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = sublift::fuzz::write_private_file("model.glb", sublift::fuzz::bytes_of(data, size));
  sublift::fuzz::expect_clean([&] { sublift::import_model(path); });
  // The animation sampler (issue 22) reads samplers, channels, skins and morph targets too.
  sublift::fuzz::expect_clean([&] {
    if (!sublift::gltf_animations(path).empty()) sublift::sample_gltf_animation(path, -1, 3, false);
  });
  return 0;
}
