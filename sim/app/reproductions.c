/* reproductions.c — the table of paper reproductions (one row each). */
#include "sim/app/reproduce.h"
#include "sim/app/rp_kurc96.h"
#include "sim/workload/dpscan/ortega93.h"
#include "sim/workload/pphigs/ellsworth90.h"
#include <math.h>
#include <string.h>

const RpReproduction *const rp_all[] = {
    &wl_dp_ortega93,
    &wl_pphigs_ellsworth90,
    &rp_kurc96,
    NULL,
};

const RpReproduction *rp_find(const char *name)
{
    for (int i = 0; rp_all[i]; i++)
        if (strcmp(rp_all[i]->name, name) == 0)
            return rp_all[i];
    return NULL;
}

RpRow *rp_row_new(const char *table, const char *row, const char *column,
                  double sim, const char *note)
{
    RpRow *r = g_new0(RpRow, 1);
    r->table = g_strdup(table);
    r->row = g_strdup(row);
    r->column = g_strdup(column);
    r->sim = sim;
    r->note = g_strdup(note);
    return r;
}

void rp_row_free(gpointer p)
{
    RpRow *r = p;
    if (!r)
        return;
    g_free(r->table);
    g_free(r->row);
    g_free(r->column);
    g_free(r->note);
    g_free(r);
}
