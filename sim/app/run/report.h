/* report.h — writing a SimResult as text, JSON or CSV (docs/output.md).
 *
 * Text is for people; JSON and CSV are for programs and are byte-for-byte
 * deterministic for a given result unless `timing` is set: wall-clock
 * figures (wall seconds, events per second) are the only
 * non-deterministic numbers and appear only with timing.  JSON is
 * json-glib's (sim/output/json.h: whole numbers as integers, others with
 * 17 significant digits, reading back exactly); CSV prints simulated
 * times as exact decimal seconds from integer picoseconds and other
 * doubles as the shortest text that reads back exactly (js_fmt_num).
 * Both carry the provenance block (sim/output/provenance.h).
 */
#ifndef PGSIM_APP_RUN_REPORT_H
#define PGSIM_APP_RUN_REPORT_H

#include "sim/core/result.h"

typedef enum { RPT_TEXT, RPT_JSON, RPT_CSV } RptFormat;

/* "text", "json", "csv" -> format; FALSE if unknown. */
gboolean rpt_format_parse(const char *s, RptFormat *out);
/* The file name used in an output directory: summary.txt, result.json,
 * result.csv. */
const char *rpt_format_file(RptFormat f);

/* Returns the rendering as a new string (g_free). */
char *rpt_render(const SimResult *r, RptFormat f, gboolean timing);
/* Writes all three renderings into dir (created if needed), together:
 * each is written beside its place and the three are renamed into place
 * only when all are written, so after a failure (a full disk, reported
 * with the system's reason) dir holds the earlier files, unchanged.
 * FALSE with *err on failure. */
gboolean rpt_write_dir(const SimResult *r, const char *dir, gboolean timing,
                       GError **err);

#endif
