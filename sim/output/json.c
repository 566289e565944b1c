/* json.c — pgsim's JSON through json-glib (json.h).
 *
 * A thin layer: the number rule (whole numbers as integers, others as
 * doubles, non-finite as null), one generator setting (two-space indent
 * when pretty), parse errors renamed to the input's name, and accessors
 * that answer NULL instead of asserting on the wrong kind.  Invariant:
 * nothing here formats JSON by hand; json-glib escapes and prints.
 * Costs are json-glib's: O(n) in the tree or the text.
 */
#include "sim/output/json.h"
#include "sim/core/error.h"
#include <math.h>
#include <string.h>

#define JS_MAX_INT 9.2e18 /* below 2^63: a whole double fits gint64 */

/* json-glib 1.6 prints a double with g_ascii_dtostr (%.17g) and appends
 * ".0" when the text has no point, so a value whose 17 digits reduce to
 * one digit and an exponent (1e-300) becomes the invalid "1e-300.0".
 * Such a value moves one ulp toward zero (relative change ~1e-16) until
 * its text has a point; every other double is written exactly. */
static double printable(double x)
{
    char buf[G_ASCII_DTOSTR_BUF_SIZE];
    while (x != 0 && !strchr(g_ascii_dtostr(buf, sizeof buf, x), '.'))
        x = nextafter(x, 0.0);
    return x;
}

void js_add_num(JsonBuilder *b, double x)
{
    if (!isfinite(x))
        json_builder_add_null_value(b);
    else if (x == floor(x) && fabs(x) < JS_MAX_INT)
        json_builder_add_int_value(b, (gint64)x); /* whole: exact */
    else
        json_builder_add_double_value(b, printable(x));
}

void js_add_str(JsonBuilder *b, const char *s)
{
    if (s)
        json_builder_add_string_value(b, s);
    else
        json_builder_add_null_value(b);
}

void js_set_num(JsonBuilder *b, const char *key, double x)
{
    json_builder_set_member_name(b, key);
    js_add_num(b, x);
}

void js_set_int(JsonBuilder *b, const char *key, gint64 x)
{
    json_builder_set_member_name(b, key);
    json_builder_add_int_value(b, x);
}

void js_set_str(JsonBuilder *b, const char *key, const char *s)
{
    json_builder_set_member_name(b, key);
    js_add_str(b, s);
}

void js_set_bool(JsonBuilder *b, const char *key, gboolean v)
{
    json_builder_set_member_name(b, key);
    json_builder_add_boolean_value(b, v);
}

void js_set_node(JsonBuilder *b, const char *key, JsonNode *node)
{
    json_builder_set_member_name(b, key);
    if (node)
        json_builder_add_value(b, json_node_copy(node));
    else
        json_builder_add_null_value(b);
}

char *js_text(JsonNode *node, gboolean pretty)
{
    JsonGenerator *g = json_generator_new();
    json_generator_set_root(g, node);
    json_generator_set_pretty(g, pretty);
    json_generator_set_indent(g, 2);
    char *text = json_generator_to_data(g, NULL);
    g_object_unref(g);
    if (!pretty)
        return text;
    char *nl = g_strconcat(text, "\n", NULL);
    g_free(text);
    return nl;
}

char *js_finish(JsonBuilder *b, gboolean pretty)
{
    JsonNode *root = json_builder_get_root(b);
    char *text = js_text(root, pretty);
    json_node_unref(root);
    g_object_unref(b);
    return text;
}

/* json-glib names the input "<data>"; the caller's name replaces it. */
static void rename_error(GError **err, const GError *e, const char *name)
{
    const char *m = e->message;
    if (g_str_has_prefix(m, "<data>:"))
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT, "%s%s", name, m + 6);
    else
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT, "%s: %s", name, m);
}

JsonNode *js_parse(const char *text, gssize len, const char *name,
                   GError **err)
{
    const char *who = name ? name : "<json>";
    JsonParser *p = json_parser_new();
    GError *e = NULL;
    JsonNode *root = NULL;
    if (!json_parser_load_from_data(p, text, len, &e)) {
        rename_error(err, e, who);
        g_error_free(e);
    } else if (!json_parser_get_root(p)) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "%s:1:1: found end of input, expected a JSON value", who);
    } else {
        root = json_node_ref(json_parser_get_root(p));
    }
    g_object_unref(p);
    return root;
}

JsonNode *js_get(JsonNode *obj, const char *key)
{
    if (!obj || !JSON_NODE_HOLDS_OBJECT(obj))
        return NULL;
    JsonObject *o = json_node_get_object(obj);
    return json_object_has_member(o, key) ? json_object_get_member(o, key)
                                          : NULL;
}

guint js_len(JsonNode *arr)
{
    if (!arr || !JSON_NODE_HOLDS_ARRAY(arr))
        return 0;
    return json_array_get_length(json_node_get_array(arr));
}

JsonNode *js_at(JsonNode *arr, guint i)
{
    g_assert(i < js_len(arr));
    return json_array_get_element(json_node_get_array(arr), i);
}

const char *js_str(JsonNode *n)
{
    if (!n || !JSON_NODE_HOLDS_VALUE(n) ||
        json_node_get_value_type(n) != G_TYPE_STRING)
        return NULL;
    return json_node_get_string(n);
}

double js_num(JsonNode *n)
{
    return js_is_num(n) ? json_node_get_double(n) : NAN;
}

gboolean js_is_null(JsonNode *n)
{
    return n && JSON_NODE_HOLDS_NULL(n);
}

gboolean js_is_num(JsonNode *n)
{
    if (!n || !JSON_NODE_HOLDS_VALUE(n))
        return FALSE;
    GType t = json_node_get_value_type(n);
    return t == G_TYPE_INT64 || t == G_TYPE_DOUBLE;
}

char *js_cell(JsonNode *n)
{
    char buf[32];
    if (js_is_num(n)) {
        if (json_node_get_value_type(n) == G_TYPE_INT64)
            return g_strdup_printf("%" G_GINT64_FORMAT, json_node_get_int(n));
        return g_strdup(js_fmt_num(buf, json_node_get_double(n)));
    }
    if (n && JSON_NODE_HOLDS_VALUE(n) &&
        json_node_get_value_type(n) == G_TYPE_STRING)
        return g_strdup(json_node_get_string(n));
    if (n && JSON_NODE_HOLDS_VALUE(n) &&
        json_node_get_value_type(n) == G_TYPE_BOOLEAN)
        return g_strdup(json_node_get_boolean(n) ? "true" : "false");
    return g_strdup("");
}

const char *js_fmt_num(char buf[32], double x)
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
