// libFuzzer target for the EULUMDAT parser (see docs/photometry.md).
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  lightsolver::fuzz::one_ldt_input(data, size);
  return 0;
}
