/* test_wl_memory.c — each workload's own memory estimate (WlOps.mem_bytes)
 * is checked when a config is loaded: an oversized workload section is
 * refused before anything runs, with an error located at the section and
 * naming the workload's estimate; the same config at its shipped size
 * passes the same limit; `pgsim validate` and `run` exit 2 and write
 * nothing. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>
#include <sys/wait.h>
#include <glib/gstdio.h>

#include "sim/run/run.h"
#include "sim/core/error.h"
#include "sim/core/memlimit.h"
#include "sim/workload/pixelmerge/pm_pixels.h"
#include "sim/workload/workload.h"

typedef struct {
    const char *config;  /* under configs/ */
    const char *name;    /* workload */
    const char *big[3];  /* overrides past the limit, NULL-ended */
    const char *sizes;   /* what the error names, inside "(...)" */
    guint64 limit_mib;   /* the limit of both halves */
    gboolean check_fits; /* also load the shipped size (fast scenes only) */
} WlMemCase;

static const WlMemCase cases[] = {
    {"tokenring.yaml", "tokenring", {"workload.nodes=1000000"},
     "1000000 nodes", 16, TRUE},
    {"quickstart.yaml", "pixelmerge",
     {"workload.resolution=4096", "workload.processors=1024"},
     "1024 processors, 4096 x 4096 pixels", 64, TRUE},
    {"dpscan-cm200.yaml", "dpscan", {"workload.processors=4294967295"},
     "4294967295 processors, 1280 x 1024 pixels", 1024, FALSE},
    {"performer-town.yaml", "performer",
     {"workload.town.blocks=256", "workload.town.houses=256"},
     "a town of 256 x 256 blocks, 256 houses", 64, TRUE},
    {"sortfirst-vehicle.yaml", "sortfirst",
     {"workload.resolution=4096", "workload.grid=1024"},
     "16 processors, 4096 x 4096 pixels, grid 1024", 64, FALSE},
    {"argus-march.yaml", "argus",
     {"workload.width=4096", "workload.height=4096"},
     "4096 x 4096 pixels", 128, FALSE},
};

/* The line of "workload:" in path + 1: where the section's map starts. */
static int section_line(const char *path)
{
    char *text = NULL;
    assert_true(g_file_get_contents(path, &text, NULL, NULL));
    char **lines = g_strsplit(text, "\n", -1);
    int at = 0;
    for (int i = 0; lines[i] && !at; i++)
        if (g_str_has_prefix(lines[i], "workload:"))
            at = i + 2;
    g_strfreev(lines);
    g_free(text);
    assert_true(at > 0);
    return at;
}

static void test_oversized_refused(void **state)
{
    (void)state;
    for (size_t i = 0; i < G_N_ELEMENTS(cases); i++) {
        const WlMemCase *c = &cases[i];
        char *path = g_build_filename("configs", c->config, NULL);
        sim_mem_set_limit(c->limit_mib << 20);
        GError *err = NULL;
        CfgRun *r = cfg_run_load(path, c->big, &err);
        if (r)
            fail_msg("%s: loaded past a %" G_GUINT64_FORMAT " MiB limit",
                     c->config, c->limit_mib);
        assert_true(g_error_matches(err, SIM_ERROR, SIM_ERROR_INPUT));
        char *want = g_strdup_printf("%s:%d:3: found workload %s's own state "
                                     "(%s",
                                     path, section_line(path), c->name,
                                     c->sizes);
        if (!g_str_has_prefix(err->message, want) ||
            !strstr(err->message, "needing about"))
            fail_msg("%s: got '%s', want a start '%s'", c->config, err->message,
                     want);
        g_free(want);
        g_clear_error(&err);
        if (c->check_fits) { /* the shipped size passes the same limit */
            r = cfg_run_load(path, NULL, &err);
            if (!r)
                fail_msg("%s refused: %s", c->config, err->message);
            cfg_run_free(r);
        }
        g_free(path);
    }
    sim_mem_set_limit(0);
}

/* pphigs: the database it generates counts; 1485 polygons of the flock
 * need about 1.5 MiB (512 B a triangle, two a quad), over 1 MiB and
 * under 8 MiB. */
static void test_pphigs_database(void **state)
{
    (void)state;
    GError *err = NULL;
    sim_mem_set_limit(1 << 20);
    CfgRun *r = cfg_run_load("configs/pphigs-flock.yaml", NULL, &err);
    assert_null(r);
    assert_non_null(strstr(err->message, "found workload pphigs's own state "
                                         "(a database of 1485 polygons"));
    g_clear_error(&err);
    sim_mem_set_limit(8 << 20);
    r = cfg_run_load("configs/pphigs-flock.yaml", NULL, &err);
    assert_non_null(r);
    cfg_run_free(r);
    sim_mem_set_limit(0);
}

/* The binary: validate and run refuse with exit 2; run writes nothing. */
static void test_binary(void **state)
{
    (void)state;
    const char *bin =
        g_getenv("PGSIM_SANITIZE") ? "build-san/pgsim" : "build/pgsim";
    char *dir = g_dir_make_tmp("pgsim-wlmem-XXXXXX", NULL);
    char *out = g_build_filename(dir, "o", NULL);
    const char *cmds[] = {"validate", "run"};
    for (size_t i = 0; i < G_N_ELEMENTS(cmds); i++) {
        char *line = g_strdup_printf("%s %s configs/tokenring.yaml --set "
                                     "workload.nodes=1000000 --mem-limit 16M "
                                     "--out %s",
                                     bin, cmds[i], out);
        if (i == 0) /* validate takes no --out */
            *strstr(line, " --out") = '\0';
        char *so = NULL, *se = NULL;
        int wait = 0;
        assert_true(g_spawn_command_line_sync(line, &so, &se, &wait, NULL));
        assert_true(WIFEXITED(wait));
        assert_int_equal(WEXITSTATUS(wait), 2);
        if (!strstr(se, "configs/tokenring.yaml:7:3: found workload "
                        "tokenring's own state (1000000 nodes) needing about"))
            fail_msg("%s: stderr '%s'", cmds[i], se);
        g_free(so);
        g_free(se);
        g_free(line);
    }
    assert_false(g_file_test(out, G_FILE_TEST_EXISTS));
    g_rmdir(dir);
    g_free(out);
    g_free(dir);
}

/* The estimate of a workload section (YAML flow map), via its op. */
static double estimate(const char *section)
{
    GError *err = NULL;
    CfgNode *n = cfg_load_string(section, "w.yaml", &err);
    assert_non_null(n);
    const WlOps *w = wl_find(cfg_scalar(cfg_get(n, "type")));
    assert_non_null(w);
    void *p = w->parse(n, &err);
    if (!p)
        fail_msg("%s: %s", section, err->message);
    GString *what = g_string_new(NULL);
    double b = w->mem_bytes(p, what);
    g_string_free(what, TRUE);
    w->free_params(p);
    cfg_free(n);
    return b;
}

/* The documented terms (docs/config.md, Limits): the serial reference of
 * check_image costs one more frame, flatten one more copy of the town,
 * and a token-ring node a fixed record. */
static void test_estimate_terms(void **state)
{
    (void)state;
    double on = estimate("{type: pixelmerge, resolution: 512, processors: 4}");
    double off = estimate("{type: pixelmerge, resolution: 512, processors: 4, "
                          "check_image: false}");
    assert_true(on - off == 512.0 * 512 * sizeof(WlPmPixel));
    assert_true(off > 512.0 * 512 * (2 * sizeof(WlPmPixel) + 3));
    on = estimate("{type: sortfirst, resolution: 512}");
    off = estimate("{type: sortfirst, resolution: 512, check_image: false}");
    assert_true(on - off == 512.0 * 512 * 16);
    double t1 = estimate("{type: tokenring, nodes: 1000}");
    double t2 = estimate("{type: tokenring, nodes: 2000}");
    assert_true(t2 == 2 * t1 && t1 > 1000 * 256.0);
    double f1 = estimate("{type: performer, flatten: false, town: {blocks: 4}}");
    double f2 = estimate("{type: performer, flatten: true, town: {blocks: 4}}");
    assert_true(f2 > f1 && f2 < 2 * f1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_oversized_refused),
        cmocka_unit_test(test_pphigs_database),
        cmocka_unit_test(test_binary),
        cmocka_unit_test(test_estimate_terms),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
