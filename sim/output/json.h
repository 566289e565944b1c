/* json.h — pgsim's JSON through json-glib: building, text, reading.
 *
 * Writing: a JsonBuilder with the few value kinds pgsim writes; numbers
 * go in as integers when whole (|x| < 9.2e18) and as doubles otherwise
 * (json-glib prints 17 significant digits, which read back to the same
 * double; see printable() in json.c for the one exception); NaN and
 * infinities become null.  Text is json-glib's
 * generator, pretty (two-space indent, newline-terminated) or on one
 * line, so output is a pure function of the tree: deterministic.
 * Reading: json-glib's parser; errors are "<name>:line:column: ...".
 * Object members keep their insertion (or file) order.
 */
#ifndef PGSIM_OUTPUT_JSON_H
#define PGSIM_OUTPUT_JSON_H

#include <glib.h>
#include <json-glib/json-glib.h>

/* Values into the builder (array item, or after a member name). */
void js_add_num(JsonBuilder *b, double x);
void js_add_str(JsonBuilder *b, const char *s); /* NULL adds null */
/* "key": value members of the object being built. */
void js_set_num(JsonBuilder *b, const char *key, double x);
void js_set_int(JsonBuilder *b, const char *key, gint64 x);
void js_set_str(JsonBuilder *b, const char *key, const char *s);
void js_set_bool(JsonBuilder *b, const char *key, gboolean v);
/* Adds a copy of node (NULL adds null) as member key. */
void js_set_node(JsonBuilder *b, const char *key, JsonNode *node);

/* The builder's tree as text (g_free); frees b. */
char *js_finish(JsonBuilder *b, gboolean pretty);
/* node as text (g_free). */
char *js_text(JsonNode *node, gboolean pretty);

/* Parses one JSON text (len -1: NUL-terminated); returns the root (free
 * with json_node_unref) or NULL with *err set (SIM_ERROR_INPUT,
 * "<name>:line:column: ..."). */
JsonNode *js_parse(const char *text, gssize len, const char *name,
                   GError **err);
/* Member key of an object node; NULL when absent or not an object. */
JsonNode *js_get(JsonNode *obj, const char *key);
/* Items of an array node (0 when not an array) and item i. */
guint js_len(JsonNode *arr);
JsonNode *js_at(JsonNode *arr, guint i);
/* A string node's text, else NULL; a number node's value, else NAN. */
const char *js_str(JsonNode *n);
double js_num(JsonNode *n);
/* TRUE for a null node (not for an absent member: NULL). */
gboolean js_is_null(JsonNode *n);
/* TRUE for an integer or double value node. */
gboolean js_is_num(JsonNode *n);
/* A value node as cell text: a string as is, a number shortest-exact,
 * true/false, "" for null, an object or an array (g_free). */
char *js_cell(JsonNode *n);

/* Shortest text of x that reads back exactly (%.15g, else %.17g), whole
 * numbers without a point, locale-free, into buf (>= 32 bytes); "" when
 * not finite.  For CSV and text cells. */
const char *js_fmt_num(char buf[32], double x);

#endif
