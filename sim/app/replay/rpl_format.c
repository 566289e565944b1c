/* rpl_format.c — reading and writing version-1 to -4 traces (rpl_format.h).
 *
 * The reader is a loop over lines: header keywords until the first group
 * or action, then body items.  State: the header, the number of actions
 * read, whether a group is open, the set of `+` actions still awaiting
 * their `on` group and the set of `&` actions still awaiting the action
 * `after` them.  Cost: O(length of the line) per item.
 */
#include "sim/app/replay/rpl_format.h"
#include "sim/core/error.h"
#include "sim/core/memlimit.h"
#include <inttypes.h>
#include <string.h>

struct RplReader {
    RplLines *l;
    RplHeader h;
    uint64_t actions;         /* actions read so far */
    gboolean in_group;        /* a group line has been read */
    GHashTable *await;        /* uint64 id -> itself: `+` without `on` yet */
    GHashTable *joins;        /* the same for `&` without `after ID` yet */
    gboolean pending;         /* the current line is a body line not yet used */
    uint64_t version;         /* 1, 2 (b, v and swap), 3 (`|` terms) or 4
                                 (`after`, `&`) */
    gboolean framed, swapped; /* a `frame` / `swap` flag was read */
};

static gboolean fail(RplReader *r, int i, const char *what, GError **err)
{
    g_propagate_error(err, rpl_lines_error(r->l, i, what));
    return FALSE;
}

void rpl_header_clear(RplHeader *h)
{
    g_free(h->machine);
    g_free(h->fidelity);
    if (h->phases)
        g_ptr_array_free(h->phases, TRUE);
    for (guint i = 0; h->kinds && i < h->kinds->len; i++)
        g_free(g_array_index(h->kinds, RplKind, i).name);
    if (h->kinds)
        g_array_free(h->kinds, TRUE);
    memset(h, 0, sizeof *h);
}

const RplKind *rpl_header_kind_of(const RplHeader *h, guint p)
{
    guint lo = 0, hi = h->kinds ? h->kinds->len : 0;
    while (lo < hi) { /* the first kind whose first id is above p */
        guint mid = lo + (hi - lo) / 2;
        if (g_array_index(h->kinds, RplKind, mid).first <= p)
            lo = mid + 1;
        else
            hi = mid;
    }
    const RplKind *k = lo ? &g_array_index(h->kinds, RplKind, lo - 1) : NULL;
    return k && p - k->first < k->count ? k : NULL;
}

static gboolean header_kind(RplReader *r, GError **err)
{
    uint64_t first, count;
    double hz;
    char *end;
    const char *w4 = rpl_lines_word(r->l, 4);
    if (rpl_lines_count(r->l) != 5)
        return fail(r, MIN(rpl_lines_count(r->l), 5),
                    "kind NAME FIRST COUNT CLOCK_HZ", err);
    if (!rpl_lines_u64(r->l, 2, G_MAXUINT32, &first, "a first processor id",
                       err) ||
        !rpl_lines_u64(r->l, 3, G_MAXUINT32, &count, "a processor count", err))
        return FALSE;
    if (count == 0)
        return fail(r, 3, "a processor count above 0", err);
    hz = g_ascii_strtod(w4, &end);
    if (*end || end == w4 || !(hz == 0 || (hz >= RPL_CLOCK_MIN &&
                                           hz <= RPL_CLOCK_MAX)))
        return fail(r, 4, "a clock from 1 Hz to 1e15 Hz (0: none)", err);
    RplKind k = {g_strdup(rpl_lines_word(r->l, 1)), (guint)first, (guint)count,
                 hz, rpl_lines_number(r->l), rpl_lines_col(r->l, 2)};
    g_array_append_val(r->h.kinds, k);
    return TRUE;
}

/* A replay keeps no state per trace processor unless a map file gives
 * one (4 bytes each); 16 bytes a processor leaves room for that and for
 * a SimGrid import's per-rank state: a huge `procs` is an input error
 * here, never a failed allocation later. */
static gboolean procs_fit(RplReader *r, uint64_t n, GError **err)
{
    char *where = g_strdup_printf("%s:%u:7", rpl_lines_path(r->l),
                                  rpl_lines_number(r->l));
    char *what = g_strdup_printf("procs %" PRIu64, n);
    gboolean ok = sim_mem_check((double)n * 16, where, what, err);
    g_free(where);
    g_free(what);
    return ok;
}

/* One header line; *body set when the line starts the body instead. */
static gboolean header_line(RplReader *r, gboolean *body, GError **err)
{
    const char *k = rpl_lines_word(r->l, 0);
    int n = rpl_lines_count(r->l);
    uint64_t v;
    *body = FALSE;
    if (!strcmp(k, "kind"))
        return header_kind(r, err);
    if (strcmp(k, "machine") && strcmp(k, "fidelity") && strcmp(k, "procs") &&
        strcmp(k, "phase")) {
        *body = TRUE;
        return TRUE;
    }
    if (n != 2)
        return fail(r, MIN(n, 2), "one word after the keyword", err);
    const char *a = rpl_lines_word(r->l, 1);
    if (!strcmp(k, "machine"))
        g_free(r->h.machine), r->h.machine = g_strdup(a);
    else if (!strcmp(k, "fidelity"))
        g_free(r->h.fidelity), r->h.fidelity = g_strdup(a);
    else if (!strcmp(k, "phase"))
        g_ptr_array_add(r->h.phases, g_strdup(a));
    else if (!rpl_lines_u64(r->l, 1, G_MAXUINT32, &v, "a processor count", err))
        return FALSE;
    else if (v == 0)
        return fail(r, 1, "a processor count above 0", err);
    else if (!procs_fit(r, v, err))
        return FALSE;
    else
        r->h.procs = (guint)v;
    return TRUE;
}

static gint by_first(gconstpointer a, gconstpointer b)
{
    guint x = ((const RplKind *)a)->first, y = ((const RplKind *)b)->first;
    return x < y ? -1 : x > y;
}

static gboolean kind_fail(RplReader *r, const RplKind *k, const char *what,
                          GError **err)
{
    g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                "%s:%u:%d: found kind '%s' over processors %u..%" G_GUINT64_FORMAT
                ", expected %s",
                rpl_lines_path(r->l), k->line, k->col, k->name, k->first,
                (guint64)k->first + k->count - 1, what);
    return FALSE;
}

/* The header is complete (the body starts on the current line when
 * body): `procs` was given, and the kinds, sorted by first id, are
 * disjoint and below procs.  O(kinds log kinds). */
static gboolean header_done(RplReader *r, gboolean body, GError **err)
{
    if (body && !r->h.procs)
        return fail(r, 0, "a 'procs N' header line before the first group",
                    err);
    g_array_sort(r->h.kinds, by_first);
    for (guint i = 0; i < r->h.kinds->len; i++) {
        const RplKind *k = &g_array_index(r->h.kinds, RplKind, i);
        const RplKind *prev = i ? k - 1 : NULL;
        char *what = NULL;
        if ((guint64)k->first + k->count > r->h.procs)
            what = g_strdup_printf("processors below procs %u", r->h.procs);
        else if (prev && prev->first + prev->count > k->first)
            what = g_strdup_printf("no processor of kind '%s' (line %u) in "
                                   "a second kind",
                                   prev->name, prev->line);
        if (what) {
            kind_fail(r, k, what, err);
            g_free(what);
            return FALSE;
        }
    }
    return TRUE;
}

static gboolean read_header(RplReader *r, GError **err)
{
    int n = rpl_lines_next(r->l, err);
    uint64_t v;
    if (n < 0)
        return FALSE;
    if (n == 0 || strcmp(rpl_lines_word(r->l, 0), "pgsim-trace"))
        return fail(r, 0, "'pgsim-trace 1' on the first line", err);
    if (!rpl_lines_u64(r->l, 1, G_MAXUINT32, &v,
                       "trace format version 1, 2, 3 or 4", err))
        return FALSE;
    if (v < 1 || v > RPL_VERSION || n != 2)
        return fail(r, v < 1 || v > RPL_VERSION ? 1 : 2,
                    "trace format version 1, 2, 3 or 4 alone", err);
    r->version = v;
    for (;;) {
        gboolean body;
        n = rpl_lines_next(r->l, err);
        if (n <= 0)
            return n == 0 && header_done(r, FALSE, err);
        if (!header_line(r, &body, err))
            return FALSE;
        if (body) {
            r->pending = TRUE;
            return header_done(r, TRUE, err);
        }
    }
}

RplReader *rpl_reader_open(const char *path, GError **err)
{
    RplLines *l = rpl_lines_open(path, err);
    if (!l)
        return NULL;
    RplReader *r = g_new0(RplReader, 1);
    r->l = l;
    r->h.phases = g_ptr_array_new_with_free_func(g_free);
    r->h.kinds = g_array_new(FALSE, FALSE, sizeof(RplKind));
    r->await = g_hash_table_new(g_int64_hash, g_int64_equal);
    r->joins = g_hash_table_new(g_int64_hash, g_int64_equal);
    if (!read_header(r, err)) {
        rpl_reader_free(r);
        return NULL;
    }
    if (r->h.phases->len == 0)
        g_ptr_array_add(r->h.phases, g_strdup("compute"));
    return r;
}

void rpl_reader_free(RplReader *r)
{
    if (!r)
        return;
    rpl_lines_free(r->l);
    rpl_header_clear(&r->h);
    GHashTable *sets[] = {r->await, r->joins};
    for (int s = 0; s < 2; s++) {
        GHashTableIter it;
        gpointer key;
        g_hash_table_iter_init(&it, sets[s]);
        while (g_hash_table_iter_next(&it, &key, NULL))
            g_free(key);
        g_hash_table_destroy(sets[s]);
    }
    g_free(r);
}

const RplHeader *rpl_reader_header(const RplReader *r)
{
    return &r->h;
}

const char *rpl_reader_path(const RplReader *r)
{
    return rpl_lines_path(r->l);
}

guint rpl_reader_awaited(const RplReader *r)
{
    return g_hash_table_size(r->await) + g_hash_table_size(r->joins);
}

/* `swap` (version 2): on a `v` action, in a trace without `frame`. */
static gboolean swap_flag(RplReader *r, int i, RplItem *it, GError **err)
{
    if (r->version < 2 || it->type != RPL_REFRESH || r->framed)
        return fail(r, i,
                    "'+', 'frame' or the end of the line ('swap' ends only "
                    "a `v` action, in a version-2 trace without 'frame')",
                    err);
    it->swap = r->swapped = TRUE;
    return TRUE;
}

/* `after ID` at word i (version 4): ID an earlier action marked `&`
 * that no other `after` names. */
static gboolean after_word(RplReader *r, int i, RplItem *it, GError **err)
{
    if (!rpl_lines_u64(r->l, i + 1, G_MAXUINT64, &it->after,
                       "an action id after 'after'", err))
        return FALSE;
    gpointer key = NULL;
    if (it->after >= r->actions ||
        !g_hash_table_steal_extended(r->joins, &it->after, &key, NULL))
        return fail(r, i + 1,
                    "an earlier action marked '&' that no other 'after' "
                    "names",
                    err);
    g_free(key);
    it->has_after = TRUE;
    return TRUE;
}

/* Trailing `after ID`, `+`, `&`, `frame` and `swap` from word i on. */
static gboolean flags(RplReader *r, int i, RplItem *it, GError **err)
{
    for (; i < rpl_lines_count(r->l); i++) {
        const char *w = rpl_lines_word(r->l, i);
        gboolean v4 = r->version >= 4;
        if (!strcmp(w, "+") && !it->handled)
            it->handled = TRUE;
        else if (v4 && !strcmp(w, "&") && !it->joined)
            it->joined = TRUE;
        else if (v4 && !strcmp(w, "after") && !it->has_after) {
            if (!after_word(r, i++, it, err))
                return FALSE;
        } else if (!strcmp(w, "frame") && !it->frame && !r->swapped)
            it->frame = r->framed = TRUE;
        else if (!strcmp(w, "swap") && !it->swap) {
            if (!swap_flag(r, i, it, err))
                return FALSE;
        } else
            return fail(r, i,
                        r->swapped ? "'+', 'swap' or the end of the line "
                                     "(a trace with 'swap' has no 'frame')"
                        : v4 ? "'+', '&', 'after ID', 'frame' or the end of "
                               "the line"
                             : "'+', 'frame' or the end of the line",
                        err);
    }
    return TRUE;
}

static gboolean proc_word(RplReader *r, int i, uint32_t *out, GError **err)
{
    uint64_t v;
    if (!r->h.procs)
        return fail(r, i, "a processor, after a 'procs N' header line", err);
    char *what = g_strdup_printf("a processor id below %u", r->h.procs);
    gboolean ok = rpl_lines_u64(r->l, i, r->h.procs - 1, &v, what, err);
    g_free(what);
    *out = (uint32_t)v;
    return ok;
}

static gboolean phase_word(RplReader *r, int i, unsigned *out, GError **err)
{
    uint64_t v;
    char *what =
        g_strdup_printf("a phase id below %u (phase lines)", r->h.phases->len);
    gboolean ok = rpl_lines_u64(r->l, i, r->h.phases->len - 1, &v, what, err);
    g_free(what);
    *out = (unsigned)v;
    return ok;
}

/* OP=COUNT words from word *i on, at most max of them, into the arrays;
 * *n gets how many; stops at the first word without '='. */
static gboolean op_words(RplReader *r, int *i, guint max, const char **op,
                         uint64_t *count, int *col, guint *n, GError **err)
{
    int end = rpl_lines_count(r->l);
    for (*n = 0; *i < end; (*i)++) {
        char *w = (char *)rpl_lines_word(r->l, *i), *eq = strchr(w, '=');
        if (!eq)
            break;
        guint64 v;
        if (eq == w || *n == max ||
            !g_ascii_string_to_unsigned(eq + 1, 10, 0, G_MAXUINT64, &v, NULL))
            return fail(r, *i,
                        max == RPL_MAX_OPS ? "OP=COUNT (at most 30 a line)"
                                           : "OP=COUNT (at most 8 a term)",
                        err);
        *eq = 0; /* the line buffer is ours until the next line */
        col[*n] = rpl_lines_col(r->l, *i);
        op[*n] = w;
        count[(*n)++] = v;
    }
    return TRUE;
}

/* One `|` term from word *i on (version 3): `@Q OP=COUNT ...` or
 * `b Q BYTES`. */
static gboolean term(RplReader *r, int *i, RplTerm *t, GError **err)
{
    const char *w = rpl_lines_word(r->l, *i);
    t->col = rpl_lines_col(r->l, *i);
    if (w && !strcmp(w, "b")) {
        t->bus = TRUE;
        *i += 3;
        return proc_word(r, *i - 2, &t->proc, err) &&
               rpl_lines_u64(r->l, *i - 1, G_MAXUINT64, &t->bytes,
                             "a byte count", err);
    }
    if (!w || w[0] != '@' || !w[1])
        return fail(r, *i, "'@PROC OP=COUNT ...' or 'b PROC BYTES' after '|'",
                    err);
    char *end;
    guint64 q = g_ascii_strtoull(w + 1, &end, 10);
    if (*end || q >= r->h.procs)
        return fail(r, *i, "'@PROC' with a processor id below procs", err);
    t->proc = (uint32_t)q;
    (*i)++;
    if (!op_words(r, i, RPL_TERM_OPS, t->op, t->count, t->op_col, &t->n_ops,
                  err))
        return FALSE;
    return t->n_ops > 0 || fail(r, *i, "OP=COUNT", err);
}

/* op=count words of a `c` line from word 3, then `|` terms, up to the
 * flags. */
static gboolean ops(RplReader *r, RplItem *it, GError **err)
{
    int i = 3;
    if (!op_words(r, &i, RPL_MAX_OPS, it->op, it->count, it->op_col, &it->n_ops,
                  err))
        return FALSE;
    if (it->n_ops == 0)
        return fail(r, 3, "OP=COUNT", err);
    while (i < rpl_lines_count(r->l) && !strcmp(rpl_lines_word(r->l, i), "|")) {
        if (r->version < 3 || it->n_terms == RPL_MAX_TERMS)
            return fail(r, i,
                        r->version < 3 ? "'+', 'frame' or the end of the "
                                         "line ('|' terms need 'pgsim-trace 3')"
                                       : "at most 3 '|' terms",
                        err);
        i++;
        memset(&it->term[it->n_terms], 0, sizeof it->term[0]);
        if (!term(r, &i, &it->term[it->n_terms++], err))
            return FALSE;
    }
    return flags(r, i, it, err);
}

/* Memory an action marked `+` holds until its `on` group is read: the
 * reader's entry here and the replay's flight (rpl_replay.c), about. */
#define RPL_AWAIT_BYTES 128.0

/* The `+` actions awaiting their groups fit the memory limit: a trace
 * whose replies never come is an input error before memory runs out.
 * Checked every 65,536 entries; O(1). */
static gboolean await_fits(RplReader *r, GError **err)
{
    guint n = rpl_reader_awaited(r);
    if (n % 65536)
        return TRUE;
    char *where = g_strdup_printf("%s:%u:1", rpl_lines_path(r->l),
                                  rpl_lines_number(r->l));
    /* `&` actions awaiting their `after` count too */
    char *what = g_strdup_printf("%u actions marked '+' whose 'on' groups "
                                 "have not come",
                                 n);
    gboolean ok = sim_mem_check(n * RPL_AWAIT_BYTES, where, what, err);
    g_free(where);
    g_free(what);
    return ok;
}

static gboolean action(RplReader *r, RplItem *it, GError **err)
{
    const char *k = rpl_lines_word(r->l, 0);
    if (!r->in_group)
        return fail(r, 0,
                    "'at TIME', 'sync TIME' or 'on ID' before the "
                    "first action",
                    err);
    it->type = !strcmp(k, "c")   ? RPL_COMPUTE
               : !strcmp(k, "w") ? RPL_WORK
               : !strcmp(k, "b") ? RPL_BUS
               : !strcmp(k, "v") ? RPL_REFRESH
                                 : RPL_SEND;
    it->id = r->actions;
    if (r->version < 2 && (it->type == RPL_BUS || it->type == RPL_REFRESH))
        return fail(r, 0, "c, w or s (b and v need 'pgsim-trace 2')", err);
    if (!proc_word(r, 1, &it->proc, err))
        return FALSE;
    gboolean ok =
        it->type == RPL_SEND || it->type == RPL_BUS
            ? proc_word(r, 2, &it->peer, err) &&
                  rpl_lines_u64(r->l, 3, G_MAXUINT64, &it->value,
                                "a byte count", err) &&
                  flags(r, 4, it, err)
        : it->type == RPL_REFRESH
            ? rpl_lines_u64(r->l, 2, G_MAXUINT64, &it->value,
                            "a refresh period in picoseconds", err) &&
                  (it->value > 0 || fail(r, 2, "a period above 0", err)) &&
                  flags(r, 3, it, err)
        : !phase_word(r, 2, &it->phase, err) ? FALSE
        : it->type == RPL_WORK ? rpl_lines_u64(r->l, 3, G_MAXUINT64, &it->value,
                                               "a time in picoseconds", err) &&
                                     flags(r, 4, it, err)
                               : ops(r, it, err);
    if (!ok)
        return FALSE;
    for (int s = 0; s < 2; s++) {
        if (!(s ? it->joined : it->handled))
            continue;
        uint64_t *key = g_new(uint64_t, 1);
        *key = it->id;
        g_hash_table_add(s ? r->joins : r->await, key);
        if (!await_fits(r, err))
            return FALSE;
    }
    r->actions++;
    return TRUE;
}

static gboolean group(RplReader *r, RplItem *it, GError **err)
{
    const char *k = rpl_lines_word(r->l, 0);
    gboolean on = !strcmp(k, "on");
    if (rpl_lines_count(r->l) > 2)
        return fail(r, 2, "the end of the line", err);
    it->type = on ? RPL_ON : !strcmp(k, "sync") ? RPL_SYNC : RPL_AT;
    if (!on)
        return rpl_lines_u64(r->l, 1, G_MAXUINT64, &it->at,
                             "a time in picoseconds", err) &&
               (r->in_group = TRUE);
    if (!rpl_lines_u64(r->l, 1, G_MAXUINT64, &it->id, "an action id", err))
        return FALSE;
    gpointer key = NULL;
    if (!g_hash_table_steal_extended(r->await, &it->id, &key, NULL))
        return fail(r, 1,
                    "an earlier action marked '+' whose group has not "
                    "been given yet",
                    err);
    g_free(key);
    r->in_group = TRUE;
    return TRUE;
}

static gboolean at_end(RplReader *r, GError **err)
{
    if (r->actions == 0) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "%s:%u:1: found the end of the trace, expected at least "
                    "one action (c, w, s, b or v)",
                    rpl_lines_path(r->l), rpl_lines_number(r->l) + 1);
        return FALSE;
    }
    gboolean on = g_hash_table_size(r->await) > 0;
    GHashTable *set = on ? r->await : r->joins;
    if (g_hash_table_size(set) == 0)
        return FALSE;
    GHashTableIter i;
    gpointer key;
    uint64_t first = G_MAXUINT64;
    g_hash_table_iter_init(&i, set);
    while (g_hash_table_iter_next(&i, &key, NULL))
        first = MIN(first, *(uint64_t *)key);
    g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                "%s:%u:1: found the end of the trace, expected %s %" PRIu64
                "%s (action %" PRIu64 " is marked '%s'; %u such %s missing)",
                rpl_lines_path(r->l), rpl_lines_number(r->l) + 1,
                on ? "'on" : "an action 'after", first, "'", first,
                on ? "+" : "&", g_hash_table_size(set),
                on ? "groups" : "actions");
    return FALSE;
}

gboolean rpl_reader_next(RplReader *r, RplItem *it, GError **err)
{
    if (!r->pending) {
        int n = rpl_lines_next(r->l, err);
        if (n < 0)
            return FALSE;
        if (n == 0)
            return at_end(r, err);
    }
    r->pending = FALSE;
    memset(it, 0, offsetof(RplItem, op));
    it->line = rpl_lines_number(r->l);
    const char *k = rpl_lines_word(r->l, 0);
    if (!strcmp(k, "at") || !strcmp(k, "on") || !strcmp(k, "sync"))
        return group(r, it, err);
    if (!strcmp(k, "c") || !strcmp(k, "w") || !strcmp(k, "s") ||
        !strcmp(k, "b") || !strcmp(k, "v"))
        return action(r, it, err);
    return fail(r, 0,
                "at, sync, on, c, w, s, b or v (header lines come before "
                "the first group)",
                err);
}

/* ---- writing ---- */

void rpl_write_header(RplWriter *w, const RplHeader *h)
{
    rpl_writer_printf(w, "pgsim-trace %d\n", RPL_VERSION);
    if (h->machine)
        rpl_writer_printf(w, "machine %s\n", h->machine);
    if (h->fidelity)
        rpl_writer_printf(w, "fidelity %s\n", h->fidelity);
    rpl_writer_printf(w, "procs %u\n", h->procs);
    for (guint i = 0; h->kinds && i < h->kinds->len; i++) {
        const RplKind *k = &g_array_index(h->kinds, RplKind, i);
        char hz[G_ASCII_DTOSTR_BUF_SIZE];
        g_ascii_formatd(hz, sizeof hz, "%.17g", k->clock_hz);
        rpl_writer_printf(w, "kind %s %u %u %s\n", k->name, k->first, k->count,
                          hz);
    }
    for (guint i = 0; i < h->phases->len; i++)
        rpl_writer_printf(w, "phase %s\n", (char *)h->phases->pdata[i]);
}

/* Appends " OP=COUNT ..." to buf (of RPL_LINE_MAX) at n; the new n. */
static int write_ops(char *buf, int n, const char *const *op,
                     const uint64_t *count, guint n_ops)
{
    for (guint i = 0; i < n_ops && n < RPL_LINE_MAX; i++)
        n += g_snprintf(buf + n, RPL_LINE_MAX - n, " %s=%" PRIu64, op[i],
                        count[i]);
    return n;
}

/* Appends " | @Q OP=COUNT ..." or " | b Q BYTES". */
static int write_term(char *buf, int n, const RplTerm *t)
{
    if (n >= RPL_LINE_MAX)
        return n;
    if (t->bus)
        return n + g_snprintf(buf + n, RPL_LINE_MAX - n, " | b %u %" PRIu64,
                              t->proc, t->bytes);
    n += g_snprintf(buf + n, RPL_LINE_MAX - n, " | @%u", t->proc);
    return write_ops(buf, n, t->op, t->count, t->n_ops);
}

void rpl_write_item(RplWriter *w, const RplItem *it)
{
    char buf[RPL_LINE_MAX];
    int n = 0;
    switch (it->type) {
    case RPL_AT:
        rpl_writer_printf(w, "at %" PRIu64 "\n", it->at);
        return;
    case RPL_ON:
        rpl_writer_printf(w, "on %" PRIu64 "\n", it->id);
        return;
    case RPL_SYNC:
        rpl_writer_printf(w, "sync %" PRIu64 "\n", it->at);
        return;
    case RPL_COMPUTE:
        n = g_snprintf(buf, sizeof buf, "c %u %u", it->proc, it->phase);
        n = write_ops(buf, n, it->op, it->count, it->n_ops);
        for (guint k = 0; k < it->n_terms; k++)
            n = write_term(buf, n, &it->term[k]);
        break;
    case RPL_WORK:
        n = g_snprintf(buf, sizeof buf, "w %u %u %" PRIu64, it->proc, it->phase,
                       it->value);
        break;
    case RPL_SEND:
    case RPL_BUS:
        n = g_snprintf(buf, sizeof buf, "%s %u %u %" PRIu64,
                       it->type == RPL_SEND ? "s" : "b", it->proc, it->peer,
                       it->value);
        break;
    case RPL_REFRESH:
        n = g_snprintf(buf, sizeof buf, "v %u %" PRIu64, it->proc, it->value);
        break;
    }
    if (it->has_after && n < RPL_LINE_MAX)
        n += g_snprintf(buf + n, RPL_LINE_MAX - n, " after %" PRIu64,
                        it->after);
    rpl_writer_printf(w, "%s%s%s%s%s\n", buf, it->handled ? " +" : "",
                      it->joined ? " &" : "", it->frame ? " frame" : "",
                      it->swap ? " swap" : "");
}
