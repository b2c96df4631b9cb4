/* platform/campath.c — see campath.h. */
#include "platform/campath.h"
#include "platform/assets.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int campath_parse_line(const char *s, double out[6])
{
    int i;
    for (i = 0; i < 6; i++) {
        char *end;
        while (*s == ' ' || *s == '\t') s++;
        out[i] = strtod(s, &end);
        if (end == s || !isfinite(out[i])) return -1;
        s = end;
        while (*s == ' ' || *s == '\t') s++;
        if (i < 5) {
            if (*s != ',') return -1;
            s++;
        }
    }
    while (*s == ' ' || *s == '\t' || *s == '\r' || *s == '\n') s++;
    return *s ? -1 : 0;
}

br_status campath_read(const char *path, campath *p, br_err *err)
{
    FILE *fp;
    char line[1024], where[ASSET_PATH_MAX];
    int lineno = 0, cap = 0;
    p->cam = NULL;
    p->n = 0;
    if (asset_resolve(path, where, sizeof where, &path, err) != BR_OK) return BR_E_IO;
    fp = fopen(path, "r");
    if (!fp) return br_err_set(err, BR_E_IO, path, "cannot open camera path");
    while (fgets(line, sizeof line, fp)) {
        char *c, *q;
        double v[6];
        size_t len = strlen(line);
        int i;
        lineno++;
        if (len + 1 < sizeof line && !feof(fp) && !strchr(line, '\n')) {
            /* the string ends before the buffer's end with no newline, yet fgets stopped
             * neither at the file's end nor with a full buffer: a NUL byte ended it */
            fclose(fp); campath_free(p);
            return br_err_set(err, BR_E_FORMAT, path, "line %d: a NUL byte (not a text file?)", lineno);
        }
        if (!strchr(line, '\n') && !feof(fp)) {
            fclose(fp); campath_free(p);
            return br_err_set(err, BR_E_FORMAT, path, "line %d: longer than %d characters", lineno, (int)sizeof line - 2);
        }
        if ((c = strchr(line, '#')) != NULL) *c = 0;
        for (q = line; *q == ' ' || *q == '\t' || *q == '\r' || *q == '\n'; q++) {}
        if (!*q) continue;
        if (campath_parse_line(q, v) != 0) {
            fclose(fp); campath_free(p);
            return br_err_set(err, BR_E_FORMAT, path, "line %d: expected EX,EY,EZ,TX,TY,TZ (six numbers in metres)", lineno);
        }
        for (i = 0; i < 6; i++)
            if (fabs(v[i]) > CAMPATH_COORD_MAX) {
                fclose(fp); campath_free(p);
                return br_err_set(err, BR_E_VALUE, path, "line %d: %g is out of range (accepted: %g..%g)", lineno, v[i],
                                  -CAMPATH_COORD_MAX, CAMPATH_COORD_MAX);
            }
        if (v[0] == v[3] && v[1] == v[4] && v[2] == v[5]) {
            fclose(fp); campath_free(p);
            return br_err_set(err, BR_E_VALUE, path, "line %d: the eye is the target", lineno);
        }
        if (p->n >= CAMPATH_MAX_FRAMES) {
            fclose(fp); campath_free(p);
            return br_err_set(err, BR_E_TOO_BIG, path, "more than %d frames", CAMPATH_MAX_FRAMES);
        }
        if (p->n == cap) {
            int nc = cap ? 2 * cap : 64;
            double (*nv)[6] = realloc(p->cam, sizeof *nv * (size_t)nc);
            if (!nv) { fclose(fp); campath_free(p); return br_err_set(err, BR_E_NOMEM, path, "out of memory"); }
            p->cam = nv;
            cap = nc;
        }
        memcpy(p->cam[p->n++], v, sizeof v);
    }
    if (ferror(fp)) { fclose(fp); campath_free(p); return br_err_set(err, BR_E_IO, path, "read error"); }
    fclose(fp);
    if (p->n == 0) return br_err_set(err, BR_E_VALUE, path, "no camera lines");
    return BR_OK;
}

void campath_free(campath *p)
{
    free(p->cam);
    p->cam = NULL;
    p->n = 0;
}
