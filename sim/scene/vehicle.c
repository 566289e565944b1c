/* vehicle.c — a procedural vehicle as a structure hierarchy (seed 000).
 *
 * Implements vehicle.h.  Leaves are parametric patches (a body-box panel,
 * a tube, an ellipsoid band, a tyre-torus sector) evaluated on a grid and
 * cut off after exactly their triangle budget; budgets use the
 * largest-remainder method (Hamilton apportionment).  Structure database:
 * sim/scene/structdb.h.  O(triangles + structures).
 *
 * Primitive order.  Seed 000 §4.1 chunks "every N primitives" of the
 * input file (its "unsorted" strategy), so the order in which the file
 * lists a structure's triangles decides the chunks' boxes.  The
 * structures are written part by part (body, chassis, wheels, interior,
 * trim) and each part's triangles as a modelling tool writes a
 * tessellated surface, not spatially sorted: (1) the tessellator sizes
 * its parameter grid by the surface's extent, so the quads are nearly
 * square in space (counts along u and v in the ratio of the patch's
 * lengths, param_length()), rather than a square grid of parameter
 * steps; (2) it writes the grid as strips, each strip one row of quads
 * (two triangles each) running the full length of the patch's longer
 * side, strip after strip — a strip maker makes its strips as long as
 * the grid allows (fewer strips, fewer vertices sent).  N consecutive
 * triangles are then a sliver of N/2 quads along the part, which
 * unsorted chunking keeps and spatial subdivision does not.  The first
 * version wrote a square parameter grid row by row along u, which on
 * the body's narrow panels ran across the short side: unsorted chunks
 * were compact by accident and equal to sorted ones (overlap 1.156 vs
 * 1.160 at P = 16, granularity 12; issue 15).
 */
#include "sim/scene/vehicle.h"
#include "sim/core/memlimit.h"
#include "sim/scene/scene_limits.h"

#include <stdlib.h>

typedef enum { P_PANEL, P_TUBE, P_ELLIPSOID, P_TORUS } PatchKind;

typedef struct {
    PatchKind kind;
    Vec3 c;        /* panel origin; tube/ellipsoid/torus centre */
    Vec3 a, b;     /* panel edges; tube axis (a) and radius (b.x);
                      ellipsoid radii (a); torus R = a.x, r = a.y */
    double u0, u1; /* angle ranges (radians) where used */
    double v0, v1;
    double weight; /* share of the triangle budget */
    guint group;
} Patch;

static const char *const group_names[SCENE_VEHICLE_GROUPS] = {
    "body", "chassis", "wheels", "interior", "trim"};
static const Vec3 group_rgb[SCENE_VEHICLE_GROUPS] = {{0.75, 0.15, 0.12},
                                                     {0.25, 0.25, 0.27},
                                                     {0.08, 0.08, 0.08},
                                                     {0.45, 0.32, 0.22},
                                                     {0.85, 0.85, 0.80}};

SceneVehicleParams scene_vehicle_defaults(void)
{
    SceneVehicleParams p = {106, 20000, 3, 6.0, 14.0, 4.0, 40.0, 3.0, 120, 0};
    return p;
}

static Vec3 perp_basis(Vec3 axis, Vec3 *e2)
{
    Vec3 n = vec3_norm(axis);
    Vec3 t = fabs(n.y) < 0.9 ? vec3(0, 1, 0) : vec3(1, 0, 0);
    Vec3 e1 = vec3_norm(vec3_cross(n, t));
    *e2 = vec3_cross(n, e1);
    return e1;
}

static Vec3 patch_eval(const Patch *p, double u, double v)
{
    double th = p->u0 + u * (p->u1 - p->u0);
    double ph = p->v0 + v * (p->v1 - p->v0);
    switch (p->kind) {
    case P_PANEL:
        return vec3_add(p->c,
                        vec3_add(vec3_scale(p->a, u), vec3_scale(p->b, v)));
    case P_TUBE: {
        Vec3 e2, e1 = perp_basis(p->a, &e2);
        Vec3 r = vec3_add(vec3_scale(e1, cos(th)), vec3_scale(e2, sin(th)));
        return vec3_add(vec3_add(p->c, vec3_scale(p->a, v - 0.5)),
                        vec3_scale(r, p->b.x));
    }
    case P_ELLIPSOID:
        return vec3_add(p->c, vec3(p->a.x * cos(ph) * cos(th), p->a.y * sin(ph),
                                   -p->a.z * cos(ph) * sin(th)));
    default: {
        double w = p->a.x + p->a.y * cos(ph);
        return vec3_add(p->c, vec3(w * cos(th), w * sin(th), p->a.y * sin(ph)));
    }
    }
}

/* ---- the part list --------------------------------------------------- */

typedef struct {
    Vec3 o, a, b;
} Face;

/* The 5 faces of box [lo, hi] other than the bottom, outward-wound. */
static void box_faces(Vec3 lo, Vec3 hi, Face f[5])
{
    Vec3 d = vec3_sub(hi, lo);
    f[0] = (Face){{lo.x, lo.y, hi.z}, {d.x, 0, 0}, {0, d.y, 0}};
    f[1] = (Face){{hi.x, lo.y, lo.z}, {-d.x, 0, 0}, {0, d.y, 0}};
    f[2] = (Face){{lo.x, hi.y, hi.z}, {d.x, 0, 0}, {0, 0, -d.z}};
    f[3] = (Face){{hi.x, lo.y, hi.z}, {0, 0, -d.z}, {0, d.y, 0}};
    f[4] = (Face){{lo.x, lo.y, lo.z}, {0, 0, d.z}, {0, d.y, 0}};
}

static void add_body(GArray *ps, guint n)
{
    Face f[10];
    box_faces(vec3(-2.1, 0.5, -0.95), vec3(2.1, 1.2, 0.95), f);
    box_faces(vec3(-1.9, 1.2, -0.9), vec3(0.4, 1.85, 0.9), f + 5);
    for (guint k = 0; k < 10; k++) {
        guint m = n / 10 + (k < n % 10);
        for (guint j = 0; j < m; j++) {
            Patch p = {P_PANEL,
                       vec3_add(f[k].o, vec3_scale(f[k].a, (double)j / m)),
                       vec3_scale(f[k].a, 1.0 / m),
                       f[k].b,
                       0,
                       0,
                       0,
                       0,
                       1.5,
                       0};
            g_array_append_val(ps, p);
        }
    }
}

static void add_chassis(GArray *ps, guint n)
{
    for (guint i = 0; i < n; i++) {
        Patch p = {P_TUBE,   {0, 0, 0}, {0, 0, 0}, {0.06, 0, 0}, 0,
                   2 * G_PI, 0,         0,         0.6,          1};
        if (i % 2 == 0) {
            p.c = vec3(-1.75 + 0.5 * ((i / 4) % 8), 0.45,
                       (i / 2) % 2 ? 0.6 : -0.6);
            p.a = vec3(0.5, 0, 0);
        } else {
            p.c = vec3(-1.9 + 3.8 * (double)i / n, 0.4, 0);
            p.a = vec3(0, 0, 1.2);
            p.b.x = 0.04;
        }
        g_array_append_val(ps, p);
    }
}

static void add_wheels(GArray *ps, guint n)
{
    guint k = n / 4, sectors = k > 1 ? k - 1 : 1;
    for (guint w = 0; w < 4; w++) {
        double side = w % 2 ? 1 : -1;
        Vec3 c = vec3(w < 2 ? 1.35 : -1.35, 0.4, 0.85 * side);
        for (guint j = 0; j < k; j++) {
            Patch p = {P_TORUS,
                       c,
                       {0.28, 0.12, 0},
                       {0, 0, 0},
                       2 * G_PI * j / sectors,
                       2 * G_PI * (j + 1) / sectors,
                       0,
                       2 * G_PI,
                       2.0,
                       2};
            if (j == sectors) { /* the hub */
                p = (Patch){P_ELLIPSOID,
                            vec3(c.x, c.y, c.z + 0.1 * side),
                            {0.2, 0.2, 0.06},
                            {0, 0, 0},
                            0,
                            2 * G_PI,
                            -0.45 * G_PI,
                            0.45 * G_PI,
                            1.0,
                            2};
            }
            g_array_append_val(ps, p);
        }
    }
}

static void add_interior(GArray *ps, guint n)
{
    for (guint i = 0; i < n; i++) {
        Patch p = {P_ELLIPSOID,
                   {-1.6 + 0.5 * (i % 4), 0.9 + 0.3 * ((i / 12) % 2),
                    0.5 * ((double)((i / 4) % 3) - 1)},
                   {0.25, 0.15, 0.2},
                   {0, 0, 0},
                   0,
                   2 * G_PI,
                   -0.45 * G_PI,
                   0.45 * G_PI,
                   1.0,
                   3};
        g_array_append_val(ps, p);
    }
}

static void add_trim(GArray *ps, guint n)
{
    for (guint i = 0; i < n; i++) {
        double x = (i / 2) % 2 ? 2.14 : -2.14;
        Patch p = {P_ELLIPSOID,
                   {x, 0.8 + 0.1 * (i % 3), -0.8 + 1.6 * (i % 7) / 6.0},
                   {0.04, 0.08, 0.1},
                   {0, 0, 0},
                   0,
                   2 * G_PI,
                   -0.45 * G_PI,
                   0.45 * G_PI,
                   0.4,
                   4};
        if (i % 2) {
            p = (Patch){P_TUBE,
                        {x + (x > 0 ? 0.03 : -0.03), 0.55 + 0.05 * (i % 8), 0},
                        {0, 0, 1.8},
                        {0.03, 0, 0},
                        0,
                        2 * G_PI,
                        0,
                        0,
                        0.4,
                        4};
        }
        g_array_append_val(ps, p);
    }
}

static GArray *part_list(guint leaves)
{
    guint nw = (leaves * 20 / 100) / 4 * 4, nb = leaves * 35 / 100;
    guint nc = leaves * 25 / 100, ni = leaves * 10 / 100;
    guint nt = leaves - nw - nb - nc - ni;
    GArray *ps = g_array_new(FALSE, FALSE, sizeof(Patch));
    add_body(ps, nb);
    add_chassis(ps, nc);
    add_wheels(ps, nw);
    add_interior(ps, ni);
    add_trim(ps, nt);
    g_assert(ps->len == leaves);
    return ps;
}

/* ---- budgets and tessellation ---------------------------------------- */

typedef struct {
    double frac;
    guint i;
} Rem;

static int rem_cmp(const void *a, const void *b)
{
    const Rem *x = a, *y = b;
    if (x->frac != y->frac)
        return x->frac < y->frac ? 1 : -1;
    return x->i < y->i ? -1 : (x->i > y->i);
}

/* Largest remainder: 2 each plus shares of the rest by weight. */
static uint64_t *budgets(const GArray *ps, uint64_t total)
{
    guint n = ps->len;
    uint64_t *b = g_new(uint64_t, n), rest = total - 2 * (uint64_t)n;
    uint64_t given = 0;
    double w = 0;
    Rem *r = g_new(Rem, n);
    for (guint i = 0; i < n; i++)
        w += g_array_index(ps, Patch, i).weight;
    for (guint i = 0; i < n; i++) {
        double q = rest * g_array_index(ps, Patch, i).weight / w;
        b[i] = (uint64_t)floor(q);
        given += b[i];
        r[i] = (Rem){q - floor(q), i};
    }
    qsort(r, n, sizeof *r, rem_cmp);
    for (guint k = 0; given < rest; k = (k + 1) % n, given++)
        b[r[k].i]++;
    for (guint i = 0; i < n; i++)
        b[i] += 2;
    g_free(r);
    return b;
}

static gboolean add_tri(SceneDb *db, guint sid, Vec3 a, Vec3 b, Vec3 c)
{
    Vec3 v[3] = {a, b, c};
    SceneElem e = scene_elem_prim(SCENE_EL_TRIANGLE, v, 3);
    return scene_db_append(db, sid, &e, NULL);
}

/* Length of the patch along u (along_u) or v, measured on its middle
 * line as a polyline of 8 segments. */
static double param_length(const Patch *p, gboolean along_u)
{
    double len = 0;
    Vec3 prev = along_u ? patch_eval(p, 0, 0.5) : patch_eval(p, 0.5, 0);
    for (guint s = 1; s <= 8; s++) {
        double t = s / 8.0;
        Vec3 q = along_u ? patch_eval(p, t, 0.5) : patch_eval(p, 0.5, t);
        len += vec3_len(vec3_sub(q, prev));
        prev = q;
    }
    return len;
}

typedef struct {
    SceneDb *db;
    guint sid;
    const Patch *p;
    guint cols, rows; /* quads along u, along v */
    uint64_t k, made; /* the budget, triangles written */
} Tess;

/* Quad (i, j) as two triangles, the second left out at the budget. */
static void quad(Tess *t, guint i, guint j)
{
    double u0 = (double)i / t->cols, u1 = (double)(i + 1) / t->cols;
    double v0 = (double)j / t->rows, v1 = (double)(j + 1) / t->rows;
    Vec3 a = patch_eval(t->p, u0, v0), b = patch_eval(t->p, u1, v0);
    Vec3 c = patch_eval(t->p, u1, v1), d = patch_eval(t->p, u0, v1);
    add_tri(t->db, t->sid, a, b, c);
    if (++t->made < t->k) {
        add_tri(t->db, t->sid, a, c, d);
        t->made++;
    }
}

/* Exactly k triangles of patch p as a modelling tool writes them: a grid
 * of nearly square quads (the counts along u and v in the ratio of the
 * patch's lengths), written strip after strip, each strip running the
 * whole of the patch's longer side. */
static void tessellate(SceneDb *db, guint sid, const Patch *p, uint64_t k)
{
    double lu = param_length(p, TRUE), lv = param_length(p, FALSE);
    double aspect = lu / lv; /* every patch has extent along u and v */
    double c = ceil(sqrt(k / 2.0 * aspect));
    Tess t = {db, sid, p, (guint)CLAMP(c, 1, (double)k), 0, k, 0};
    t.rows = (guint)((k + 2 * t.cols - 1) / (2 * t.cols));
    gboolean along_u = lu >= lv;
    guint strips = along_u ? t.rows : t.cols, len = along_u ? t.cols : t.rows;
    for (guint s = 0; s < strips && t.made < k; s++)
        for (guint q = 0; q < len && t.made < k; q++)
            quad(&t, along_u ? q : s, along_u ? s : q);
    g_assert(t.made == k);
}

static void append_exec(SceneDb *db, guint parent, guint child)
{
    SceneElem e = scene_elem_execute(child);
    gboolean ok = scene_db_append(db, parent, &e, NULL);
    g_assert(ok); /* a fresh tree cannot close a cycle */
}

/* The vehicle's structures, their names suffixed with `suffix` (one
 * tree of several: "" for the first). */
static gboolean build_tree(SceneDb *db, guint structures, uint64_t triangles,
                           const char *what, const char *suffix, guint *root,
                           GError **err)
{
    if (structures < 10 || triangles < 2 * (uint64_t)(structures - 6) ||
        triangles > (1u << 28)) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "%s: found %u structures and %" G_GUINT64_FORMAT
                    " triangles, expected >= 10 structures and 2 to 2^28 "
                    "triangles per part structure",
                    what, structures, triangles);
        return FALSE;
    }
    GArray *ps = part_list(structures - 1 - SCENE_VEHICLE_GROUPS);
    uint64_t *b = budgets(ps, triangles);
    char *rname = g_strconcat("vehicle", suffix, NULL);
    *root = scene_db_add_struct(db, rname);
    g_free(rname);
    guint groups[SCENE_VEHICLE_GROUPS];
    for (guint g = 0; g < SCENE_VEHICLE_GROUPS; g++) {
        char *gname = g_strconcat(group_names[g], suffix, NULL);
        groups[g] = scene_db_add_struct(db, gname);
        g_free(gname);
        SceneElem c = scene_elem_color(group_rgb[g]);
        scene_db_append(db, groups[g], &c, NULL);
        append_exec(db, *root, groups[g]);
    }
    for (guint i = 0; i < ps->len; i++) {
        const Patch *p = &g_array_index(ps, Patch, i);
        char *name =
            g_strdup_printf("%s.%u%s", group_names[p->group], i, suffix);
        guint sid = scene_db_add_struct(db, name);
        g_free(name);
        tessellate(db, sid, p, b[i]);
        append_exec(db, groups[p->group], sid);
    }
    g_free(b);
    g_array_free(ps, TRUE);
    return TRUE;
}

gboolean scene_vehicle_build(SceneDb *db, guint structures, uint64_t triangles,
                             const char *what, guint *root, GError **err)
{
    return build_tree(db, structures, triangles, what, "", root, err);
}

/* ---- the scene ------------------------------------------------------- */

static void collect(const ScenePrimInst *pi, void *ud)
{
    SceneMesh *m = ud;
    uint32_t v[3];
    for (guint k = 0; k < 3; k++) {
        Vec4 h = mat4_apply_point(pi->matrix, pi->el->verts[k]);
        v[k] = scene_mesh_add_vertex(m, vec3(h.x, h.y, h.z));
    }
    SceneColor c = {(float)pi->color.x, (float)pi->color.y, (float)pi->color.z};
    scene_mesh_add_poly(m, v, 3, c, pi->sid);
}

static Mat4 copy_xform(const SceneVehicleParams *p, guint k)
{
    double a = 2 * G_PI * k / p->instances;
    Mat4 rot = mat4_rotate(vec3(0, 1, 0), -(a + G_PI / 2));
    return mat4_mul(
        mat4_translate(p->circle_radius * cos(a), 0, p->circle_radius * sin(a)),
        rot);
}

/* Copies per vehicle tree: `instancing`, 0 meaning all of them. */
static guint per_tree(const SceneVehicleParams *p)
{
    return p->instancing ? MIN(p->instancing, p->instances) : p->instances;
}

/* The world: copy k executes tree k / per_tree() (tree 0 is `root`, the
 * others are built again, named "vehicle#t", "body#t" ...). */
static void add_world(SceneDb *db, const SceneVehicleParams *p, guint root)
{
    guint w = scene_db_add_struct(db, "world"), tree = root, per = per_tree(p);
    for (guint k = 0; k < p->instances; k++) {
        if (k && k % per == 0) {
            char *suffix = g_strdup_printf("#%u", k / per);
            gboolean ok = build_tree(db, p->structures, p->triangles, "",
                                     suffix, &tree, NULL);
            g_assert(ok); /* the first tree was built from the same */
            g_free(suffix);
        }
        SceneElem m = scene_elem_matrix(copy_xform(p, k), SCENE_MAT_REPLACE);
        scene_db_append(db, w, &m, NULL);
        append_exec(db, w, tree);
    }
    scene_db_post(db, w);
}

static void set_camera(Scene *s, const SceneVehicleParams *p)
{
    SceneCamera c = scene_camera_default();
    c.eye = vec3(p->camera_radius, p->camera_height, 0);
    c.target = vec3(0, 0, 0);
    c.fov_deg = p->fov_deg;
    double far = p->camera_radius + p->circle_radius + 5;
    c.near = far * 1e-3;
    c.far = far;
    s->camera = c;
    scene_set_path(s, scene_path_new_orbit(&c, vec3(0, 0, 0), vec3(0, 1, 0), 0,
                                           p->degrees_per_frame, p->frames));
}

Scene *scene_vehicle_new(const SceneVehicleParams *p, const char *what,
                         GError **err)
{
    g_assert(p->instances >= 1);
    char *size = g_strdup_printf("%u instances x %" G_GUINT64_FORMAT
                                 " triangles",
                                 p->instances, (guint64)p->triangles);
    gboolean fits = sim_mem_check((double)p->instances * (double)p->triangles *
                                      SCENE_POLY_BYTES,
                                  what, size, err);
    g_free(size);
    if (!fits)
        return NULL;
    SceneDb *db = scene_db_new();
    guint root;
    if (!scene_vehicle_build(db, p->structures, p->triangles, what, &root,
                             err)) {
        scene_db_free(db);
        return NULL;
    }
    SceneMesh *m = scene_mesh_new();
    int64_t prio = 0;
    scene_db_traverse_from(db, root, mat4_identity(), vec3(1, 1, 1), &prio,
                           collect, m);
    Scene *s = scene_new("vehicle");
    guint id = scene_add_mesh(s, m);
    for (guint k = 0; k < p->instances; k++)
        scene_add_instance(s, id, copy_xform(p, k), scene_color(1, 1, 1), k);
    add_world(db, p, root);
    scene_set_db(s, db);
    set_camera(s, p);
    return s;
}
