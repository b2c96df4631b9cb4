/* platform/geocam.h — cameras in the terrain's own coordinates: latitude, longitude
 * (degrees, WGS 84 as the grid's georeference gives them) and metres above sea level,
 * for grids georeferenced in degrees (SRTM HGT, geographic GeoTIFF/ASC).
 *   --look-from LAT,LON,ALT   the eye
 *   --look-at LAT,LON,ALT     the point looked at
 * Conversion: the scene's own linear map (platform/scene.h: x east from the west edge,
 * y north from the south edge, metres per degree at the grid's centre latitude as the
 * loader sets dx_um/dy_um), so a position and its latitude/longitude agree with the
 * grid's samples exactly at sample centres. */
#ifndef BR_GEOCAM_H
#define BR_GEOCAM_H
#include "platform/opt.h"
#include "platform/scene.h"

#define GEOCAM_ARGS_N 3     /* entries of the table, OPT_END included */

typedef struct geocam_args {
    double from[3], at[3];
    int from_seen, at_seen;
} geocam_args;

/* Fills t with --look-from and --look-at writing into a. */
void geocam_args_table(geocam_args *a, opt_spec t[GEOCAM_ARGS_N]);
/* After the scene is open: 0 when neither option was given; 1 with eye and target in
 * scene metres in out[0..6); -OPT_ERR with a message naming cmd when only one was
 * given, the grid is not in degrees, or a point lies far outside the grid. */
int geocam_resolve(const geocam_args *a, const scene *s, const char *cmd, double out[6]);

/* 1 when the scene's grid is in degrees. */
int geocam_ok(const scene *s);
/* Scene metres -> latitude, longitude in degrees (geocam_ok grids). */
void geocam_to_deg(const scene *s, double x, double y, double *lat, double *lon);
/* Latitude, longitude (degrees), metres above sea level -> scene metres. */
void geocam_from_deg(const scene *s, double lat, double lon, double alt, double out[3]);

#endif
