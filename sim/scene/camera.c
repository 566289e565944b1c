/* camera.c — perspective and orthographic cameras, and camera paths.
 *
 * Implements camera.h.  Matrices follow gluLookAt, glFrustum and glOrtho
 * (OpenGL 1.x reference manual) so clip space is the usual -w..w cube.
 * Orbit paths rotate with Rodrigues' formula (vec.h mat4_rotate).
 * Catmull-Rom keyframes use uniform parameterisation with the end keys
 * duplicated (Catmull & Rom, "A class of local interpolating splines",
 * 1974).  Paths are immutable once built except for appending keys.
 */
#include "sim/scene/camera.h"

struct SceneCameraPath {
    ScenePathKind kind;
    SceneInterp interp;
    SceneCamera base;  /* fixed / orbit */
    Vec3 center, axis; /* orbit */
    double deg0, deg_per_frame;
    GArray *key_frame; /* double, increasing */
    GArray *key_cam;   /* SceneCamera */
    guint frames;
};

SceneCamera scene_camera_default(void)
{
    SceneCamera c = {SCENE_PERSPECTIVE,
                     {0, 0, 5},
                     {0, 0, 0},
                     {0, 1, 0},
                     45.0,
                     2.0,
                     0.1,
                     100.0,
                     1.0};
    return c;
}

Mat4 scene_camera_view(const SceneCamera *c)
{
    Vec3 f = vec3_norm(vec3_sub(c->target, c->eye));
    Vec3 s = vec3_norm(vec3_cross(f, c->up));
    Vec3 u = vec3_cross(s, f);
    Mat4 r = mat4_identity();
    Vec3 rows[3] = {s, u, vec3_scale(f, -1)};
    for (int i = 0; i < 3; i++) {
        r.m[i][0] = rows[i].x;
        r.m[i][1] = rows[i].y;
        r.m[i][2] = rows[i].z;
        r.m[i][3] = -vec3_dot(rows[i], c->eye);
    }
    return r;
}

static Mat4 perspective(const SceneCamera *c)
{
    double f = 1.0 / tan(c->fov_deg * G_PI / 360.0);
    double n = c->near, fa = c->far;
    Mat4 r = {{{0}}};
    r.m[0][0] = f / c->aspect;
    r.m[1][1] = f;
    r.m[2][2] = (fa + n) / (n - fa);
    r.m[2][3] = 2 * fa * n / (n - fa);
    r.m[3][2] = -1;
    return r;
}

static Mat4 orthographic(const SceneCamera *c)
{
    double t = c->height / 2, rgt = t * c->aspect;
    double n = c->near, fa = c->far;
    Mat4 r = mat4_identity();
    r.m[0][0] = 1 / rgt;
    r.m[1][1] = 1 / t;
    r.m[2][2] = -2 / (fa - n);
    r.m[2][3] = -(fa + n) / (fa - n);
    return r;
}

Mat4 scene_camera_projection(const SceneCamera *c)
{
    g_assert(c->near > 0 && c->far > c->near && c->aspect > 0);
    return c->proj == SCENE_PERSPECTIVE ? perspective(c) : orthographic(c);
}

Mat4 scene_camera_view_proj(const SceneCamera *c)
{
    return mat4_mul(scene_camera_projection(c), scene_camera_view(c));
}

static void fit_near_far(SceneCamera *c, double dist, double r)
{
    c->far = dist + r * 1.01;
    c->near = fmax(dist - r * 1.01, c->far * 1e-3);
}

void scene_camera_fit(SceneCamera *c, SceneBox box, double fill)
{
    g_assert(fill > 0 && fill <= SCENE_FILL_MAX);
    Vec3 ctr = scene_box_center(box);
    double r = fmax(scene_box_radius(box), 1e-9);
    Vec3 dir = vec3_norm(vec3_sub(c->eye, c->target));
    if (vec3_len(dir) == 0)
        dir = vec3(0, 0, 1);
    if (c->proj == SCENE_PERSPECTIVE) {
        double half = c->fov_deg * G_PI / 360.0;
        double hx = atan(tan(half) * c->aspect);
        double d = r / (fill * sin(fmin(half, hx)));
        c->target = ctr;
        c->eye = vec3_add(ctr, vec3_scale(dir, d));
        fit_near_far(c, d, r);
    } else {
        double h = 2 * r / fill;
        c->height = c->aspect < 1 ? h / c->aspect : h;
        c->target = ctr;
        c->eye = vec3_add(ctr, vec3_scale(dir, 2 * r));
        fit_near_far(c, 2 * r, r);
    }
}

typedef struct {
    Vec3 dir, right, up; /* towards the eye; screen right and up */
    double tx, ty;       /* tan of the half-angles, times fill */
} FitFrame;

/* Eye distance from ctr so every point projects inside the frame;
 * *mx, *my receive the centre of the points' projected extent (in units
 * of the half-screen) and *r the largest distance from ctr. */
static double fit_distance(const FitFrame *f, const Vec3 *pts, guint n,
                           Vec3 ctr, double *mx, double *my, double *r)
{
    double d = 1e-9, lo[2] = {G_MAXDOUBLE, G_MAXDOUBLE};
    double hi[2] = {-G_MAXDOUBLE, -G_MAXDOUBLE};
    *r = 1e-9;
    for (guint i = 0; i < n; i++) {
        Vec3 q = vec3_sub(pts[i], ctr);
        double x = vec3_dot(q, f->right), y = vec3_dot(q, f->up);
        double z = vec3_dot(q, f->dir);
        /* depth from the eye is d - z; need |x| <= tx (d - z) */
        d = fmax(d, fmax(fabs(x) / f->tx, fabs(y) / f->ty) + z);
        *r = fmax(*r, vec3_len(q));
    }
    for (guint i = 0; i < n; i++) {
        Vec3 q = vec3_sub(pts[i], ctr);
        double w = d - vec3_dot(q, f->dir);
        double x = vec3_dot(q, f->right) / (f->tx * w);
        double y = vec3_dot(q, f->up) / (f->ty * w);
        lo[0] = fmin(lo[0], x), hi[0] = fmax(hi[0], x);
        lo[1] = fmin(lo[1], y), hi[1] = fmax(hi[1], y);
    }
    *mx = (lo[0] + hi[0]) / 2;
    *my = (lo[1] + hi[1]) / 2;
    return d;
}

static void fit_ortho(SceneCamera *c, const FitFrame *f, const Vec3 *pts,
                      guint n, Vec3 ctr, double fill)
{
    double h = 1e-9, r = 1e-9;
    for (guint i = 0; i < n; i++) {
        Vec3 q = vec3_sub(pts[i], ctr);
        h = fmax(h, fmax(fabs(vec3_dot(q, f->up)),
                         fabs(vec3_dot(q, f->right)) / c->aspect));
        r = fmax(r, vec3_len(q));
    }
    c->height = 2 * h / fill;
    c->target = ctr;
    c->eye = vec3_add(ctr, vec3_scale(f->dir, 2 * r));
    fit_near_far(c, 2 * r, r);
}

void scene_camera_fit_points(SceneCamera *c, const Vec3 *pts, guint n,
                             double fill)
{
    g_assert(fill > 0 && fill <= SCENE_FILL_MAX && n > 0);
    SceneBox b = scene_box_empty();
    for (guint i = 0; i < n; i++)
        b = scene_box_add_point(b, pts[i]);
    FitFrame f;
    f.dir = vec3_norm(vec3_sub(c->eye, c->target));
    if (vec3_len(f.dir) == 0)
        f.dir = vec3(0, 0, 1);
    f.right = vec3_norm(vec3_cross(vec3_scale(f.dir, -1), c->up));
    f.up = vec3_cross(f.right, vec3_scale(f.dir, -1));
    f.ty = tan(c->fov_deg * G_PI / 360.0) * fill;
    f.tx = f.ty * c->aspect;
    Vec3 ctr = scene_box_center(b);
    if (c->proj == SCENE_ORTHOGRAPHIC) {
        fit_ortho(c, &f, pts, n, ctr, fill);
        return;
    }
    /* Re-centre the projected extent a few times: each step moves the
     * target sideways by the offset of the extent's centre. */
    double d = 0, mx, my, r;
    for (int it = 0; it < 8; it++) {
        d = fit_distance(&f, pts, n, ctr, &mx, &my, &r);
        ctr = vec3_add(ctr, vec3_add(vec3_scale(f.right, mx * f.tx * d),
                                     vec3_scale(f.up, my * f.ty * d)));
    }
    d = fit_distance(&f, pts, n, ctr, &mx, &my, &r);
    c->target = ctr;
    c->eye = vec3_add(ctr, vec3_scale(f.dir, d));
    fit_near_far(c, d, r);
}

void scene_camera_fit_box(SceneCamera *c, SceneBox b, double fill)
{
    Vec3 k[8];
    for (int i = 0; i < 8; i++)
        k[i] = vec3(i & 1 ? b.max.x : b.min.x, i & 2 ? b.max.y : b.min.y,
                    i & 4 ? b.max.z : b.min.z);
    scene_camera_fit_points(c, k, 8, fill);
}

static SceneCameraPath *path_new(ScenePathKind kind, guint frames)
{
    SceneCameraPath *p = g_new0(SceneCameraPath, 1);
    p->kind = kind;
    p->frames = frames ? frames : 1;
    p->key_frame = g_array_new(FALSE, FALSE, sizeof(double));
    p->key_cam = g_array_new(FALSE, FALSE, sizeof(SceneCamera));
    return p;
}

SceneCameraPath *scene_path_new_fixed(const SceneCamera *c, guint frames)
{
    SceneCameraPath *p = path_new(SCENE_PATH_FIXED, frames);
    p->base = *c;
    return p;
}

SceneCameraPath *scene_path_new_orbit(const SceneCamera *base, Vec3 center,
                                      Vec3 axis, double deg0,
                                      double deg_per_frame, guint frames)
{
    g_assert(vec3_len(axis) > 0);
    SceneCameraPath *p = path_new(SCENE_PATH_ORBIT, frames);
    p->base = *base;
    p->center = center;
    p->axis = vec3_norm(axis);
    p->deg0 = deg0;
    p->deg_per_frame = deg_per_frame;
    return p;
}

SceneCameraPath *scene_path_new_keyframes(SceneInterp interp)
{
    SceneCameraPath *p = path_new(SCENE_PATH_KEYFRAMES, 1);
    p->interp = interp;
    return p;
}

void scene_path_add_key(SceneCameraPath *p, double frame, const SceneCamera *c)
{
    g_assert(p->kind == SCENE_PATH_KEYFRAMES);
    guint n = p->key_frame->len;
    g_assert(n == 0 || frame > g_array_index(p->key_frame, double, n - 1));
    g_array_append_val(p->key_frame, frame);
    g_array_append_val(p->key_cam, *c);
    guint need = frame < 0 ? 1 : (guint)ceil(frame) + 1;
    if (need > p->frames)
        p->frames = need;
}

void scene_path_free(SceneCameraPath *p)
{
    if (!p)
        return;
    g_array_free(p->key_frame, TRUE);
    g_array_free(p->key_cam, TRUE);
    g_free(p);
}

ScenePathKind scene_path_kind(const SceneCameraPath *p)
{
    return p->kind;
}

guint scene_path_n_frames(const SceneCameraPath *p)
{
    return p->frames;
}

void scene_path_set_n_frames(SceneCameraPath *p, guint frames)
{
    p->frames = frames ? frames : 1;
}

guint scene_path_n_keys(const SceneCameraPath *p)
{
    return p->key_frame->len;
}

static Vec3 rotate_about(Vec3 p, Vec3 center, Mat4 rot)
{
    Vec4 h = mat4_apply_point(rot, vec3_sub(p, center));
    return vec3_add(center, vec3(h.x, h.y, h.z));
}

static SceneCamera orbit_camera(const SceneCameraPath *p, double frame)
{
    double deg = p->deg0 + frame * p->deg_per_frame;
    Mat4 rot = mat4_rotate(p->axis, deg * G_PI / 180.0);
    SceneCamera c = p->base;
    c.eye = rotate_about(p->base.eye, p->center, rot);
    c.target = rotate_about(p->base.target, p->center, rot);
    Vec4 u = mat4_apply(rot, (Vec4){c.up.x, c.up.y, c.up.z, 0});
    c.up = vec3(u.x, u.y, u.z);
    return c;
}

static double lerp(double a, double b, double t)
{
    return a + (b - a) * t;
}

static Vec3 vlerp(Vec3 a, Vec3 b, double t)
{
    return vec3(lerp(a.x, b.x, t), lerp(a.y, b.y, t), lerp(a.z, b.z, t));
}

/* Uniform Catmull-Rom between p1 and p2. */
static Vec3 catmull(Vec3 p0, Vec3 p1, Vec3 p2, Vec3 p3, double t)
{
    double t2 = t * t, t3 = t2 * t;
    double a = -0.5 * t3 + t2 - 0.5 * t, b = 1.5 * t3 - 2.5 * t2 + 1;
    double c = -1.5 * t3 + 2 * t2 + 0.5 * t, d = 0.5 * t3 - 0.5 * t2;
    return vec3_add(vec3_add(vec3_scale(p0, a), vec3_scale(p1, b)),
                    vec3_add(vec3_scale(p2, c), vec3_scale(p3, d)));
}

/* Index i of the key segment [i, i+1] holding frame (binary search). */
static guint find_segment(const GArray *kf, double frame)
{
    guint lo = 0, hi = kf->len - 1;
    while (hi - lo > 1) {
        guint mid = (lo + hi) / 2;
        if (g_array_index(kf, double, mid) <= frame)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

static const SceneCamera *key(const SceneCameraPath *p, int i)
{
    int n = (int)p->key_cam->len;
    i = i < 0 ? 0 : (i >= n ? n - 1 : i);
    return &g_array_index(p->key_cam, SceneCamera, i);
}

static SceneCamera key_camera(const SceneCameraPath *p, double frame)
{
    guint n = p->key_frame->len;
    g_assert(n > 0);
    const GArray *kf = p->key_frame;
    if (n == 1 || frame <= g_array_index(kf, double, 0))
        return *key(p, 0);
    if (frame >= g_array_index(kf, double, n - 1))
        return *key(p, (int)n - 1);
    int i = (int)find_segment(kf, frame);
    double f0 = g_array_index(kf, double, i);
    double f1 = g_array_index(kf, double, i + 1);
    double t = (frame - f0) / (f1 - f0);
    const SceneCamera *a = key(p, i), *b = key(p, i + 1);
    SceneCamera c = *a;
    if (p->interp == SCENE_INTERP_CATMULL_ROM) {
        const SceneCamera *a0 = key(p, i - 1), *b1 = key(p, i + 2);
        c.eye = catmull(a0->eye, a->eye, b->eye, b1->eye, t);
        c.target = catmull(a0->target, a->target, b->target, b1->target, t);
    } else {
        c.eye = vlerp(a->eye, b->eye, t);
        c.target = vlerp(a->target, b->target, t);
    }
    c.up = vlerp(a->up, b->up, t);
    c.fov_deg = lerp(a->fov_deg, b->fov_deg, t);
    c.height = lerp(a->height, b->height, t);
    c.near = lerp(a->near, b->near, t);
    c.far = lerp(a->far, b->far, t);
    c.aspect = lerp(a->aspect, b->aspect, t);
    return c;
}

void scene_path_set_base(SceneCameraPath *p, const SceneCamera *c)
{
    g_assert(p->kind != SCENE_PATH_KEYFRAMES);
    p->base = *c;
    if (p->kind != SCENE_PATH_ORBIT)
        return;
    Mat4 back = mat4_rotate(p->axis, -p->deg0 * G_PI / 180.0);
    p->base.eye = rotate_about(c->eye, p->center, back);
    p->base.target = rotate_about(c->target, p->center, back);
    Vec4 u = mat4_apply(back, (Vec4){c->up.x, c->up.y, c->up.z, 0});
    p->base.up = vec3(u.x, u.y, u.z);
}

SceneCamera scene_path_camera(const SceneCameraPath *p, double frame)
{
    switch (p->kind) {
    case SCENE_PATH_ORBIT:
        return orbit_camera(p, frame);
    case SCENE_PATH_KEYFRAMES:
        return key_camera(p, frame);
    default:
        return p->base;
    }
}
