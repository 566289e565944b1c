/* vec.h — small vector and 4x4 matrix math (doubles), all inline.
 *
 * Matrices are row-major, applied to column vectors: p' = M p, so
 * mat4_mul(A, B) applies B first.  Pure functions, O(1) each.
 */
#ifndef PGSIM_SCENE_VEC_H
#define PGSIM_SCENE_VEC_H

#include <math.h>

typedef struct {
    double x, y, z;
} Vec3;
typedef struct {
    double x, y, z, w;
} Vec4;
typedef struct {
    double m[4][4];
} Mat4;

static inline Vec3 vec3(double x, double y, double z)
{
    return (Vec3){x, y, z};
}
static inline Vec3 vec3_add(Vec3 a, Vec3 b)
{
    return vec3(a.x + b.x, a.y + b.y, a.z + b.z);
}
static inline Vec3 vec3_sub(Vec3 a, Vec3 b)
{
    return vec3(a.x - b.x, a.y - b.y, a.z - b.z);
}
static inline Vec3 vec3_scale(Vec3 a, double s)
{
    return vec3(a.x * s, a.y * s, a.z * s);
}
static inline double vec3_dot(Vec3 a, Vec3 b)
{
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
static inline Vec3 vec3_cross(Vec3 a, Vec3 b)
{
    return vec3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z,
                a.x * b.y - a.y * b.x);
}
static inline double vec3_len(Vec3 a)
{
    return sqrt(vec3_dot(a, a));
}
static inline Vec3 vec3_norm(Vec3 a)
{
    double l = vec3_len(a);
    return l > 0 ? vec3_scale(a, 1.0 / l) : a;
}

static inline Mat4 mat4_identity(void)
{
    Mat4 r = {{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}};
    return r;
}
static inline Mat4 mat4_mul(Mat4 a, Mat4 b)
{
    Mat4 r;
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            r.m[i][j] = a.m[i][0] * b.m[0][j] + a.m[i][1] * b.m[1][j] +
                        a.m[i][2] * b.m[2][j] + a.m[i][3] * b.m[3][j];
    return r;
}
static inline Vec4 mat4_apply(Mat4 a, Vec4 v)
{
    Vec4 r;
    r.x = a.m[0][0] * v.x + a.m[0][1] * v.y + a.m[0][2] * v.z + a.m[0][3] * v.w;
    r.y = a.m[1][0] * v.x + a.m[1][1] * v.y + a.m[1][2] * v.z + a.m[1][3] * v.w;
    r.z = a.m[2][0] * v.x + a.m[2][1] * v.y + a.m[2][2] * v.z + a.m[2][3] * v.w;
    r.w = a.m[3][0] * v.x + a.m[3][1] * v.y + a.m[3][2] * v.z + a.m[3][3] * v.w;
    return r;
}
static inline Vec4 mat4_apply_point(Mat4 a, Vec3 p)
{
    return mat4_apply(a, (Vec4){p.x, p.y, p.z, 1.0});
}
static inline Mat4 mat4_translate(double x, double y, double z)
{
    Mat4 r = mat4_identity();
    r.m[0][3] = x;
    r.m[1][3] = y;
    r.m[2][3] = z;
    return r;
}
static inline Mat4 mat4_scale(double x, double y, double z)
{
    Mat4 r = mat4_identity();
    r.m[0][0] = x;
    r.m[1][1] = y;
    r.m[2][2] = z;
    return r;
}
/* Rotation by `rad` radians about a unit axis (right-handed). */
static inline Mat4 mat4_rotate(Vec3 axis, double rad)
{
    Vec3 u = vec3_norm(axis);
    double c = cos(rad), s = sin(rad), t = 1 - c;
    Mat4 r = mat4_identity();
    r.m[0][0] = t * u.x * u.x + c;
    r.m[0][1] = t * u.x * u.y - s * u.z;
    r.m[0][2] = t * u.x * u.z + s * u.y;
    r.m[1][0] = t * u.x * u.y + s * u.z;
    r.m[1][1] = t * u.y * u.y + c;
    r.m[1][2] = t * u.y * u.z - s * u.x;
    r.m[2][0] = t * u.x * u.z - s * u.y;
    r.m[2][1] = t * u.y * u.z + s * u.x;
    r.m[2][2] = t * u.z * u.z + c;
    return r;
}

/* The normal matrix of `a`: the cofactor matrix of its upper 3x3, i.e.
 * det(A) times the inverse transpose, in a 4x4 with no translation.
 * Normals must be transformed by it (and renormalised), not by A: under
 * a non-uniform scale A moves a normal off its surface.  Using the
 * cofactors rather than the inverse keeps singular matrices defined and
 * gives exactly the normal of the transformed winding: (A u) x (A v) =
 * cof(A) (u x v), so a mirror flips normals along with windings. */
static inline Mat4 mat4_normal_matrix(Mat4 a)
{
    Mat4 r = mat4_identity();
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
            int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
            r.m[i][j] = a.m[i1][j1] * a.m[i2][j2] - a.m[i1][j2] * a.m[i2][j1];
        }
    return r;
}

#endif
