/* rast_testutil.c — shared helpers for the raster test suites. */
#include "tests/raster/rast_testutil.h"

TuCoverage *tu_coverage_new(int width, int height)
{
    TuCoverage *cv = g_new0(TuCoverage, 1);
    cv->width = width;
    cv->height = height;
    cv->count = g_new0(uint16_t, (size_t)width * height);
    return cv;
}

void tu_coverage_free(TuCoverage *cv)
{
    if (!cv)
        return;
    g_free(cv->count);
    g_free(cv);
}

static void cover(void *ctx, const RastSpan *s, RastCounters *c)
{
    (void)c;
    TuCoverage *cv = ctx;
    g_assert(s->y >= 0 && s->y < cv->height);
    g_assert(s->x0 >= 0 && s->x0 < s->x1 && s->x1 <= cv->width);
    for (int x = s->x0; x < s->x1; x++)
        cv->count[(size_t)s->y * cv->width + x]++;
    cv->spans++;
}

RastSpanSink tu_coverage_sink(TuCoverage *cv)
{
    return (RastSpanSink){cover, cv};
}

uint64_t tu_coverage_count(const TuCoverage *cv, unsigned k)
{
    uint64_t n = 0;
    for (size_t i = 0; i < (size_t)cv->width * cv->height; i++)
        n += cv->count[i] == k;
    return n;
}

unsigned tu_coverage_max(const TuCoverage *cv)
{
    unsigned m = 0;
    for (size_t i = 0; i < (size_t)cv->width * cv->height; i++)
        m = MAX(m, cv->count[i]);
    return m;
}

RastScreenVert tu_sv(double x, double y, double z)
{
    RastScreenVert v;
    v.x = (int64_t)llround(x * RAST_SUBPIX);
    v.y = (int64_t)llround(y * RAST_SUBPIX);
    v.z = z;
    v.col = (RastColor){1, 1, 1};
    return v;
}

gboolean tu_scan(double ax, double ay, double bx, double by, double cx,
                 double cy, uint32_t prim, int w, int h, RastSpanSink sink,
                 RastCounters *c)
{
    RastScreenVert v[3] = {tu_sv(ax, ay, 0.5), tu_sv(bx, by, 0.5),
                           tu_sv(cx, cy, 0.5)};
    if (rast_area2(&v[0], &v[1], &v[2]) == 0)
        return FALSE;
    rast_scan_triangle(v, prim, w, h, sink, c);
    return TRUE;
}

RastVert tu_cv(double x, double y, double z, double w)
{
    return (RastVert){{x, y, z, w}, {1, 1, 1}};
}

void tu_render_both(const RastView *view, const SceneMesh *m,
                    const uint32_t *subset, guint n_subset, RastImage **full,
                    RastImage **scan, RastCounters *cf, RastCounters *cs)
{
    int w = view->width, h = view->height;
    RastZBuffer *zb = rast_zbuffer_new(w, h);
    rast_draw_mesh(view, m, mat4_identity(), scene_color(1, 1, 1), 0,
                   &(RastSubset){subset, n_subset}, rast_zbuffer_sink(zb), cf);
    cf->winners += rast_zbuffer_covered(zb);
    RastSpanList *sl = rast_spanlist_new(w, h);
    rast_draw_mesh(view, m, mat4_identity(), scene_color(1, 1, 1), 0,
                   &(RastSubset){subset, n_subset}, rast_spanlist_sink(sl), cs);
    rast_spanlist_sort(sl);
    RastActive *a = rast_active_new(w, h);
    rast_scanline_zbuffer(a, sl, cs);
    RastColor bg = {0.1f, 0.2f, 0.3f};
    *full = rast_image_new(w, h);
    *scan = rast_image_new(w, h);
    rast_image_from_zbuffer(*full, zb, bg);
    rast_image_from_active(*scan, a, bg);
    rast_active_free(a);
    rast_spanlist_free(sl);
    rast_zbuffer_free(zb);
}

static Vec3 sphere_pt(double r, int i, int j, int slices, int stacks)
{
    double th = G_PI * j / stacks, ph = 2 * G_PI * i / slices;
    return vec3(r * sin(th) * cos(ph), r * cos(th), r * sin(th) * sin(ph));
}

SceneMesh *tu_sphere(double r, int slices, int stacks, gboolean invert)
{
    SceneMesh *m = scene_mesh_new();
    for (int j = 0; j <= stacks; j++)
        for (int i = 0; i < slices; i++)
            scene_mesh_add_vertex(m, sphere_pt(r, i, j, slices, stacks));
    for (int j = 0; j < stacks; j++)
        for (int i = 0; i < slices; i++) {
            uint32_t a = j * slices + i, b = j * slices + (i + 1) % slices;
            uint32_t c = a + slices, d = b + slices;
            SceneColor col = scene_color((i % 7) / 7.0f, (j % 5) / 5.0f, 0.5f);
            uint32_t q[4] = {a, b, d, c};
            if (invert) {
                q[1] = c;
                q[3] = b;
            }
            /* At the poles two corners coincide: drop the repeated one. */
            if (j == 0)
                scene_mesh_add_tri(m, a, invert ? c : d, invert ? d : c, col,
                                   0);
            else if (j == stacks - 1)
                scene_mesh_add_tri(m, a, invert ? c : b, invert ? b : d, col,
                                   0);
            else
                scene_mesh_add_poly(m, q, 4, col, 0);
        }
    return m;
}

SceneMesh *tu_random_tris(uint64_t seed, int n, double size)
{
    SimRng r;
    sim_rng_init(&r, seed, 0);
    SceneMesh *m = scene_mesh_new();
    for (int i = 0; i < n; i++) {
        Vec3 c = vec3(sim_rng_uniform(&r) * 2 - 1, sim_rng_uniform(&r) * 2 - 1,
                      sim_rng_uniform(&r) * 1.6 - 0.8);
        uint32_t v[3];
        for (int k = 0; k < 3; k++) {
            Vec3 d = vec3((sim_rng_uniform(&r) - 0.5) * size,
                          (sim_rng_uniform(&r) - 0.5) * size,
                          (sim_rng_uniform(&r) - 0.5) * 0.4);
            v[k] = scene_mesh_add_vertex(m, vec3_add(c, d));
        }
        SceneColor col =
            scene_color((float)sim_rng_uniform(&r), (float)sim_rng_uniform(&r),
                        (float)sim_rng_uniform(&r));
        scene_mesh_add_tri(m, v[0], v[1], v[2], col, 0);
    }
    return m;
}
