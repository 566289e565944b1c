/* test_json.c — pgsim's JSON layer over json-glib (sim/output/json.h). */
#include "sim/output/json.h"
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include <cmocka.h>

static void test_fmt_num(void **state)
{
    (void)state;
    const double xs[] = {0.1,    1.0 / 3.0, 12.0,          -0.25,
                         1e-300, 6.02e23,   123456789012.5};
    char buf[32];
    for (size_t i = 0; i < G_N_ELEMENTS(xs); i++) {
        js_fmt_num(buf, xs[i]);
        assert_true(g_ascii_strtod(buf, NULL) == xs[i]);
    }
    assert_string_equal(js_fmt_num(buf, 0.1), "0.1");
    assert_string_equal(js_fmt_num(buf, 12.0), "12");
    assert_string_equal(js_fmt_num(buf, NAN), "");
}

/* Numbers written through the builder read back to the same double;
 * whole ones are integers, non-finite ones null. */
static void test_numbers_round_trip(void **state)
{
    (void)state;
    const double xs[] = {0.1,   1.0 / 3.0, 12.0,   -0.25,
                         6.02e23, 123456789012.5, 0.003000000001,
                         2.5e-7};
    JsonBuilder *b = json_builder_new();
    json_builder_begin_array(b);
    for (size_t i = 0; i < G_N_ELEMENTS(xs); i++)
        js_add_num(b, xs[i]);
    js_add_num(b, NAN);
    js_add_num(b, INFINITY);
    json_builder_end_array(b);
    char *text = js_finish(b, FALSE);
    assert_non_null(strstr(text, ",12,"));
    assert_true(g_str_has_suffix(text, ",null,null]"));
    JsonNode *v = js_parse(text, -1, "t", NULL);
    assert_int_equal(js_len(v), G_N_ELEMENTS(xs) + 2);
    for (size_t i = 0; i < G_N_ELEMENTS(xs); i++)
        assert_true(js_num(js_at(v, (guint)i)) == xs[i]);
    assert_true(js_is_null(js_at(v, G_N_ELEMENTS(xs))));
    json_node_unref(v);
    g_free(text);
}

/* json-glib 1.6 would print 1e-300 as "1e-300.0" (not JSON): the value
 * is written one ulp toward zero instead, and the text parses. */
static void test_one_digit_exponent(void **state)
{
    (void)state;
    JsonBuilder *b = json_builder_new();
    json_builder_begin_array(b);
    js_add_num(b, 1e-300);
    js_add_num(b, -3e-200);
    json_builder_end_array(b);
    char *text = js_finish(b, FALSE);
    GError *err = NULL;
    JsonNode *v = js_parse(text, -1, "t", &err);
    g_assert_no_error(err);
    assert_true(js_num(js_at(v, 0)) == nextafter(1e-300, 0));
    assert_true(fabs(js_num(js_at(v, 1)) / -3e-200 - 1) < 1e-15);
    json_node_unref(v);
    g_free(text);
}

static void test_strings_round_trip(void **state)
{
    (void)state;
    const char *s = "a \"quoted\" \\ line\nnext\ttab \x01 é";
    JsonBuilder *b = json_builder_new();
    json_builder_begin_object(b);
    js_set_str(b, "s", s);
    js_set_str(b, "none", NULL);
    json_builder_end_object(b);
    char *text = js_finish(b, TRUE);
    assert_true(g_str_has_suffix(text, "}\n"));
    JsonNode *v = js_parse(text, -1, "t", NULL);
    assert_string_equal(js_str(js_get(v, "s")), s);
    assert_true(js_is_null(js_get(v, "none")));
    assert_null(js_str(js_get(v, "none")));
    json_node_unref(v);
    g_free(text);
    v = js_parse("\"\\u00e9\\ud83d\\ude00\"", -1, "t", NULL);
    assert_string_equal(js_str(v), "é\xf0\x9f\x98\x80");
    json_node_unref(v);
}

static void test_structure(void **state)
{
    (void)state;
    const char *text = " {\"a\": [1, 2.5e1, -3], \"b\": {\"c\": null},"
                       " \"d\": true, \"e\": \"x\"} ";
    JsonNode *v = js_parse(text, -1, "t", NULL);
    assert_non_null(v);
    JsonNode *a = js_get(v, "a");
    assert_int_equal(js_len(a), 3);
    assert_true(js_num(js_at(a, 1)) == 25.0);
    assert_true(js_is_null(js_get(js_get(v, "b"), "c")));
    assert_null(js_get(v, "zz"));
    assert_null(js_get(a, "x"));  /* not an object */
    assert_int_equal(js_len(js_get(v, "b")), 0); /* not an array */
    assert_true(isnan(js_num(js_get(v, "e"))));
    char *cells[] = {js_cell(js_at(a, 0)), js_cell(js_at(a, 1)),
                     js_cell(js_get(v, "d")), js_cell(js_get(v, "e")),
                     js_cell(js_get(js_get(v, "b"), "c"))};
    const char *want[] = {"1", "25", "true", "x", ""};
    for (int i = 0; i < 5; i++) {
        assert_string_equal(cells[i], want[i]);
        g_free(cells[i]);
    }
    json_node_unref(v);
}

/* Members keep their insertion order; the same tree prints the same. */
static void test_order_and_determinism(void **state)
{
    (void)state;
    char *t[2];
    for (int k = 0; k < 2; k++) {
        JsonBuilder *b = json_builder_new();
        json_builder_begin_object(b);
        js_set_int(b, "zeta", 1);
        js_set_num(b, "alpha", 0.5);
        js_set_bool(b, "mid", TRUE);
        json_builder_end_object(b);
        t[k] = js_finish(b, FALSE);
    }
    assert_string_equal(t[0], "{\"zeta\":1,\"alpha\":0.5,\"mid\":true}");
    assert_string_equal(t[0], t[1]);
    g_free(t[0]);
    g_free(t[1]);
}

static void expect_error(const char *text, const char *prefix)
{
    GError *err = NULL;
    assert_null(js_parse(text, -1, "bad.json", &err));
    assert_non_null(err);
    if (!g_str_has_prefix(err->message, prefix))
        fail_msg("'%s' does not start with '%s'", err->message, prefix);
    g_error_free(err);
}

static void test_errors(void **state)
{
    (void)state;
    expect_error("{\"a\": 1,}", "bad.json:1:");
    expect_error("[1 2]", "bad.json:1:");
    expect_error("\n\"abc", "bad.json:2:");
    expect_error("", "bad.json:1:1: found end of input, expected a JSON");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fmt_num),
        cmocka_unit_test(test_numbers_round_trip),
        cmocka_unit_test(test_one_digit_exponent),
        cmocka_unit_test(test_strings_round_trip),
        cmocka_unit_test(test_structure),
        cmocka_unit_test(test_order_and_determinism),
        cmocka_unit_test(test_errors),
    };
    return cmocka_run_group_tests_name("json", tests, NULL, NULL);
}
