/* test_cfg_limits.c — the loader's limits at their exact boundaries:
 * nesting of 200 levels loads and 201 is refused at the node that goes
 * over; aliases may copy a million nodes in all and not one more; path
 * indices are at most nine decimal digits.  Each limit is checked on both
 * sides, so moving it by one (or counting nodes differently) fails. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/core/cfg.h"
#include "sim/core/cfg_impl.h"
#include "tests/support.h"

static CfgNode *try_load(const char *text, GError **err)
{
    return cfg_load_string(text, "t.yaml", err);
}

/* "[[...[1]...]]" with `levels` nodes on the way down (the scalar too). */
static char *nested(int levels)
{
    GString *s = g_string_new("");
    for (int i = 1; i < levels; i++)
        g_string_append_c(s, '[');
    g_string_append_c(s, '1');
    for (int i = 1; i < levels; i++)
        g_string_append_c(s, ']');
    return g_string_free(s, FALSE);
}

static void test_nesting_limit(void **state)
{
    (void)state;
    GError *err = NULL;
    char *ok = nested(200), *deep = nested(201);
    CfgNode *r = try_load(ok, &err);
    assert_non_null(r);
    const CfgNode *n = r;
    for (int i = 1; i < 200; i++) {
        assert_int_equal(cfg_kind(n), CFG_SEQ);
        assert_int_equal(cfg_col(n), i);
        n = cfg_seq_at(n, 0);
    }
    assert_string_equal(cfg_scalar(n), "1");
    assert_int_equal(cfg_col(n), 200);
    cfg_free(r);
    assert_null(try_load(deep, &err));
    assert_string_equal(err->message,
                        "t.yaml:1:201: found nesting deeper than 200 "
                        "levels, expected a shallower document");
    g_clear_error(&err);
    /* the limit is on depth, not on the count of nested nodes: 200 levels
     * twice in a row load */
    char *half = nested(199);
    char *twice = g_strdup_printf("[%s, %s]", half, half);
    g_free(half);
    r = try_load(twice, &err);
    assert_non_null(r);
    cfg_free(r);
    g_free(twice);
    g_free(ok);
    g_free(deep);
}

/* A list of `leaves` scalars anchored as &a, then `aliases` copies of it:
 * each copy counts 1 + leaves nodes. */
static char *aliased(int leaves, int aliases)
{
    GString *s = g_string_new("a: &a [");
    for (int i = 0; i < leaves; i++)
        g_string_append(s, i ? ", ~" : "~");
    g_string_append(s, "]\nb: [");
    for (int i = 0; i < aliases; i++)
        g_string_append(s, i ? ", *a" : "*a");
    g_string_append(s, "]\n");
    return g_string_free(s, FALSE);
}

static void test_alias_limit(void **state)
{
    (void)state;
    GError *err = NULL;
    /* 1000 copies of 1000 nodes: exactly the million allowed */
    char *ok = aliased(999, 1000), *over = aliased(999, 1001);
    CfgNode *r = try_load(ok, &err);
    assert_non_null(r);
    assert_int_equal(cfg_seq_len(cfg_get(r, "b")), 1000);
    assert_int_equal(cfg_seq_len(cfg_seq_at(cfg_get(r, "b"), 999)), 999);
    cfg_free(r);
    assert_null(try_load(over, &err));
    /* the 1001st alias, "*a" at column 4 + 4 * 1000 of line 2 */
    assert_string_equal(err->message,
                        "t.yaml:2:4005: found aliases expanding to over a "
                        "million nodes, expected a smaller document");
    g_clear_error(&err);
    g_free(ok);
    g_free(over);
}

static void test_path_index(void **state)
{
    (void)state;
    assert_int_equal(cfg_path_index("0", 1), 0);
    assert_int_equal(cfg_path_index("7", 1), 7);
    assert_int_equal(cfg_path_index("12", 2), 12);
    assert_int_equal(cfg_path_index("907", 3), 907);
    assert_int_equal(cfg_path_index("123456789", 9), 123456789);
    assert_int_equal(cfg_path_index("999999999", 9), 999999999);
    assert_int_equal(cfg_path_index("1234567890", 10), -1);
    assert_int_equal(cfg_path_index("12", 1), 1); /* only len characters */
    assert_int_equal(cfg_path_index("", 0), -1);
    assert_int_equal(cfg_path_index("/", 1), -1); /* '0' - 1 */
    assert_int_equal(cfg_path_index(":", 1), -1); /* '9' + 1 */
    assert_int_equal(cfg_path_index("1x", 2), -1);
    assert_int_equal(cfg_path_index("-1", 2), -1);
    GError *err = NULL;
    CfgNode *r = try_load("l: [a, b, [c, d]]\n", &err);
    assert_string_equal(cfg_scalar(cfg_path(r, "l.0")), "a");
    assert_string_equal(cfg_scalar(cfg_path(r, "l.1")), "b");
    assert_string_equal(cfg_scalar(cfg_path(r, "l.2.1")), "d");
    assert_null(cfg_path(r, "l.3"));
    assert_null(cfg_path(r, "l.-1"));
    assert_null(cfg_path(r, "l.x"));
    assert_null(cfg_path(r, "l.0.0"));
    cfg_free(r);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_nesting_limit),
        cmocka_unit_test(test_alias_limit),
        cmocka_unit_test(test_path_index),
    };
    return cmocka_run_group_tests_name("cfg_limits", tests, NULL, NULL);
}
