/* error.h — the error domain.
 *
 * Two tiers (docs/architecture.md): recoverable input errors return
 * gboolean and fill a GError in SIM_ERROR; programming errors are
 * g_assert.  Input error messages read
 *     file:line:column: found <what was found>, expected <what was expected>
 * and map to exit status 2; SIM_ERROR_INTERNAL maps to 1.
 */
#ifndef PGSIM_CORE_ERROR_H
#define PGSIM_CORE_ERROR_H

#include <glib.h>

#define SIM_ERROR (sim_error_quark())
GQuark sim_error_quark(void);

typedef enum {
    SIM_ERROR_INPUT,    /* bad config, model, scene file or CLI flag: exit 2 */
    SIM_ERROR_OVERFLOW, /* simulated time or a counter would overflow: 2 */
    SIM_ERROR_IO,       /* a file could not be read or written: exit 2 */
    SIM_ERROR_INTERNAL, /* anything else that stopped a run: exit 1 */
    SIM_ERROR_DRY_RUN   /* a dry run reached its first event (validate) */
} SimErrorCode;

/* Exit status for an error (0 for NULL). */
int sim_error_exit_status(const GError *err);

/* Sets *err to a located input error:
 * "<file>:<line>:<col>: found <found>, expected <expected>". */
void sim_error_located(GError **err, const char *file, int line, int col,
                       const char *found, const char *expected);

#endif
