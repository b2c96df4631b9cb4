/* platform/err.h — error messages that name the file and the problem.
 *
 * Every platform call that can fail takes a br_err* (may be NULL) and fills it
 * with the status and "FILE: what is wrong".  The CLI prints msg and exits 1. */
#ifndef BR_ERR_H
#define BR_ERR_H
#include "core/status.h"

typedef struct br_err {
    br_status code;
    char msg[512];
} br_err;

/* Sets e->code and e->msg = "<file>: <formatted>"; returns code.  file may be NULL. */
br_status br_err_set(br_err *e, br_status code, const char *file, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;
const char *br_status_name(br_status s);

#endif
