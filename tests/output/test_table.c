/* test_table.c — CSV tables: comment lines (provenance headers) are
 * skipped wherever a record may start, but not inside a quoted field; a
 * field starting with '#' is written quoted, so it reads back as data. */
#include "sim/output/table.h"
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include <cmocka.h>

static void test_comments_skipped(void **state)
{
    (void)state;
    const char text[] = "# pgsim_version: v1\r\n# config: a,b.yaml\n"
                        "x,y\n1,2\n# between rows\n3,\"4\n# not a comment\"\n"
                        "#\n";
    GError *err = NULL;
    DataTable *t = dt_parse_csv(text, "t.csv", &err);
    g_assert_no_error(err);
    assert_int_equal(t->cols->len, 2);
    assert_string_equal(g_ptr_array_index(t->cols, 0), "x");
    assert_int_equal(t->rows->len, 2);
    assert_string_equal(dt_cell(t, 1, 0), "3");
    assert_string_equal(dt_cell(t, 1, 1), "4\n# not a comment");
    dt_free(t);
}

/* Without the skip, the first comment would be the header: a table
 * whose only column is the comment, and a located error at the 2-field
 * record. */
static void test_comment_is_not_header(void **state)
{
    (void)state;
    GError *err = NULL;
    DataTable *t = dt_parse_csv("#c\nx,y\n1,2\n", "t.csv", &err);
    g_assert_no_error(err);
    assert_int_equal(dt_col(t, "x"), 0);
    assert_int_equal(dt_col(t, "#c"), -1);
    dt_free(t);
    /* a comment does not hide a malformed record's line number */
    assert_null(dt_parse_csv("#c\nx,y\n#d\n1\n", "t.csv", &err));
    assert_non_null(strstr(err->message, "t.csv:4:1:"));
    g_error_free(err);
}

static void test_hash_field_round_trip(void **state)
{
    (void)state;
    GPtrArray *cols = g_ptr_array_new();
    g_ptr_array_add(cols, "name");
    g_ptr_array_add(cols, "n");
    DataTable *t = dt_new(cols);
    g_ptr_array_free(cols, TRUE);
    char *row[] = {"#1 pick", "#"};
    dt_add_row(t, row);
    GString *s = g_string_new(NULL);
    dt_write_csv(t, s);
    assert_string_equal(s->str, "name,n\n\"#1 pick\",\"#\"\n");
    GError *err = NULL;
    DataTable *back = dt_parse_csv(s->str, "t.csv", &err);
    g_assert_no_error(err);
    assert_int_equal(back->rows->len, 1);
    assert_string_equal(dt_cell(back, 0, 0), "#1 pick");
    assert_string_equal(dt_cell(back, 0, 1), "#");
    dt_free(back);
    dt_free(t);
    g_string_free(s, TRUE);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_comments_skipped),
        cmocka_unit_test(test_comment_is_not_header),
        cmocka_unit_test(test_hash_field_round_trip),
    };
    return cmocka_run_group_tests_name("table", tests, NULL, NULL);
}
