/* progress.c — rate-limited progress line on a terminal (progress.h).
 *
 * State: the last drawn wall time; a redraw happens when at least
 * RPT_PROGRESS_PERIOD_US has passed, so the cost of update() between
 * redraws is one clock read.  The line is redrawn in place with "\r" and
 * cleared to the end ("\033[K").  O(1) per call.
 */
#include "sim/output/progress.h"
#include <unistd.h>

#define RPT_PROGRESS_PERIOD_US 100000 /* at most 10 redraws per second */
#define RPT_PROGRESS_EVERY 16384      /* engine callback period (events) */

struct RptProgress {
    FILE *out;
    gint64 (*clock_us)(void);
    char *label;
    char *note; /* NULL: none */
    uint64_t total, done;
    gint64 start, last; /* wall clock, us; last < 0: never drawn */
    SimEngine *eng;     /* borrowed; shows simulated time when set */
};

RptProgress *rpt_progress_new_full(uint64_t total, const char *label, FILE *out,
                                   gint64 (*clock_us)(void))
{
    if (!out)
        return NULL;
    RptProgress *p = g_new0(RptProgress, 1);
    p->out = out;
    p->clock_us = clock_us ? clock_us : g_get_monotonic_time;
    p->label = g_strdup(label ? label : "");
    p->total = total;
    p->start = p->clock_us();
    p->last = -1;
    return p;
}

RptProgress *rpt_progress_new(uint64_t total, const char *label)
{
    return rpt_progress_new_full(total, label,
                                 isatty(STDERR_FILENO) ? stderr : NULL, NULL);
}

static void draw(RptProgress *p, gint64 now)
{
    double secs = (double)(now - p->start) * 1e-6;
    fprintf(p->out, "\r%s: ", p->label);
    if (p->total)
        fprintf(p->out, "%3.0f%% (%" G_GUINT64_FORMAT "/%" G_GUINT64_FORMAT ")",
                100.0 * (double)p->done / (double)p->total, p->done, p->total);
    else
        fprintf(p->out, "%" G_GUINT64_FORMAT, p->done);
    if (p->eng)
        fprintf(p->out, " events, simulated %.6f s",
                sim_time_to_s(sim_now(p->eng)));
    if (p->note)
        fprintf(p->out, ", %s", p->note);
    fprintf(p->out, ", %.1f s", secs);
    if (p->total && p->done && p->done < p->total) {
        int eta = (int)(secs / (double)p->done * (double)(p->total - p->done));
        fprintf(p->out, ", ETA %d:%02d", eta / 60, eta % 60);
    }
    fputs("\033[K", p->out);
    fflush(p->out);
    p->last = now;
}

void rpt_progress_update(RptProgress *p, uint64_t done)
{
    if (!p)
        return;
    p->done = done;
    gint64 now = p->clock_us();
    if (p->last < 0 || now - p->last >= RPT_PROGRESS_PERIOD_US)
        draw(p, now);
}

uint64_t rpt_progress_done(const RptProgress *p)
{
    return p ? p->done : 0;
}

void rpt_progress_note(RptProgress *p, const char *note)
{
    if (!p)
        return;
    g_free(p->note);
    p->note = g_strdup(note);
}

void rpt_progress_finish(RptProgress *p)
{
    if (!p)
        return;
    if (p->eng)
        p->done = sim_engine_events(p->eng);
    if (p->last >= 0) { /* only a drawn line needs finishing */
        draw(p, p->clock_us());
        fputc('\n', p->out);
        fflush(p->out);
    }
    if (p->eng)
        sim_engine_set_progress(p->eng, 0, NULL, NULL);
    g_free(p->label);
    g_free(p->note);
    g_free(p);
}

static void on_events(SimEngine *eng, void *ctx)
{
    rpt_progress_update(ctx, sim_engine_events(eng));
}

void rpt_progress_attach(RptProgress *p, SimEngine *eng)
{
    if (!p)
        return;
    p->eng = eng;
    sim_engine_set_progress(eng, RPT_PROGRESS_EVERY, on_events, p);
}
