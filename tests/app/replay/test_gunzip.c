/* test_gunzip.c — a .gz trace made of several gzip members (`cat a.gz
 * b.gz`, RFC 1952 section 2.2) is read to the end, not only its first
 * member (issue 32); bytes after a member that are not a gzip member,
 * and a member cut short, are errors, not a silent end of the file. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include <cmocka.h>
#include <gio/gio.h>
#include <glib/gstdio.h>

#include "sim/app/replay/rpl_lines.h"

/* `text` as one gzip member, appended to `out`. */
static void add_member(GByteArray *out, const char *text)
{
    GConverter *z = G_CONVERTER(
        g_zlib_compressor_new(G_ZLIB_COMPRESSOR_FORMAT_GZIP, -1));
    guint8 buf[4096];
    gsize at = 0, len = strlen(text);
    GConverterResult res;
    do { /* output in 4 KiB pieces */
        gsize r = 0, w = 0;
        res = g_converter_convert(z, text + at, len - at, buf, sizeof buf,
                                  G_CONVERTER_INPUT_AT_END, &r, &w, NULL);
        assert_int_not_equal(res, G_CONVERTER_ERROR);
        at += r;
        g_byte_array_append(out, buf, (guint)w);
    } while (res != G_CONVERTER_FINISHED);
    assert_int_equal(at, len);
    g_object_unref(z);
}

/* Reads every line of `bytes` saved as a .gz file; returns the first
 * word of each line joined by spaces, or NULL with *err. */
static char *read_all(const GByteArray *bytes, GError **err)
{
    char *dir = g_dir_make_tmp("pgsim-gunzip-XXXXXX", NULL);
    char *path = g_build_filename(dir, "t.pgt.gz", NULL);
    assert_true(g_file_set_contents(path, (const char *)bytes->data,
                                    bytes->len, NULL));
    RplLines *l = rpl_lines_open(path, err);
    assert_non_null(l);
    GString *words = g_string_new(NULL);
    int n;
    while ((n = rpl_lines_next(l, err)) > 0)
        g_string_append_printf(words, "%s%s", words->len ? " " : "",
                               rpl_lines_word(l, 0));
    rpl_lines_free(l);
    g_remove(path);
    g_rmdir(dir);
    g_free(path);
    g_free(dir);
    return g_string_free(words, n < 0);
}

static void test_members_read_to_the_end(void **state)
{
    (void)state;
    GByteArray *b = g_byte_array_new();
    add_member(b, "a 1\nb 2\n");
    add_member(b, "c 3\n");
    add_member(b, "");
    add_member(b, "d 4\ne 5"); /* no line end at the very end */
    GError *err = NULL;
    char *words = read_all(b, &err);
    g_assert_no_error(err);
    assert_string_equal(words, "a b c d e");
    g_free(words);
    /* a long second member, read over many buffer refills */
    GString *big = g_string_new(NULL);
    for (int i = 0; i < 50000; i++)
        g_string_append_printf(big, "w%d %d\n", i, i);
    g_byte_array_set_size(b, 0);
    add_member(b, "first 0\n");
    add_member(b, big->str);
    words = read_all(b, &err);
    g_assert_no_error(err);
    assert_true(g_str_has_suffix(words, " w49998 w49999"));
    g_free(words);
    g_string_free(big, TRUE);
    g_byte_array_free(b, TRUE);
}

static void test_garbage_and_truncation_are_errors(void **state)
{
    (void)state;
    GByteArray *b = g_byte_array_new();
    add_member(b, "a 1\n");
    g_byte_array_append(b, (const guint8 *)"junk after it\n", 14);
    GError *err = NULL;
    assert_null(read_all(b, &err));
    assert_non_null(err);
    g_clear_error(&err);
    g_byte_array_set_size(b, 0);
    add_member(b, "a 1\n");
    add_member(b, "b 2\nc 3\nd 4\n");
    g_byte_array_set_size(b, b->len - 6); /* the second member cut short */
    assert_null(read_all(b, &err));
    assert_non_null(err);
    g_clear_error(&err);
    g_byte_array_free(b, TRUE);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_members_read_to_the_end),
        cmocka_unit_test(test_garbage_and_truncation_are_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
