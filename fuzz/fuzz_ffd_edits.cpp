// libFuzzer target: the FFD edits parser (`level index dx dy dz` lines, sublift-cli ffd --edits)
// and the animation edits parser (`level frame point dx dy dz`, sublift-cli animation --edits).
#include "core/anim/animation_edits.h"
#include "core/ffd/ffd_edits.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes = sublift::fuzz::bytes_of(data, size);
  sublift::fuzz::expect_clean([&] { sublift::parse_ffd_edits(bytes, "fuzz.edits"); });
  sublift::fuzz::expect_clean([&] { sublift::parse_animation_edits(bytes, "fuzz.edits"); });
  return 0;
}
