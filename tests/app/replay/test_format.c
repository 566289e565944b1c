/* test_format.c — the trace reader: items and flags read back as
 * written (plain and gzip), located errors for each kind of bad input,
 * and a located error listing every cost a target lacks. */
#include "sim/app/replay/rpl_format.h"
#include "sim/app/replay/rpl_replay.h"
#include "sim/core/error.h"
#include <glib/gstdio.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include <cmocka.h>

static char *dir;

static char *put(const char *name, const char *text)
{
    char *p = g_build_filename(dir, name, NULL);
    assert_true(g_file_set_contents(p, text, -1, NULL));
    return p;
}

/* Reads every item of path; returns the error message or NULL. */
static char *read_all(const char *path, guint *items)
{
    GError *e = NULL;
    RplReader *r = rpl_reader_open(path, &e);
    RplItem it;
    *items = 0;
    while (r && rpl_reader_next(r, &it, &e))
        ++*items;
    rpl_reader_free(r);
    char *msg = e ? g_strdup(e->message) : NULL;
    g_clear_error(&e);
    return msg;
}

static const char good[] = "pgsim-trace 1\n"
                           "machine ipsc2\n"
                           "procs 4\n"
                           "kind node 0 4 16000000\n"
                           "phase compute\n"
                           "phase span\n"
                           "# a comment\n"
                           "at 0\n"
                           "c 0 1 span=10 zcmp=3 +\n"
                           "w 1 0 2500\n"
                           "on 0\n"
                           "s 0 3 1024 frame\n";

static void test_round_trip_gz(void **s)
{
    (void)s;
    char *src = put("good.pgt", good);
    char *gz = g_build_filename(dir, "copy.pgt.gz", NULL);
    GError *e = NULL;
    RplReader *r = rpl_reader_open(src, &e);
    g_assert_no_error(e);
    RplWriter *w = rpl_writer_open(gz, &e);
    rpl_write_header(w, rpl_reader_header(r));
    RplItem it;
    while (rpl_reader_next(r, &it, &e))
        rpl_write_item(w, &it);
    g_assert_no_error(e);
    assert_true(rpl_writer_close(w, &e));
    rpl_reader_free(r);
    r = rpl_reader_open(gz, &e);
    g_assert_no_error(e);
    assert_int_equal(rpl_reader_header(r)->procs, 4);
    assert_true(rpl_reader_next(r, &it, &e) && it.type == RPL_AT);
    assert_true(rpl_reader_next(r, &it, &e) && it.type == RPL_COMPUTE);
    assert_int_equal(it.n_ops, 2);
    assert_string_equal(it.op[1], "zcmp");
    assert_int_equal(it.count[0], 10);
    assert_true(it.handled && !it.frame);
    assert_true(rpl_reader_next(r, &it, &e) && it.type == RPL_WORK);
    assert_int_equal(it.value, 2500);
    assert_true(rpl_reader_next(r, &it, &e) && it.type == RPL_ON);
    assert_true(rpl_reader_next(r, &it, &e) && it.type == RPL_SEND);
    assert_true(it.frame && it.peer == 3 && it.value == 1024 && it.id == 2);
    assert_false(rpl_reader_next(r, &it, &e));
    g_assert_no_error(e);
    rpl_reader_free(r);
    /* the .gz file really is compressed: gzip's magic bytes */
    char *bytes;
    assert_true(g_file_get_contents(gz, &bytes, NULL, NULL));
    assert_true((guchar)bytes[0] == 0x1f && (guchar)bytes[1] == 0x8b);
    g_free(bytes);
    g_remove(gz);
    g_remove(src);
    g_free(gz);
    g_free(src);
}

typedef struct {
    const char *text;
    const char *where; /* "file:line:col" suffix expected in the message */
    const char *found;
} Bad;

static const Bad bads[] = {
    {"pgsim-trace 5\n", "t.pgt:1:13:", "found '5'"},
    /* version 4's joins: `after ID` names an earlier `&` action, once;
     * a `&` nobody is after; neither before version 4 */
    {"pgsim-trace 3\nprocs 2\nat 0\nw 0 0 5 &\n", "t.pgt:4:9:",
     "'+', 'frame'"},
    {"pgsim-trace 4\nprocs 2\nat 0\nw 0 0 5\nw 1 0 5 after 0\n",
     "t.pgt:5:15:", "an earlier action marked '&'"},
    {"pgsim-trace 4\nprocs 2\nat 0\nw 0 0 5 &\nw 1 0 5 after 0\n"
     "w 1 0 5 after 0\n",
     "t.pgt:6:15:", "no other 'after'"},
    {"pgsim-trace 4\nprocs 2\nat 0\nw 0 0 5 after 0 &\n", "t.pgt:4:15:",
     "an earlier action"},
    {"pgsim-trace 4\nprocs 2\nat 0\nw 0 0 5 after x\n", "t.pgt:4:15:",
     "an action id"},
    {"pgsim-trace 4\nprocs 2\nat 0\nw 0 0 5 &\n", "t.pgt:5:1:",
     "expected an action 'after 0'"},
    /* version 2's actions: b and v not in version 1; swap only on v, and
     * not with frame */
    {"pgsim-trace 1\nprocs 2\nat 0\nb 0 1 5\n", "t.pgt:4:1:",
     "'pgsim-trace 2'"},
    {"pgsim-trace 2\nprocs 2\nat 0\nv 0 0\n", "t.pgt:4:5:",
     "a period above 0"},
    {"pgsim-trace 2\nprocs 2\nat 0\nb 0 1 5 swap\n", "t.pgt:4:9:",
     "'swap' ends only a `v`"},
    {"pgsim-trace 2\nprocs 2\nat 0\nw 0 0 5 frame\nv 1 7 swap\n",
     "t.pgt:5:7:", "without 'frame'"},
    {"pgsim-trace 2\nprocs 2\nat 0\nv 1 7 swap\nw 0 0 5 frame\n",
     "t.pgt:5:9:", "has no 'frame'"},
    {"hello\n", "t.pgt:1:1:", "found 'hello'"},
    {"pgsim-trace 1\nprocs 2\nc 0 0 a=1\n", "t.pgt:3:1:", "'at TIME'"},
    {"pgsim-trace 1\nprocs 2\nat 0\nw 2 0 5\n", "t.pgt:4:3:", "below 2"},
    {"pgsim-trace 1\nprocs 2\nat 0\nw 1 1 5\n", "t.pgt:4:5:", "phase id"},
    {"pgsim-trace 1\nprocs 2\nat 0\nw 1 0 5 x\n", "t.pgt:4:9:", "'+'"},
    {"pgsim-trace 1\nprocs 2\nat 0\nw 1 0 5\non 0\n", "t.pgt:5:4:",
     "marked '+'"},
    {"pgsim-trace 1\nprocs 2\nat 0\nw 1 0 5 +\n", "t.pgt:5:1:",
     "expected 'on 0'"},
    {"pgsim-trace 1\nprocs 2\nat 0\nc 1 0 span\n", "t.pgt:4:7:", "OP=COUNT"},
    {"pgsim-trace 1\nprocs 2\nat 0\ns 1 0\n", "t.pgt:4:6:",
     "the end of the line"},
    {"pgsim-trace 1\nprocs 2\nat 0\nw 1 0 -5\n", "t.pgt:4:7:", "'-5'"},
};

static void test_located_errors(void **s)
{
    (void)s;
    for (guint i = 0; i < G_N_ELEMENTS(bads); i++) {
        char *p = put("t.pgt", bads[i].text);
        guint n;
        char *msg = read_all(p, &n);
        if (!msg || !strstr(msg, bads[i].where) ||
            !strstr(msg, bads[i].found))
            fail_msg("case %u: got '%s'", i, msg ? msg : "(no error)");
        g_free(msg);
        g_remove(p);
        g_free(p);
    }
}

static void test_long_line(void **s)
{
    (void)s;
    GString *t = g_string_new("pgsim-trace 1\nprocs 2\nat 0\nc 0 0");
    for (int i = 0; i < 1000; i++)
        g_string_append(t, " op=1");
    char *p = put("t.pgt", t->str);
    g_string_free(t, TRUE);
    guint n;
    char *msg = read_all(p, &n);
    assert_non_null(msg);
    assert_non_null(strstr(msg, "t.pgt:4:1: found a line longer"));
    g_free(msg);
    g_remove(p);
    g_free(p);
}

/* Named operations the target lacks are all listed, with where each is
 * first used; nothing runs. */
static void test_missing_costs(void **s)
{
    (void)s;
    char *p = put("ops.pgt", "pgsim-trace 1\nprocs 2\nphase compute\n"
                             "at 0\nc 0 0 span=4 warp=2\nc 1 0 warp=1 "
                             "teleport=3\n");
    RplReplayOpts o = {.trace = p, .machine = "ipsc2"};
    GError *e = NULL;
    SimResult *r = rpl_replay(&o, &e);
    assert_null(r);
    assert_non_null(e);
    assert_int_equal(e->code, SIM_ERROR_INPUT);
    assert_non_null(strstr(e->message, "ops.pgt:5:14: nodes.node.costs.warp"));
    assert_non_null(
        strstr(e->message, "ops.pgt:6:14: nodes.node.costs.teleport"));
    assert_null(strstr(e->message, "costs.span")); /* ipsc2 has span */
    g_error_free(e);
    g_remove(p);
    g_free(p);
}

/* A `sync` group waits for the work before it, wherever that ends: at
 * twice the clock it comes at half the recorded time (an `at` group
 * would stay at 5000 ps). */
static void test_sync_follows_work(void **s)
{
    (void)s;
    char *p = put("sync.pgt", "pgsim-trace 1\nmachine ipsc2\nprocs 3\n"
                              "kind node 0 3 16000000\nat 0\nw 0 0 1000\n"
                              "w 1 0 5000\nsync 5000\nw 2 0 10 frame\n");
    const char *fast[] = {"machine.nodes.node.clock=32 MHz", NULL};
    for (int k = 0; k < 2; k++) {
        RplReplayOpts o = {.trace = p, .machine = "ipsc2",
                           .sets = k ? fast : NULL};
        GError *e = NULL;
        SimResult *r = rpl_replay(&o, &e);
        g_assert_no_error(e);
        assert_int_equal(r->elapsed, k ? 2505 : 5010);
        assert_int_equal(g_array_index(r->frame_times, SimTime, 0),
                         k ? 2505 : 5010);
        sim_result_free(r);
    }
    g_remove(p);
    g_free(p);
}

/* Block keeps consecutive processors together, cyclic deals them out;
 * a map file puts them where it says, and a bad line is located. */
static void test_maps(void **s)
{
    (void)s;
    assert_int_equal(rpl_map_block(5, 8, 4), 2);
    assert_int_equal(rpl_map_cyclic(5, 8, 4), 1);
    assert_int_equal(rpl_map_block(3, 4, 16), 3);
    char *t = put("m.pgt", "pgsim-trace 1\nmachine ipsc2\nprocs 2\n"
                           "kind node 0 2 16000000\nat 0\nw 0 0 1000\n"
                           "w 1 0 3000\n");
    char *map = put("m.map", "# trace target\n0 5\n1 5\n");
    RplReplayOpts o = {.trace = t, .machine = "ipsc2", .map = map};
    GError *e = NULL;
    SimResult *r = rpl_replay(&o, &e);
    g_assert_no_error(e);
    assert_int_equal(r->nodes->len, 1); /* both on node5, one after the other */
    assert_string_equal(((SimNodeResult *)r->nodes->pdata[0])->name, "node5");
    assert_int_equal(r->elapsed, 4000);
    sim_result_free(r);
    g_free(map);
    map = put("m.map", "0 5\n1 99\n");
    o.map = map;
    assert_null(rpl_replay(&o, &e));
    assert_non_null(strstr(e->message, "m.map:2:3: found '99'"));
    g_clear_error(&e);
    g_remove(map);
    g_remove(t);
    g_free(map);
    g_free(t);
}

int main(void)
{
    dir = g_dir_make_tmp("pgsim-fmt-XXXXXX", NULL);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_round_trip_gz),
        cmocka_unit_test(test_located_errors),
        cmocka_unit_test(test_long_line),
        cmocka_unit_test(test_missing_costs),
        cmocka_unit_test(test_sync_follows_work),
        cmocka_unit_test(test_maps),
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    g_rmdir(dir);
    g_free(dir);
    return rc;
}
