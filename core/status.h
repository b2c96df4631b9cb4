/* core/status.h — the status every fallible bitrain call returns (0 = ok).
 *
 * core/ and raster/ never print: they return one of these and leave their
 * objects as they were.  platform/ turns a status plus context into a message
 * that names the file and the problem (platform/err.h).  Tests compare codes,
 * never message strings. */
#ifndef BR_STATUS_H
#define BR_STATUS_H

typedef enum br_status {
    BR_OK = 0,
    BR_E_ARG,          /* caller error: bad parameter, buffer too small */
    BR_E_IO,           /* cannot open/read/write a file */
    BR_E_FORMAT,       /* not this format / wrong magic / corrupt structure */
    BR_E_TRUNCATED,    /* file shorter than its header says */
    BR_E_TOO_BIG,      /* dimensions or size beyond what we accept (checked before allocating) */
    BR_E_VALUE,        /* a value is absurd: NaN/inf, out of range, non-numeric */
    BR_E_UNSUPPORTED,  /* a valid file using a feature we do not read */
    BR_E_NOMEM,        /* allocation failed (platform only) or a pool ran out */
    BR_E_MERGE,        /* tiles overlap with different values, leave gaps, or do not fit */
    BR_E_COUNT
} br_status;

#endif
