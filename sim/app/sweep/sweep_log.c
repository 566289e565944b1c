/* sweep_log.c — the append-only results log of a sweep and its final,
 * ordered outputs.
 *
 * Durability: each line is written with one write() on an O_APPEND
 * descriptor (more when a filling disk takes only part of it; the error
 * then carries the system's reason) and followed by fsync(), so after a crash the file is a
 * sequence of complete lines plus at most one partial line at the end,
 * which resume truncates.  Lines are never edited in place.  Reading the
 * log is O(bytes); finishing is O(points * columns).
 */
#include "sim/app/sweep/sweep_log.h"
#include "sim/core/datapath.h"
#include "sim/output/provenance.h"
#include <errno.h>
#include <fcntl.h>
#include <string.h>
#include <unistd.h>

#define LOG_NAME "results.jsonl"
#define FP_NAME "sweep.fingerprint"

struct SweepLog {
    int fd;
    char *path;
    guint n_points;
    guint8 *done; /* n_points flags */
    guint n_done;
};

static gboolean io_error(GError **err, const char *path, const char *what)
{
    g_set_error(err, SIM_ERROR, SIM_ERROR_IO, "%s: cannot %s: %s", path, what,
                g_strerror(errno));
    return FALSE;
}

static char *in_dir(const char *dir, const char *name)
{
    return g_build_filename(dir, name, NULL);
}

/* Splits text into complete lines; *complete = bytes up to the last '\n'. */
static char **complete_lines(const char *text, gsize len, gsize *complete)
{
    const char *last = len ? g_strrstr_len(text, (gssize)len, "\n") : NULL;
    *complete = last ? (gsize)(last - text) + 1 : 0;
    char *body = g_strndup(text, *complete);
    char **lines = g_strsplit(body, "\n", -1);
    g_free(body);
    return lines;
}

static gboolean line_point(const char *line, guint n, guint *idx, gboolean *ok)
{
    JsonNode *v = js_parse(line, -1, LOG_NAME, NULL);
    JsonNode *p = js_get(v, "point"), *s = js_get(v, "status");
    double pt = js_is_num(p) ? json_node_get_double(p) : -1.0;
    gboolean good = pt >= 0 && pt < n && pt == (guint)pt && s &&
                    json_node_get_value_type(s) == G_TYPE_STRING;
    if (good) {
        *idx = (guint)pt;
        *ok = strcmp(json_node_get_string(s), "ok") == 0;
    }
    if (v)
        json_node_unref(v);
    return good;
}

static gboolean check_fingerprint(const char *dir, const SweepSpec *spec,
                                  gboolean resume, GError **err)
{
    char *path = in_dir(dir, FP_NAME), *old = NULL;
    char *fp = sweep_spec_fingerprint(spec);
    gboolean ok = TRUE;
    if (resume && sim_file_read(path, &old, NULL, NULL) &&
        strcmp(g_strstrip(old), fp) != 0) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "%s: found the log of another sweep (the sweep file or "
                    "its base config changed), expected the same sweep to "
                    "resume",
                    dir);
        ok = FALSE;
    }
    char *text = g_strconcat(fp, "\n", NULL);
    ok = ok && sim_file_write(path, text, strlen(text), err);
    g_free(text);
    g_free(old);
    g_free(fp);
    g_free(path);
    return ok;
}

static gboolean load_existing(SweepLog *log, gboolean resume, GError **err)
{
    char *text = NULL;
    gsize len = 0, complete = 0;
    if (!sim_file_read(log->path, &text, &len, NULL) || len == 0) {
        g_free(text);
        return TRUE;
    }
    if (!resume) {
        g_free(text);
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "%s: found results of an earlier run, expected an "
                    "empty output (use --resume, or another --out)",
                    log->path);
        return FALSE;
    }
    char **lines = complete_lines(text, len, &complete);
    for (char **l = lines; *l; l++) {
        guint idx;
        gboolean ok;
        if (**l && line_point(*l, log->n_points, &idx, &ok) && ok &&
            !log->done[idx]) {
            log->done[idx] = 1;
            log->n_done++;
        }
    }
    g_strfreev(lines);
    g_free(text);
    if (complete < len && truncate(log->path, (off_t)complete) != 0)
        return io_error(err, log->path, "truncate the partial last line");
    return TRUE;
}

SweepLog *sweep_log_open(const char *dir, const SweepSpec *spec,
                         gboolean resume, GError **err)
{
    if (g_mkdir_with_parents(dir, 0777) != 0) {
        io_error(err, dir, "create the directory");
        return NULL;
    }
    SweepLog *log = g_new0(SweepLog, 1);
    log->fd = -1;
    log->path = in_dir(dir, LOG_NAME);
    log->n_points = sweep_spec_points(spec);
    log->done = g_new0(guint8, log->n_points);
    if (!load_existing(log, resume, err) ||
        !check_fingerprint(dir, spec, resume, err)) {
        sweep_log_close(log);
        return NULL;
    }
    log->fd = open(log->path, O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0666);
    if (log->fd < 0) {
        io_error(err, log->path, "open");
        sweep_log_close(log);
        return NULL;
    }
    return log;
}

void sweep_log_close(SweepLog *log)
{
    if (!log)
        return;
    if (log->fd >= 0)
        close(log->fd);
    g_free(log->path);
    g_free(log->done);
    g_free(log);
}

gboolean sweep_log_done(const SweepLog *log, guint i)
{
    g_assert(i < log->n_points);
    return log->done[i] != 0;
}

guint sweep_log_n_done(const SweepLog *log)
{
    return log->n_done;
}

gboolean sweep_log_append(SweepLog *log, const char *line, GError **err)
{
    size_t len = strlen(line);
    g_assert(len > 0 && line[len - 1] == '\n');
    /* a full disk first takes part of the line (a short count, errno
     * untouched: "Success"), then fails with the reason: write the rest */
    while (len > 0) {
        ssize_t w = write(log->fd, line, len);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0) {
            if (w == 0)
                errno = EIO;
            return io_error(err, log->path, "append a line");
        }
        line += w;
        len -= (size_t)w;
    }
    if (fsync(log->fd) != 0)
        return io_error(err, log->path, "sync");
    return TRUE;
}

/* ---- finishing ------------------------------------------------------- */

static GPtrArray *base_columns(const SweepSpec *spec)
{
    GPtrArray *cols = g_ptr_array_new_with_free_func(g_free);
    const char *const first[] = {"point", "repetition", "seed"};
    for (int i = 0; i < 3; i++)
        g_ptr_array_add(cols, g_strdup(first[i]));
    for (guint i = 0; i < spec->params->len; i++)
        g_ptr_array_add(
            cols,
            g_strdup(((SweepParam *)g_ptr_array_index(spec->params, i))->key));
    g_ptr_array_add(cols, g_strdup("status"));
    g_ptr_array_add(cols, g_strdup("error"));
    return cols;
}

static gboolean has_col(const GPtrArray *cols, const char *k)
{
    for (guint i = 0; i < cols->len; i++)
        if (strcmp(g_ptr_array_index(cols, i), k) == 0)
            return TRUE;
    return FALSE;
}

/* Adds the members of row that cols lacks, in the row's order. */
static void add_columns(GPtrArray *cols, JsonNode *row)
{
    GList *keys = json_object_get_members(json_node_get_object(row));
    for (GList *k = keys; k; k = k->next)
        if (!has_col(cols, k->data) && strcmp(k->data, SWEEP_INPUTS_KEY))
            g_ptr_array_add(cols, g_strdup(k->data));
    g_list_free(keys);
}

static DataTable *build_table(const SweepSpec *spec, JsonNode **rows, guint n)
{
    GPtrArray *cols = base_columns(spec);
    for (guint i = 0; i < n; i++)
        if (rows[i])
            add_columns(cols, rows[i]);
    DataTable *t = dt_new(cols);
    char **cells = g_new0(char *, cols->len + 1);
    for (guint i = 0; i < n; i++) {
        if (!rows[i])
            continue;
        for (guint c = 0; c < cols->len; c++)
            cells[c] = js_cell(js_get(rows[i], cols->pdata[c]));
        dt_add_row(t, cells);
        for (guint c = 0; c < cols->len; c++)
            g_free(cells[c]);
    }
    g_free(cells);
    g_ptr_array_free(cols, TRUE);
    return t;
}

static gboolean write_atomic(const char *dir, const char *name,
                             const GString *s, GError **err)
{
    char *path = in_dir(dir, name);
    gboolean ok = sim_file_write(path, s->str, s->len, err);
    g_free(path);
    return ok;
}

/* A sweep's provenance: the sweep file, its SHA-256, the base seed and
 * fidelity, and the expanded base config (each point adds its parameter
 * values, the columns of results.csv, and its seed).  Works on a copy:
 * reading the tree marks its keys used. */
typedef struct {
    SimProvenance p;
    CfgNode *base;
    char *sha, *eff;
    SimInputs *inputs; /* the union of the points' inputs, in point order */
} SweepProv;

/* Adds the files of a point's line (its SWEEP_INPUTS_KEY array). */
static void add_inputs(SimInputs *in, JsonNode *row)
{
    JsonNode *a = row ? js_get(row, SWEEP_INPUTS_KEY) : NULL;
    if (!a || !JSON_NODE_HOLDS_ARRAY(a))
        return;
    JsonArray *arr = json_node_get_array(a);
    for (guint i = 0; i < json_array_get_length(arr); i++) {
        JsonNode *e = json_array_get_element(arr, i);
        if (!JSON_NODE_HOLDS_OBJECT(e))
            continue;
        JsonObject *o = json_node_get_object(e);
        const char *kind = json_object_get_string_member_with_default(
            o, "kind", NULL);
        const char *path = json_object_get_string_member_with_default(
            o, "path", NULL);
        const char *sha = json_object_get_string_member_with_default(
            o, "sha256", NULL);
        if (kind && path && sha)
            sim_inputs_add(in, kind, path, sha,
                           json_object_get_boolean_member_with_default(
                               o, "shipped", TRUE));
    }
}

static void sweep_prov_init(SweepProv *s, const SweepSpec *spec,
                            JsonNode **rows, guint n)
{
    s->base = cfg_copy(spec->base);
    s->sha = prov_file_sha256(spec->path);
    s->eff = prov_cfg_json(s->base);
    s->inputs = sim_inputs_new();
    for (guint i = 0; i < n; i++)
        add_inputs(s->inputs, rows[i]);
    const char *fid =
        cfg_scalar(cfg_get(cfg_get(s->base, "run"), "fidelity"));
    s->p = (SimProvenance){spec->path, s->sha, NULL, spec->seed,
                           fid,        s->eff, s->inputs};
}

static void sweep_prov_clear(SweepProv *s)
{
    sim_inputs_free(s->inputs);
    g_free(s->eff);
    g_free(s->sha);
    cfg_free(s->base);
}

/* DIR/provenance.json: the sweep's provenance, its name and size. */
static gboolean write_provenance(const char *dir, const SweepSpec *spec,
                                 const SimProvenance *p, GError **err)
{
    JsonBuilder *b = json_builder_new();
    json_builder_begin_object(b);
    js_set_str(b, "schema", "pgsim-sweep-provenance");
    js_set_str(b, "sweep", spec->name);
    js_set_int(b, "points", sweep_spec_points(spec));
    prov_json(b, p);
    json_builder_end_object(b);
    char *text = js_finish(b, TRUE);
    GString *g = g_string_new(text);
    gboolean ok = write_atomic(dir, "provenance.json", g, err);
    g_string_free(g, TRUE);
    g_free(text);
    return ok;
}

static gboolean write_outputs(const char *dir, const SweepSpec *spec,
                              char **lines, JsonNode **rows, guint n,
                              DataTable **table_out, GError **err)
{
    GString *jl = g_string_new(NULL), *csv = g_string_new(NULL);
    for (guint i = 0; i < n; i++)
        if (lines[i])
            g_string_append_printf(jl, "%s\n", lines[i]);
    DataTable *t = build_table(spec, rows, n);
    SweepProv prov;
    sweep_prov_init(&prov, spec, rows, n);
    prov_comment_lines(csv, &prov.p);
    dt_write_csv(t, csv);
    gboolean ok = write_atomic(dir, LOG_NAME, jl, err) &&
                  write_atomic(dir, "results.csv", csv, err) &&
                  write_provenance(dir, spec, &prov.p, err);
    sweep_prov_clear(&prov);
    if (ok && table_out)
        *table_out = t;
    else
        dt_free(t);
    g_string_free(jl, TRUE);
    g_string_free(csv, TRUE);
    return ok;
}

gboolean sweep_log_finish(const char *dir, const SweepSpec *spec,
                          DataTable **table_out, GError **err)
{
    char *path = in_dir(dir, LOG_NAME), *text = NULL;
    gsize len = 0, complete;
    if (!sim_file_read(path, &text, &len, NULL)) {
        g_free(path);
        g_set_error(err, SIM_ERROR, SIM_ERROR_IO, "%s: cannot read", dir);
        return FALSE;
    }
    guint n = sweep_spec_points(spec);
    char **lines = complete_lines(text, len, &complete);
    char **last = g_new0(char *, n);
    JsonNode **rows = g_new0(JsonNode *, n);
    for (char **l = lines; *l; l++) {
        guint idx;
        gboolean ok;
        if (!**l || !line_point(*l, n, &idx, &ok))
            continue;
        if (rows[idx])
            json_node_unref(rows[idx]);
        rows[idx] = js_parse(*l, -1, LOG_NAME, NULL);
        last[idx] = *l;
    }
    gboolean ok = write_outputs(dir, spec, last, rows, n, table_out, err);
    for (guint i = 0; i < n; i++)
        if (rows[i])
            json_node_unref(rows[i]);
    g_free(rows);
    g_free(last);
    g_strfreev(lines);
    g_free(text);
    g_free(path);
    return ok;
}
