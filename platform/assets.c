#define _POSIX_C_SOURCE 200809L   /* readlink under -std=c99 */
/* platform/assets.c — where the bundled data lies: see assets.h. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "platform/assets.h"

#define ASSET_PREFIX "assets/"
#define ASSET_PREFIX_LEN (sizeof ASSET_PREFIX - 1)
#define ASSET_DIR_MAX 1024
/* The installed data directory (`make install` compiles this file again with its
 * DATADIR); the default is the Makefile's for PREFIX=/usr/local. */
#ifndef ASSET_DATADIR
#define ASSET_DATADIR "/usr/local/share/bitrain"
#endif

/* 1 when path names a regular file this process can read. */
static int readable_file(const char *path)
{
    struct stat sb;
    return stat(path, &sb) == 0 && S_ISREG(sb.st_mode) && access(path, R_OK) == 0;
}

/* Cuts path (absolute) at its last slash, keeping "/" for the root; 0 when it has none. */
static int cut_last(char *path)
{
    char *slash = strrchr(path, '/');
    if (!slash) return 0;
    if (slash == path) slash[1] = 0; else *slash = 0;
    return 1;
}

/* The running program's directory and the one above it; 0 when unknown. */
static int program_dirs(char dir[ASSET_DIR_MAX], char parent[ASSET_DIR_MAX])
{
    ssize_t n = readlink("/proc/self/exe", dir, ASSET_DIR_MAX - 1);
    if (n <= 0 || n >= ASSET_DIR_MAX - 1) return 0;
    dir[n] = 0;
    if (!cut_last(dir)) return 0;
    memcpy(parent, dir, ASSET_DIR_MAX);
    return cut_last(parent);
}

/* dir/middle/rest into buf when it fits and names a readable file. */
static int try_place(char *buf, size_t size, const char *dir, const char *middle, const char *rest)
{
    int n = snprintf(buf, size, "%s/%s%s", dir, middle, rest);
    return n > 0 && (size_t)n < size && readable_file(buf);
}

br_status asset_resolve(const char *name, char *buf, size_t size, const char **out, br_err *err)
{
    const char *rest, *env = getenv("BITRAIN_ASSETS");
    char dir[ASSET_DIR_MAX], parent[ASSET_DIR_MAX];
    int known, other_share;
    *out = name;
    if (!name || strncmp(name, ASSET_PREFIX, ASSET_PREFIX_LEN) != 0) return BR_OK;
    rest = name + ASSET_PREFIX_LEN;
    if (env && *env && try_place(buf, size, env, "", rest)) { *out = buf; return BR_OK; }
    if (readable_file(name)) return BR_OK;
    known = program_dirs(dir, parent);
    if (known && (try_place(buf, size, dir, ASSET_PREFIX, rest)
                  || try_place(buf, size, parent, "share/bitrain/", rest))) { *out = buf; return BR_OK; }
    if (try_place(buf, size, ASSET_DATADIR, "", rest)) { *out = buf; return BR_OK; }
    if (!known)
        return br_err_set(err, BR_E_IO, name, "cannot open (looked in %s./assets and %s; the program's own directory is unknown)",
                          env && *env ? "$BITRAIN_ASSETS, " : "", ASSET_DATADIR);
    /* the data directory named once: an installed program's share/bitrain is that directory */
    snprintf(buf, size, "%s%sshare/bitrain", parent, parent[1] ? "/" : "");
    other_share = strcmp(buf, ASSET_DATADIR) != 0;
    return br_err_set(err, BR_E_IO, name, "cannot open (looked in %s./assets, %s/assets%s%s and %s)",
                      env && *env ? "$BITRAIN_ASSETS, " : "", dir, other_share ? ", " : "", other_share ? buf : "",
                      ASSET_DATADIR);
}
