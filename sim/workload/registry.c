/* registry.c — the table of workloads (one row per workload). */
#include "sim/workload/workload.h"
#include "sim/workload/argus/ag_workload.h"
#include "sim/workload/dpscan/dp_workload.h"
#include "sim/workload/performer/pf_workload.h"
#include "sim/workload/pixelmerge/pm_workload.h"
#include "sim/workload/sortfirst/sf_workload.h"
#include "sim/workload/tokenring/tokenring_workload.h"
#include "sim/core/error.h"
#include "sim/core/trace.h"
#include <string.h>

extern const WlOps wl_pphigs_ops;

const WlOps *const wl_all[] = {
    &wl_pphigs_ops,    &wl_dpscan_ops,    &wl_pixelmerge_ops,
    &wl_sortfirst_ops, &wl_tokenring_ops, &wl_argus_ops,
    &wl_pf_ops,        NULL,
};

const WlOps *wl_find(const char *name)
{
    for (int i = 0; wl_all[i]; i++)
        if (strcmp(wl_all[i]->name, name) == 0)
            return wl_all[i];
    return NULL;
}

void wl_plan_machine_scene(const void *params, WlPlan *plan)
{
    (void)params;
    plan->reads = WL_READS_MACHINE | WL_READS_SCENE;
}

char *wl_frame_log_path(const WlContext *ctx, const char *path,
                        const char *name)
{
    if (path)
        return g_strdup(path);
    if (!ctx->out_dir || g_mkdir_with_parents(ctx->out_dir, 0755) != 0)
        return NULL;
    return g_build_filename(ctx->out_dir, name, NULL);
}

gboolean wl_frame_log_write(const char *path, const GString *text,
                            const char *workload, GError **err)
{
    if (g_file_set_contents(path, text->str, (gssize)text->len, NULL))
        return TRUE;
    g_set_error(err, SIM_ERROR, SIM_ERROR_IO,
                "%s: found an unwritable frame_log '%s', expected a "
                "writable path",
                workload, path);
    return FALSE;
}

gboolean wl_wants_frame(const WlContext *ctx, int frame)
{
    return ctx && ctx->out_dir &&
           (ctx->all_frames || frame == ctx->frames - 1);
}

gboolean wl_emit_frame(const WlContext *ctx, int frame, const RastImage *img,
                       GError **err)
{
    if (!wl_wants_frame(ctx, frame))
        return TRUE;
    char *name = ctx->all_frames ? g_strdup_printf("frame-%04d.png", frame)
                                 : g_strdup("frame.png");
    char *path = g_build_filename(ctx->out_dir, name, NULL);
    gboolean ok = g_mkdir_with_parents(ctx->out_dir, 0777) == 0 &&
                  rast_image_write_png(img, path, err);
    if (!ok && err && !*err)
        g_set_error(err, SIM_ERROR, SIM_ERROR_IO, "%s: cannot create",
                    ctx->out_dir);
    g_free(path);
    g_free(name);
    return ok;
}

void wl_mark_frame(SimEngine *eng, guint frame, SimTime end)
{
    SimTrace *tr = sim_engine_trace(eng);
    if (!tr)
        return;
    char name[32];
    g_snprintf(name, sizeof name, "frame %u", frame);
    sim_trace_mark(tr, name, end);
}
