/* platform/assets.h — the bundled data of assets/ (the default terrain, its camera
 * paths), found wherever the program runs from.
 *
 * A name under assets/, such as "assets/N47E009.hgt.gz", is looked for in order:
 *   1. $BITRAIN_ASSETS/N47E009.hgt.gz, when that variable is set and not empty;
 *   2. assets/N47E009.hgt.gz from the working directory (the source tree);
 *   3. DIR/assets/N47E009.hgt.gz, DIR the running program's directory (the
 *      source tree's ./bitrain run from elsewhere);
 *   4. PARENT/share/bitrain/N47E009.hgt.gz, PARENT the directory above DIR (where
 *      `make install` puts assets/: PREFIX/bin/bitrain, PREFIX/share/bitrain/);
 *   5. ASSET_DATADIR/N47E009.hgt.gz, the data directory the installed library and
 *      program were built for (`make install` compiles platform/assets.c with its
 *      DATADIR: a program linked against the installed library, or bitrain in
 *      another BINDIR, finds the data there).
 * 3 and 4 read the program's path from /proc/self/exe (Linux); elsewhere they are
 * skipped.  dem_load and campath_read resolve their names this way, so
 * the defaults and a user's "assets/lake-path.cam" work from any directory. */
#ifndef BR_ASSETS_H
#define BR_ASSETS_H
#include <stddef.h>
#include "platform/err.h"

/* The bundled files, by their names in the source tree. */
#define ASSET_DEFAULT_DEM "assets/N47E009.hgt.gz"
#define ASSET_DEFAULT_PATH "assets/default-path.cam"
/* Room for a resolved name (the caller's buffer). */
#define ASSET_PATH_MAX 4096

/* *out = name when name is not under assets/; else the first place above holding a
 * readable regular file of that name (written to buf, size bytes), or BR_E_IO naming
 * name and the places looked in. */
br_status asset_resolve(const char *name, char *buf, size_t size, const char **out, br_err *err);

#endif
