/* sf_fbuf.c — the frame buffer's assembly and read-out (sf_frame.h;
 * seed 000 §4.1: "A host process spawns processes for each graphics
 * processor plus a framebuffer"; issue 37 point 4).
 *
 * With `framebuffer: node` (the default) a processor that has rendered
 * its region reads the region's pixels out of its colour buffer
 * (pixel_readout per pixel of the region, phase `readout`) and sends
 * them to the frame-buffer node (bytes.message + bytes.pixel per
 * pixel), which stores them at their screen positions (pixel_assemble
 * per pixel, phase `assemble`).  The frame ends when every region is
 * assembled.  The display's scan-out of the finished frame overlaps the
 * next frame (a double-buffered frame buffer: an assumption), so it is
 * not on the frame's path.  The frame-buffer node is node P of the
 * machine (the processor after the renderers) when the machine has one
 * on its network, else node 0, which then assembles beside its own rendering
 * and reads its own region without a message.  With `framebuffer: none` the
 * frame ends when every processor has rendered (the model before). Cost O(1)
 * per region.
 */
#include "sim/workload/sortfirst/sf_frame_internal.h"

const char *const wl_sf_framebuffer_names[] = {"none", "node", NULL};

MachProc *wl_sf_fbuf_proc(MachMachine *m, guint procs)
{
    const MachKindInfo *k = mach_kind(m, "node");
    MachProc *fb = k && k->count > procs ? mach_proc(m, "node", procs) : NULL;
    if (fb && mach_proc_id(fb) < net_nodes(mach_net(m)))
        return fb;
    return mach_proc(m, "node", 0); /* no network endpoint after P */
}

uint64_t wl_sf_fbuf_pixels(const WlSfRun *r, guint p)
{
    WlSfRect rc = wl_sf_region_rect(&r->regions, p);
    return (uint64_t)(rc.x1 - rc.x0) * (uint64_t)(rc.y1 - rc.y0);
}

uint64_t wl_sf_fbuf_bytes(const WlSfRun *r, guint p)
{
    return r->s.sizes.message + wl_sf_fbuf_pixels(r, p) * r->s.pixel_bytes;
}

static void assembled(SimEngine *eng, void *ctx, void *arg)
{
    (void)arg;
    WlSfRun *r = ctx;
    if (++r->done == r->s.procs)
        wl_sf_frame_end(r, eng);
}

/* Region p's pixels are at the frame buffer: stored there. */
static void assemble(WlSfRun *r, guint p)
{
    MachOps o = {.op = {{"pixel_assemble", wl_sf_fbuf_pixels(r, p)}}, .n = 1};
    mach_proc_compute_list(r->fb, &o, r->ph_assemble, assembled, r, NULL);
}

static void region_arrive(NetNet *net, const NetDelivery *d, void *ctx)
{
    (void)net;
    assemble(ctx, GPOINTER_TO_UINT(d->payload));
}

static void read_done(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    WlSfRun *r = ctx;
    guint p = GPOINTER_TO_UINT(arg);
    MachProc *src = r->procs[p].proc;
    if (src == r->fb) {
        assemble(r, p);
        return;
    }
    r->fb_bytes += wl_sf_fbuf_bytes(r, p);
    net_send(r->net, mach_proc_id(src), mach_proc_id(r->fb),
             wl_sf_fbuf_bytes(r, p), arg, region_arrive, r);
}

void wl_sf_fbuf_region(WlSfRun *r, WlSfProc *pr)
{
    if (r->s.fb == WL_SF_FB_NONE) {
        assembled(r->eng, r, NULL);
        return;
    }
    MachOps o = {.op = {{"pixel_readout", wl_sf_fbuf_pixels(r, pr->p)}},
                 .n = 1};
    mach_proc_compute_list(pr->proc, &o, r->ph_readout, read_done, r,
                           GUINT_TO_POINTER(pr->p));
}

/* ---- the keys and metrics of the costed additions ------------------------
 * (issue 37 point 4: the frame buffer here, the pull interrupt in
 * sf_frame.c, the off-screen spread in sf_mastership.c) */

gboolean wl_sf_parse_costed(const CfgNode *sec, WlSfSetup *s, GError **err)
{
    int fb = WL_SF_FB_NODE, off = WL_SF_OFF_SPREAD;
    const CfgNode *bytes = cfg_get(sec, "bytes");
    s->pixel_bytes = 4; /* RGBA, 8 bits a channel: an assumption */
    if (!cfg_get_enum(sec, "framebuffer", FALSE, wl_sf_framebuffer_names, &fb,
                      err) ||
        !cfg_get_enum(sec, "offscreen", FALSE, wl_sf_offscreen_names, &off,
                      err) ||
        (bytes && cfg_kind(bytes) == CFG_MAP &&
         !cfg_get_size(bytes, "pixel", FALSE, &s->pixel_bytes, err)))
        return FALSE;
    s->fb = (WlSfFrameBuffer)fb;
    s->off = (WlSfOffscreen)off;
    return TRUE;
}

void wl_sf_fill_costed_metrics(SimResult *out, const GArray *stats, guint from,
                               const WlSfSetup *s)
{
    double n = stats->len - from, spread = 0, irq = 0, bytes = 0, fb = 0;
    for (guint f = from; f < stats->len; f++) {
        const WlSfFrameStats *t = &g_array_index(stats, WlSfFrameStats, f);
        spread += (double)t->spread;
        irq += sim_time_to_ms(t->interrupt_busy);
        bytes += (double)t->fb_bytes;
        fb += sim_time_to_ms(t->fb_busy);
    }
    if (s->ms == WL_SF_DYNAMIC)
        sim_result_set_metric(out, "offscreen_spread_per_frame", spread / n,
                              "");
    if (s->mig == WL_SF_PULL)
        sim_result_set_metric(out, "interrupt_ms", irq / n, "ms");
    if (s->fb == WL_SF_FB_NODE) {
        sim_result_set_metric(out, "framebuffer_bytes_per_frame", bytes / n,
                              "B");
        sim_result_set_metric(out, "assembly_ms", fb / n, "ms");
    }
}
