/* rp_doc.h — docs/reproduction.md: every paper's table with published
 * value, simulated value and error, and its charts.
 *
 * rp_doc_chart() draws, for one pass, simulated against published values
 * (log-log, with y = x) as <dir>/<paper>-vs-published.{png,svg,gp,dat};
 * rp_doc_paper() appends a paper's section (summary, one Markdown table
 * per paper table with its caption, links to the charts that exist).
 */
#ifndef PGSIM_REPRODUCE_RP_DOC_H
#define PGSIM_REPRODUCE_RP_DOC_H

#include "sim/reproduce/rp_papers.h"
#include "sim/reproduce/rp_table.h"

gboolean rp_doc_chart(const RpTable *t, const char *dir, GError **err);
/* passes: RpTable * (one, or one per fidelity); captions may be NULL;
 * chart_rel: the charts' directory relative to the document. */
void rp_doc_paper(GString *md, const GPtrArray *passes, GHashTable *captions,
                  const char *chart_dir, const char *chart_rel);
/* The document's opening lines. */
void rp_doc_head(GString *md, const char *fidelity);

#endif
