/* tiny_rec.c — the shared tiny-machine fixture with a recorder
 * (tiny_rec.h). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "tests/machine/tiny_rec.h"

int tiny_rec_setup(void **state)
{
    TinyRec *f = g_new0(TinyRec, 1);
    GError *err = NULL;
    g_setenv("PGSIM_MODELS", "tests/data/models", TRUE);
    f->eng = sim_engine_new(1);
    f->m = mach_new_from_model(f->eng, "tiny", "analytic", &err);
    if (!f->m)
        fail_msg("%s", err->message);
    rec_log_init(&f->log);
    sim_engine_set_recorder(f->eng, &f->log.rec);
    *state = f;
    return 0;
}

int tiny_rec_teardown(void **state)
{
    TinyRec *f = *state;
    mach_free(f->m);
    sim_engine_free(f->eng);
    rec_log_clear(&f->log);
    g_free(f);
    return 0;
}
