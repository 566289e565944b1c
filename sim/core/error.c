/* error.c — the pgsim error domain and located input errors. */
#include "sim/core/error.h"

G_DEFINE_QUARK(pgsim - error - quark, sim_error)

int sim_error_exit_status(const GError *err)
{
    if (!err)
        return 0;
    if (err->domain == SIM_ERROR && err->code == SIM_ERROR_INTERNAL)
        return 1;
    return 2;
}

void sim_error_located(GError **err, const char *file, int line, int col,
                       const char *found, const char *expected)
{
    g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                "%s:%d:%d: found %s, expected %s", file ? file : "<input>",
                line, col, found, expected);
}
