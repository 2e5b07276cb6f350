// libFuzzer target for the IES LM-63 parser (see docs/photometry.md).
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  lightsolver::fuzz::one_ies_input(data, size);
  return 0;
}
