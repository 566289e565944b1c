/* rpl_fixture.c — recorded traces for replay tests (rpl_fixture.h). */
#include "tests/app/replay/rpl_fixture.h"
#include "sim/app/replay/rpl_record.h"
#include <glib/gstdio.h>

void rpl_fixture_record(RplFixture *f, const char *config,
                        const char *const *sets, const char *name)
{
    GError *e = NULL;
    CfgRun *r = cfg_run_load(config, sets, &e);
    g_assert_no_error(e);
    RplRecorder *rec = rpl_recorder_new();
    CfgRunOpts o = {.quiet = TRUE, .recorder = rpl_recorder_hook(rec)};
    f->res = cfg_run_exec(r, &o, &e);
    g_assert_no_error(e);
    f->dir = g_dir_make_tmp("pgsim-rpl-XXXXXX", NULL);
    f->path = g_build_filename(f->dir, name, NULL);
    g_assert_true(
        rpl_recorder_write(rec, f->path, r, f->res, &f->unplaced, &e));
    g_assert_no_error(e);
    f->actions = rpl_recorder_actions(rec);
    rpl_recorder_free(rec);
    cfg_run_free(r);
}

void rpl_fixture_clear(RplFixture *f)
{
    g_remove(f->path);
    g_rmdir(f->dir);
    g_free(f->path);
    g_free(f->dir);
    sim_result_free(f->res);
    *f = (RplFixture){0};
}
