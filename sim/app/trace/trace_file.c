/* trace_file.c — opening, capping and closing trace files.
 *
 * Invariants: at most `cap` events are recorded; after the cap the note
 * is written exactly once and every hook is a no-op.  The file is written
 * as <path>.tmp and renamed to <path> on a successful close, so a reader
 * never sees half a trace under the final name.  O(1) per event.
 */
#include "sim/app/trace/trace_impl.h"
#include <errno.h>
#include <stdio.h>
#include <string.h>

static const TrcFormat *format_for(const char *path)
{
    if (g_str_has_suffix(path, ".json"))
        return &trc_chrome;
    if (g_str_has_suffix(path, ".paje") || g_str_has_suffix(path, ".trace"))
        return &trc_paje;
    return NULL;
}

SimTrace *trc_open(const char *path, uint64_t max_events, GError **err)
{
    const TrcFormat *fmt = format_for(path);
    if (!fmt) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "--trace: found '%s', expected a file ending in .json "
                    "(Chrome/Perfetto) or .paje (ViTE)",
                    path);
        return NULL;
    }
    TrcWriter *w = g_new0(TrcWriter, 1);
    w->tmp = g_strconcat(path, ".tmp", NULL);
    w->f = fopen(w->tmp, "w");
    if (!w->f) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_IO, "%s: cannot write: %s",
                    w->tmp, g_strerror(errno));
        g_free(w->tmp);
        g_free(w);
        return NULL;
    }
    w->fmt = fmt;
    w->path = g_strdup(path);
    w->cap = max_events ? max_events : TRC_DEFAULT_CAP;
    w->nodes = g_hash_table_new_full(NULL, NULL, NULL, g_free);
    w->default_named = g_hash_table_new(NULL, NULL);
    w->trace.ops = fmt->ops;
    w->trace.state = w;
    fmt->begin(w);
    return &w->trace;
}

gboolean trc_admit(TrcWriter *w, SimTime t)
{
    if (w->truncated)
        return FALSE;
    if (w->events < w->cap) {
        w->events++;
        return TRUE;
    }
    w->truncated = TRUE;
    w->fmt->cap_note(w, t);
    fprintf(stderr,
            "pgsim: trace %s: cap of %" G_GUINT64_FORMAT
            " events reached at %.6f ms; later events are not "
            "recorded\n",
            w->path, w->cap, sim_time_to_ms(t));
    return FALSE;
}

gboolean trc_new_node(TrcWriter *w, uint32_t node, const char *name)
{
    gpointer key = GUINT_TO_POINTER(node + 1);
    const char *old = g_hash_table_lookup(w->nodes, key);
    /* a flow knows only the id; a later span may bring the real name */
    if (old && (!name || strcmp(old, name) == 0 ||
                !g_hash_table_contains(w->default_named, key)))
        return FALSE;
    g_hash_table_insert(
        w->nodes, key, name ? g_strdup(name) : g_strdup_printf("node%u", node));
    if (name)
        g_hash_table_remove(w->default_named, key);
    else
        g_hash_table_add(w->default_named, key);
    return TRUE;
}

uint64_t trc_events(const SimTrace *tr)
{
    return ((const TrcWriter *)tr->state)->events;
}

gboolean trc_truncated(const SimTrace *tr)
{
    return ((const TrcWriter *)tr->state)->truncated;
}

static void writer_free(TrcWriter *w);

gboolean trc_close(SimTrace *tr, GError **err)
{
    if (!tr)
        return TRUE;
    TrcWriter *w = tr->state;
    w->fmt->end(w);
    gboolean ok = !ferror(w->f);
    ok = fclose(w->f) == 0 && ok;
    if (ok && rename(w->tmp, w->path) != 0)
        ok = FALSE;
    if (!ok) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_IO, "%s: cannot write: %s",
                    w->path, g_strerror(errno));
        remove(w->tmp);
    }
    writer_free(w);
    return ok;
}

void trc_discard(SimTrace *tr)
{
    if (!tr)
        return;
    TrcWriter *w = tr->state;
    fclose(w->f);
    remove(w->tmp);
    writer_free(w);
}

static void writer_free(TrcWriter *w)
{
    g_hash_table_destroy(w->nodes);
    g_hash_table_destroy(w->default_named);
    if (w->buffer)
        g_ptr_array_free(w->buffer, TRUE);
    g_free(w->path);
    g_free(w->tmp);
    g_free(w);
}
