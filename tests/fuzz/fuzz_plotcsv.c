/* fuzz_plotcsv.c — libFuzzer harness: a CSV read as `pgsim plot` reads
 * it (dt_parse_csv), charted from its first columns (x, y, series; the
 * first cell as title, the second column name as x label), logx/logy
 * from the input's length, through plot_texts(): grouping, data file and
 * gnuplot script, whose safety plot_texts() asserts (no command can run
 * from a cell or a name, issue 32).  gnuplot itself is not run.  See
 * fuzz.h. */
#include "sim/output/plot.h"
#include "tests/fuzz/fuzz.h"

static void chart(const DataTable *t, size_t size)
{
    PlotSpec *p = plot_spec_new("fuzz", g_ptr_array_index(t->cols, 0),
                                g_ptr_array_index(t->cols, 1));
    if (t->cols->len > 2)
        p->series = g_strdup(g_ptr_array_index(t->cols, 2));
    if (t->rows->len > 0)
        p->title = g_strdup(dt_cell(t, 0, 0));
    p->xlabel = g_strdup(g_ptr_array_index(t->cols, 1));
    p->logx = size & 1;
    p->logy = (size >> 1) & 1;
    p->diagonal = (size >> 2) & 1;
    GString *dat = NULL, *gp = NULL;
    GError *err = NULL;
    if (plot_texts(p, t, &dat, &gp, &err)) {
        g_string_free(dat, TRUE);
        g_string_free(gp, TRUE);
    }
    g_clear_error(&err);
    plot_spec_free(p);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_setup();
    char *text = fuzz_text(data, size);
    GError *err = NULL;
    DataTable *t = dt_parse_csv(text, "fuzz.csv", &err);
    if (t && t->cols->len >= 2)
        chart(t, size);
    dt_free(t);
    g_clear_error(&err);
    g_free(text);
    return 0;
}
