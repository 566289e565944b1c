/* json.c — a small JSON writer and reader (RFC 8259).
 *
 * The reader is a recursive-descent parser over a byte range with a depth
 * limit of 64; strings are decoded (escapes, \u with surrogate pairs) to
 * UTF-8.  Invariant: a returned tree is complete; on any error nothing is
 * returned and everything built so far is freed.  O(n) time and memory.
 */
#include "sim/output/json.h"
#include "sim/core/error.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define JSON_MAX_DEPTH 64

void json_put_str(GString *out, const char *s)
{
    if (!s) {
        g_string_append(out, "null");
        return;
    }
    g_string_append_c(out, '"');
    for (const unsigned char *p = (const unsigned char *)s; *p; p++) {
        switch (*p) {
        case '"':
            g_string_append(out, "\\\"");
            break;
        case '\\':
            g_string_append(out, "\\\\");
            break;
        case '\n':
            g_string_append(out, "\\n");
            break;
        case '\r':
            g_string_append(out, "\\r");
            break;
        case '\t':
            g_string_append(out, "\\t");
            break;
        default:
            if (*p < 0x20)
                g_string_append_printf(out, "\\u%04x", *p);
            else
                g_string_append_c(out, (char)*p);
        }
    }
    g_string_append_c(out, '"');
}

const char *json_fmt_num(char buf[32], double x)
{
    if (!isfinite(x)) {
        buf[0] = '\0';
        return buf;
    }
    if (x == floor(x) && fabs(x) < 1e15) {
        g_snprintf(buf, 32, "%.0f", x);
        return buf;
    }
    g_ascii_formatd(buf, 32, "%.15g", x);
    if (g_ascii_strtod(buf, NULL) != x)
        g_ascii_formatd(buf, 32, "%.17g", x);
    return buf;
}

void json_put_num(GString *out, double x)
{
    char buf[32];
    if (!isfinite(x))
        g_string_append(out, "null");
    else
        g_string_append(out, json_fmt_num(buf, x));
}

/* ---- reader ---------------------------------------------------------- */

typedef struct {
    const char *s;
    size_t len, pos;
    const char *name;
    GError **err;
    int depth;
} JsonParser;

static gboolean fail(JsonParser *p, const char *expected)
{
    char found[32];
    if (p->pos >= p->len)
        g_strlcpy(found, "end of input", sizeof found);
    else if ((unsigned char)p->s[p->pos] >= 0x20)
        g_snprintf(found, sizeof found, "'%c'", p->s[p->pos]);
    else
        g_snprintf(found, sizeof found, "byte 0x%02x",
                   (unsigned char)p->s[p->pos]);
    if (p->err && !*p->err)
        g_set_error(p->err, SIM_ERROR, SIM_ERROR_INPUT,
                    "%s: offset %zu: found %s, expected %s", p->name, p->pos,
                    found, expected);
    return FALSE;
}

static void skip_ws(JsonParser *p)
{
    while (p->pos < p->len && strchr(" \t\r\n", p->s[p->pos]) && p->s[p->pos])
        p->pos++;
}

static gboolean peek_is(JsonParser *p, char c)
{
    skip_ws(p);
    return p->pos < p->len && p->s[p->pos] == c;
}

static gboolean expect(JsonParser *p, char c, const char *what)
{
    if (!peek_is(p, c))
        return fail(p, what);
    p->pos++;
    return TRUE;
}

static JsonVal *val_new(JsonKind k)
{
    JsonVal *v = g_new0(JsonVal, 1);
    v->kind = k;
    return v;
}

void json_free(JsonVal *v)
{
    if (!v)
        return;
    g_free(v->str);
    g_free(v->raw);
    if (v->keys)
        g_ptr_array_free(v->keys, TRUE);
    if (v->items)
        g_ptr_array_free(v->items, TRUE);
    g_free(v);
}

static JsonVal *parse_value(JsonParser *p);

static int hex4(const char *s)
{
    int v = 0;
    for (int i = 0; i < 4; i++) {
        int c = s[i], d;
        if (c >= '0' && c <= '9')
            d = c - '0';
        else if (c >= 'a' && c <= 'f')
            d = c - 'a' + 10;
        else if (c >= 'A' && c <= 'F')
            d = c - 'A' + 10;
        else
            return -1;
        v = v * 16 + d;
    }
    return v;
}

static gboolean parse_uescape(JsonParser *p, GString *out)
{
    if (p->pos + 4 > p->len || hex4(p->s + p->pos) < 0)
        return fail(p, "four hex digits after \\u");
    gunichar c = (gunichar)hex4(p->s + p->pos);
    p->pos += 4;
    if (c >= 0xd800 && c < 0xdc00 && p->pos + 6 <= p->len &&
        p->s[p->pos] == '\\' && p->s[p->pos + 1] == 'u') {
        int lo = hex4(p->s + p->pos + 2);
        if (lo >= 0xdc00 && lo < 0xe000) {
            c = 0x10000 + ((c - 0xd800) << 10) + ((gunichar)lo - 0xdc00);
            p->pos += 6;
        }
    }
    g_string_append_unichar(out, c);
    return TRUE;
}

static gboolean parse_escape(JsonParser *p, GString *out)
{
    static const char from[] = "\"\\/bfnrt", to[] = "\"\\/\b\f\n\r\t";
    if (p->pos >= p->len)
        return fail(p, "an escape character");
    char c = p->s[p->pos];
    const char *k = c ? strchr(from, c) : NULL;
    if (k) {
        g_string_append_c(out, to[k - from]);
        p->pos++;
        return TRUE;
    }
    if (c != 'u')
        return fail(p, "one of \\\" \\\\ \\/ \\b \\f \\n \\r \\t \\u");
    p->pos++;
    return parse_uescape(p, out);
}

static char *parse_string(JsonParser *p)
{
    if (!expect(p, '"', "a string"))
        return NULL;
    GString *out = g_string_new(NULL);
    while (p->pos < p->len && p->s[p->pos] != '"') {
        unsigned char c = (unsigned char)p->s[p->pos];
        if (c < 0x20) {
            fail(p, "a printable character or '\"'");
            return g_string_free(out, TRUE), NULL;
        }
        p->pos++;
        if (c == '\\' && !parse_escape(p, out))
            return g_string_free(out, TRUE), NULL;
        if (c != '\\')
            g_string_append_c(out, (char)c);
    }
    if (p->pos >= p->len) {
        fail(p, "'\"' closing the string");
        return g_string_free(out, TRUE), NULL;
    }
    p->pos++;
    return g_string_free(out, FALSE);
}

static size_t span_of(JsonParser *p, size_t i, const char *set)
{
    while (i < p->len && p->s[i] && strchr(set, p->s[i]))
        i++;
    return i;
}

static JsonVal *parse_number(JsonParser *p)
{
    size_t i = p->pos;
    if (i < p->len && p->s[i] == '-')
        i++;
    size_t d = span_of(p, i, "0123456789");
    if (d == i || (p->s[i] == '0' && d > i + 1))
        return fail(p, "a JSON value"), NULL;
    i = d;
    if (i < p->len && p->s[i] == '.') {
        d = span_of(p, i + 1, "0123456789");
        if (d == i + 1)
            return p->pos = i + 1, fail(p, "a digit"), NULL;
        i = d;
    }
    if (i < p->len && (p->s[i] == 'e' || p->s[i] == 'E')) {
        i++;
        if (i < p->len && (p->s[i] == '+' || p->s[i] == '-'))
            i++;
        d = span_of(p, i, "0123456789");
        if (d == i)
            return p->pos = i, fail(p, "a digit"), NULL;
        i = d;
    }
    JsonVal *v = val_new(JSON_NUMBER);
    v->raw = g_strndup(p->s + p->pos, i - p->pos);
    v->num = g_ascii_strtod(v->raw, NULL);
    p->pos = i;
    return v;
}

static JsonVal *parse_word(JsonParser *p)
{
    static const char *const words[] = {"true", "false", "null"};
    for (int w = 0; w < 3; w++) {
        size_t n = strlen(words[w]);
        if (p->pos + n <= p->len && memcmp(p->s + p->pos, words[w], n) == 0) {
            p->pos += n;
            JsonVal *v = val_new(w == 2 ? JSON_NULL : JSON_BOOL);
            v->b = w == 0;
            return v;
        }
    }
    return parse_number(p);
}

static JsonVal *parse_array(JsonParser *p)
{
    JsonVal *v = val_new(JSON_ARRAY);
    v->items = g_ptr_array_new_with_free_func((GDestroyNotify)json_free);
    p->pos++;
    if (peek_is(p, ']'))
        return p->pos++, v;
    do {
        JsonVal *item = parse_value(p);
        if (!item)
            return json_free(v), NULL;
        g_ptr_array_add(v->items, item);
    } while (peek_is(p, ',') && ++p->pos);
    if (!expect(p, ']', "',' or ']'"))
        return json_free(v), NULL;
    return v;
}

static JsonVal *parse_object(JsonParser *p)
{
    JsonVal *v = val_new(JSON_OBJECT);
    v->items = g_ptr_array_new_with_free_func((GDestroyNotify)json_free);
    v->keys = g_ptr_array_new_with_free_func(g_free);
    p->pos++;
    if (peek_is(p, '}'))
        return p->pos++, v;
    do {
        char *key = parse_string(p);
        if (!key)
            return json_free(v), NULL;
        g_ptr_array_add(v->keys, key);
        JsonVal *item = expect(p, ':', "':'") ? parse_value(p) : NULL;
        if (!item)
            return json_free(v), NULL;
        g_ptr_array_add(v->items, item);
    } while (peek_is(p, ',') && ++p->pos);
    if (!expect(p, '}', "',' or '}'"))
        return json_free(v), NULL;
    return v;
}

static JsonVal *parse_value(JsonParser *p)
{
    skip_ws(p);
    if (p->pos >= p->len)
        return fail(p, "a JSON value"), NULL;
    if (++p->depth > JSON_MAX_DEPTH)
        return fail(p, "nesting at most 64 deep"), NULL;
    JsonVal *v;
    char c = p->s[p->pos];
    if (c == '{')
        v = parse_object(p);
    else if (c == '[')
        v = parse_array(p);
    else if (c == '"') {
        char *s = parse_string(p);
        v = s ? val_new(JSON_STRING) : NULL;
        if (v)
            v->str = s;
    } else
        v = parse_word(p);
    p->depth--;
    return v;
}

JsonVal *json_parse(const char *text, gssize len, const char *name,
                    GError **err)
{
    JsonParser p = {text, len < 0 ? strlen(text) : (size_t)len,
                    0,    name ? name : "<json>",
                    err,  0};
    JsonVal *v = parse_value(&p);
    skip_ws(&p);
    if (v && p.pos < p.len) {
        fail(&p, "end of input");
        json_free(v);
        return NULL;
    }
    return v;
}

const JsonVal *json_get(const JsonVal *obj, const char *key)
{
    if (!obj || obj->kind != JSON_OBJECT)
        return NULL;
    for (guint i = 0; i < obj->keys->len; i++)
        if (strcmp(g_ptr_array_index(obj->keys, i), key) == 0)
            return g_ptr_array_index(obj->items, i);
    return NULL;
}

guint json_len(const JsonVal *v)
{
    return v && v->items ? v->items->len : 0;
}

const JsonVal *json_at(const JsonVal *v, guint i)
{
    g_assert(v && v->items && i < v->items->len);
    return g_ptr_array_index(v->items, i);
}
