/* fuzz_main: the libFuzzer entry point for one target, chosen with -DFUZZ_TARGET=fuzz_xxx. */
#include "fuzz_targets.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    return FUZZ_TARGET(data, size);
}
