#define _POSIX_C_SOURCE 200809L
/* tests/test_cli_opts.c — the one option parser (platform/opt.h) as users meet it: every
 * command refuses a malformed or out-of-range value with a line that names the option
 * and the value, instead of printing the usage or silently taking something else; the
 * mesh stays monotone in the error threshold up to the top of its range; `mesh -o` to a
 * path that cannot be written fails before any work; `bitrain --version`. */
#include <fcntl.h>
#include <unistd.h>
#include "tests/test.h"
#include "platform/cmd.h"
#include "platform/opt.h"

/* Runs fn(argc, argv) with stdout and stderr sent to files; returns its exit code and
 * leaves stderr's text in err (NUL-terminated, truncated to errlen - 1). */
static int run_cmd(int (*fn)(int, char **), int argc, char **argv, char *err, size_t errlen, const char *outpath)
{
    char errpath[256];
    int s1, s2, fo, fe, rc;
    FILE *f;
    size_t n;
    snprintf(errpath, sizeof errpath, "%s/opts_stderr.txt", t_outdir());
    fflush(stdout);
    fflush(stderr);
    s1 = dup(1);
    s2 = dup(2);
    fo = open(outpath ? outpath : "/dev/null", O_WRONLY | O_CREAT | O_TRUNC, 0644);
    fe = open(errpath, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (s1 < 0 || s2 < 0 || fo < 0 || fe < 0) return -100;
    dup2(fo, 1);
    dup2(fe, 2);
    close(fo);
    close(fe);
    rc = fn(argc, argv);
    fflush(stdout);
    fflush(stderr);
    dup2(s1, 1);
    dup2(s2, 2);
    close(s1);
    close(s2);
    err[0] = 0;
    f = fopen(errpath, "r");
    if (f) {
        n = fread(err, 1, errlen - 1, f);
        err[n] = 0;
        fclose(f);
    }
    return rc;
}

/* `bitrain render DEM -o x.png OPTION VALUE` must exit 2 with a message naming both. */
static void bad_render(const char *option, const char *value)
{
    char dem[] = "assets/N47E009.hgt.gz", o[] = "-o", png[] = "tests/out/opts.png", err[1024];
    char *argv[5];
    int rc;
    argv[0] = dem; argv[1] = o; argv[2] = png; argv[3] = (char *)option; argv[4] = (char *)value;
    rc = run_cmd(cmd_render, 5, argv, err, sizeof err, NULL);
    CHECK_MSG(rc == 2, "render %s %s: exit %d", option, value, rc);
    CHECK_MSG(strstr(err, option) && strstr(err, value), "render %s %s: message '%s'", option, value, err);
    CHECK_MSG(!strstr(err, "usage:"), "render %s %s: printed the usage instead of the reason", option, value);
}

static void test_bad_values_named(void)
{
    /* the values new users tried: each was silently taken as something else */
    bad_render("--size", "640x360x3");
    bad_render("--size", "0x480");
    bad_render("--size", "5000x480");
    bad_render("--depth", "24");
    bad_render("--max-error", "1e16");
    bad_render("--max-error", "nan");
    bad_render("--max-error", "inf");
    bad_render("--max-error", "-3");
    bad_render("--pixel-error", "0.001");
    bad_render("--pixel-error", "8388609");
    bad_render("--fov", "abc");
    bad_render("--fov", "0x10");
    bad_render("--camera", "1,2,3");
    bad_render("--camera", "1,2,3,4,5,6,7");
    bad_render("--format", "rgb555");
    bad_render("--bands", "-1");
    bad_render("--bands", "2.5");
    bad_render("--ambient", "2");
    bad_render("--zscale", "0");
    bad_render("--png-encoding", "jpeg");
}

static void test_budget_and_unknown(void)
{
    char dem[] = "assets/N47E009.hgt.gz", b[] = "--budget", v[] = "1e9", bogus[] = "--bogus", err[1024];
    char *argv[3];
    argv[0] = dem; argv[1] = b; argv[2] = v;
    CHECK_EQ(run_cmd(cmd_mesh, 3, argv, err, sizeof err, NULL), 2);
    CHECK(strstr(err, "--budget") && strstr(err, "1e9"));
    argv[1] = bogus;
    CHECK_EQ(run_cmd(cmd_mesh, 2, argv, err, sizeof err, NULL), 2);
    CHECK(strstr(err, "--bogus") != NULL);
    /* a value missing at the end of the line */
    argv[1] = b;
    CHECK_EQ(run_cmd(cmd_mesh, 2, argv, err, sizeof err, NULL), 2);
    CHECK(strstr(err, "--budget") && strstr(err, "needs a value"));
}

/* `mesh --json --max-error E` triangles: never more for a larger error, up to the top of
 * the accepted range (1e16 used to wrap round to the finest mesh). */
static long mesh_tris(const char *maxerr)
{
    char dem[] = "assets/N47E009.hgt.gz", me[] = "--max-error", js[] = "--json", err[1024], out[256], line[512];
    char *argv[4];
    long tri = -1;
    FILE *f;
    snprintf(out, sizeof out, "%s/opts_mesh.json", t_outdir());
    argv[0] = dem; argv[1] = me; argv[2] = (char *)maxerr; argv[3] = js;
    if (run_cmd(cmd_mesh, 4, argv, err, sizeof err, out) != 0) return -1;
    f = fopen(out, "r");
    if (f && fgets(line, sizeof line, f)) sscanf(line, "{\"triangles\": %ld", &tri);
    if (f) fclose(f);
    return tri;
}

static void test_monotone_error(void)
{
    const char *e[] = { "5", "50", "500", "5000", "100000" };
    long prev = -1;
    size_t i;
    for (i = 0; i < sizeof e / sizeof e[0]; i++) {
        long t = mesh_tris(e[i]);
        CHECK_MSG(t > 0, "--max-error %s: no mesh", e[i]);
        if (prev >= 0) CHECK_MSG(t <= prev, "--max-error %s: %ld triangles, more than %ld", e[i], t, prev);
        prev = t;
    }
}

static void test_mesh_output_checked_first(void)
{
    /* the input does not exist either: the output's message proves it is checked first */
    char missing[] = "tests/out/no_such_dem.hgt", o[] = "-o", obj[] = "/nonexistent/dir/x.obj", err[1024];
    char *argv[3];
    argv[0] = missing; argv[1] = o; argv[2] = obj;
    CHECK_EQ(run_cmd(cmd_mesh, 3, argv, err, sizeof err, NULL), 1);
    CHECK_MSG(strstr(err, "/nonexistent/dir/x.obj") && strstr(err, "cannot open"), "message '%s'", err);
}

static void test_parser_unit(void)
{
    int n = 0, flag = 0, choice = 0, size[2] = { 0, 0 }, npos = 0, step = 0;
    double x = 0, v3[3] = { 0, 0, 0 };
    const char *pos[4];
    const opt_spec t[] = {
        { "--n", OPT_INT, &n, -5, 5, 0, NULL, "N", "n", NULL },
        { "--x", OPT_NUM, &x, 0, 1, 0, NULL, "X", "x", NULL },
        { "--f", OPT_FLAG, &flag, 0, 0, 0, NULL, NULL, "f", NULL },
        { "--c", OPT_CHOICE, &choice, 0, 0, 0, "a|bb|c", "C", "c", NULL },
        { "--s", OPT_SIZE, size, 1, 100, 0, NULL, "WxH", "s", NULL },
        { "--v", OPT_NUMS, v3, -10, 10, 3, NULL, "A,B,C", "v", NULL },
        { "--full", OPT_INT_OPT, &step, 1, 64, 0, NULL, "[STEP]", "full", NULL },
        OPT_END
    };
    const opt_spec *const tabs[] = { t, NULL };
    char a0[] = "in1", a1[] = "--n", a2[] = "-5", a3[] = "--c", a4[] = "bb", a5[] = "--s", a6[] = "3x4", a7[] = "--v",
         a8[] = "1,-2.5,3e0", a9[] = "--f", a10[] = "--full", a11[] = "in2", a12[] = "--x", a13[] = "0.5";
    char *ok[] = { a0, a1, a2, a3, a4, a5, a6, a7, a8, a9, a10, a11, a12, a13 };
    CHECK_EQ(opt_parse("t", "", tabs, 14, ok, pos, 4, &npos), OPT_OK);
    CHECK_EQ(n, -5); CHECK_EQ(choice, 1); CHECK_EQ(size[0], 3); CHECK_EQ(size[1], 4); CHECK_EQ(flag, 1);
    CHECK(v3[0] == 1 && v3[1] == -2.5 && v3[2] == 3);
    CHECK_EQ(step, 1);               /* --full without a number: its lowest value */
    CHECK(x == 0.5);
    CHECK_EQ(npos, 2);
    CHECK(npos == 2 && !strcmp(pos[0], "in1") && !strcmp(pos[1], "in2"));
    {
        char b0[] = "--n", b1[] = "6", b2[] = "--s", b3[] = "3x4x5", b4[] = "--v", b5[] = "1,2", b6[] = "--x",
             b7[] = "1.5", b8[] = "--c", b9[] = "b", b10[] = "--n", b11[] = "1.5", b12[] = "--x", b13[] = "0x1p-1";
        char *bad[][2] = { { b0, b1 }, { b2, b3 }, { b4, b5 }, { b6, b7 }, { b8, b9 }, { b10, b11 }, { b12, b13 } };
        size_t i;
        for (i = 0; i < sizeof bad / sizeof bad[0]; i++) {
            CHECK_MSG(opt_parse("t", "", tabs, 2, bad[i], pos, 4, &npos) == OPT_ERR, "%s %s taken", bad[i][0],
                      bad[i][1]);
        }
    }
}

/* A file name given twice is refused (the second would silently replace the first); a
 * list option (bench's --dem) keeps every value in order, up to its room. */
static void test_strings(void)
{
    const char *file = "default.png", *list_v[2], *pos[1];
    opt_strs list = { list_v, 0, 2 };
    int npos = 0;
    const opt_spec t[] = {
        { "-o", OPT_STR, &file, 0, 0, 0, NULL, "OUT", "o", NULL },
        { "--dem", OPT_STRS, &list, 0, 0, 0, NULL, "FILE", "dem", NULL },
        OPT_END
    };
    const opt_spec *const tabs[] = { t, NULL };
    char a0[] = "-o", a1[] = "a.png", a2[] = "--dem", a3[] = "x.hgt", a4[] = "--dem", a5[] = "y.hgt", a6[] = "-o",
         a7[] = "b.png", a8[] = "--dem", a9[] = "z.hgt";
    char *one[] = { a0, a1, a2, a3, a4, a5 };
    char *twice[] = { a0, a1, a6, a7 };
    char *three[] = { a2, a3, a4, a5, a8, a9 };
    CHECK_EQ(opt_parse("t", "", tabs, 6, one, pos, 1, &npos), OPT_OK);
    CHECK(!strcmp(file, "a.png"));
    CHECK(list.n == 2 && !strcmp(list_v[0], "x.hgt") && !strcmp(list_v[1], "y.hgt"));
    file = "default.png";
    CHECK_EQ(opt_parse("t", "", tabs, 4, twice, pos, 1, &npos), OPT_ERR);
    list.n = 0;
    CHECK_EQ(opt_parse("t", "", tabs, 6, three, pos, 1, &npos), OPT_ERR);
}

static void test_version(void)
{
    FILE *p = popen("./bitrain --version", "r");
    char line[128] = "";
    CHECK(p != NULL);
    if (!p) return;
    if (!fgets(line, sizeof line, p)) line[0] = 0;
    CHECK_EQ(pclose(p), 0);
    CHECK_MSG(!strncmp(line, "bitrain ", 8) && line[8] >= '0' && line[8] <= '9', "'%s'", line);
}

int main(void)
{
    T_RUN(test_parser_unit);
    T_RUN(test_strings);
    T_RUN(test_bad_values_named);
    T_RUN(test_budget_and_unknown);
    T_RUN(test_monotone_error);
    T_RUN(test_mesh_output_checked_first);
    if (!t_emulated()) T_RUN(test_version);   /* runs ./bitrain, built for the host only */
    else t_skip("test_version", "runs ./bitrain, built for the host only");
    return t_finish();
}
