/* cmd_models.c — `pgsim models [--markdown | --pairings LIST] [DIR]`:
 * the machine models.  --pairings: every workload config of configs/ on
 * every model of DIR, checked against LIST (pairings.h).
 *
 * Without --markdown, one line per model of DIR (default models/): its
 * name and description.  With --markdown, the "Parameters" tables of
 * docs/models.md, made from the YAML: per model (files in name order) a
 * heading, the description, one row per parameter of nodes.KIND (costs
 * and cycles included), network and roles in file order (value as written, provenance kind
 * and text, the note after it), then the references.  docs/models.md
 * holds that output between two marker lines; scripts/gen-models-doc.sh
 * rewrites it and tests/app/cli/test_models_doc.c fails when they differ,
 * so a value changed in a model and not in the doc fails `make test`.
 * Linear in the size of the files.
 */
#include "sim/app/cli/cli.h"
#include "sim/app/cli/commands.h"
#include "sim/app/cli/pairings.h"
#include "sim/core/cfg.h"
#include <stdio.h>
#include <string.h>

static const char *const prov_kinds[] = {"source", "calibrated",
                                         "assumption"};

/* Text for a table cell: line ends as spaces, '|' escaped. */
static void cell(GString *s, const char *text)
{
    for (const char *c = text; *c; c++) {
        if (*c == '|')
            g_string_append(s, "\\|");
        else
            g_string_append_c(s, *c == '\n' ? ' ' : *c);
    }
}

/* A value as written: a scalar, or a list as "[a, b]". */
static void value_text(GString *s, const CfgNode *v)
{
    if (cfg_kind(v) == CFG_SEQ) {
        g_string_append_c(s, '[');
        for (guint i = 0; i < cfg_seq_len(v); i++) {
            if (i)
                g_string_append(s, ", ");
            value_text(s, cfg_seq_at(v, i));
        }
        g_string_append_c(s, ']');
    } else if (cfg_kind(v) == CFG_SCALAR) {
        cell(s, cfg_scalar(v));
    } else {
        g_string_append(s, "(see the YAML)");
    }
}

/* "| `prefix.key` | value | **kind**: text; *note*: text |" */
static void param_row(GString *s, const char *prefix, const char *key,
                      const CfgNode *p)
{
    g_string_append_printf(s, "| `%s.%s` | ", prefix, key);
    const CfgNode *v = cfg_get(p, "value");
    if (v)
        value_text(s, v);
    g_string_append(s, " |");
    for (guint k = 0; k < G_N_ELEMENTS(prov_kinds); k++) {
        const CfgNode *t = cfg_get(p, prov_kinds[k]);
        if (!t)
            continue;
        g_string_append_printf(s, " **%s**: ", prov_kinds[k]);
        value_text(s, t);
    }
    const CfgNode *note = cfg_get(p, "note");
    if (note) {
        g_string_append(s, "; *note*: ");
        value_text(s, note);
    }
    g_string_append(s, " |\n");
}

/* The parameters of one map (a node kind or the network); `costs` and
 * `cycles` (a processor description) are maps of parameters one level
 * down. */
static void params(GString *s, const char *prefix, const CfgNode *map)
{
    for (guint i = 0; map && i < cfg_map_len(map); i++) {
        const char *key = cfg_map_key(map, i);
        const CfgNode *p = cfg_map_value(map, i);
        if (!strcmp(key, "costs") || !strcmp(key, "cycles")) {
            char *sub = g_strdup_printf("%s.%s", prefix, key);
            params(s, sub, p);
            g_free(sub);
        } else if (cfg_kind(p) == CFG_MAP) {
            param_row(s, prefix, key, p);
        }
    }
}

static void one_model(GString *s, const CfgNode *m)
{
    const CfgNode *name = cfg_get(m, "name"), *d = cfg_get(m, "description");
    g_string_append_printf(s, "### `%s`\n\n",
                           name ? cfg_scalar(name) : "(unnamed)");
    if (d) {
        value_text(s, d);
        g_string_append(s, "\n\n");
    }
    g_string_append(s, "| parameter | value | provenance |\n|---|---|---|\n");
    const CfgNode *nodes = cfg_get(m, "nodes");
    for (guint i = 0; nodes && i < cfg_map_len(nodes); i++)
        params(s, cfg_map_key(nodes, i), cfg_map_value(nodes, i));
    params(s, "network", cfg_get(m, "network"));
    params(s, "roles", cfg_get(m, "roles")); /* kinds that play others */
    const CfgNode *refs = cfg_get(m, "references");
    if (refs && cfg_map_len(refs)) {
        g_string_append(s, "\nReferences:\n\n");
        for (guint i = 0; i < cfg_map_len(refs); i++) {
            g_string_append_printf(s, "- `%s`: ", cfg_map_key(refs, i));
            value_text(s, cfg_map_value(refs, i));
            g_string_append_c(s, '\n');
        }
    }
    g_string_append_c(s, '\n');
}

static int list_models(const char *dir, gboolean markdown)
{
    GError *e = NULL;
    GPtrArray *files = cli_yaml_files(dir, &e);
    if (!files)
        return cli_fail(e);
    GString *s = g_string_new(NULL);
    for (guint i = 0; i < files->len; i++) {
        CfgNode *m = cfg_load_file(files->pdata[i], &e);
        if (!m) {
            g_string_free(s, TRUE);
            g_ptr_array_unref(files);
            return cli_fail(e);
        }
        const CfgNode *n = cfg_get(m, "name"), *d = cfg_get(m, "description");
        if (markdown)
            one_model(s, m);
        else
            g_string_append_printf(s, "%-16s %s\n", n ? cfg_scalar(n) : "?",
                                   d ? cfg_scalar(d) : "");
        cfg_free(m);
    }
    if (markdown && s->len)
        g_string_truncate(s, s->len - 1); /* no blank line at the end */
    fputs(s->str, stdout);
    g_string_free(s, TRUE);
    g_ptr_array_unref(files);
    return 0;
}

int cmd_models(int argc, char **argv)
{
    gboolean markdown = FALSE;
    char *pairings = NULL;
    const GOptionEntry entries[] = {
        {"pairings", 0, 0, G_OPTION_ARG_FILENAME, &pairings,
         "run every workload config of configs/ on every model, check the "
         "meaningless ones LIST names, print the table of docs/models.md",
         "LIST"},
        {"markdown", 0, 0, G_OPTION_ARG_NONE, &markdown,
         "print the parameter tables of docs/models.md (made from the YAML)",
         NULL},
        G_OPTION_ENTRY_NULL,
    };
    int status;
    if (!cli_parse("models", "[DIR]",
                   "Lists the machine models of DIR (default models/) with "
                   "their descriptions, or with --markdown prints their "
                   "parameter tables as docs/models.md holds them "
                   "(scripts/gen-models-doc.sh writes them there).",
                   entries, &argc, &argv, &status))
        return status;
    if (argc > 2) {
        fprintf(stderr, "pgsim models: found '%s', expected at most one "
                        "folder\n",
                argv[2]);
        return 2;
    }
    const char *dir = argc == 2 ? argv[1] : "models";
    if (!pairings)
        return list_models(dir, markdown);
    GString *md = g_string_new(NULL);
    GError *e = NULL;
    gboolean ok = pairings_table(pairings, "configs", dir, md, &e);
    g_free(pairings);
    if (ok)
        fputs(md->str, stdout);
    g_string_free(md, TRUE);
    return ok ? 0 : cli_fail(e);
}
