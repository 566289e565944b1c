/* test_rp_driver.c — the reproduction driver: paper files, the join,
 * relative errors, the summary, CSV/JSON output, the provenance each
 * output carries, and located errors.
 * Uses a fake reproduction that is not registered in rp_all. */
#include "sim/output/json.h"
#include <glib/gstdio.h>
#include "sim/reproduce/rp_doc.h"
#include "sim/reproduce/rp_driver.h"
#include "sim/reproduce/rp_speed.h"
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include <cmocka.h>

static const char paper_yaml[] =
    "paper: {name: fake, citation: \"A. Author, Fake results, 1990\"}\n"
    "cells:\n"
    "  - {table: \"1\", row: a, column: t_ms, value: 10, unit: ms}\n"
    "  - {table: \"1\", row: b, column: t_ms, value: 12, unit: ms}\n"
    "  - {table: \"1\", row: c, column: t_ms, withheld: true,\n"
    "     note: prediction}\n"
    "  - {table: \"2\", row: y, column: speedup, value: 4}\n";

/* sim values scale with fidelity so the passes differ. */
static gboolean fake_run(const RpContext *ctx, GPtrArray *rows, GError **err)
{
    (void)err;
    double k = strcmp(ctx->fidelity, "packet") == 0 ? 1.0
               : strcmp(ctx->fidelity, "flow") == 0 ? 1.1
                                                    : 1.5;
    g_ptr_array_add(rows, rp_row_new("1", "a", "t_ms", 11.0 * k, NULL));
    g_ptr_array_add(rows, rp_row_new("1", "b", "t_ms", 9.0 * k, NULL));
    g_ptr_array_add(rows, rp_row_new("1", "c", "t_ms", 5.0 * k, NULL));
    g_ptr_array_add(rows, rp_row_new("2", "x", "speedup", 3.0, "extra"));
    return TRUE;
}

static gboolean failing_run(const RpContext *ctx, GPtrArray *rows, GError **err)
{
    (void)ctx;
    (void)rows;
    g_set_error(err, SIM_ERROR, SIM_ERROR_INTERNAL, "model exploded");
    return FALSE;
}

static const RpPaperOps fake = {.name = "fake",
                                .citation = "test only",
                                .setup = "setup.yaml",
                                .rows = fake_run};
static const RpPaperOps failing = {.name = "fake",
                                   .citation = "test only",
                                   .setup = "setup.yaml",
                                   .rows = failing_run};

static char *tmpdir_with(const char *name, const char *text)
{
    char *dir = g_dir_make_tmp("pgsim-rp-XXXXXX", NULL);
    g_assert_nonnull(dir);
    char *sub = g_build_filename(dir, name, NULL);
    g_assert_true(g_mkdir(sub, 0755) == 0);
    g_free(sub);
    char *path = rp_paper_path(dir, name);
    g_assert_true(g_file_set_contents(path, text, -1, NULL));
    g_free(path);
    path = rp_paper_file(dir, name, "setup.yaml");
    g_assert_true(g_file_set_contents(path, "setup: {n: 1}\n", -1, NULL));
    g_free(path);
    return dir;
}

static void rm_dir(char *dir, const char *name)
{
    char *path = rp_paper_path(dir, name);
    g_remove(path);
    g_free(path);
    path = rp_paper_file(dir, name, "setup.yaml");
    g_remove(path);
    g_free(path);
    char *sub = g_build_filename(dir, name, NULL);
    g_rmdir(sub);
    g_free(sub);
    g_rmdir(dir);
    g_free(dir);
}

static RpTable *drive(const char *fidelity, char **dir_out)
{
    char *dir = tmpdir_with("fake", paper_yaml);
    RpContext ctx = {.fidelity = fidelity, .quiet = TRUE};
    GError *err = NULL;
    RpTable *t = rp_drive(&fake, dir, &ctx, &err);
    g_assert_no_error(err);
    *dir_out = dir;
    return t;
}

static void test_join_errors(void **state)
{
    (void)state;
    char *dir;
    RpTable *t = drive("packet", &dir);
    assert_int_equal(t->cells->len, 5);
    const RpJoined *a = rp_table_find(t, "1", "a", "t_ms");
    const RpJoined *b = rp_table_find(t, "1", "b", "t_ms");
    const RpJoined *c = rp_table_find(t, "1", "c", "t_ms");
    const RpJoined *x = rp_table_find(t, "2", "x", "speedup");
    const RpJoined *y = rp_table_find(t, "2", "y", "speedup");
    assert_true(fabs(a->rel_error - 0.1) < 1e-12);
    assert_true(fabs(b->rel_error + 0.25) < 1e-12);
    assert_int_equal(c->status, RP_WITHHELD);
    assert_true(isnan(c->published) && isnan(c->rel_error));
    assert_int_equal(x->status, RP_UNLISTED);
    assert_int_equal(y->status, RP_MISSING);
    assert_true(isnan(y->sim));
    assert_string_equal(a->unit, "ms");
    assert_string_equal(c->note, "prediction");
    /* the rows' order, then the cell the reproduction did not make */
    assert_ptr_equal(g_ptr_array_index(t->cells, 4), y);
    rp_table_free(t);
    rm_dir(dir, "fake");
}

static void test_summary(void **state)
{
    (void)state;
    char *dir;
    RpTable *t = drive("packet", &dir);
    assert_int_equal(t->compared, 2);
    assert_true(fabs(t->mean_abs - 0.175) < 1e-12);
    assert_true(fabs(t->worst_abs - 0.25) < 1e-12);
    GString *s = g_string_new(NULL);
    rp_table_summary(t, s);
    assert_string_equal(s->str, "mean |rel_error| 17.5% over 2 cells, "
                                "worst 25.0% (table 1, b, t_ms)");
    g_string_truncate(s, 0);
    rp_table_text(t, s);
    char *setup = rp_paper_file(dir, "fake", "setup.yaml");
    char *sha = g_compute_checksum_for_string(G_CHECKSUM_SHA256,
                                              "setup: {n: 1}\n", -1);
    char *line = g_strdup_printf("\nprovenance: pgsim %s; config %s (sha256 "
                                 "%s); overrides none; seed %d; fidelity "
                                 "packet\n",
                                 prov_version(), setup, sha, RP_SEED);
    assert_non_null(strstr(s->str, line));
    g_free(line);
    g_free(sha);
    g_free(setup);
    assert_non_null(strstr(s->str, "withheld"));
    assert_non_null(strstr(s->str, "+10.0%"));
    assert_non_null(strstr(s->str, "not simulated"));
    g_string_free(s, TRUE);
    rp_table_free(t);
    rm_dir(dir, "fake");
}

/* The provenance comment lines of the fake paper's CSV at a fidelity:
 * the setup file written by tmpdir_with() and the SHA-256 of its bytes. */
static char *prov_comments(const char *dir, const char *fidelity)
{
    char *setup = rp_paper_file(dir, "fake", "setup.yaml");
    char *sha = g_compute_checksum_for_string(G_CHECKSUM_SHA256,
                                              "setup: {n: 1}\n", -1);
    char *c = g_strdup_printf(
        "# pgsim_version: %s\n# config: %s\n# config_sha256: %s\n"
        "# seed: %d\n# fidelity: %s\n"
        "# effective_config: {\"setup\":{\"n\":\"1\"}}\n",
        prov_version(), setup, sha, RP_SEED, fidelity);
    g_free(sha);
    g_free(setup);
    return c;
}

static void test_csv(void **state)
{
    (void)state;
    char *dir;
    RpTable *t = drive("packet", &dir);
    GString *s = g_string_new(NULL);
    rp_table_csv(t, TRUE, s);
    char *prov = prov_comments(dir, "packet");
    assert_true(g_str_has_prefix(s->str, prov));
    g_string_erase(s, 0, (gssize)strlen(prov));
    g_free(prov);
    assert_string_equal(s->str,
                        "paper,table,row,column,sim,published,rel_error\n"
                        "fake,1,a,t_ms,11,10,0.1\n"
                        "fake,1,b,t_ms,9,12,-0.25\n"
                        "fake,1,c,t_ms,5,,\n"
                        "fake,2,x,speedup,3,,\n"
                        "fake,2,y,speedup,,4,\n");
    g_string_free(s, TRUE);
    rp_table_free(t);
    rm_dir(dir, "fake");
}

static void test_json(void **state)
{
    (void)state;
    char *dir;
    RpTable *t = drive("flow", &dir);
    GString *s = g_string_new(NULL);
    rp_table_json(t, s);
    GError *err = NULL;
    JsonNode *v = js_parse(s->str, (gssize)s->len, "rp.json", &err);
    g_assert_no_error(err);
    assert_string_equal(js_str(js_get(v, "paper")), "fake");
    assert_string_equal(js_str(js_get(v, "fidelity")), "flow");
    JsonNode *cells = js_get(v, "cells");
    assert_int_equal(js_len(cells), 5);
    JsonNode *a = js_at(cells, 0);
    assert_true(fabs(js_num(js_get(a, "sim")) - 12.1) < 1e-12);
    assert_true(js_is_null(js_get(js_at(cells, 2), "published")));
    JsonNode *sum = js_get(v, "summary");
    assert_int_equal((int)js_num(js_get(sum, "compared")), 2);
    JsonNode *prov = js_get(v, "provenance");
    assert_true(g_str_has_suffix(js_str(js_get(prov, "config")), "setup.yaml"));
    assert_int_equal(strlen(js_str(js_get(prov, "config_sha256"))), 64);
    assert_int_equal((int)js_num(js_get(prov, "seed")), RP_SEED);
    assert_string_equal(js_str(js_get(prov, "fidelity")), "flow");
    assert_non_null(js_get(js_get(prov, "effective_config"), "setup"));
    json_node_unref(v);
    g_string_free(s, TRUE);
    rp_table_free(t);
    rm_dir(dir, "fake");
}

/* A paper found through a data root ($PGSIM_DATA here; the binary's
 * <exe>/.. in a build tree) is named in the provenance as asked,
 * relative to that root, not as "<root>/papers/fake/setup.yaml"; the
 * SHA-256 is still of the file read. */
static void test_setup_path_clean(void **state)
{
    (void)state;
    char *root = g_dir_make_tmp("pgsim-rp-XXXXXX", NULL);
    char *papers = g_build_filename(root, "papers", NULL);
    assert_int_equal(g_mkdir(papers, 0755), 0);
    g_rmdir(papers);
    char *made = tmpdir_with("fake", paper_yaml);
    assert_int_equal(g_rename(made, papers), 0);
    g_free(made);
    char *old = g_strdup(g_getenv("PGSIM_DATA"));
    g_setenv("PGSIM_DATA", root, TRUE);
    RpContext ctx = {.fidelity = "flow", .quiet = TRUE};
    GError *err = NULL;
    RpTable *t = rp_drive(&fake, "papers", &ctx, &err);
    g_assert_no_error(err);
    assert_string_equal(t->setup, "papers/fake/setup.yaml");
    char *file = g_build_filename(papers, "fake", "setup.yaml", NULL);
    char *sha = prov_file_sha256(file);
    assert_string_equal(t->setup_sha256, sha);
    assert_null(strstr(t->setup, root));
    if (old)
        g_setenv("PGSIM_DATA", old, TRUE);
    else
        g_unsetenv("PGSIM_DATA");
    rp_table_free(t);
    rm_dir(papers, "fake");
    assert_int_equal(g_rmdir(root), 0);
    g_free(sha);
    g_free(file);
    g_free(old);
    g_free(root);
}

static void test_fidelities(void **state)
{
    (void)state;
    char *dir = tmpdir_with("fake", paper_yaml);
    RpContext ctx = {.fidelity = NULL, .quiet = TRUE};
    GError *err = NULL;
    GPtrArray *passes = rp_drive_fidelities(&fake, dir, &ctx, &err);
    g_assert_no_error(err);
    assert_int_equal(passes->len, 3);
    const RpTable *an = g_ptr_array_index(passes, 0);
    assert_string_equal(an->fidelity, "analytic");
    assert_true(fabs(rp_table_find(an, "1", "a", "t_ms")->sim - 16.5) < 1e-12);
    const RpTable *fl = g_ptr_array_index(passes, 1);
    const RpTable *pk = g_ptr_array_index(passes, 2);
    assert_true(fabs(rp_speed_mean_vs_ref(an, pk) - 0.375) < 1e-12);
    assert_true(fabs(rp_speed_mean_vs_ref(fl, pk) - 0.075) < 1e-12);
    assert_true(rp_speed_mean_vs_ref(pk, pk) == 0.0);
    GString *s = g_string_new(NULL);
    rp_speed_csv(passes, TRUE, s);
    /* each pass's rows follow its provenance; the header comes once,
     * after the first pass's */
    const char *fids[] = {"analytic", "flow", "packet"};
    for (int f = 0; f < 3; f++) {
        char *prov = prov_comments(dir, fids[f]);
        const char *at = strstr(s->str, prov);
        assert_non_null(at);
        if (f == 0) {
            assert_ptr_equal(at, s->str);
            g_string_erase(s, 0, (gssize)strlen(prov));
        }
        g_free(prov);
    }
    assert_true(g_str_has_prefix(s->str, "paper,table,row,column,sim,"
                                         "published,rel_error,fidelity,"
                                         "wall_s,rel_error_vs_packet\n"
                                         "fake,1,a,t_ms,16.5,10,0.65,"
                                         "analytic,"));
    assert_non_null(strstr(s->str, "fake,2,y,speedup,,4,,packet,"));
    g_string_truncate(s, 0);
    rp_speed_text(passes, s);
    assert_non_null(strstr(s->str, "speed against error"));
    g_string_free(s, TRUE);
    GError *e = NULL;
    char *cdir = g_dir_make_tmp("pgsim-rpc-XXXXXX", NULL);
    gboolean charted = rp_speed_chart(passes, cdir, &e);
    g_assert_no_error(e);
    assert_true(charted);
    char *png = g_build_filename(cdir, "fake-speed.png", NULL), *data;
    gsize len;
    assert_true(g_file_get_contents(png, &data, &len, NULL));
    assert_true(len > 8 && memcmp(data, "\x89PNG", 4) == 0);
    g_free(data);
    const char *ext[] = {".png", ".svg", ".gp", ".dat"};
    for (int i = 0; i < 4; i++) {
        char *f = g_strconcat(cdir, "/fake-speed", ext[i], NULL);
        assert_int_equal(g_remove(f), 0);
        g_free(f);
    }
    g_rmdir(cdir);
    g_free(cdir);
    g_free(png);
    g_ptr_array_free(passes, TRUE);
    rm_dir(dir, "fake");
}

static void expect_bad(const char *yaml, const char *where, const char *what)
{
    char *dir = tmpdir_with("fake", yaml);
    RpContext ctx = {.fidelity = "flow", .quiet = TRUE};
    GError *err = NULL;
    RpTable *t = rp_drive(&fake, dir, &ctx, &err);
    assert_null(t);
    assert_non_null(err);
    if (!strstr(err->message, where) || !strstr(err->message, what))
        fail_msg("unexpected error: %s", err->message);
    g_error_free(err);
    rm_dir(dir, "fake");
}

static void test_bad_papers(void **state)
{
    (void)state;
    expect_bad("paper: {name: fake}\n"
               "cells:\n"
               "  - {table: \"1\", row: a, column: t, value: 1}\n"
               "  - {table: \"1\", row: a, column: t, value: 2}\n",
               "fake/published.yaml:4:", "a second cell (1, a, t)");
    expect_bad("paper: {name: fake}\n"
               "cells:\n"
               "  - {table: \"1\", row: a, column: t}\n",
               "fake/published.yaml:3:", "'value: <number>' or 'withheld: true'");
    expect_bad("paper: {name: fake}\n"
               "cells:\n"
               "  - {table: \"1\", row: a, column: t, value: 1,\n"
               "     withheld: true}\n",
               "fake/published.yaml:3:", "either 'value' or 'withheld: true'");
    expect_bad("paper: {name: fake}\n"
               "cells:\n"
               "  - {table: \"1\", row: a, column: t, valu: 1}\n",
               "fake/published.yaml:3:", "valu");
    expect_bad("paper: {name: other}\ncells: []\n", "fake/published.yaml",
               "expected 'fake'");
}

static const char compact_yaml[] =
    "paper: fake\n"
    "citation: A. Author\n"
    "tables:\n"
    "  \"1\":\n"
    "    caption: Table 1.\n"
    "    rows:\n"
    "      a: {t_ms: 10}\n"
    "      b: {t_ms: {value: 12, unit: ms, note: read off}}\n"
    "      c: {t_ms: ~}\n"
    "  fig9: {caption: only a picture, rows: {}}\n"
    "cells:\n"
    "  - {table: \"2\", row: y, column: speedup, value: 4}\n";

static void test_compact_shape(void **state)
{
    (void)state;
    char *dir = tmpdir_with("fake", compact_yaml);
    RpContext ctx = {.fidelity = "packet", .quiet = TRUE};
    GError *err = NULL;
    RpTable *t = rp_drive(&fake, dir, &ctx, &err);
    g_assert_no_error(err);
    assert_string_equal(t->citation, "A. Author");
    assert_true(fabs(rp_table_find(t, "1", "a", "t_ms")->rel_error - 0.1) <
                1e-12);
    const RpJoined *b = rp_table_find(t, "1", "b", "t_ms");
    assert_string_equal(b->unit, "ms");
    assert_string_equal(b->note, "read off");
    assert_int_equal(rp_table_find(t, "1", "c", "t_ms")->status, RP_WITHHELD);
    assert_int_equal(rp_table_find(t, "2", "y", "speedup")->status, RP_MISSING);
    assert_int_equal(t->compared, 2);
    rp_table_free(t);
    rm_dir(dir, "fake");
    expect_bad("paper: fake\ntables:\n  \"1\":\n    rows:\n"
               "      a: {t_ms: 1O}\n",
               "fake/published.yaml:5:", "found '1O', expected a number or ~");
}

static void test_doc(void **state)
{
    (void)state;
    char *dir;
    RpTable *t = drive("packet", &dir);
    char *cdir = g_dir_make_tmp("pgsim-doc-XXXXXX", NULL);
    GError *err = NULL;
    assert_true(rp_doc_chart(t, cdir, &err));
    g_assert_no_error(err);
    GPtrArray *passes = g_ptr_array_new();
    g_ptr_array_add(passes, t);
    GHashTable *caps = g_hash_table_new(g_str_hash, g_str_equal);
    g_hash_table_insert(caps, "1", "Table 1. Times.");
    GString *md = g_string_new(NULL);
    rp_doc_paper(md, passes, caps, cdir, "reproduction");
    assert_non_null(strstr(md->str, "## fake\n"));
    char *setup = rp_paper_file(dir, "fake", "setup.yaml");
    char *want = g_strdup_printf("\n\nprovenance: pgsim %s; config %s (sha256 ",
                                 prov_version(), setup);
    assert_non_null(strstr(md->str, want));
    g_free(want);
    g_free(setup);
    GString *head = g_string_new(NULL);
    rp_doc_head(head, "packet");
    want = g_strdup_printf("`pgsim reproduce all --fidelity packet` (pgsim %s)",
                           prov_version());
    assert_non_null(strstr(head->str, want));
    g_string_free(head, TRUE);
    g_free(want);
    assert_non_null(strstr(md->str, "### Table 1\n\nTable 1. Times.\n"));
    assert_non_null(strstr(md->str, "| a | t_ms [ms] | 10 | 11 | +10.0% |"));
    assert_non_null(strstr(md->str, "| c | t_ms | *withheld* | 5 | |"));
    assert_non_null(strstr(md->str, "![simulated against published]"
                                    "(reproduction/fake-vs-published.png)"));
    const char *ext[] = {".png", ".svg", ".gp", ".dat"};
    for (int i = 0; i < 4; i++) {
        char *f = g_strconcat(cdir, "/fake-vs-published", ext[i], NULL);
        assert_int_equal(g_remove(f), 0);
        g_free(f);
    }
    g_rmdir(cdir);
    g_free(cdir);
    g_string_free(md, TRUE);
    g_hash_table_destroy(caps);
    g_ptr_array_free(passes, TRUE);
    rp_table_free(t);
    rm_dir(dir, "fake");
}

static void test_run_failure(void **state)
{
    (void)state;
    char *dir = tmpdir_with("fake", paper_yaml);
    RpContext ctx = {.fidelity = "packet", .quiet = TRUE};
    GError *err = NULL;
    assert_null(rp_drive(&failing, dir, &ctx, &err));
    assert_non_null(err);
    assert_string_equal(err->message, "fake (fidelity packet): model exploded");
    g_error_free(err);
    rm_dir(dir, "fake");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_join_errors),
        cmocka_unit_test(test_summary),
        cmocka_unit_test(test_csv),
        cmocka_unit_test(test_json),
        cmocka_unit_test(test_fidelities),
        cmocka_unit_test(test_setup_path_clean),
        cmocka_unit_test(test_bad_papers),
        cmocka_unit_test(test_run_failure),
        cmocka_unit_test(test_compact_shape),
        cmocka_unit_test(test_doc),
    };
    return cmocka_run_group_tests_name("reproduce", tests, NULL, NULL);
}
