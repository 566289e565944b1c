/* test_cfg_unused.c — unknown keys (sim/core/cfg.c): the error names the
 * first unread key at its location and lists the keys consumers asked
 * for, each once, in the order first asked (present or not); a map nobody
 * read says so; sequences and nested maps are searched; keys in the skip
 * list are not descended into. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/core/cfg.h"
#include "tests/support.h"

static void expect_unused(const CfgNode *n, const char *const *skip,
                          const char *want)
{
    GError *err = NULL;
    gboolean ok = cfg_check_unused_except(n, skip, &err);
    assert_true(ok == (want == NULL));
    if (want)
        assert_string_equal(err->message, want);
    g_clear_error(&err);
}

static void test_asked_once_in_order(void **state)
{
    (void)state;
    GError *err = NULL;
    CfgNode *r = cfg_load_string("a: 1\nb: 2\nzz: 3\n", "f.yaml", &err);
    expect_unused(r, NULL,
                  "f.yaml:1:1: found unknown key 'a', expected no "
                  "key here (nothing reads this map)");
    assert_non_null(cfg_get(r, "b"));
    assert_non_null(cfg_get(r, "a"));
    assert_non_null(cfg_get(r, "b"));
    assert_null(cfg_get(r, "c"));
    assert_non_null(cfg_get(r, "a"));
    expect_unused(r, NULL,
                  "f.yaml:3:1: found unknown key 'zz', expected one "
                  "of: b, a, c");
    assert_true(cfg_has(r, "zz"));
    assert_false(cfg_has(r, "q"));
    cfg_mark_read(r);
    expect_unused(r, NULL, NULL);
    cfg_free(r);
}

static void test_nested_and_skipped(void **state)
{
    (void)state;
    GError *err = NULL;
    CfgNode *r = cfg_load_string("m: {x: 1, y: 2}\n"
                                 "s:\n  - {u: 1}\n  - {v: 2}\n",
                                 "n.yaml", &err);
    const CfgNode *m = cfg_get(r, "m");
    const CfgNode *s = cfg_get(r, "s");
    assert_non_null(cfg_get(m, "x"));
    expect_unused(r, NULL,
                  "n.yaml:1:11: found unknown key 'y', expected one "
                  "of: x");
    static const char *const skip_m[] = {"m", NULL};
    expect_unused(r, skip_m,
                  "n.yaml:3:6: found unknown key 'u', expected no "
                  "key here (nothing reads this map)");
    assert_non_null(cfg_get(cfg_seq_at(s, 0), "u"));
    expect_unused(r, skip_m,
                  "n.yaml:4:6: found unknown key 'v', expected no "
                  "key here (nothing reads this map)");
    cfg_mark_read(cfg_seq_at(s, 1));
    expect_unused(r, skip_m, NULL);
    static const char *const skip_other[] = {"s", NULL};
    expect_unused(r, skip_other,
                  "n.yaml:1:11: found unknown key 'y', "
                  "expected one of: x");
    expect_unused(NULL, NULL, NULL);
    cfg_free(r);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_asked_once_in_order),
        cmocka_unit_test(test_nested_and_skipped),
    };
    return cmocka_run_group_tests_name("cfg_unused", tests, NULL, NULL);
}
