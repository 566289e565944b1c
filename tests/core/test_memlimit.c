/* test_memlimit.c — the memory limit (sim/core/memlimit.c): the parser of
 * --mem-limit / $PGSIM_MEM_LIMIT (bytes, or k M G T as powers of 1024;
 * 0, junk and values that do not fit 64 bits refused), the order of
 * precedence of the limit's sources, and the check's boundary and
 * message. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <unistd.h>

#include "sim/core/error.h"
#include "sim/core/memlimit.h"
#include "tests/support.h"

static void test_parse(void **state)
{
    (void)state;
    static const struct {
        const char *text;
        guint64 v;
    } ok[] = {
        {"1", 1},
        {"4096", 4096},
        {"3k", 3ull << 10},
        {"2M", 2ull << 20},
        {"5G", 5ull << 30},
        {"7T", 7ull << 40},
        {"18446744073709551615", G_MAXUINT64},
        {"16777215T", 16777215ull << 40},
    };
    for (guint i = 0; i < G_N_ELEMENTS(ok); i++) {
        guint64 v = 0;
        if (!sim_mem_parse(ok[i].text, &v) || v != ok[i].v)
            fail_msg("'%s': %" G_GUINT64_FORMAT, ok[i].text, v);
    }
    static const char *const bad[] = {"0", "0k", "", "k", "-1", " 1", "1 k",
                                      "1K", "1m", "1P", "1kk", "1.5G",
                                      "16777216T", "18446744073709551616"};
    for (guint i = 0; i < G_N_ELEMENTS(bad); i++) {
        guint64 v = 99;
        if (sim_mem_parse(bad[i], &v) || v != 99)
            fail_msg("'%s' accepted", bad[i]);
    }
    guint64 v = 99;
    assert_false(sim_mem_parse(NULL, &v));
    assert_int_equal(v, 99);
}

static void test_limit_sources(void **state)
{
    (void)state;
    guint64 phys = (guint64)sysconf(_SC_PHYS_PAGES) *
                   (guint64)sysconf(_SC_PAGESIZE);
    g_unsetenv("PGSIM_MEM_LIMIT");
    sim_mem_set_limit(0);
    assert_true(sim_mem_limit() == phys);
    g_setenv("PGSIM_MEM_LIMIT", "3M", TRUE);
    assert_true(sim_mem_limit() == 3ull << 20);
    g_setenv("PGSIM_MEM_LIMIT", "junk", TRUE);
    assert_true(sim_mem_limit() == phys);
    g_setenv("PGSIM_MEM_LIMIT", "3M", TRUE);
    sim_mem_set_limit(12345);
    assert_true(sim_mem_limit() == 12345);
    g_unsetenv("PGSIM_MEM_LIMIT");
    sim_mem_set_limit(0);
}

static void test_check(void **state)
{
    (void)state;
    GError *err = NULL;
    sim_mem_set_limit(2ull << 20);
    assert_true(sim_mem_check(2097152.0, "a.yaml:1:2", "a grid", &err));
    assert_true(sim_mem_check(0.0, "a.yaml:1:2", "a grid", &err));
    assert_null(err);
    assert_false(sim_mem_check(2097153.0, "a.yaml:1:2", "a grid", &err));
    assert_string_equal(err->message,
                        "a.yaml:1:2: found a grid needing about 2.0 MiB, "
                        "expected at most 2.0 MiB (--mem-limit; "
                        "docs/config.md, Limits)");
    assert_int_equal(sim_error_exit_status(err), 2);
    g_clear_error(&err);
    assert_false(sim_mem_check(3.5 * 1048576, "x", "y", &err));
    assert_string_equal(err->message,
                        "x: found y needing about 3.5 MiB, expected at most "
                        "2.0 MiB (--mem-limit; docs/config.md, Limits)");
    g_clear_error(&err);
    /* below a MiB the unit steps down: not "about 0 MiB" */
    sim_mem_set_limit(1000);
    assert_false(sim_mem_check(524288.0, "x", "y", &err));
    assert_string_equal(err->message,
                        "x: found y needing about 512.0 KiB, expected at "
                        "most 1000 B (--mem-limit; docs/config.md, Limits)");
    g_clear_error(&err);
    sim_mem_set_limit(0);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_parse),
        cmocka_unit_test(test_limit_sources),
        cmocka_unit_test(test_check),
    };
    return cmocka_run_group_tests_name("memlimit", tests, NULL, NULL);
}
