/* sf_figures.c — a sort-first frame's figures (sf_frame.h
 * WlSfFrameStats): migration and bookkeeping sums, where the master
 * copies are, the edits' work, load and busy-time imbalance, instance
 * overlap with the regions (seed 000 §4.2), utilisation, and the checks
 * a frame must pass (the migration invariant of sf_book.h; with
 * check_image, the same pixels as the serial render).  Busy times are
 * read from the machine's processors; the traversal's share is priced
 * from the node's costs.  Cost: O(P + chunks + instances) per frame.
 */
#include "sim/workload/sortfirst/sf_frame_internal.h"
#include <math.h>
#include <string.h>

double wl_sf_max_over_mean(double max, double total, guint n)
{
    return total > 0 ? max * n / total : 0;
}

/* Work = each processor's busy time in the frame. */
/* One bounding-volume test of the database's kind (sf_bv.h). */
static SimTime bv_test_time(const WlSfRun *r)
{
    WlSfBvCost c = wl_sf_bv_cost(r->db);
    return sim_time_add_sat(sim_time_mul_sat(r->c.transform_vertex, c.verts),
                            sim_time_mul_sat(r->c.sphere_bound, c.spheres));
}

static void sum_busy(const WlSfRun *r, WlSfFrameStats *st)
{
    double total = 0, max = 0;
    for (guint p = 0; p < r->s.procs; p++) {
        const WlSfProc *pr = &r->procs[p];
        double busy = (double)(mach_proc_busy(pr->proc) - pr->busy0);
        total += busy;
        max = MAX(max, busy);
    }
    st->imbalance = wl_sf_max_over_mean(max, total, r->s.procs);
    for (guint p = 0; p < r->s.procs; p++)
        st->traverse_busy = sim_time_add_sat(
            st->traverse_busy,
            sim_time_add_sat(sim_time_mul_sat(r->c.node_visit, r->tp[p].nodes),
                sim_time_mul_sat(bv_test_time(r),
                                 r->tp[p].tests)));
    if (r->adapt) {
        for (guint p = 0; p < r->s.procs; p++) {
            st->estimate_bytes += (r->s.procs - 1) * wl_sf_estimate_bytes(r, p);
            st->estimate_cells += wl_sf_partition_cells(r, p);
        }
        st->split_imbalance = r->split_imbalance;
        for (guint p = 0; p < r->s.procs; p++)
            st->estimate_cells += r->adapt->added[p];
    }
}

/* Where the master copies are: per processor its master polygons and
 * those with no instance in any region (off-screen, seed 000 §3.3.2.1). */
static void masters(const WlSfRun *r, WlSfFrameStats *st)
{
    uint64_t poly[WL_SF_MAX_PROCS] = {0}, off[WL_SF_MAX_PROCS] = {0};
    double total = 0, max = 0;
    for (guint c = 0; c < wl_sf_n_chunks(r->db); c++) {
        const WlSfChunk *ch = wl_sf_chunk(r->db, c);
        guint m = wl_sf_book_master(r->book, c);
        uint64_t any = 0;
        for (guint i = ch->inst_first; i < ch->inst_first + ch->n_inst; i++)
            any |= r->book->need[i];
        poly[m] += ch->polys;
        off[m] += any ? 0 : ch->polys;
    }
    for (guint p = 0; p < r->s.procs; p++) {
        total += (double)poly[p];
        max = MAX(max, (double)poly[p]);
        st->offscreen_max = MAX(st->offscreen_max, off[p]);
        st->offscreen_total += off[p];
        st->held_polys += r->procs[p].w.held_polys;
    }
    st->master_imbalance = wl_sf_max_over_mean(max, total, r->s.procs);
}

static void sum_edits(const WlSfRun *r, WlSfFrameStats *st)
{
    st->edits = r->ef.commands;
    st->nodes_created = r->ef.nodes_created;
    st->nodes_collected = r->ef.nodes_collected;
    if (r->ef.commands) {
        st->messages += r->s.procs - 1;
        st->edit_bytes = (r->s.procs - 1) * wl_sf_edit_message(r);
    }
    for (guint p = 0; p < r->s.procs; p++) {
        const WlSfProc *pr = &r->procs[p];
        st->pointers_collected += r->ew[p].ptr_collected;
        st->edit_bytes += pr->w.edit_bytes;
        st->chunks_collected += pr->w.collected;
        MachOps o = wl_sf_edit_ops(r, p);
        if (r->ef.commands)
            st->edit_busy = sim_time_add_sat(st->edit_busy,
                                             mach_proc_ops_cost(pr->proc, &o));
    }
}

static void sum_work(const WlSfRun *r, WlSfFrameStats *st)
{
    uint64_t total = 0;
    st->load_min = UINT64_MAX;
    for (guint p = 0; p < r->s.procs; p++) {
        const WlSfProc *pr = &r->procs[p];
        st->migrated_chunks += pr->w.sent_chunks;
        st->migrated_polys += pr->w.sent_polys;
        st->migrated_insts += pr->w.sent_insts;
        st->migrated_bytes += pr->w.sent_bytes;
        st->master_boxes += pr->w.master_boxes;
        st->slave_boxes += pr->w.slave_boxes;
        st->new_boxes += pr->w.new_boxes;
        st->probe_boxes += pr->w.probe_boxes;
        st->deleted_chunks += pr->w.deleted_chunks;
        st->requests += pr->w.requested;
        st->handovers += pr->w.handed;
        st->spread += pr->w.spread;
        st->interrupts += pr->w.served;
        st->pixels += pr->pixels;
        st->load_max = MAX(st->load_max, pr->polys);
        st->load_min = MIN(st->load_min, pr->polys);
        total += pr->polys;
    }
    st->peak_memory = wl_sf_book_peak_memory(r->book);
    st->messages = (uint64_t)r->s.procs * (r->s.procs - 1);
    if (r->s.mig == WL_SF_PULL) {
        st->messages = 0;
        for (guint p = 0; p < r->s.procs; p++)
            st->messages += 2 * r->procs[p].expect;
    }
    sum_edits(r, st);
    masters(r, st);
    st->polys_rendered = total;
    st->poly_imbalance =
        wl_sf_max_over_mean((double)st->load_max, (double)total, r->s.procs);
    sum_busy(r, st);
}

/* √ area of instance i's screen rectangle clipped to the screen, pixels
 * (seed 000 §4.2, Chart 3: chunk box size against region size).  Only
 * for an instance some region needs: need[i] comes from this frame's
 * r->scr (start_frame) and is 0 for a rectangle not on screen
 * (wl_sf_screen_regions), so the rectangle is on. */
static double box_side(const WlSfRun *r, guint i)
{
    const WlSfScreen *s = &r->scr[i];
    g_assert(s->on);
    double w = MIN(s->x1, r->regions.width) - MAX(s->x0, 0);
    double h = MIN(s->y1, r->regions.height) - MAX(s->y0, 0);
    return w > 0 && h > 0 ? sqrt(w * h) : 0;
}

static void overlap(const WlSfRun *r, WlSfFrameStats *st)
{
    for (guint i = 0; i < wl_sf_n_insts(r->db); i++) {
        uint64_t m = r->book->need[i];
        if (m) {
            st->onscreen_insts++;
            st->region_insts += (uint64_t)__builtin_popcountll(m);
            st->box_side += box_side(r, i);
        }
    }
}

static double utilisation(const WlSfRun *r, SimTime frame)
{
    SimTime busy = 0;
    for (guint p = 0; p < r->s.procs; p++)
        busy += mach_proc_busy(r->procs[p].proc) - r->procs[p].busy0;
    return frame ? (double)busy / ((double)frame * r->s.procs) : 0;
}

gboolean wl_sf_frame_check(WlSfRun *r, WlSfFrameStats *st, GError **err)
{
    guint inst, proc;
    if (!wl_sf_book_check(r->book, &inst, &proc)) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_INTERNAL,
                    "sortfirst: frame %d: found chunk instance %u over "
                    "region %u not held by processor %u, expected every "
                    "overlapping instance held",
                    r->frame, inst, proc, proc);
        return FALSE;
    }
    if (!r->s.check_image)
        return TRUE;
    wl_sf_render_serial(r->scene, r->db, &r->s, (guint)r->frame, r->serial);
    size_t n = (size_t)r->s.resolution * (size_t)r->s.resolution;
    st->image_checked = TRUE;
    st->image_ok = memcmp(r->zb->rgba, r->serial->rgba, n * 4) == 0 &&
                   memcmp(r->zb->prim, r->serial->prim, n * 4) == 0;
    if (!st->image_ok)
        g_set_error(err, SIM_ERROR, SIM_ERROR_INTERNAL,
                    "sortfirst: frame %d: found an image that differs from "
                    "the serial render, expected the same pixels",
                    r->frame);
    return st->image_ok;
}

void wl_sf_frame_sum(const WlSfRun *r, WlSfFrameStats *st)
{
    sum_work(r, st);
    overlap(r, st);
    st->utilisation = utilisation(r, st->end - st->start);
    st->fb_bytes = r->fb_bytes;
    st->interrupt_busy =
        sim_time_mul_sat(r->c.request_interrupt, st->interrupts);
    if (r->s.fb == WL_SF_FB_NODE)
        st->fb_busy =
            mach_proc_busy_phase(r->fb, r->ph_assemble) - r->fb_busy0;
}
