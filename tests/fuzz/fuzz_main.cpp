// One libFuzzer binary per target (FACESKETCH_FUZZ=ON, tests/fuzz/CMakeLists.txt): the target's
// name is compiled in as FACESKETCH_FUZZ_TARGET.
#include "entry_points.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    static const facesketch::fuzz::Target& target = facesketch::fuzz::target(FACESKETCH_FUZZ_TARGET);
    target.run(data, size);
    return 0;
}
