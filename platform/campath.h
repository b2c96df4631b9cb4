/* platform/campath.h — camera path files: text, one frame per line in the
 * `--camera` syntax EX,EY,EZ,TX,TY,TZ (eye and target in metres in the scene's
 * frame: x east from the west edge, y north from the south edge, z height; see
 * platform/scene.h), blanks around the numbers allowed, `#` starts a comment,
 * blank lines are skipped.  A line that is not six finite numbers, holds one beyond
 * +-CAMPATH_COORD_MAX or a NUL byte, or whose eye equals its target, is an error
 * naming the file and the line. */
#ifndef BR_CAMPATH_H
#define BR_CAMPATH_H
#include "platform/err.h"

#define CAMPATH_MAX_FRAMES 1000000
/* |coordinate| accepted, metres: a path line and `--camera` (render, view, mesh) alike */
#define CAMPATH_COORD_MAX 1e7

typedef struct campath {
    double (*cam)[6];   /* n frames: eye x, y, z, target x, y, z */
    int n;
} campath;

/* Parses one line (no comment handling): 0 ok, -1 not six finite numbers. */
int campath_parse_line(const char *s, double out[6]);
/* Reads path into p (p->cam allocated; campath_free releases it); a name under
 * assets/ is found as platform/assets.h says.  BR_E_IO when
 * the file cannot be read, BR_E_FORMAT naming the line, BR_E_VALUE for an empty
 * path; p is left empty on error. */
br_status campath_read(const char *path, campath *p, br_err *err);
void campath_free(campath *p);

#endif
