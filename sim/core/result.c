/* result.c — the run result that workloads fill and writers print. */
#include "sim/core/result.h"
#include <math.h>
#include <string.h>

static void node_free(gpointer p)
{
    SimNodeResult *n = p;
    g_free(n->name);
    g_free(n->kind);
    sim_busy_clear(&n->busy);
    g_free(n);
}

static void metric_free(gpointer p)
{
    SimMetric *m = p;
    g_free(m->name);
    g_free(m->unit);
    g_free(m);
}

static void idle_free(gpointer p)
{
    SimIdleResult *i = p;
    g_free(i->kind);
    g_free(i);
}

void sim_result_add_idle(SimResult *r, const char *kind, uint64_t n)
{
    for (guint i = 0; i < r->idle->len; i++) {
        SimIdleResult *e = g_ptr_array_index(r->idle, i);
        if (strcmp(e->kind, kind) == 0) {
            e->count += n;
            return;
        }
    }
    SimIdleResult *e = g_new0(SimIdleResult, 1);
    e->kind = g_strdup(kind);
    e->count = n;
    g_ptr_array_add(r->idle, e);
}

uint64_t sim_result_n_idle(const SimResult *r)
{
    uint64_t n = 0;
    for (guint i = 0; i < r->idle->len; i++)
        n += ((const SimIdleResult *)g_ptr_array_index(r->idle, i))->count;
    return n;
}

SimResult *sim_result_new(const char *workload, const char *machine)
{
    SimResult *r = g_new0(SimResult, 1);
    r->workload = g_strdup(workload);
    r->machine = g_strdup(machine);
    r->fidelity = g_strdup("analytic");
    r->frame_times = g_array_new(FALSE, FALSE, sizeof(SimTime));
    r->phases = g_ptr_array_new_with_free_func(g_free);
    r->nodes = g_ptr_array_new_with_free_func(node_free);
    r->idle = g_ptr_array_new_with_free_func(idle_free);
    r->metrics = g_ptr_array_new_with_free_func(metric_free);
    r->overrides = g_ptr_array_new_with_free_func(g_free);
    r->mem_peak = NAN;
    r->notes = g_ptr_array_new_with_free_func(g_free);
    return r;
}

void sim_result_free(SimResult *r)
{
    if (!r)
        return;
    g_free(r->workload);
    g_free(r->machine);
    g_free(r->fidelity);
    g_free(r->busiest_link);
    g_array_free(r->frame_times, TRUE);
    g_ptr_array_free(r->phases, TRUE);
    g_ptr_array_free(r->nodes, TRUE);
    g_ptr_array_free(r->idle, TRUE);
    g_ptr_array_free(r->metrics, TRUE);
    g_ptr_array_free(r->overrides, TRUE);
    g_free(r->config_path);
    g_free(r->config_sha256);
    g_free(r->config_effective);
    g_free(r->mem_kind);
    g_ptr_array_free(r->notes, TRUE);
    sim_inputs_free(r->inputs);
    g_free(r);
}

void sim_result_add_frame(SimResult *r, SimTime t)
{
    g_array_append_val(r->frame_times, t);
}

SimNodeResult *sim_result_add_node(SimResult *r, const char *name,
                                   const char *kind)
{
    SimNodeResult *n = g_new0(SimNodeResult, 1);
    n->name = g_strdup(name);
    n->kind = g_strdup(kind);
    sim_busy_init(&n->busy);
    g_ptr_array_add(r->nodes, n);
    return n;
}

static SimMetric *find_metric(const SimResult *r, const char *name)
{
    for (guint i = 0; i < r->metrics->len; i++) {
        SimMetric *m = g_ptr_array_index(r->metrics, i);
        if (strcmp(m->name, name) == 0)
            return m;
    }
    return NULL;
}

void sim_result_set_metric(SimResult *r, const char *name, double value,
                           const char *unit)
{
    SimMetric *m = find_metric(r, name);
    if (!m) {
        m = g_new0(SimMetric, 1);
        m->name = g_strdup(name);
        g_ptr_array_add(r->metrics, m);
    }
    g_free(m->unit);
    m->unit = g_strdup(unit ? unit : "");
    m->value = value;
}

gboolean sim_result_get_metric(const SimResult *r, const char *name,
                               double *value)
{
    SimMetric *m = find_metric(r, name);
    if (m && value)
        *value = m->value;
    return m != NULL;
}

double sim_result_metric(const SimResult *r, const char *name)
{
    double v = NAN;
    sim_result_get_metric(r, name, &v);
    return v;
}

void sim_result_set_phases(SimResult *r, const SimEngine *eng)
{
    g_ptr_array_set_size(r->phases, 0);
    for (unsigned i = 0; i < sim_engine_phase_count(eng); i++)
        g_ptr_array_add(r->phases, g_strdup(sim_engine_phase_name(eng, i)));
}

double sim_result_mean_frame_s(const SimResult *r)
{
    if (r->frame_times->len == 0)
        return 0.0;
    SimSum s = {0};
    for (guint i = 0; i < r->frame_times->len; i++)
        sim_sum_add(&s,
                    sim_time_to_s(g_array_index(r->frame_times, SimTime, i)));
    return sim_sum_value(&s) / r->frame_times->len;
}

double sim_result_node_util(const SimResult *r, const SimNodeResult *n)
{
    return r->elapsed ? (double)n->busy.total / (double)r->elapsed : 0.0;
}

SimUtilUsed sim_result_util_used(const SimResult *r)
{
    SimUtilUsed u = {r->nodes->len, sim_result_n_idle(r), 0.0, 0.0};
    SimSum sum = {0};
    for (guint i = 0; i < r->nodes->len; i++) {
        double v = sim_result_node_util(r, g_ptr_array_index(r->nodes, i));
        sim_sum_add(&sum, v);
        u.max = MAX(u.max, v);
    }
    if (u.used)
        u.mean = sim_sum_value(&sum) / (double)u.used;
    return u;
}

gboolean sim_result_mem_exceeds(const SimResult *r)
{
    return isfinite(r->mem_peak) && r->mem_node > 0 &&
           r->mem_peak > (double)r->mem_node;
}

char *sim_result_mem_note(const SimResult *r)
{
    if (!sim_result_mem_exceeds(r))
        return NULL;
    const double mib = 1048576.0;
    return g_strdup_printf("per-node memory %.2f MiB exceeds the %.2f MiB of "
                           "a node (kind %s): this configuration does not "
                           "fit on %s",
                           r->mem_peak / mib, (double)r->mem_node / mib,
                           r->mem_kind ? r->mem_kind : "?", r->machine);
}

void sim_result_add_note(SimResult *r, const char *text)
{
    g_ptr_array_add(r->notes, g_strdup(text));
}
