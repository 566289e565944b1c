/* rp_papers.h — published values of a paper, read from YAML.
 *
 * configs/papers/<name>/published.yaml holds what a paper printed, cell by cell,
 * keyed by (table, row, column); docs/reproduction-format.md is the
 * schema.  A withheld cell has no value (the paper did not print one, or
 * the reproduction keeps it back as a prediction).  Lookups are O(1).
 */
#ifndef PGSIM_REPRODUCE_RP_PAPERS_H
#define PGSIM_REPRODUCE_RP_PAPERS_H

#include <glib.h>

typedef struct {
    char *table;
    char *row;
    char *column;
    double value; /* NAN when withheld */
    gboolean withheld;
    char *unit; /* "" when dimensionless or not given */
    char *note; /* NULL when none */
} RpCell;

typedef struct {
    char *name;           /* paper.name */
    char *citation;       /* paper.citation */
    GPtrArray *cells;     /* RpCell *, in file order */
    GHashTable *index;    /* "table\x1frow\x1fcolumn" -> RpCell * (borrowed) */
    GHashTable *captions; /* table -> caption, from the compact shape */
} RpPaper;

/* Reads a paper file; returns a new RpPaper (free with rp_paper_free())
 * or NULL with a located *err (unknown key, duplicate cell, a cell with
 * neither value nor withheld). */
RpPaper *rp_paper_load(const char *path, GError **err);
void rp_paper_free(RpPaper *p);
/* The cell for (table, row, column); NULL when the paper lists none.
 * Borrowed. */
const RpCell *rp_paper_cell(const RpPaper *p, const char *table,
                            const char *row, const char *column);
#define RP_PUBLISHED_FILE "published.yaml"

/* "<dir>/<name>/<file>", found through sim_data_path(); free with
 * g_free(). */
char *rp_paper_file(const char *dir, const char *name, const char *file);
/* The paper's published values: "<dir>/<name>/published.yaml". */
char *rp_paper_path(const char *dir, const char *name);

#endif
