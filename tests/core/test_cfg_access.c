/* test_cfg_access.c — the accessors of sim/core/cfg.c on every kind of
 * node: lengths are 0 for what is not a map (or a sequence), NULL for
 * nothing; map keys and values by index; sequence items; path indexes of
 * up to 9 digits. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/core/cfg.h"
#include "sim/core/cfg_impl.h" /* cfg_path_index */
#include "tests/support.h"

static void test_lengths_and_kinds(void **state)
{
    (void)state;
    GError *err = NULL;
    CfgNode *r = cfg_load_string("m: {a: 1, b: 2, c: 3}\ns: [x, y]\nv: 7\n"
                                 "q: [[1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11]]\n",
                                 "a.yaml", &err);
    const CfgNode *m = cfg_get(r, "m"), *s = cfg_get(r, "s"),
                  *v = cfg_get(r, "v");
    assert_int_equal(cfg_map_len(r), 4);
    assert_int_equal(cfg_map_len(m), 3);
    assert_int_equal(cfg_map_len(s), 0);
    assert_int_equal(cfg_map_len(v), 0);
    assert_int_equal(cfg_map_len(NULL), 0);
    assert_int_equal(cfg_seq_len(s), 2);
    assert_int_equal(cfg_seq_len(m), 0);
    assert_int_equal(cfg_seq_len(v), 0);
    assert_int_equal(cfg_seq_len(NULL), 0);
    assert_int_equal(cfg_kind(m), CFG_MAP);
    assert_int_equal(cfg_kind(s), CFG_SEQ);
    assert_int_equal(cfg_kind(v), CFG_SCALAR);
    assert_string_equal(cfg_map_key(m, 2), "c");
    assert_string_equal(cfg_scalar(cfg_map_value(m, 1)), "2");
    assert_string_equal(cfg_scalar(cfg_seq_at(s, 1)), "y");
    assert_null(cfg_scalar(m));
    assert_null(cfg_scalar(NULL));
    assert_string_equal(cfg_scalar(cfg_path(r, "q.0.10")), "11");
    assert_null(cfg_path(r, "q.0.11"));
    assert_null(cfg_path(r, "s.2"));
    assert_string_equal(cfg_scalar(cfg_path(r, "s.0")), "x");
    assert_null(cfg_path(r, "v.0"));
    assert_null(cfg_path(r, "m.z"));
    assert_int_equal(cfg_path_index("123456789", 9), 123456789);
    assert_int_equal(cfg_path_index("1234567890", 10), -1);
    assert_int_equal(cfg_path_index("", 0), -1);
    assert_int_equal(cfg_path_index("0", 1), 0);
    assert_int_equal(cfg_path_index("9", 1), 9);
    assert_int_equal(cfg_path_index("1a", 2), -1);
    assert_int_equal(cfg_path_index("/", 1), -1);
    assert_int_equal(cfg_path_index(":", 1), -1);
    assert_int_equal(cfg_path_index("42x", 2), 42);
    cfg_free(r);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_lengths_and_kinds),
    };
    return cmocka_run_group_tests_name("cfg_access", tests, NULL, NULL);
}
