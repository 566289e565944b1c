/* isosurface.c — isosurfaces of procedural fields, and large polygons.
 *
 * Implements isosurface.h.  Marching tetrahedra over the lattice: each
 * cube (corners numbered by bits x = 1, y = 2, z = 4) is split into the
 * six tetrahedra 0-a-b-7 along the paths 0 -> a -> b -> 7 of the cube's
 * edges (Doi & Koide 1991, as a table-free variant of Lorensen & Cline's
 * marching cubes).  A tetrahedron with one or three corners inside gives
 * one triangle, with two a quad split in two.  Edge vertices are welded
 * through a hash keyed by the pair of lattice-point ids.  O(grid^3).
 */
#include "sim/scene/isosurface.h"
#include "sim/core/memlimit.h"
#include "sim/scene/scene_limits.h"

#include "sim/core/rng.h"
#include <string.h>

static const int tets[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7},
                               {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};

SceneIsoParams scene_iso_defaults(void)
{
    SceneIsoParams p = {SCENE_FIELD_GYROID,   32, 0.0, 2.0, 12, 1,
                        {0.55f, 0.75f, 0.95f}};
    return p;
}

double scene_iso_field(const SceneIsoParams *p, const Vec3 *centres, Vec3 x)
{
    if (p->field == SCENE_FIELD_GYROID) {
        double k = G_PI * p->periods;
        return sin(k * x.x) * cos(k * x.y) + sin(k * x.y) * cos(k * x.z) +
               sin(k * x.z) * cos(k * x.x);
    }
    double f = 0;
    for (guint i = 0; i < p->balls; i++) {
        Vec3 d = vec3_sub(x, centres[i]);
        f += 0.0625 / (vec3_dot(d, d) + 1e-12);
    }
    return f;
}

typedef struct {
    const SceneIsoParams *p;
    guint n;     /* lattice points per axis = grid + 1 */
    double *val; /* field at lattice points */
    SceneMesh *m;
    GHashTable *edges; /* (lo id, hi id) -> vertex index + 1 */
    uint32_t tag;      /* cell of the cubes being polygonised */
} Iso;

static Vec3 lattice_point(const Iso *s, guint64 id)
{
    guint n = s->n;
    double h = 2.0 / (n - 1);
    return vec3(-1 + h * (id % n), -1 + h * ((id / n) % n),
                -1 + h * (id / ((guint64)n * n)));
}

static uint32_t edge_vertex(Iso *s, guint64 a, guint64 b)
{
    if (a > b) {
        guint64 t = a;
        a = b;
        b = t;
    }
    guint64 key = a * (guint64)s->n * s->n * s->n + b;
    gpointer hit = g_hash_table_lookup(s->edges, &key);
    if (hit)
        return GPOINTER_TO_UINT(hit) - 1;
    double fa = s->val[a], fb = s->val[b];
    double t = (s->p->iso - fa) / (fb - fa);
    Vec3 pa = lattice_point(s, a), pb = lattice_point(s, b);
    uint32_t v = scene_mesh_add_vertex(
        s->m, vec3_add(pa, vec3_scale(vec3_sub(pb, pa), t)));
    g_hash_table_insert(s->edges, g_memdup2(&key, sizeof key),
                        GUINT_TO_POINTER(v + 1));
    return v;
}

/* Midpoint of the lattice edge a-b. */
static Vec3 mid(const Iso *s, guint64 a, guint64 b)
{
    return vec3_scale(vec3_add(lattice_point(s, a), lattice_point(s, b)), 0.5);
}

/* Emits triangle (a, b, c) wound so its normal points from the inside
 * (f >= iso) towards the outside (f < iso).  The winding is decided on
 * the midpoints ma, mb, mc of the triangle's lattice edges, never on the
 * interpolated vertices: those coincide when a lattice value equals iso
 * (the gyroid is 0 at many lattice points) and the orientation of a
 * zero-area triangle would be arbitrary.  The midpoint triangle lies in
 * a plane that strictly separates the tetrahedron's inside corners from
 * its outside ones, and moving the vertices along their edges never
 * flips a triangle, so the two windings agree whenever the real
 * triangle has an area; neighbours share edges in opposite directions. */
static void emit(Iso *s, const uint32_t v[3], const Vec3 m[3], Vec3 inside)
{
    Vec3 n = vec3_cross(vec3_sub(m[1], m[0]), vec3_sub(m[2], m[0]));
    gboolean flip = vec3_dot(n, vec3_sub(m[0], inside)) < 0;
    scene_mesh_add_tri(s->m, v[0], flip ? v[2] : v[1], flip ? v[1] : v[2],
                       s->p->color, s->tag);
}

static void do_tet(Iso *s, const guint64 id[4])
{
    guint64 in[4], out[4];
    guint ni = 0, no = 0;
    for (int k = 0; k < 4; k++) {
        if (s->val[id[k]] >= s->p->iso)
            in[ni++] = id[k];
        else
            out[no++] = id[k];
    }
    if (ni == 0 || no == 0)
        return;
    Vec3 ref = lattice_point(s, in[0]);
    if (ni == 1 || no == 1) {
        guint64 apex = ni == 1 ? in[0] : out[0];
        guint64 *rest = ni == 1 ? out : in;
        uint32_t v[3];
        Vec3 m[3];
        for (int k = 0; k < 3; k++) {
            v[k] = edge_vertex(s, apex, rest[k]);
            m[k] = mid(s, apex, rest[k]);
        }
        emit(s, v, m, ref);
        return;
    }
    /* a quad: edges in0-out0, in0-out1, in1-out1, in1-out0 */
    guint64 e[4][2] = {
        {in[0], out[0]}, {in[0], out[1]}, {in[1], out[1]}, {in[1], out[0]}};
    uint32_t q[4];
    Vec3 mq[4];
    for (int k = 0; k < 4; k++) {
        q[k] = edge_vertex(s, e[k][0], e[k][1]);
        mq[k] = mid(s, e[k][0], e[k][1]);
    }
    uint32_t t1[3] = {q[0], q[1], q[2]}, t2[3] = {q[0], q[2], q[3]};
    Vec3 m1[3] = {mq[0], mq[1], mq[2]}, m2[3] = {mq[0], mq[2], mq[3]};
    emit(s, t1, m1, ref);
    emit(s, t2, m2, ref);
}

Vec3 *scene_iso_centres(const SceneIsoParams *p)
{
    Vec3 *centres = g_new(Vec3, p->balls ? p->balls : 1);
    SimRng r;
    sim_rng_init(&r, p->seed, 0);
    for (guint i = 0; i < p->balls; i++) {
        double x = sim_rng_uniform(&r), y = sim_rng_uniform(&r);
        double z = sim_rng_uniform(&r);
        centres[i] = vec3(1.2 * x - 0.6, 1.2 * y - 0.6, 1.2 * z - 0.6);
    }
    return centres;
}

static void sample(Iso *s)
{
    const SceneIsoParams *p = s->p;
    Vec3 *centres = scene_iso_centres(p);
    guint64 total = (guint64)s->n * s->n * s->n;
    s->val = g_new(double, total);
    for (guint64 id = 0; id < total; id++)
        s->val[id] = scene_iso_field(p, centres, lattice_point(s, id));
    g_free(centres);
}

/* The six tetrahedra of the cube at lattice point (x, y, z). */
static void do_cube(Iso *s, guint x, guint y, guint z)
{
    guint n = s->n;
    guint64 base = x + (guint64)n * (y + (guint64)n * z);
    guint64 c[8];
    for (int k = 0; k < 8; k++)
        c[k] = base + (k & 1) + (k & 2 ? n : 0) + (k & 4 ? (guint64)n * n : 0);
    for (int t = 0; t < 6; t++) {
        guint64 id[4] = {c[tets[t][0]], c[tets[t][1]], c[tets[t][2]],
                         c[tets[t][3]]};
        do_tet(s, id);
    }
}

/* The cubes of cell (cx, cy, cz), z slowest, tagged with the cell. */
static void do_cell(Iso *s, guint cell, guint cx, guint cy, guint cz)
{
    guint nc = s->p->grid / cell;
    s->tag = cx + nc * (cy + nc * cz);
    for (guint z = cz * cell; z < (cz + 1) * cell; z++)
        for (guint y = cy * cell; y < (cy + 1) * cell; y++)
            for (guint x = cx * cell; x < (cx + 1) * cell; x++)
                do_cube(s, x, y, z);
}

SceneMesh *scene_iso_mesh_cells(const SceneIsoParams *p, guint cell)
{
    g_assert(p->grid >= 2 && p->grid <= 2048);
    g_assert(cell >= 1 && p->grid % cell == 0);
    Iso s = {p, p->grid + 1, NULL, scene_mesh_new(), NULL, 0};
    s.edges = g_hash_table_new_full(g_int64_hash, g_int64_equal, g_free, NULL);
    sample(&s);
    guint nc = p->grid / cell;
    for (guint cz = 0; cz < nc; cz++)
        for (guint cy = 0; cy < nc; cy++)
            for (guint cx = 0; cx < nc; cx++)
                do_cell(&s, cell, cx, cy, cz);
    g_hash_table_destroy(s.edges);
    g_free(s.val);
    return s.m;
}

SceneMesh *scene_iso_mesh(const SceneIsoParams *p)
{
    return scene_iso_mesh_cells(p, p->grid);
}

/* TRUE when the surface reaches the lattice's boundary, where it is cut
 * open (vertices there have a coordinate of -1 or 1, up to rounding). */
static gboolean reaches_boundary(const SceneMesh *m)
{
    const double b = 1 - 1e-9;
    for (guint i = 0; i < scene_mesh_n_vertices(m); i++) {
        Vec3 v = scene_mesh_vertex(m, i);
        if (fabs(v.x) >= b || fabs(v.y) >= b || fabs(v.z) >= b)
            return TRUE;
    }
    return FALSE;
}

Scene *scene_iso_new(const SceneIsoParams *p)
{
    Scene *s = scene_new("isosurface");
    SceneMesh *m = scene_iso_mesh(p);
    s->two_sided = reaches_boundary(m);
    guint id = scene_add_mesh(s, m);
    scene_add_instance(s, id, mat4_identity(), scene_color(1, 1, 1), 0);
    SceneView v = scene_view_default();
    v.azimuth_deg = 30;
    v.elevation_deg = 20;
    scene_apply_view(s, &v);
    return s;
}

SceneBigPolyParams scene_bigpoly_defaults(void)
{
    SceneBigPolyParams p = {1000, 6, 0.05, 0.1, 0.5, 1};
    return p;
}

/* Area of polygon pts[0..n) clipped to the square [-1, 1]^2
 * (Sutherland-Hodgman against the four sides, then the shoelace). */
static double area_in_square(const Vec3 *pts, guint n)
{
    Vec3 a[40], b[40];
    guint na = n;
    memcpy(a, pts, n * sizeof(Vec3));
    for (int side = 0; side < 4; side++) {
        int axis = side / 2;
        double sgn = side % 2 ? -1.0 : 1.0; /* keep sgn * coord <= 1 */
        guint nb = 0;
        for (guint k = 0; k < na; k++) {
            Vec3 p = a[k], q = a[(k + 1) % na];
            double dp = 1 - sgn * (axis ? p.y : p.x);
            double dq = 1 - sgn * (axis ? q.y : q.x);
            if (dp >= 0)
                b[nb++] = p;
            if ((dp >= 0) != (dq >= 0)) {
                double t = dp / (dp - dq);
                b[nb++] = vec3_add(p, vec3_scale(vec3_sub(q, p), t));
            }
        }
        na = nb;
        memcpy(a, b, nb * sizeof(Vec3));
    }
    double area = 0;
    for (guint k = 0; k < na; k++)
        area += a[k].x * a[(k + 1) % na].y - a[(k + 1) % na].x * a[k].y;
    return fabs(area) / 2;
}

/* A huge polygon: a randomly turned convex polygon of 4-8 corners about
 * the screen centre, drawn again until it covers over 3/4 of the screen
 * (seed 004 §6: "polygons which covered over 3/4 of the image"). */
static guint huge_polygon(SimRng *r, Vec3 *pts)
{
    for (;;) {
        guint n = 4 + (guint)sim_rng_below(r, 5);
        double rad = 0.95 + 0.3 * sim_rng_uniform(r);
        double rot = 2 * G_PI * sim_rng_uniform(r);
        double cx = 0.2 * (2 * sim_rng_uniform(r) - 1);
        double cy = 0.2 * (2 * sim_rng_uniform(r) - 1);
        double z = -1 + 2 * sim_rng_uniform(r);
        for (guint k = 0; k < n; k++) {
            double a = rot + 2 * G_PI * k / n;
            pts[k] = vec3(cx + rad * cos(a), cy + rad * sin(a), z);
        }
        if (area_in_square(pts, n) > 0.75 * 4.0)
            return n;
    }
}

/* A regular polygon of 3..max_sides corners, radius in [min, max]. */
static guint small_polygon(SimRng *r, const SceneBigPolyParams *p, Vec3 *pts)
{
    double rad = p->min_size + (p->max_size - p->min_size) * sim_rng_uniform(r);
    guint sides = 3 + (guint)sim_rng_below(r, p->max_sides - 2);
    double cx = 2 * sim_rng_uniform(r) - 1, cy = 2 * sim_rng_uniform(r) - 1;
    double z = -1 + 2 * sim_rng_uniform(r);
    double rot = 2 * G_PI * sim_rng_uniform(r);
    for (guint k = 0; k < sides; k++) {
        double a = rot + 2 * G_PI * k / sides;
        pts[k] = vec3(cx + rad * cos(a), cy + rad * sin(a), z);
    }
    return sides;
}

static void big_polygon(SceneMesh *m, SimRng *r, const SceneBigPolyParams *p,
                        guint i)
{
    Vec3 pts[16];
    uint32_t v[16];
    guint n = sim_rng_uniform(r) < p->huge_fraction ? huge_polygon(r, pts)
                                                    : small_polygon(r, p, pts);
    for (guint k = 0; k < n; k++)
        v[k] = scene_mesh_add_vertex(m, pts[k]);
    SceneColor c = {(float)sim_rng_uniform(r), (float)sim_rng_uniform(r),
                    (float)sim_rng_uniform(r)};
    scene_mesh_add_poly(m, v, n, c, i);
}

/* Triangles of a surface on a grid, taken as 30 x k x grid^2 and never
 * more than the 12 per cell six tetrahedra can make.  k = max(1,
 * periods) for the gyroid (measured: 58,968 triangles at grid 32 and 2
 * periods, 930,980 at grid 64 and 8 periods: 28 x periods x grid^2);
 * k = max(1, balls / 12) for metaballs (98,106 at grid 64, 12 balls,
 * iso 1: 24 x grid^2). */
static double iso_triangles(const SceneIsoParams *p)
{
    double g = p->grid;
    double k = p->field == SCENE_FIELD_GYROID ? MAX(1.0, p->periods)
                                              : MAX(1.0, p->balls / 12.0);
    return MIN(12 * g * g * g, 30 * k * g * g);
}

gboolean scene_iso_check(const SceneIsoParams *p, const char *what,
                         GError **err)
{
    if (p->grid < 2 || p->grid > SCENE_ISO_GRID_MAX) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "%s: found grid %u, expected 2 to %d cells", what, p->grid,
                    SCENE_ISO_GRID_MAX);
        return FALSE;
    }
    double n = p->grid + 1.0;
    double bytes = n * n * n * sizeof(double) + iso_triangles(p) * SCENE_POLY_BYTES;
    char *size = g_strdup_printf("grid %u", p->grid);
    gboolean ok = sim_mem_check(bytes, what, size, err);
    g_free(size);
    return ok;
}

gboolean scene_bigpoly_check(const SceneBigPolyParams *p, const char *what,
                             GError **err)
{
    char *size = g_strdup_printf("%u polygons of up to %u sides", p->count,
                                 p->max_sides);
    double per = SCENE_POLY_BYTES * MAX(1.0, (p->max_sides - 2) / 2.0);
    gboolean ok = sim_mem_check(p->count * per, what, size, err);
    g_free(size);
    return ok;
}

Scene *scene_bigpoly_new(const SceneBigPolyParams *p)
{
    g_assert(p->max_sides >= 3 && p->max_sides <= 16);
    SimRng r;
    sim_rng_init(&r, p->seed, 0);
    SceneMesh *m = scene_mesh_new();
    for (guint i = 0; i < p->count; i++)
        big_polygon(m, &r, p, i);
    Scene *s = scene_new("large_polygons");
    guint id = scene_add_mesh(s, m);
    scene_add_instance(s, id, mat4_identity(), scene_color(1, 1, 1), 0);
    SceneCamera c = scene_camera_default();
    c.proj = SCENE_ORTHOGRAPHIC;
    c.eye = vec3(0, 0, 2);
    c.target = vec3(0, 0, 0);
    c.height = 2;
    c.near = 0.5;
    c.far = 3.5;
    s->camera = c;
    return s;
}
