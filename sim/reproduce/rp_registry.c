/* rp_registry.c — the table of papers (one row each) and the rows they
 * fill.  A new paper adds one line here. */
#include "sim/reproduce/beermann02.h"
#include "sim/reproduce/ellsworth90.h"
#include "sim/reproduce/igehy98.h"
#include "sim/reproduce/kurc96.h"
#include "sim/reproduce/mueller97.h"
#include "sim/reproduce/ortega93.h"
#include "sim/reproduce/reproduce.h"
#include <math.h>
#include <string.h>

const RpPaperOps *const rp_all[] = {
    &rp_ortega93,
    &rp_ellsworth90,
    &rp_kurc96,
    &rp_igehy98,
    &rp_mueller97,
    &rp_beermann02,
    NULL,
};

const RpPaperOps *rp_find(const char *name)
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
