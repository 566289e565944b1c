/* support.c — set-up steps many test binaries share (support.h). */
#include "tests/support.h"

#include <glib.h>

void support_warnings_fatal(void)
{
    g_log_set_always_fatal(G_LOG_FATAL_MASK | G_LOG_LEVEL_WARNING |
                           G_LOG_LEVEL_CRITICAL);
}

int support_test_models(void **state)
{
    (void)state;
    g_setenv("PGSIM_MODELS", "tests/data/models", TRUE);
    return 0;
}
