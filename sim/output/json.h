/* json.h — a small JSON writer and reader for pgsim's own files.
 *
 * Writing: string escaping and numbers that read back to the same double
 * (shortest of %.15g/%.17g; NaN and infinities become null).  Reading: a
 * strict RFC 8259 parser into a tree of JsonVal, enough to read back sweep
 * logs (JSON Lines) and to check trace files in tests.  Object members keep
 * their order.  Parsing is O(n) in the text; depth is limited to 64.
 */
#ifndef PGSIM_OUTPUT_JSON_H
#define PGSIM_OUTPUT_JSON_H

#include <glib.h>

typedef enum {
    JSON_NULL,
    JSON_BOOL,
    JSON_NUMBER,
    JSON_STRING,
    JSON_ARRAY,
    JSON_OBJECT
} JsonKind;

typedef struct JsonVal JsonVal;
struct JsonVal {
    JsonKind kind;
    gboolean b;
    double num;
    char *str;        /* JSON_STRING: the decoded text */
    char *raw;        /* JSON_NUMBER: the text as written */
    GPtrArray *keys;  /* JSON_OBJECT: char *, in order */
    GPtrArray *items; /* JSON_ARRAY items / JSON_OBJECT values: JsonVal * */
};

/* Appends s as a quoted JSON string (NULL appends null). */
void json_put_str(GString *out, const char *s);
/* Appends a number that reads back exactly; null when not finite. */
void json_put_num(GString *out, double x);
/* Formats a double the same way into buf (>= 32 bytes); "" if not finite. */
const char *json_fmt_num(char buf[32], double x);

/* Parses one JSON text (len may be -1 for NUL-terminated); returns a new
 * tree (free with json_free()) or NULL with *err set ("<name>: offset N:
 * found <what>, expected <what>"). */
JsonVal *json_parse(const char *text, gssize len, const char *name,
                    GError **err);
void json_free(JsonVal *v);
/* Object member by key (first match); NULL when absent or not an object. */
const JsonVal *json_get(const JsonVal *obj, const char *key);
guint json_len(const JsonVal *v); /* items of an array or object */
const JsonVal *json_at(const JsonVal *v, guint i);

#endif
