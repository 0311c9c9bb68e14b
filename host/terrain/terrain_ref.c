/* terrain_ref.c — the terrain's height field and ray hits in double precision
 * (atmo/terrain_ref.h), the host reference of kernels/terrain/noise.h and terrain.h.
 *
 * The same integer hash and lattice values as the kernels (exact in both precisions), the same
 * quintic value noise, eroded fBm with the octave rotation, the domain warp of its first
 * octave's lattice point and the exact gradient (the warp's Jacobian by the chain rule), coverage
 * field and planar placement u = R x / r, v = R z / r, the detail below a DEM's cells
 * (terrain_detail.h: plain octaves i0 .. i0 + K - 1 of the same lattices) and the heightmap's
 * bilinear lookup of its float texels, all in double. A ray hit is brute force:
 * steps of at most `step` metres along the ray, each no longer than the clearance over a slope
 * of 4 allows near the surface, a sign change bracketed and bisected. */
#include <math.h>
#include <stddef.h>
#include "atmo/terrain_ref.h"
#include "terrain/noise.h"

#define ROT_C 0.8
#define ROT_S 0.6
#define COAST 0.05
#define RELIEF ((double)TERRAIN_RELIEF)

static unsigned hash(int ix, int iy, unsigned seed)
{
    unsigned h = ((unsigned)ix * 0x8da6b343u) ^ ((unsigned)iy * 0xd8163841u) ^
                 (seed * 0xcb1ab31fu + 0x9e3779b9u);
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    h *= 0x846ca68bu;
    h ^= h >> 16;
    return h;
}

static double lattice(int ix, int iy, unsigned seed)
{
    return (double)(hash(ix, iy, seed) >> 8) / 8388608.0 - 1.0;
}

/* value, gradient and Hessian (xx, yy, xy) */
static void noise(double x, double y, unsigned seed, double n[6])
{
    double x0 = floor(x), y0 = floor(y), fx = x - x0, fy = y - y0;
    int ix = (int)x0, iy = (int)y0;
    double qx = fx * fx * fx * (fx * (fx * 6 - 15) + 10), qy = fy * fy * fy * (fy * (fy * 6 - 15) + 10);
    double dqx = 30 * fx * fx * (fx - 1) * (fx - 1), dqy = 30 * fy * fy * (fy - 1) * (fy - 1);
    double ddqx = 60 * fx * (fx - 1) * (2 * fx - 1), ddqy = 60 * fy * (fy - 1) * (2 * fy - 1);
    double a = lattice(ix, iy, seed), b = lattice(ix + 1, iy, seed);
    double c = lattice(ix, iy + 1, seed), d = lattice(ix + 1, iy + 1, seed);
    double k1 = b - a, k2 = c - a, k3 = a - b - c + d;
    n[0] = a + k1 * qx + k2 * qy + k3 * qx * qy;
    n[1] = dqx * (k1 + k3 * qy);
    n[2] = dqy * (k2 + k3 * qx);
    n[3] = ddqx * (k1 + k3 * qy);
    n[4] = ddqy * (k2 + k3 * qx);
    n[5] = k3 * dqx * dqy;
}

static void next_octave(double *x, double *y, double j[4])
{
    double nx = 2 * (ROT_C * *x - ROT_S * *y), ny = 2 * (ROT_S * *x + ROT_C * *y);
    *x = nx, *y = ny;
    double n00 = 2 * (ROT_C * j[0] - ROT_S * j[2]), n01 = 2 * (ROT_C * j[1] - ROT_S * j[3]);
    double n10 = 2 * (ROT_S * j[0] + ROT_C * j[2]), n11 = 2 * (ROT_S * j[1] + ROT_C * j[3]);
    j[0] = n00, j[1] = n01, j[2] = n10, j[3] = n11;
}

/* the warped first-octave point of lattice point (x, y) and its Jacobian (noise.h's
 * terrain_fbm_point: octave o of the warp at frequency F 2^o, turned by M^(o+1), amplitude
 * A 2^-o, seeds seed + TERRAIN_WARP_SEED + 2 o and + 1) */
static void warp(const atmo_gpu_terrain_field *f, double *x, double *y, double j[4])
{
    double A = (double)f->warp, F = (double)TERRAIN_WARP_FREQUENCY;
    double x0 = *x, y0 = *y;
    double amp = A, fr = F, c = ROT_C, sn = ROT_S;
    unsigned seed = f->seed + TERRAIN_WARP_SEED;
    for (int o = 0; o < TERRAIN_WARP_OCTAVES; o++) {
        double s = fr * (c * x0 - sn * y0), t = fr * (sn * x0 + c * y0), wa[6], wb[6];
        noise(s, t, seed + 2u * o, wa);
        noise(s, t, seed + 2u * o + 1u, wb);
        *x += amp * wa[0];
        *y += amp * wb[0];
        j[0] += amp * fr * (c * wa[1] + sn * wa[2]);
        j[1] += amp * fr * (c * wa[2] - sn * wa[1]);
        j[2] += amp * fr * (c * wb[1] + sn * wb[2]);
        j[3] += amp * fr * (c * wb[2] - sn * wb[1]);
        double nc = c * ROT_C - sn * ROT_S, ns = sn * ROT_C + c * ROT_S; /* turn by M again */
        c = nc, sn = ns;
        amp *= 0.5, fr *= 2;
    }
}

static double fbm(const atmo_gpu_terrain_field *f, double x, double y, double *ex, double *ey)
{
    double a = 0, ax = 0, ay = 0, b = 1, norm = 0, dx = 0, dy = 0;
    double s[4] = {0, 0, 0, 0}, j[4] = {1, 0, 0, 1};
    int octaves = f->octaves;
    unsigned seed = f->seed;
    warp(f, &x, &y, j);
    for (int i = 0; i < octaves; i++) {
        double n[6];
        noise(x, y, seed + (unsigned)i, n);
        dx += n[1];
        dy += n[2];
        s[0] += j[0] * n[3] + j[2] * n[5];
        s[1] += j[0] * n[5] + j[2] * n[4];
        s[2] += j[1] * n[3] + j[3] * n[5];
        s[3] += j[1] * n[5] + j[3] * n[4];
        double den = 1 + dx * dx + dy * dy;
        double gx = j[0] * n[1] + j[2] * n[2], gy = j[1] * n[1] + j[3] * n[2];
        double hx = s[0] * dx + s[1] * dy, hy = s[2] * dx + s[3] * dy;
        a += b * n[0] / den;
        ax += b * (gx * den - 2 * n[0] * hx) / (den * den);
        ay += b * (gy * den - 2 * n[0] * hy) / (den * den);
        norm += b;
        b *= 0.5;
        next_octave(&x, &y, j);
    }
    double k = RELIEF / norm, th = tanh(2 * k * a), slope = k * (1 - th * th);
    *ex = ax * slope;
    *ey = ay * slope;
    return 0.5 + 0.5 * th;
}

static double coverage(const atmo_gpu_terrain_field *f, double u, double v, double *cu, double *cv)
{
    double fr = (double)f->coverage_frequency_per_m, x = u * fr, y = v * fr;
    double c = 0, cx = 0, cy = 0, b = 1, norm = 0, j[4] = {1, 0, 0, 1};
    unsigned seed = f->seed + 0x51ed27u;
    for (int i = 0; i < f->coverage_octaves; i++) {
        double n[6];
        noise(x, y, seed + (unsigned)i, n);
        c += b * n[0];
        cx += b * (j[0] * n[1] + j[2] * n[2]);
        cy += b * (j[1] * n[1] + j[3] * n[2]);
        norm += b;
        b *= 0.5;
        next_octave(&x, &y, j);
    }
    double c0 = 0.5 * c / norm + 0.5, t = 1.0 - (double)f->land_fraction;
    double s = (c0 - (t - COAST)) / (2 * COAST);
    s = s < 0 ? 0 : s > 1 ? 1 : s;
    double ds = s > 0 && s < 1 ? 6 * s * (1 - s) / (2 * COAST) : 0;
    double k = ds * 0.5 / norm * fr;
    *cu = cx * k;
    *cv = cy * k;
    return s * s * (3 - 2 * s);
}

double terrain_ref_height(const atmo_gpu_terrain_field *f, double u, double v, double grad[2],
                          double *cov)
{
    double cu, cv, ex = 0, ey = 0, e = 0, fr = (double)f->frequency_per_m;
    double c = coverage(f, u, v, &cu, &cv);
    if (c > 0)
        e = fbm(f, u * fr, v * fr, &ex, &ey);
    double H = (double)f->max_height_m;
    if (grad) {
        grad[0] = c > 0 ? H * (cu * e + c * ex * fr) : 0;
        grad[1] = c > 0 ? H * (cv * e + c * ey * fr) : 0;
    }
    if (cov)
        *cov = c;
    return H * c * e;
}

double terrain_ref_warp_stretch(const atmo_gpu_terrain_field *f, double u, double v)
{
    double fr = (double)f->frequency_per_m, x = u * fr, y = v * fr, j[4] = {1, 0, 0, 1};
    warp(f, &x, &y, j);
    /* the largest singular value (noise.h's terrain_warp_stretch) */
    return 0.5 * (hypot(j[0] + j[3], j[2] - j[1]) + hypot(j[0] - j[3], j[1] + j[2]));
}

double terrain_ref_detail(const atmo_gpu_terrain_field *f, double u, double v, double grad[2])
{
    double fr = (double)f->frequency_per_m, x = u * fr, y = v * fr, j[4] = {fr, 0, 0, fr};
    double a = (double)f->detail_amplitude_m, d = 0, du = 0, dv = 0;
    for (int i = 0; i < f->detail_octave0; i++)
        next_octave(&x, &y, j);
    for (int k = 0; k < f->detail_octaves; k++, a *= 0.5) {
        double n[6];
        noise(x, y, f->seed + (unsigned)(f->detail_octave0 + k), n);
        d += a * n[0];
        du += a * (j[0] * n[1] + j[2] * n[2]);
        dv += a * (j[1] * n[1] + j[3] * n[2]);
        next_octave(&x, &y, j);
    }
    if (grad)
        grad[0] = du, grad[1] = dv;
    return d;
}

static double texel(const atmo_gpu_terrain_field *f, const float *hm, int i, int j)
{
    int n = f->heightmap_size;
    i = i < 0 ? 0 : i >= n ? n - 1 : i;
    j = j < 0 ? 0 : j >= n ? n - 1 : j;
    return (double)hm[(size_t)j * (size_t)n + (size_t)i];
}

double terrain_ref_height_map(const atmo_gpu_terrain_field *f, const float *hm, double u,
                              double v)
{
    int n = f->heightmap_size;
    double E = (double)f->heightmap_extent_m, cell = E / n;
    double gx = (u + 0.5 * E) / cell - 0.5, gy = (v + 0.5 * E) / cell - 0.5;
    if (!hm || n < 2 || gx < 0 || gy < 0 || gx > n - 1 || gy > n - 1)
        return terrain_ref_height(f, u, v, NULL, NULL);
    double x0 = floor(gx), y0 = floor(gy), fx = gx - x0, fy = gy - y0;
    int i = (int)x0, j = (int)y0;
    double h = (1 - fy) * ((1 - fx) * texel(f, hm, i, j) + fx * texel(f, hm, i + 1, j)) +
               fy * ((1 - fx) * texel(f, hm, i, j + 1) + fx * texel(f, hm, i + 1, j + 1));
    return h + terrain_ref_detail(f, u, v, NULL);
}

double terrain_ref_clearance_map(const atmo_gpu_terrain_field *f, const float *hm, double R,
                                 double sea_level_m, const double p[3])
{
    double q[3] = {p[0], p[1] + R, p[2]};
    double r = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
    double h = terrain_ref_height_map(f, hm, R * q[0] / r, R * q[2] / r);
    return (r - R) - (h > sea_level_m ? h : sea_level_m);
}

double terrain_ref_clearance(const atmo_gpu_terrain_field *f, double R, double sea_level_m,
                             const double p[3])
{
    return terrain_ref_clearance_map(f, NULL, R, sea_level_m, p);
}

int terrain_ref_hit(const atmo_gpu_terrain_field *f, double R, double sea_level_m,
                    const double o[3], const double d[3], double t_max, double step, double *t,
                    double *min_clearance)
{
    return terrain_ref_hit_map(f, NULL, R, sea_level_m, o, d, t_max, step, t, min_clearance);
}

int terrain_ref_hit_map(const atmo_gpu_terrain_field *f, const float *hm, double R,
                        double sea_level_m, const double o[3], const double d[3], double t_max,
                        double step, double *t, double *min_clearance)
{
    double top = (double)f->max_height_m;
    for (int k = 0; k < f->detail_octaves; k++) /* the detail's bound, terrain_detail.h */
        top += ldexp((double)f->detail_amplitude_m, -k);
    double p[3], t0 = 0, g0, lo_g = INFINITY;
    for (int k = 0; k < 3; k++)
        p[k] = o[k];
    g0 = terrain_ref_clearance_map(f, hm, R, sea_level_m, p);
    if (g0 <= 0) {
        *t = 0;
        return 1;
    }
    while (t0 < t_max) {
        double dt = fmin(step, fmax(g0 / 4.0, 1e-3 * step));
        double t1 = fmin(t0 + dt, t_max);
        for (int k = 0; k < 3; k++)
            p[k] = o[k] + t1 * d[k];
        double g1 = terrain_ref_clearance_map(f, hm, R, sea_level_m, p);
        if (g1 <= 0) {
            double a = t0, b = t1;
            while (b - a > 1e-9 * b + 1e-9) {
                double m = 0.5 * (a + b);
                for (int k = 0; k < 3; k++)
                    p[k] = o[k] + m * d[k];
                if (terrain_ref_clearance_map(f, hm, R, sea_level_m, p) > 0)
                    a = m;
                else
                    b = m;
            }
            *t = 0.5 * (a + b);
            return 1;
        }
        lo_g = fmin(lo_g, g1);
        t0 = t1, g0 = g1;
        /* above the highest terrain and rising: it never comes back down */
        double q[3] = {p[0], p[1] + R, p[2]}, r = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
        if (r - R > fmax(top, sea_level_m) &&
            q[0] * d[0] + q[1] * d[1] + q[2] * d[2] > 0)
            break;
    }
    if (min_clearance)
        *min_clearance = lo_g;
    return 0;
}
