/* test_report.c — report writers (JSON parses back with the documented
 * fields, CSV has the documented columns, timing only on request), atomic
 * writes (a failed write leaves no file behind) and the progress display
 * (nothing when disabled, rate limited by a fake clock). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <glib/gstdio.h>
#include <errno.h>
#include <signal.h>
#include <string.h>
#include <sys/resource.h>

#include "sim/core/datapath.h"
#include "sim/output/json.h"
#include "sim/output/provenance.h"
#include "sim/output/progress.h"
#include "sim/raster/image.h"
#include <sys/stat.h>
#include "sim/app/run/report.h"

/* A small hand-made result: 2 frames, 2 nodes, 2 phases, one metric. */
static SimResult *sample(void)
{
    SimResult *r = sim_result_new("demo", "m,1");
    r->seed = 3;
    r->elapsed = 4 * SIM_MS;
    sim_result_add_frame(r, 1 * SIM_MS);
    sim_result_add_frame(r, 3 * SIM_MS + 1);
    g_ptr_array_add(r->phases, g_strdup("compute"));
    g_ptr_array_add(r->phases, g_strdup("send"));
    SimNodeResult *a = sim_result_add_node(r, "a", "gp");
    sim_busy_add(&a->busy, 0, 1 * SIM_MS);
    sim_busy_add(&a->busy, 1, 1 * SIM_MS);
    sim_result_add_node(r, "b", "gp");
    r->comm_bytes = 100;
    r->comm_messages = 2;
    r->busiest_link = g_strdup("a->b");
    r->busiest_link_bytes = 60;
    sim_result_set_metric(r, "rate \"x\"", 0.1, "1/s");
    r->events = 10;
    r->wall_s = 0.5;
    return r;
}

static void test_json(void **state)
{
    (void)state;
    SimResult *r = sample();
    char *text = rpt_render(r, RPT_JSON, FALSE);
    GError *e = NULL;
    JsonNode *v = js_parse(text, -1, "result.json", &e);
    if (!v)
        fail_msg("%s\n%s", e->message, text);
    assert_string_equal(js_str(js_get(v, "machine")), "m,1");
    assert_true(js_num(js_get(v, "elapsed_s")) == 0.004);
    JsonNode *fr = js_get(v, "frames");
    assert_int_equal(js_len(js_get(fr, "times_s")), 2);
    /* the double nearest the picosecond time reads back exactly */
    assert_true(js_num(js_at(js_get(fr, "times_s"), 1)) == 0.003000000001);
    JsonNode *n0 = js_at(js_get(v, "nodes"), 0);
    assert_true(js_num(js_get(n0, "utilisation")) == 0.5);
    JsonNode *send = js_get(js_get(n0, "phases"), "send");
    assert_true(js_num(js_get(send, "utilisation")) == 0.25);
    assert_string_equal(js_str(js_get(js_get(v, "comm"), "busiest_link")),
                        "a->b");
    JsonNode *m = js_at(js_get(v, "metrics"), 0);
    assert_string_equal(js_str(js_get(m, "name")), "rate \"x\"");
    JsonNode *sim = js_get(v, "sim");
    assert_true(js_num(js_get(sim, "events")) == 10);
    assert_null(js_get(sim, "wall_s")); /* only with timing */
    json_node_unref(v);
    g_free(text);
    text = rpt_render(r, RPT_JSON, TRUE);
    v = js_parse(text, -1, "result.json", &e);
    assert_non_null(v);
    assert_true(js_num(js_get(js_get(v, "sim"), "events_per_s")) == 20);
    json_node_unref(v);
    g_free(text);
    sim_result_free(r);
}

static void test_csv_and_text(void **state)
{
    (void)state;
    SimResult *r = sample();
    char *csv = rpt_render(r, RPT_CSV, FALSE);
    assert_true(g_str_has_prefix(csv, "section,name,phase,field,value,unit"
                                      "\n"));
    assert_non_null(strstr(csv, "\nrun,,,machine,\"m,1\",\n"));
    assert_non_null(strstr(csv, "\nframe,1,,time,0.003000000001,s\n"));
    assert_non_null(strstr(csv, "\nnode,a,send,utilisation,0.25,\n"));
    assert_non_null(strstr(csv, "\nmetric,\"rate \"\"x\"\"\",,value,0.1,"
                                "1/s\n"));
    assert_null(strstr(csv, "wall"));
    g_free(csv);
    csv = rpt_render(r, RPT_CSV, TRUE);
    assert_non_null(strstr(csv, "\nsim,,,wall,0.5,s\n"));
    g_free(csv);
    char *text = rpt_render(r, RPT_TEXT, TRUE);
    assert_non_null(strstr(text, "demo on m,1"));
    assert_non_null(strstr(text, "frames        2, mean 2.000 ms"));
    assert_non_null(strstr(text, "50.0%"));
    assert_non_null(strstr(text, "events/s"));
    g_free(text);
    RptFormat f;
    assert_true(rpt_format_parse("csv", &f));
    assert_int_equal(f, RPT_CSV);
    assert_false(rpt_format_parse("xml", &f));
    sim_result_free(r);
}

static guint dir_entries(const char *dir)
{
    GDir *d = g_dir_open(dir, 0, NULL);
    guint n = 0;
    while (g_dir_read_name(d))
        n++;
    g_dir_close(d);
    return n;
}

static void test_atomic(void **state)
{
    (void)state;
    char *dir = g_dir_make_tmp("pgsim-atomic-XXXXXX", NULL);
    char *path = g_build_filename(dir, "out.json", NULL);
    GError *e = NULL;
    assert_true(sim_file_write(path, "old", 3, &e));
    assert_true(sim_file_write(path, "new!", 4, &e));
    char *text = NULL;
    assert_true(g_file_get_contents(path, &text, NULL, NULL));
    assert_string_equal(text, "new!");
    g_free(text);
    assert_int_equal(dir_entries(dir), 1);
    /* the rename fails (target is a directory): no temporary is left */
    char *sub = g_build_filename(dir, "sub", NULL);
    assert_int_equal(g_mkdir(sub, 0755), 0);
    assert_false(sim_file_write(sub, "x", 1, &e));
    assert_int_equal(sim_error_exit_status(e), 2);
    assert_non_null(strstr(e->message, "expected a writable file"));
    g_clear_error(&e);
    assert_int_equal(dir_entries(dir), 2);
    /* a missing directory: nothing created anywhere */
    char *nodir = g_build_filename(dir, "none", "f.json", NULL);
    assert_false(sim_file_write(nodir, "x", 1, &e));
    g_clear_error(&e);
    assert_int_equal(dir_entries(dir), 2);
    /* rpt_write_dir writes the three files */
    SimResult *r = sample();
    char *outd = g_build_filename(dir, "o", NULL);
    assert_true(rpt_write_dir(r, outd, FALSE, &e));
    assert_int_equal(dir_entries(outd), 3);
    const char *names[] = {"summary.txt", "result.json", "result.csv"};
    for (int i = 0; i < 3; i++) {
        char *p = g_build_filename(outd, names[i], NULL);
        assert_int_equal(g_remove(p), 0);
        g_free(p);
    }
    sim_result_free(r);
    g_rmdir(outd);
    g_rmdir(sub);
    g_remove(path);
    assert_int_equal(g_rmdir(dir), 0);
    g_free(outd);
    g_free(nodir);
    g_free(sub);
    g_free(path);
    g_free(dir);
}

static char *file_text(const char *dir, const char *name)
{
    char *p = g_build_filename(dir, name, NULL), *text = NULL;
    assert_true(g_file_get_contents(p, &text, NULL, NULL));
    g_free(p);
    return text;
}

/* run --out over an earlier run's folder on a disk that fills after
 * summary.txt (issue 32; RLIMIT_FSIZE stands in for the full disk):
 * the folder stays wholly old, with no stray file, and the error carries
 * the system's reason. */
static void test_write_dir_all_or_nothing(void **state)
{
    (void)state;
    const char *names[] = {"summary.txt", "result.json", "result.csv"};
    char *dir = g_dir_make_tmp("pgsim-full-XXXXXX", NULL);
    char *old_d = g_build_filename(dir, "old", NULL);
    char *new_d = g_build_filename(dir, "new", NULL);
    SimResult *r1 = sample(), *r2 = sample();
    for (int i = 0; i < 2000; i++) /* new files larger than the old */
        sim_result_add_frame(r2, (SimTime)i * SIM_MS);
    GError *e = NULL;
    assert_true(rpt_write_dir(r1, old_d, FALSE, &e));
    assert_true(rpt_write_dir(r2, new_d, FALSE, &e));
    char *old_text[3];
    for (int i = 0; i < 3; i++)
        old_text[i] = file_text(old_d, names[i]);
    char *new_sum = file_text(new_d, names[0]);
    char *new_json = file_text(new_d, names[1]);
    assert_true(strlen(new_sum) < strlen(new_json));
    struct rlimit lim, was;
    assert_int_equal(getrlimit(RLIMIT_FSIZE, &was), 0);
    lim = was;
    lim.rlim_cur = strlen(new_sum) + 1; /* summary.txt fits, JSON not */
    void (*prev)(int) = signal(SIGXFSZ, SIG_IGN);
    assert_int_equal(setrlimit(RLIMIT_FSIZE, &lim), 0);
    gboolean ok = rpt_write_dir(r2, old_d, FALSE, &e);
    setrlimit(RLIMIT_FSIZE, &was);
    signal(SIGXFSZ, prev);
    assert_false(ok);
    if (!strstr(e->message, g_strerror(EFBIG)))
        fail_msg("got: %s", e->message);
    g_clear_error(&e);
    assert_int_equal(dir_entries(old_d), 3);
    for (int i = 0; i < 3; i++) {
        char *now = file_text(old_d, names[i]);
        if (strcmp(now, old_text[i]) != 0)
            fail_msg("%s changed: the folder mixes two runs", names[i]);
        g_free(now);
        g_free(old_text[i]);
    }
    g_free(new_sum);
    g_free(new_json);
    sim_result_free(r1);
    sim_result_free(r2);
    char *rm[] = {(char *)"rm", (char *)"-rf", dir, NULL};
    assert_true(g_spawn_sync(NULL, rm, NULL, G_SPAWN_SEARCH_PATH, NULL, NULL,
                             NULL, NULL, NULL, NULL));
    g_free(old_d);
    g_free(new_d);
    g_free(dir);
}

/* Text reports scale times and sizes like the header (issue 18, point
 * 11); JSON keeps the exact value. */
/* summary.txt ends with the provenance line (config, its SHA-256, the
 * overrides, seed and fidelity; no time of day, so two writes of one
 * result are the same bytes); stdout's text report has none. */
static void test_summary_provenance(void **state)
{
    (void)state;
    SimResult *r = sample();
    r->config_path = g_strdup("configs/demo.yaml");
    r->config_sha256 = g_strdup("ab12");
    g_free(r->fidelity);
    r->fidelity = g_strdup("flow");
    g_ptr_array_add(r->overrides, g_strdup("run.frames=2"));
    char *dir = g_dir_make_tmp("pgsim-sum-XXXXXX", NULL);
    char *path = g_build_filename(dir, "summary.txt", NULL);
    char *text[2] = {NULL, NULL};
    for (int i = 0; i < 2; i++) {
        assert_true(rpt_write_dir(r, dir, FALSE, NULL));
        assert_true(g_file_get_contents(path, &text[i], NULL, NULL));
    }
    assert_string_equal(text[0], text[1]);
    char *want = g_strdup_printf(
        "\nprovenance: pgsim %s; config configs/demo.yaml (sha256 ab12); "
        "overrides run.frames=2; seed 3; fidelity flow\n",
        prov_version());
    assert_true(g_str_has_suffix(text[0], want));
    char *out = rpt_render(r, RPT_TEXT, FALSE);
    assert_null(strstr(out, "provenance:"));
    assert_true(g_str_has_prefix(text[0], out));
    for (int i = 0; i < 3; i++) {
        char *p = g_build_filename(dir, i == 0   ? "summary.txt"
                                        : i == 1 ? "result.json"
                                                 : "result.csv",
                                   NULL);
        g_remove(p);
        g_free(p);
    }
    assert_int_equal(g_rmdir(dir), 0);
    g_free(out);
    g_free(want);
    g_free(text[0]);
    g_free(text[1]);
    g_free(path);
    g_free(dir);
    sim_result_free(r);
}

static void test_human_metrics(void **state)
{
    (void)state;
    SimResult *r = sample();
    sim_result_set_metric(r, "latency", 7.47891e-05, "s");
    sim_result_set_metric(r, "volume", 5.4e6, "B");
    sim_result_set_metric(r, "small", 512, "B");
    sim_result_set_metric(r, "phase_ms", 1500, "ms");
    char *t = rpt_render(r, RPT_TEXT, FALSE);
    assert_non_null(strstr(t, "latency                      74.789 us\n"));
    assert_non_null(strstr(t, "volume                       5.4 MB\n"));
    assert_non_null(strstr(t, "small                        512 B\n"));
    assert_non_null(strstr(t, "phase_ms                     1.500 s\n"));
    assert_null(strstr(t, "e-05"));
    char *j = rpt_render(r, RPT_JSON, FALSE);
    JsonNode *v = js_parse(j, -1, "result.json", NULL);
    JsonNode *m = js_at(js_get(v, "metrics"), 1);
    assert_string_equal(js_str(js_get(m, "name")), "latency");
    assert_true(js_num(js_get(m, "value")) == 7.47891e-05);
    json_node_unref(v);
    g_free(j);
    g_free(t);
    sim_result_free(r);
}

/* Above 32 processors the text gives min / mean / max per kind: 30 "gp"
 * busy 1..30 ms of 40 ms, 10 "rd" busy 2 ms each. */
static void test_kind_summary(void **state)
{
    (void)state;
    SimResult *r = sim_result_new("demo", "m");
    r->elapsed = 40 * SIM_MS;
    g_ptr_array_add(r->phases, g_strdup("work"));
    for (int i = 0; i < 40; i++) {
        char name[16];
        g_snprintf(name, sizeof name, "p%d", i);
        SimNodeResult *n = sim_result_add_node(r, name, i < 30 ? "gp" : "rd");
        sim_busy_add(&n->busy, 0, (i < 30 ? i + 1 : 2) * SIM_MS);
    }
    char *t = rpt_render(r, RPT_TEXT, FALSE);
    assert_non_null(strstr(t, "  min of 30    gp             2.5%       2.5%\n"));
    assert_non_null(strstr(t, "  mean of 30   gp            38.8%      38.8%\n"));
    assert_non_null(strstr(t, "  max of 30    gp            75.0%      75.0%\n"));
    assert_non_null(strstr(t, "  mean of 10   rd             5.0%       5.0%\n"));
    assert_null(strstr(t, "p31"));
    g_free(t);
    /* 32 or fewer: every processor by name */
    g_ptr_array_set_size(r->nodes, 32);
    t = rpt_render(r, RPT_TEXT, FALSE);
    assert_non_null(strstr(t, "  p31 "));
    assert_null(strstr(t, "mean of"));
    g_free(t);
    sim_result_free(r);
}

static unsigned mode_of(const char *path)
{
    GStatBuf st;
    assert_int_equal(g_stat(path, &st), 0);
    return st.st_mode & 0777;
}

/* Outputs are created with the user's umask (issue 18: PNGs were 0600,
 * results forced to 0644): 027 gives 0640, 002 gives 0664. */
static void test_file_modes(void **state)
{
    (void)state;
    char *dir = g_dir_make_tmp("pgsim-mode-XXXXXX", NULL);
    char *outd = g_build_filename(dir, "o", NULL);
    char *png = g_build_filename(dir, "f.png", NULL);
    char *json = g_build_filename(outd, "result.json", NULL);
    static const mode_t masks[] = {027, 002};
    static const unsigned want[] = {0640, 0664};
    SimResult *r = sample();
    RastImage *img = rast_image_new(4, 3);
    for (int i = 0; i < 2; i++) {
        mode_t old = umask(masks[i]);
        GError *e = NULL;
        assert_true(rpt_write_dir(r, outd, FALSE, &e));
        assert_true(rast_image_write_png(img, png, &e));
        umask(old);
        assert_int_equal(mode_of(json), want[i]);
        assert_int_equal(mode_of(png), want[i]);
        /* a rewrite takes the mode of the new file, not the old one */
        const char *names[] = {"summary.txt", "result.json", "result.csv"};
        for (int k = 0; k < 3; k++) {
            char *p = g_build_filename(outd, names[k], NULL);
            assert_int_equal(mode_of(p), want[i]);
            if (i == 1)
                g_remove(p);
            g_free(p);
        }
    }
    rast_image_free(img);
    sim_result_free(r);
    g_remove(png);
    g_rmdir(outd);
    assert_int_equal(g_rmdir(dir), 0);
    g_free(json);
    g_free(png);
    g_free(outd);
    g_free(dir);
}

static gint64 fake_now;

static gint64 fake_clock(void)
{
    return fake_now;
}

static void test_progress(void **state)
{
    (void)state;
    assert_null(rpt_progress_new_full(10, "x", NULL, NULL)); /* disabled */
    rpt_progress_update(NULL, 1);
    rpt_progress_finish(NULL);
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    fake_now = 0;
    RptProgress *p = rpt_progress_new_full(10, "run", f, fake_clock);
    rpt_progress_update(p, 1); /* first update draws */
    fake_now = 50000;
    rpt_progress_update(p, 2); /* 50 ms later: rate limited */
    fake_now = 100000;
    rpt_progress_update(p, 5); /* 100 ms: draws */
    rpt_progress_finish(p);    /* final line and newline */
    fclose(f);
    gchar **lines = g_strsplit(buf, "\r", -1);
    assert_int_equal(g_strv_length(lines), 4); /* "", 1, 5, final */
    assert_non_null(strstr(lines[1], "run:  10% (1/10)"));
    assert_non_null(strstr(lines[2], "run:  50% (5/10)"));
    assert_true(g_str_has_suffix(lines[3], "\n"));
    g_strfreev(lines);
    free(buf);
}

static void test_progress_note_eta(void **state)
{
    (void)state;
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    fake_now = 0;
    RptProgress *p = rpt_progress_new_full(4, "sweep", f, fake_clock);
    rpt_progress_note(p, "1 failed");
    fake_now = 2000000;
    rpt_progress_update(p, 1); /* 2 s for 1 of 4: 6 s to go */
    rpt_progress_finish(p);
    fclose(f);
    assert_non_null(strstr(buf, "sweep:  25% (1/4), 1 failed, 2.0 s, "
                                "ETA 0:06"));
    free(buf);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_json),
        cmocka_unit_test(test_csv_and_text),
        cmocka_unit_test(test_atomic),
        cmocka_unit_test(test_write_dir_all_or_nothing),
        cmocka_unit_test(test_file_modes),
        cmocka_unit_test(test_human_metrics),
        cmocka_unit_test(test_kind_summary),
        cmocka_unit_test(test_summary_provenance),
        cmocka_unit_test(test_progress),
        cmocka_unit_test(test_progress_note_eta),
    };
    return cmocka_run_group_tests_name("report", tests, NULL, NULL);
}
