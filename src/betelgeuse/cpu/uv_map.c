/* Texture coordinates of a prototype point and dP/du (docs/shading.md section 4). */
#include "cpu_internal.h"

#define TWO_PI 6.283185307179586476925286766559

/* Longitude u in [0, 1]: 0.5 faces +z, increasing towards +x; the seam is the -z half-plane. */
static double longitude_u(double x, double z)
{
    if (x == 0.0 && z == 0.0)
        return 0.5; /* on the axis: atan2(0, 0) is guarded explicitly for GLSL's sake */
    return 0.5 + atan2(x, z) / TWO_PI;
}

static void spherical(const double p[3], double uv[2], double dpdu[3])
{
    double len = sqrt(bg_v3_dot(p, p));
    uv[0] = longitude_u(p[0], p[2]);
    if (len > 0.0) {
        double s = p[1] / len;
        s = s < -1.0 ? -1.0 : (s > 1.0 ? 1.0 : s);
        uv[1] = 0.5 + asin(s) / 3.14159265358979323846264338327950288;
    } else {
        uv[1] = 0.5;
    }
    bg_v3_set(dpdu, p[2], 0.0, -p[0]);
}

static void planar(const double p[3], double uv[2], double dpdu[3])
{
    uv[0] = 0.5 * (p[0] + 1.0);
    uv[1] = 0.5 * (1.0 - p[2]);
    bg_v3_set(dpdu, 1.0, 0.0, 0.0);
}

/* The face of the dominant axis (ties go to x, then y), each showing the whole texture upright
 * when seen from outside. */
static void box(const double p[3], double uv[2], double dpdu[3])
{
    double ax = fabs(p[0]), ay = fabs(p[1]), az = fabs(p[2]);
    double x = p[0], y = p[1], z = p[2];
    if (ax >= ay && ax >= az) {
        if (x >= 0.0) {
            uv[0] = 0.5 * (1.0 - z);
            bg_v3_set(dpdu, 0.0, 0.0, -1.0);
        } else {
            uv[0] = 0.5 * (1.0 + z);
            bg_v3_set(dpdu, 0.0, 0.0, 1.0);
        }
        uv[1] = 0.5 * (1.0 + y);
    } else if (ay >= az) {
        uv[0] = 0.5 * (1.0 + x);
        uv[1] = y >= 0.0 ? 0.5 * (1.0 - z) : 0.5 * (1.0 + z);
        bg_v3_set(dpdu, 1.0, 0.0, 0.0);
    } else {
        if (z >= 0.0) {
            uv[0] = 0.5 * (1.0 + x);
            bg_v3_set(dpdu, 1.0, 0.0, 0.0);
        } else {
            uv[0] = 0.5 * (1.0 - x);
            bg_v3_set(dpdu, -1.0, 0.0, 0.0);
        }
        uv[1] = 0.5 * (1.0 + y);
    }
}

static void cylindrical(const double p[3], double uv[2], double dpdu[3])
{
    double radial = sqrt(p[0] * p[0] + p[2] * p[2]);
    if (fabs(p[1]) > radial) {
        /* a cap: planar like the box's +y / -y faces */
        uv[0] = 0.5 * (1.0 + p[0]);
        uv[1] = p[1] >= 0.0 ? 0.5 * (1.0 - p[2]) : 0.5 * (1.0 + p[2]);
        bg_v3_set(dpdu, 1.0, 0.0, 0.0);
        return;
    }
    uv[0] = longitude_u(p[0], p[2]);
    uv[1] = 0.5 * (1.0 + p[1]);
    bg_v3_set(dpdu, p[2], 0.0, -p[0]);
}

void bgi_cpu_uv_map(bg_uv_mapping mapping, const double p[3], double uv[2], double dpdu[3])
{
    switch (mapping) {
    case BG_UV_PLANAR: planar(p, uv, dpdu); break;
    case BG_UV_BOX: box(p, uv, dpdu); break;
    case BG_UV_CYLINDRICAL: cylindrical(p, uv, dpdu); break;
    case BG_UV_SPHERICAL:
    default: spherical(p, uv, dpdu); break;
    }
}
