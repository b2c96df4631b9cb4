/* platform/hillshade.h — shaded-relief PNG output (used by `hillshade` and `run`). */
#ifndef BR_HILLSHADE_H
#define BR_HILLSHADE_H
#include "core/fx.h"
#include "core/hf.h"
#include "platform/err.h"

/* Unit vector towards a light at azimuth (clockwise from north) and altitude, Q14. */
void hillshade_light(double azimuth_deg, double altitude_deg, fx_q14 l[3]);
/* Writes the hillshade of f as an RGB PNG (grey), streaming row by row. */
br_status hillshade_write_png(const hf *f, const fx_q14 l[3], const char *out, br_err *err);

#endif
