/* tests/fuzz_common.h — what every libFuzzer harness does with its input:
 * load it from memory under a name that selects one reader, and on success
 * check the heightfield's invariants (abort = a finding).  tests/fuzz.sh. */
#ifndef BR_FUZZ_COMMON_H
#define BR_FUZZ_COMMON_H
#include <stdlib.h>
#include "platform/load.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static inline void fuzz_one(const char *name, const uint8_t *data, size_t size, const dem_opts *o)
{
    hf f;
    br_err e;
    br_status s = dem_load_mem(name, data, size, o, &f, &e);
    if (s == BR_OK) {
        size_t i, n = (size_t)f.w * (size_t)f.h;
        if (hf_validate(&f) != BR_OK) abort();
        for (i = 0; i < n; i++)
            if (f.z[i] != HF_NODATA && (f.z[i] > BR_Z_LIMIT || f.z[i] < -BR_Z_LIMIT)) abort();
        dem_free(&f);
    } else if (s <= BR_OK || s >= BR_E_COUNT || e.msg[0] == 0) {
        abort();                      /* a failure must have a code and a message */
    }
}

#endif
