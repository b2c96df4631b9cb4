/* platform/load_bt.c — reader not written yet. */
#include "platform/load_internal.h"

br_status dem_read_bt(const char *name, const uint8_t *p, size_t n, const dem_opts *o,
                       hf *out, br_err *err)
{
    (void)p; (void)n; (void)o; (void)out;
    return br_err_set(err, BR_E_UNSUPPORTED, name, "this format's reader is not written yet");
}
