/* platform/load_internal.h — what the readers behind platform/load.h share.
 *
 * Every reader works on a whole file in memory (p, n) and a display name used
 * for messages, extension checks and SRTM tile names.  A reader fills *out only
 * on success (out->z malloc'd); on failure it frees what it allocated, leaves
 * *out untouched and returns the status it set in err.
 * Platform code: double is allowed here (core/ stays integer). */
#ifndef BR_LOAD_INTERNAL_H
#define BR_LOAD_INTERNAL_H
#include <stddef.h>
#include <stdint.h>
#include "platform/load.h"

/* Ceiling on a decompressed .gz file or .zip member, in bytes, on top of the
 * format caps (dem_format_cap); the fuzz build lowers it so a zip bomb stays cheap. */
#ifndef DEM_MAX_INFLATE
#define DEM_MAX_INFLATE SIZE_MAX
#endif

typedef br_status dem_reader(const char *name, const uint8_t *p, size_t n,
                             const dem_opts *o, hf *out, br_err *err);

dem_reader dem_read_hgt, dem_read_png, dem_read_asc, dem_read_bt, dem_read_tif, dem_read_xyz, dem_read_geoclaw;

/* 1 when the text starts like a GeoClaw topotype 2/3 header: a number, then
 * a keyword (ncols, nrows, mx, my) on the first line that is not blank. */
int dem_geoclaw_start(const uint8_t *p, size_t n);

/* Checks w x h against core/hf.h's limits (before allocating), mallocs the
 * heights and sets defaults: unit 1 m, spacing 1 m, no georeference. */
br_status dem_alloc(hf *out, int64_t w, int64_t h, const char *name, br_err *err);

/* Georeference with sample (0,0)'s centre at (lon0, lat0) degrees and steps
 * slon east, slat south per column/row; sets geo (nano-degrees) and the ground
 * spacing in micrometres at the grid's centre latitude (WGS84 series). */
br_status dem_geo_degrees(hf *f, double lon0, double lat0, double slon, double slat,
                          const char *name, br_err *err);
/* Same for projected coordinates in metres (geo in micrometres). */
br_status dem_geo_projected(hf *f, double x0, double y0, double sx, double sy,
                            const char *name, br_err *err);
/* Metres per degree of latitude and of longitude at latitude lat_deg (WGS84). */
void dem_m_per_degree(double lat_deg, double *m_lat, double *m_lon);
/* Recomputes dx_um/dy_um of a geographic heightfield for its centre latitude
 * (after a merge): from like's spacing when given (same steps), else from geo. */
br_status dem_geo_spacing(hf *f, const hf *like, const char *name, br_err *err);

/* Float sources: the largest den in {1000, 10^4, 10^5, 10^6} with
 * maxabs*den <= 2^27; 0 when even 1000 does not fit (|h| > 134 km). */
int32_t dem_float_den(double maxabs);
/* Rounds a finite height (metres) to units of 1/den; caller checked the range. */
int32_t dem_float_z(double h, int32_t den);

/* v ~ num/den with den <= maxden (powers of ten first, then continued
 * fractions); returns 0 if no approximation within 1e-9 relative exists. */
int dem_rational(double v, int64_t maxden, int64_t *num, int64_t *den);

/* The values of a text grid (ASC, GeoClaw) from pos: exactly w*h numbers,
 * north row first; have_nd/nd (the header's) and o->nodata mark voids; negate
 * for depths.  Heights keep 1 m when all are integers, else the float rule.
 * fmt names the format in messages.  Fills *out (malloc'd) on success. */
br_status dem_text_values(const char *name, const char *fmt, const uint8_t *p, size_t n, size_t pos,
                          int64_t w, int64_t h, int have_nd, double nd, int negate, const dem_opts *o,
                          hf *out, br_err *err);

/* Text: skips separators (white space; also ',' and ';' when commas) from *pos
 * up to n and reads one number token.  Returns 1 with *v set, 0 at the end of
 * data, -1 for a token that is not a number, -2 for NaN or infinity; *tok and
 * *toklen give the token (for messages).  *pos ends after the token. */
int dem_scan_number(const uint8_t *p, size_t n, size_t *pos, int commas, double *v,
                    const uint8_t **tok, size_t *toklen);
/* Copies a token for a message: at most 24 printable characters. */
void dem_token_str(const uint8_t *tok, size_t len, char out[32]);

/* Coordinates that look geographic: a step of at most 1 (one-degree grids
 * such as ETOPO's coarsest are geographic) and a grid inside
 * [-360, 360] x [-90, 90] whose first corner is not (0, 0) (within 1/1000
 * of a step: text rounding; lab grids start there). */
int dem_looks_degrees(double xmin, double ymin, double xmax, double ymax, double sx, double sy);

/* Passes a note about name to the function set by dem_set_note, if any. */
void dem_note(const char *name, const char *msg);

const char *dem_basename(const char *name);
/* 1 if name ends with ext (".hgt"), case-insensitive. */
int dem_has_ext(const char *name, const char *ext);
/* SRTM tile name (N50E008...) in the basename: lower-left corner in degrees. */
int dem_srtm_name(const char *name, int *lat, int *lon);

/* The most bytes a file of the format shown by its first n bytes (n may be 0)
 * and its name can have while holding at most BR_MAX_SAMPLES samples; *what
 * names the format for messages.  Headers that state the size (BT) or the
 * dimensions (PNG's IHDR) tighten it. */
uint64_t dem_format_cap(const char *name, const uint8_t *p, size_t n, const char **what);
/* Reads a regular file whole (malloc'd), refusing other kinds of file and
 * files beyond dem_format_cap. */
br_status dem_read_file(const char *path, uint8_t **data, size_t *n, br_err *err);

enum { DEM_DECLARED_NONE = 0, DEM_DECLARED_EXACT = 1, DEM_DECLARED_MOD32 = 2 };
/* Inflates src into a malloc'd buffer (windowBits as zlib: 15+16 gzip, -15 raw
 * deflate).  inner names the payload (its format's cap applies); declared is
 * the size its container states, exactly (zip) or modulo 2^32 (gzip ISIZE).
 * A zip size beyond the cap is refused before inflating; inflation stops with
 * BR_E_TOO_BIG one byte past the declared size or the cap (load_io.c). */
br_status dem_inflate_alloc(const char *name, const char *inner, const uint8_t *src, size_t n, int window_bits,
                            uint64_t declared, int declared_kind, uint8_t **out, size_t *outn, br_err *err);
/* Inflates a zlib stream into exactly dn bytes of dst (GeoTIFF deflate tiles). */
br_status dem_inflate_into(const char *name, const uint8_t *src, size_t n, uint8_t *dst,
                           size_t dn, br_err *err);

/* Little- and big-endian reads (no alignment needed). */
static inline uint16_t dem_le16(const uint8_t *p) { return (uint16_t)(p[0] | p[1] << 8); }
static inline uint16_t dem_be16(const uint8_t *p) { return (uint16_t)(p[0] << 8 | p[1]); }
static inline uint32_t dem_le32(const uint8_t *p)
{ return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24; }
static inline uint32_t dem_be32(const uint8_t *p)
{ return (uint32_t)p[3] | (uint32_t)p[2] << 8 | (uint32_t)p[1] << 16 | (uint32_t)p[0] << 24; }

#endif
