/* test_wl_share.c — what consecutive runs share (sim/workload/share.h):
 * an object is found under its key and no other, putting a key again
 * frees the object kept there, and freeing the share frees the rest. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/workload/share.h"

static int freed[3];

static void count_free(gpointer p)
{
    freed[*(int *)p]++;
}

static void test_put_get_free(void **st)
{
    (void)st;
    static int ids[3] = {0, 1, 2};
    WlShare *s = wl_share_new();
    assert_null(wl_share_get(s, "a"));
    wl_share_put(s, "a", &ids[0], count_free);
    wl_share_put(s, "b", &ids[1], count_free);
    assert_ptr_equal(wl_share_get(s, "a"), &ids[0]);
    assert_ptr_equal(wl_share_get(s, "b"), &ids[1]);
    assert_null(wl_share_get(s, "c"));
    wl_share_put(s, "a", &ids[2], count_free); /* replaces, frees ids[0] */
    assert_int_equal(freed[0], 1);
    assert_ptr_equal(wl_share_get(s, "a"), &ids[2]);
    wl_share_put(s, "n", &ids[0], NULL); /* no free function: kept as is */
    wl_share_free(s);
    assert_int_equal(freed[0], 1);
    assert_int_equal(freed[1], 1);
    assert_int_equal(freed[2], 1);
    wl_share_free(NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_put_get_free),
    };
    return cmocka_run_group_tests_name("wl_share", tests, NULL, NULL);
}
