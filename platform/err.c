/* platform/err.c — see err.h. */
#include "platform/err.h"
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

br_status br_err_set(br_err *e, br_status code, const char *file, const char *fmt, ...)
{
    va_list ap;
    size_t n = 0;
    if (!e) return code;
    e->code = code;
    e->msg[0] = 0;
    if (file) {
        snprintf(e->msg, sizeof e->msg, "%s: ", file);
        n = strlen(e->msg);
    }
    va_start(ap, fmt);
    vsnprintf(e->msg + n, sizeof e->msg - n, fmt, ap);
    va_end(ap);
    return code;
}

const char *br_status_name(br_status s)
{
    static const char *const names[BR_E_COUNT] = {
        "ok", "bad argument", "i/o error", "bad format", "truncated", "too big",
        "bad value", "unsupported", "out of memory", "cannot merge"
    };
    return (unsigned)s < BR_E_COUNT ? names[s] : "unknown error";
}
