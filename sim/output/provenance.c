/* provenance.c — the provenance block every output carries
 * (provenance.h).
 *
 * One writer for JSON and one for report-style CSV, so `run`, sweeps and
 * reproductions cannot drift apart in what they record.  The version is
 * a compile-time string (Makefile: -DPGSIM_GIT_VERSION on this file).
 * O(size of the effective config).
 */
#include "sim/output/provenance.h"
#include "sim/core/datapath.h"
#include "sim/output/table.h"

#ifndef PGSIM_GIT_VERSION
#define PGSIM_GIT_VERSION "unknown"
#endif

const char *prov_version(void)
{
    return PGSIM_GIT_VERSION;
}

char *prov_file_sha256(const char *path)
{
    char *bytes = NULL;
    gsize len = 0;
    if (!path || !sim_file_read(path, &bytes, &len, NULL))
        return NULL;
    char *sha = g_compute_checksum_for_data(G_CHECKSUM_SHA256,
                                            (const guchar *)bytes, len);
    g_free(bytes);
    return sha;
}

static void cfg_add(JsonBuilder *b, const CfgNode *n)
{
    if (cfg_kind(n) == CFG_MAP) {
        json_builder_begin_object(b);
        for (guint i = 0; i < cfg_map_len(n); i++) {
            json_builder_set_member_name(b, cfg_map_key(n, i));
            cfg_add(b, cfg_map_value(n, i));
        }
        json_builder_end_object(b);
    } else if (cfg_kind(n) == CFG_SEQ) {
        json_builder_begin_array(b);
        for (guint i = 0; i < cfg_seq_len(n); i++)
            cfg_add(b, cfg_seq_at(n, i));
        json_builder_end_array(b);
    } else {
        js_add_str(b, cfg_kind(n) == CFG_SCALAR ? cfg_scalar(n) : NULL);
    }
}

char *prov_cfg_json(const CfgNode *n)
{
    JsonBuilder *b = json_builder_new();
    cfg_add(b, n);
    return js_finish(b, FALSE);
}

void prov_inputs_json(JsonBuilder *b, const SimInputs *inputs)
{
    json_builder_begin_array(b);
    for (guint i = 0; i < sim_inputs_len(inputs); i++) {
        const SimInput *in = sim_inputs_at(inputs, i);
        json_builder_begin_object(b);
        js_set_str(b, "kind", in->kind);
        js_set_str(b, "path", in->path);
        js_set_str(b, "sha256", in->sha256);
        json_builder_set_member_name(b, "shipped");
        json_builder_add_boolean_value(b, in->shipped);
        json_builder_end_object(b);
    }
    json_builder_end_array(b);
}

void prov_json(JsonBuilder *b, const SimProvenance *p)
{
    json_builder_set_member_name(b, "provenance");
    json_builder_begin_object(b);
    js_set_str(b, "pgsim_version", prov_version());
    js_set_str(b, "config", p->config);
    js_set_str(b, "config_sha256", p->config_sha256);
    json_builder_set_member_name(b, "overrides");
    json_builder_begin_array(b);
    for (guint i = 0; p->overrides && i < p->overrides->len; i++)
        js_add_str(b, g_ptr_array_index(p->overrides, i));
    json_builder_end_array(b);
    js_set_int(b, "seed", (gint64)p->seed);
    js_set_str(b, "fidelity", p->fidelity);
    JsonNode *eff =
        p->effective_config ? js_parse(p->effective_config, -1, NULL, NULL)
                            : NULL;
    js_set_node(b, "effective_config", eff);
    if (eff)
        json_node_unref(eff);
    json_builder_set_member_name(b, "inputs");
    prov_inputs_json(b, p->inputs);
    json_builder_end_object(b);
}

static void csv_row(GString *out, const char *name, const char *field,
                    const char *value)
{
    g_string_append(out, "provenance,");
    dt_csv_field(out, name);
    g_string_append(out, ",,");
    dt_csv_field(out, field);
    g_string_append_c(out, ',');
    dt_csv_field(out, value);
    g_string_append(out, ",\n");
}

void prov_csv_rows(GString *out, const SimProvenance *p)
{
    csv_row(out, NULL, "pgsim_version", prov_version());
    csv_row(out, NULL, "config", p->config);
    csv_row(out, NULL, "config_sha256", p->config_sha256);
    for (guint i = 0; p->overrides && i < p->overrides->len; i++) {
        char idx[16];
        g_snprintf(idx, sizeof idx, "%u", i);
        csv_row(out, idx, "override", g_ptr_array_index(p->overrides, i));
    }
    char seed[24];
    g_snprintf(seed, sizeof seed, "%" G_GUINT64_FORMAT, p->seed);
    csv_row(out, NULL, "seed", seed);
    csv_row(out, NULL, "fidelity", p->fidelity);
    csv_row(out, NULL, "effective_config", p->effective_config);
    for (guint i = 0; i < sim_inputs_len(p->inputs); i++) {
        const SimInput *in = sim_inputs_at(p->inputs, i);
        char idx[16];
        g_snprintf(idx, sizeof idx, "%u", i);
        csv_row(out, idx, "input_kind", in->kind);
        csv_row(out, idx, "input_path", in->path);
        csv_row(out, idx, "input_sha256", in->sha256);
    }
}

/* Appends s with line breaks escaped ("\n", "\r"); NULL as "-". */
static void one_line(GString *out, const char *s)
{
    if (!s) {
        g_string_append_c(out, '-');
        return;
    }
    for (; *s; s++) {
        if (*s == '\n')
            g_string_append(out, "\\n");
        else if (*s == '\r')
            g_string_append(out, "\\r");
        else
            g_string_append_c(out, *s);
    }
}

static void comment(GString *out, const char *field, const char *value)
{
    g_string_append_printf(out, "# %s: ", field);
    one_line(out, value);
    g_string_append_c(out, '\n');
}

void prov_comment_lines(GString *out, const SimProvenance *p)
{
    comment(out, "pgsim_version", prov_version());
    comment(out, "config", p->config);
    comment(out, "config_sha256", p->config_sha256);
    for (guint i = 0; p->overrides && i < p->overrides->len; i++)
        comment(out, "override", g_ptr_array_index(p->overrides, i));
    char seed[24];
    g_snprintf(seed, sizeof seed, "%" G_GUINT64_FORMAT, p->seed);
    comment(out, "seed", seed);
    comment(out, "fidelity", p->fidelity);
    comment(out, "effective_config", p->effective_config);
    for (guint i = 0; i < sim_inputs_len(p->inputs); i++) {
        const SimInput *in = sim_inputs_at(p->inputs, i);
        g_string_append_printf(out, "# input: %s ", in->kind);
        one_line(out, in->path);
        g_string_append_printf(out, " sha256 %s%s\n", in->sha256,
                               in->shipped ? "" : " (not shipped)");
    }
}

void prov_text_line(GString *out, const SimProvenance *p)
{
    g_string_append_printf(out, "provenance: pgsim %s; config ",
                           prov_version());
    one_line(out, p->config);
    g_string_append(out, " (sha256 ");
    one_line(out, p->config_sha256);
    g_string_append(out, "); overrides ");
    for (guint i = 0; p->overrides && i < p->overrides->len; i++) {
        if (i)
            g_string_append(out, ", ");
        one_line(out, g_ptr_array_index(p->overrides, i));
    }
    if (!p->overrides || !p->overrides->len)
        g_string_append(out, "none");
    g_string_append_printf(out, "; seed %" G_GUINT64_FORMAT "; fidelity ",
                           p->seed);
    one_line(out, p->fidelity);
    for (guint i = 0; i < sim_inputs_len(p->inputs); i++) {
        const SimInput *in = sim_inputs_at(p->inputs, i);
        g_string_append_printf(out, "%s %s ", i ? "," : "; inputs", in->kind);
        one_line(out, in->path);
        g_string_append_printf(out, " (sha256 %s)", in->sha256);
    }
}

void prov_text_notes(GString *out, const SimProvenance *p)
{
    for (guint i = 0; i < sim_inputs_len(p->inputs); i++) {
        const SimInput *in = sim_inputs_at(p->inputs, i);
        if (in->shipped)
            continue;
        g_string_append(out, "note: machine model ");
        one_line(out, in->path);
        g_string_append_printf(out, " is not a shipped model (sha256 %s)\n",
                               in->sha256);
    }
}
