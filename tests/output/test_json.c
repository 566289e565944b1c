/* test_json.c — the small JSON writer and reader. */
#include "sim/output/json.h"
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include <cmocka.h>

static void test_numbers_round_trip(void **state)
{
    (void)state;
    const double xs[] = {0.1,    1.0 / 3.0, 12.0,          -0.25,
                         1e-300, 6.02e23,   123456789012.5};
    char buf[32];
    for (size_t i = 0; i < G_N_ELEMENTS(xs); i++) {
        json_fmt_num(buf, xs[i]);
        assert_true(g_ascii_strtod(buf, NULL) == xs[i]);
    }
    assert_string_equal(json_fmt_num(buf, 0.1), "0.1");
    assert_string_equal(json_fmt_num(buf, 12.0), "12");
    assert_string_equal(json_fmt_num(buf, NAN), "");
}

static void test_strings_round_trip(void **state)
{
    (void)state;
    const char *s = "a \"quoted\" \\ line\nnext\ttab \x01 é";
    GString *out = g_string_new(NULL);
    json_put_str(out, s);
    JsonVal *v = json_parse(out->str, -1, "t", NULL);
    assert_non_null(v);
    assert_int_equal(v->kind, JSON_STRING);
    assert_string_equal(v->str, s);
    json_free(v);
    g_string_free(out, TRUE);
    v = json_parse("\"\\u00e9\\ud83d\\ude00\"", -1, "t", NULL);
    assert_string_equal(v->str, "é\xf0\x9f\x98\x80");
    json_free(v);
}

static void test_structure(void **state)
{
    (void)state;
    const char *text = " {\"a\": [1, 2.5e1, -3], \"b\": {\"c\": null},"
                       " \"d\": true, \"e\": \"x\"} ";
    JsonVal *v = json_parse(text, -1, "t", NULL);
    assert_non_null(v);
    assert_int_equal(json_len(v), 4);
    const JsonVal *a = json_get(v, "a");
    assert_int_equal(json_len(a), 3);
    assert_true(json_at(a, 1)->num == 25.0);
    assert_string_equal(json_at(a, 1)->raw, "2.5e1");
    assert_int_equal(json_get(json_get(v, "b"), "c")->kind, JSON_NULL);
    assert_true(json_get(v, "d")->b);
    assert_null(json_get(v, "zz"));
    json_free(v);
}

static void expect_error(const char *text, const char *msg)
{
    GError *err = NULL;
    assert_null(json_parse(text, -1, "bad.json", &err));
    assert_non_null(err);
    assert_string_equal(err->message, msg);
    g_error_free(err);
}

static void test_errors(void **state)
{
    (void)state;
    expect_error("{\"a\": 1,}",
                 "bad.json: offset 8: found '}', expected a string");
    expect_error("[1 2]", "bad.json: offset 3: found '2', "
                          "expected ',' or ']'");
    expect_error("{\"a\": 01}",
                 "bad.json: offset 6: found '0', expected a JSON value");
    expect_error("\"abc", "bad.json: offset 4: found end of input, "
                          "expected '\"' closing the string");
    expect_error("{} x", "bad.json: offset 3: found 'x', "
                         "expected end of input");
    expect_error("", "bad.json: offset 0: found end of input, "
                     "expected a JSON value");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_numbers_round_trip),
        cmocka_unit_test(test_strings_round_trip),
        cmocka_unit_test(test_structure),
        cmocka_unit_test(test_errors),
    };
    return cmocka_run_group_tests_name("json", tests, NULL, NULL);
}
