/* trace_paje.c — Paje trace files (Schnorr, Stein, de Kergommeaux, "Paje
 * trace file format", 2013), as read by ViTE.
 *
 * Containers: one "machine" holding one container per node.  A span sets
 * the node's state to the phase at its start and back to "idle" at its
 * end; a message is a link (StartLink on the source, EndLink on the
 * destination, sharing a key); a mark (frame boundary) is a PajeNewEvent
 * on the machine; the counters derived from flows ("messages in flight",
 * "bytes in flight") are variables of the machine (PajeSetVariable).
 * As SimGrid writes them, each network link that carried a message is a
 * container of type "LINK" in the machine with a variable
 * "bandwidth_used" (B/s); a link a message waited for at the packet rung
 * also has a variable "messages_waiting" (its queue depth).
 * Paje needs events in time order, but spans are reported when they end,
 * so lines are buffered with (time, seq) and sorted on close: O(n log n)
 * for n events, memory bounded by the event cap.
 */
#include "sim/app/trace/trace_impl.h"
#include <string.h>

typedef struct {
    SimTime t;
    uint64_t seq;
    char *line; /* after the time field */
    int code;
} PajeLine;

static const char header[] =
    "%EventDef PajeDefineContainerType 0\n% Alias string\n% Type string\n"
    "% Name string\n%EndEventDef\n"
    "%EventDef PajeDefineStateType 1\n% Alias string\n% Type string\n"
    "% Name string\n%EndEventDef\n"
    "%EventDef PajeDefineLinkType 2\n% Alias string\n% Type string\n"
    "% StartContainerType string\n% EndContainerType string\n"
    "% Name string\n%EndEventDef\n"
    "%EventDef PajeDefineEventType 3\n% Alias string\n% Type string\n"
    "% Name string\n%EndEventDef\n"
    "%EventDef PajeCreateContainer 4\n% Time date\n% Alias string\n"
    "% Type string\n% Container string\n% Name string\n%EndEventDef\n"
    "%EventDef PajeDestroyContainer 5\n% Time date\n% Type string\n"
    "% Name string\n%EndEventDef\n"
    "%EventDef PajeSetState 6\n% Time date\n% Type string\n"
    "% Container string\n% Value string\n%EndEventDef\n"
    "%EventDef PajeStartLink 7\n% Time date\n% Type string\n"
    "% Container string\n% Value string\n% StartContainer string\n"
    "% Key string\n%EndEventDef\n"
    "%EventDef PajeEndLink 8\n% Time date\n% Type string\n"
    "% Container string\n% Value string\n% EndContainer string\n"
    "% Key string\n%EndEventDef\n"
    "%EventDef PajeNewEvent 9\n% Time date\n% Type string\n"
    "% Container string\n% Value string\n%EndEventDef\n"
    "%EventDef PajeDefineVariableType 10\n% Alias string\n% Type string\n"
    "% Name string\n%EndEventDef\n"
    "%EventDef PajeSetVariable 11\n% Time date\n% Type string\n"
    "% Container string\n% Value double\n%EndEventDef\n"
    "0 CT_Machine 0 \"Machine\"\n"
    "0 CT_Node CT_Machine \"Node\"\n"
    "1 ST_Phase CT_Node \"Phase\"\n"
    "2 LT_Msg CT_Machine CT_Node CT_Node \"Message\"\n"
    "3 ET_Mark CT_Machine \"Mark\"\n"
    "10 VT_0 CT_Machine \"messages in flight\"\n"
    "10 VT_1 CT_Machine \"bytes in flight (B)\"\n"
    "0 CT_Link CT_Machine \"LINK\"\n"
    "10 VT_bw CT_Link \"bandwidth_used\"\n"
    "10 VT_q CT_Link \"messages_waiting\"\n"
    "4 0.000000000000 machine CT_Machine 0 \"machine\"\n";

static void line_free(gpointer p)
{
    PajeLine *l = p;
    g_free(l->line);
    g_free(l);
}

static char *quoted(const char *s)
{
    char *q = g_strdup(s);
    g_strdelimit(q, "\"\n", '\'');
    return q;
}

/* Buffers "<code> <time> <rest>". */
static void add(TrcWriter *w, int code, SimTime t, char *rest)
{
    PajeLine *l = g_new(PajeLine, 1);
    *l = (PajeLine){t, w->buffer->len, rest, code};
    g_ptr_array_add(w->buffer, l);
}

/* Containers are created in end(), with the last name learnt. */
static void on_node(TrcWriter *w, uint32_t node)
{
    (void)w;
    (void)node;
}

static void on_span(TrcWriter *w, uint32_t node, const char *phase,
                    SimTime start, SimTime end)
{
    char *q = quoted(phase);
    add(w, 6, start, g_strdup_printf("ST_Phase n%u \"%s\"", node, q));
    add(w, 6, end, g_strdup_printf("ST_Phase n%u \"idle\"", node));
    g_free(q);
}

static void on_flow(TrcWriter *w, uint32_t src, uint32_t dst, uint64_t bytes,
                    SimTime sent, SimTime arrived, uint64_t key)
{
    add(w, 7, sent,
        g_strdup_printf("LT_Msg machine \"%" G_GUINT64_FORMAT
                        " B\" n%u m%" G_GUINT64_FORMAT,
                        bytes, src, key));
    add(w, 8, arrived,
        g_strdup_printf("LT_Msg machine \"%" G_GUINT64_FORMAT
                        " B\" n%u m%" G_GUINT64_FORMAT,
                        bytes, dst, key));
}

static void on_mark(TrcWriter *w, const char *name, SimTime t)
{
    char *q = quoted(name);
    add(w, 9, t, g_strdup_printf("ET_Mark machine \"%s\"", q));
    g_free(q);
}

static void on_counter(TrcWriter *w, int which, SimTime t, double value)
{
    char num[G_ASCII_DTOSTR_BUF_SIZE];
    g_ascii_formatd(num, sizeof num, "%.17g", value);
    add(w, 11, t, g_strdup_printf("VT_%d machine %s", which, num));
}

static void on_link_counter(TrcWriter *w, guint link, int which, SimTime t,
                            double value)
{
    char num[G_ASCII_DTOSTR_BUF_SIZE];
    g_ascii_formatd(num, sizeof num, "%.17g", value);
    add(w, 11, t,
        g_strdup_printf("%s l%u %s", which == TRC_LINK_BW ? "VT_bw" : "VT_q",
                        link, num));
}

static void begin(TrcWriter *w)
{
    w->buffer = g_ptr_array_new_with_free_func(line_free);
    fputs("# pgsim trace in Paje format (open with ViTE)\n", w->f);
    fputs(header, w->f);
}

static gint by_time(gconstpointer a, gconstpointer b)
{
    const PajeLine *x = *(PajeLine *const *)a, *y = *(PajeLine *const *)b;
    if (x->t != y->t)
        return x->t < y->t ? -1 : 1;
    return x->seq < y->seq ? -1 : x->seq > y->seq;
}

static gint by_id(gconstpointer a, gconstpointer b)
{
    guint x = *(const guint *)a, y = *(const guint *)b;
    return x < y ? -1 : x > y;
}

static GArray *node_ids(TrcWriter *w)
{
    GHashTableIter it;
    gpointer key;
    GArray *ids = g_array_new(FALSE, FALSE, sizeof(guint));
    g_hash_table_iter_init(&it, w->nodes);
    while (g_hash_table_iter_next(&it, &key, NULL)) {
        guint id = GPOINTER_TO_UINT(key) - 1;
        g_array_append_val(ids, id);
    }
    g_array_sort(ids, by_id);
    return ids;
}

static void end(TrcWriter *w)
{
    GArray *ids = node_ids(w);
    for (guint i = 0; i < ids->len; i++) {
        guint id = g_array_index(ids, guint, i);
        char *q =
            quoted(g_hash_table_lookup(w->nodes, GUINT_TO_POINTER(id + 1)));
        fprintf(w->f, "4 0.000000000000 n%u CT_Node machine \"%s\"\n", id, q);
        g_free(q);
    }
    for (guint i = 0; i < w->link_names->len; i++) {
        char *q = quoted(w->link_names->pdata[i]);
        fprintf(w->f, "4 0.000000000000 l%u CT_Link machine \"%s\"\n", i, q);
        g_free(q);
    }
    g_ptr_array_sort(w->buffer, by_time);
    SimTime last = 0;
    for (guint i = 0; i < w->buffer->len; i++) {
        const PajeLine *l = g_ptr_array_index(w->buffer, i);
        fprintf(w->f, "%d %" G_GUINT64_FORMAT ".%012" G_GUINT64_FORMAT " %s\n",
                l->code, l->t / SIM_S, l->t % SIM_S, l->line);
        last = l->t;
    }
    for (guint i = 0; i < ids->len; i++)
        fprintf(w->f,
                "5 %" G_GUINT64_FORMAT ".%012" G_GUINT64_FORMAT
                " CT_Node n%u\n",
                last / SIM_S, last % SIM_S, g_array_index(ids, guint, i));
    g_array_free(ids, TRUE);
    for (guint i = 0; i < w->link_names->len; i++)
        fprintf(w->f,
                "5 %" G_GUINT64_FORMAT ".%012" G_GUINT64_FORMAT
                " CT_Link l%u\n",
                last / SIM_S, last % SIM_S, i);
    fprintf(w->f,
            "5 %" G_GUINT64_FORMAT ".%012" G_GUINT64_FORMAT
            " CT_Machine machine\n",
            last / SIM_S, last % SIM_S);
}

const TrcFormat trc_paje = {begin,   on_node,    on_span,         on_flow,
                            on_mark, on_counter, on_link_counter, end};
