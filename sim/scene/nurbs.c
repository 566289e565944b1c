/* nurbs.c — the Nurbs scene of Argus: a closed bicubic B-spline surface
 * cut into 14 x 14-control-point patches and tessellated into triangle
 * strips (nurbs.h).  Uniform cubic B-spline basis: de Boor, "A Practical
 * Guide to Splines" (1978); any span of 4 x 4 control points is a
 * bicubic patch.  O(patches tess^2) time and memory.
 */
#include "sim/scene/nurbs.h"
#include "sim/core/rng.h"
#include <math.h>

#define SPANS (SCENE_NURBS_CONTROL - 3) /* knot spans per patch side */

SceneNurbsParams scene_nurbs_defaults(void)
{
    SceneNurbsParams p = {6, 17, 24, 6, 0.25, 1, {0.80f, 0.62f, 0.45f}};
    return p;
}

/* Radius modulation: a seeded sum of low-frequency sinusoids in the two
 * angles, scaled to amplitude. */
static double bumpiness(const SceneNurbsParams *p, double th, double ph)
{
    SimRng r;
    sim_rng_init(&r, p->seed, 7);
    double f = 0;
    for (guint k = 0; k < p->bumps; k++) {
        double m = 1 + (double)sim_rng_below(&r, 3);
        double n = 1 + (double)sim_rng_below(&r, 5);
        double phase = 2 * G_PI * sim_rng_uniform(&r);
        f += sin(m * th + n * ph + phase);
    }
    return p->bumps ? p->amplitude * f / sqrt((double)p->bumps) : 0;
}

Vec3 scene_nurbs_control(const SceneNurbsParams *p, guint i, guint j)
{
    guint nu = SPANS * p->patches_u, nv = SPANS * p->patches_v;
    double th = 2 * G_PI * (double)(i % nu) / nu;
    double ph = 2 * G_PI * (double)(j % nv) / nv;
    double r = 0.45 * (1 + bumpiness(p, th, ph));
    double ring = 1 + r * cos(th);
    return vec3(ring * cos(ph), r * sin(th), ring * sin(ph));
}

static void basis(double t, double b[4])
{
    double u = 1 - t;
    b[0] = u * u * u / 6;
    b[1] = (3 * t * t * t - 6 * t * t + 4) / 6;
    b[2] = (-3 * t * t * t + 3 * t * t + 3 * t + 1) / 6;
    b[3] = t * t * t / 6;
}

/* Span index and local parameter of s in [0, SPANS]. */
static guint span_of(double s, double *t)
{
    guint k = s >= SPANS ? SPANS - 1 : (guint)floor(s);
    *t = s - k;
    return k;
}

/* The control net, computed once per mesh (NULL: on demand). */
typedef struct {
    const SceneNurbsParams *p;
    Vec3 *net; /* nu x nv, row-major in i */
    guint nu, nv;
} Net;

static Vec3 net_at(const Net *n, guint i, guint j)
{
    if (!n->net)
        return scene_nurbs_control(n->p, i, j);
    return n->net[(i % n->nu) * n->nv + j % n->nv];
}

static Vec3 eval(const Net *n, guint a, guint b, double s, double t)
{
    double ls, lt, bs[4], bt[4];
    guint ks = span_of(s, &ls), kt = span_of(t, &lt);
    basis(ls, bs);
    basis(lt, bt);
    Vec3 x = vec3(0, 0, 0);
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) {
            Vec3 c = net_at(n, SPANS * a + ks + i, SPANS * b + kt + j);
            x = vec3_add(x, vec3_scale(c, bs[i] * bt[j]));
        }
    return x;
}

Vec3 scene_nurbs_eval(const SceneNurbsParams *p, guint a, guint b, double s,
                      double t)
{
    Net n = {p, NULL, SPANS * p->patches_u, SPANS * p->patches_v};
    return eval(&n, a, b, s, t);
}

/* The (tess + 1)^2 grid of one patch, appended to m; returns the first
 * vertex index. */
static uint32_t patch_grid(SceneMesh *m, const Net *n, guint a, guint b)
{
    const SceneNurbsParams *p = n->p;
    uint32_t first = scene_mesh_n_vertices(m);
    double h = (double)SPANS / p->tess;
    for (guint r = 0; r <= p->tess; r++)
        for (guint q = 0; q <= p->tess; q++)
            scene_mesh_add_vertex(m, eval(n, a, b, r * h, q * h));
    return first;
}

/* Strip r of a patch: S = a0 b0 a1 b1 ... (a on row r, b on row r + 1);
 * triangle k is (S[k], S[k+1], S[k+2]), every other one flipped so all
 * keep one orientation. */
static void patch_strips(SceneMesh *m, const SceneNurbsParams *p,
                         uint32_t first, uint32_t tag)
{
    guint w = p->tess + 1;
    for (guint r = 0; r < p->tess; r++)
        for (guint k = 0; k < 2 * p->tess; k++) {
            uint32_t s[3];
            for (guint i = 0; i < 3; i++) {
                guint e = k + i;
                s[i] = first + (r + (e & 1)) * w + e / 2;
            }
            if (k & 1)
                scene_mesh_add_tri(m, s[1], s[0], s[2], p->color, tag);
            else
                scene_mesh_add_tri(m, s[0], s[1], s[2], p->color, tag);
        }
}

SceneMesh *scene_nurbs_mesh(const SceneNurbsParams *p)
{
    g_assert(p->patches_u >= 1 && p->patches_v >= 1 && p->tess >= 1);
    SceneMesh *m = scene_mesh_new();
    Net n = {p, NULL, SPANS * p->patches_u, SPANS * p->patches_v};
    n.net = g_new(Vec3, (gsize)n.nu * n.nv);
    for (guint i = 0; i < n.nu; i++)
        for (guint j = 0; j < n.nv; j++)
            n.net[i * n.nv + j] = scene_nurbs_control(p, i, j);
    for (guint a = 0; a < p->patches_u; a++)
        for (guint b = 0; b < p->patches_v; b++) {
            uint32_t tag = a * p->patches_v + b;
            patch_strips(m, p, patch_grid(m, &n, a, b), tag);
        }
    g_free(n.net);
    scene_mesh_compute_normals(m);
    return m;
}

Scene *scene_nurbs_new(const SceneNurbsParams *p)
{
    return scene_new_app("nurbs", scene_nurbs_mesh(p), 20, 35, 0.95);
}
