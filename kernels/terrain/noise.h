/* noise.h — the terrain's height field: value noise from an integer hash with analytic first
 * and second derivatives, the "eroded" fBm over it, and the land/sea coverage field.
 *
 * Value noise (Quilez, "Value noise derivatives", 2008). Lattice values come from an integer
 * hash of the cell corner and the seed (a 32-bit multiply-xorshift finaliser), mapped exactly
 * to k 2^-23 - 1 in [-1, 1): the same on every device and in the double-precision host
 * reference (host/terrain/terrain_ref.c). In a cell with corners a, b, c, d and fractions
 * (x, y), with the quintic fade q(x) = x^3 (6 x^2 - 15 x + 10) (Perlin 2002),
 *     n = a + k1 qx + k2 qy + k3 qx qy,  k1 = b - a, k2 = c - a, k3 = a - b - c + d,
 *     n_x = q'x (k1 + k3 qy),  n_y = q'y (k2 + k3 qx),
 *     n_xx = q''x (k1 + k3 qy),  n_yy = q''y (k2 + k3 qx),  n_xy = k3 q'x q'y,
 * q'(x) = 30 x^2 (x - 1)^2, q''(x) = 60 x (x - 1)(2 x - 1): C2 across cells.
 *
 * Eroded fBm (Quilez, "Terrain", the thesis' terrain): octaves i = 0 .. N-1 at points
 * p_i = (2 M)^i p_0 with the octave rotation M = [[0.8, -0.6], [0.6, 0.8]] (lacunarity 2) and
 * weights b_i = 0.5^i (gain 0.5); with D_i = sum_{j <= i} grad n_j(p_j) (each gradient in its
 * octave's own coordinates, as the original accumulates it)
 *     a = sum_i b_i n_i / (1 + |D_i|^2),
 * so slopes of the coarse octaves damp the fine ones ("erosion"). Its gradient in p_0 is exact:
 * with J_i = (2 M)^i and H_j the Hessian of octave j,
 *     grad a = sum_i b_i [J_i^T g_i (1 + |D_i|^2) - 2 n_i (sum_{j<=i} J_j^T H_j) D_i]
 *              / (1 + |D_i|^2)^2.
 * The terrain's elevation is e = (1 + tanh(2 TERRAIN_RELIEF a / sum b_i)) / 2 in (0, 1): a
 * relief of 1.2 spreads the fBm's narrow distribution (a / sum b_i mostly within +-0.3) so that
 * 90 % of the land lies in e in [0.2, 0.8] and 1 % above 0.89 (grass valleys to snowy peaks
 * under a 4 km maximum: docs/guide/terrain.md) with slope 1.2 / sum b_i at the middle, the rare
 * values beyond saturating smoothly (a clamp would leave flat plateaus whose edges trace the
 * lattice). The relief and the first octave's frequency together set the slopes: each octave
 * adds a slope of about H f TERRAIN_RELIEF / sum b_i, so steep mountains need both.
 *
 * Coverage (land and sea): plain fBm c0 of `coverage_octaves` octaves (no erosion), normalised
 * to [0, 1] the same way, then smoothstep(t - 0.05, t + 0.05, c0) with t = 1 - land_fraction.
 * The height is h = H coverage e (H = max_height_m); water covers h <= sea level.
 *
 * Domain warp. Value noise's lattice is square and its first octave is not turned, so level
 * sets of the elevation (the snow line, the grass line) seen from orbit, where the first
 * octaves dominate, run along the world's axes in right angles. The fBm is therefore evaluated
 * at a warped lattice point (after Quilez, "Domain warping", 2002):
 *     x = x0 + A w(x0),  x0 = f (u, v),
 *     w(x0) = sum_{o < TERRAIN_WARP_OCTAVES} 2^-o (n_a,o(F_o R_o x0), n_b,o(F_o R_o x0)),
 * F_o = TERRAIN_WARP_FREQUENCY 2^o (a period of 2 first-octave cells, then 1), R_o = M^(o+1)
 * (the octave rotation, so the warp's own lattices lie along neither the world's axes nor each
 * other), A = warp (terrain.warp, in first-octave cells), each component its own value noise
 * (seeds seed + TERRAIN_WARP_SEED + 2 o and + 1). Its Jacobian J = I + A sum_o 2^-o F_o G_o R_o
 * (G_o the rows grad n_a,o, grad n_b,o) is exact, and the fBm's gradient in x0 is J^T times
 * its gradient in x: terrain_fbm starts its octaves' Jacobians J_i = (2 M)^i J instead of
 * (2 M)^i, which carries the erosion's Hessian term too (D_i sums gradients in each octave's
 * own coordinates, so d D_i / d x0 = sum_j H_j J_j). ||J|| <= 1 + A (15/4) sqrt 2 sum_o
 * 2^-o F_o (features/terrain/plan_terrain.c's slope bound). One octave of warp leaves a preference
 * of its own (contour normals scarce at the diagonals at A 1.5, at the world's axes at 2); two
 * octaves at A 1.25 to 1.5 leave none that tests/test_terrain_isotropy.c detects, and at 2
 * the first warp octave's lattice shows (docs/guide/terrain.md). A = 0 gives x = x0 and
 * J = I exactly (the field bitwise as without the warp).
 *
 * Octave i hashes with seed + i (the coverage with seed + 0x51ed27 + i), so octaves are
 * independent lattices. Coordinates: (u, v) in metres, the planar coordinates of terrain.h; octave 0 samples the
 * lattice at the warped point of (u, v) times frequency_per_m. The coverage is not warped (its
 * 5000 km cells span a whole view from orbit). Parameters: gpu_terrain.h's field. */
#ifndef ATMO_TERRAIN_NOISE_H
#define ATMO_TERRAIN_NOISE_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "atmo/gpu_terrain.h"
#endif

#define TERRAIN_ROT_C 0.8f
#define TERRAIN_ROT_S 0.6f
#define TERRAIN_COAST_HALF_WIDTH 0.05f
#define TERRAIN_RELIEF 1.2f
#define TERRAIN_BOUND_OCTAVE_A 4
#define TERRAIN_BOUND_OCTAVE_B 7
#define TERRAIN_WARP_FREQUENCY 0.5f
#define TERRAIN_WARP_OCTAVES 2
#define TERRAIN_WARP_SEED 0xa3c59ac3u

/* Value noise at a point and its derivatives (see the top of the file). */
typedef struct terrain_noise {
    float v, dx, dy, dxx, dyy, dxy;
} terrain_noise;

/* A height with its gradient in (u, v). */
typedef struct terrain_height {
    float h, du, dv;
} terrain_height;

ATMO_FN uint terrain_hash(int ix, int iy, uint seed)
{
    uint h = ((uint)ix * 0x8da6b343u) ^ ((uint)iy * 0xd8163841u) ^ (seed * 0xcb1ab31fu + 0x9e3779b9u);
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    h *= 0x846ca68bu;
    h ^= h >> 16;
    return h;
}

/* The lattice value k 2^-23 - 1 (exact in float and double). */
ATMO_FN float terrain_lattice(int ix, int iy, uint seed)
{
    return (float)(terrain_hash(ix, iy, seed) >> 8) * (1.0f / 8388608.0f) - 1.0f;
}

/* The cell of (x, y): its fractions, their fades and the corner terms k of the top of the
 * file, shared by the noise with its derivatives and by its value alone. */
typedef struct terrain_cell {
    float fx, fy, qx, qy, a, k1, k2, k3;
} terrain_cell;

ATMO_FN terrain_cell terrain_cell_at(float x, float y, uint seed)
{
    terrain_cell c;
    float fx0 = floorf(x), fy0 = floorf(y);
    int ix = (int)fx0, iy = (int)fy0;
    c.fx = x - fx0, c.fy = y - fy0;
    c.qx = c.fx * c.fx * c.fx * (c.fx * (c.fx * 6.0f - 15.0f) + 10.0f);
    c.qy = c.fy * c.fy * c.fy * (c.fy * (c.fy * 6.0f - 15.0f) + 10.0f);
    float a = terrain_lattice(ix, iy, seed), b = terrain_lattice(ix + 1, iy, seed);
    float cc = terrain_lattice(ix, iy + 1, seed), d = terrain_lattice(ix + 1, iy + 1, seed);
    c.a = a, c.k1 = b - a, c.k2 = cc - a, c.k3 = a - b - cc + d;
    return c;
}

ATMO_FN terrain_noise terrain_value_noise(float x, float y, uint seed)
{
    terrain_cell c = terrain_cell_at(x, y, seed);
    float fx = c.fx, fy = c.fy;
    float dqx = 30.0f * fx * fx * (fx - 1.0f) * (fx - 1.0f);
    float dqy = 30.0f * fy * fy * (fy - 1.0f) * (fy - 1.0f);
    float ddqx = 60.0f * fx * (fx - 1.0f) * (2.0f * fx - 1.0f);
    float ddqy = 60.0f * fy * (fy - 1.0f) * (2.0f * fy - 1.0f);
    terrain_noise n;
    n.v = c.a + c.k1 * c.qx + c.k2 * c.qy + c.k3 * c.qx * c.qy;
    n.dx = dqx * (c.k1 + c.k3 * c.qy);
    n.dy = dqy * (c.k2 + c.k3 * c.qx);
    n.dxx = ddqx * (c.k1 + c.k3 * c.qy);
    n.dyy = ddqy * (c.k2 + c.k3 * c.qx);
    n.dxy = c.k3 * dqx * dqy;
    return n;
}

/* The next octave's coordinates: (x, y) <- 2 R (x, y), R the octave rotation [[c, -s], [s, c]].
 * Applied to the columns (j00, j10) and (j01, j11) of the Jacobian J = d(x, y)/d(u, v) it
 * carries J along (J <- 2 R J), which turns each octave's gradient into the base frame. */
ATMO_FN void terrain_octave_next(float *x, float *y)
{
    float nx = 2.0f * (TERRAIN_ROT_C * *x - TERRAIN_ROT_S * *y);
    float ny = 2.0f * (TERRAIN_ROT_S * *x + TERRAIN_ROT_C * *y);
    *x = nx;
    *y = ny;
}

/* Value noise's value alone (terrain_value_noise's n). */
ATMO_FN float terrain_value_noise_value(float x, float y, uint seed)
{
    terrain_cell c = terrain_cell_at(x, y, seed);
    return c.a + c.k1 * c.qx + c.k2 * c.qy + c.k3 * c.qx * c.qy;
}

/* The fBm's first-octave lattice point of (u, v) metres, x = x0 + A w(x0) with x0 = f (u, v)
 * (the domain warp, top of the file), and with jac non-NULL its Jacobian d x / d x0 in lattice
 * units, row-major: jac[0] = dx/dx0, jac[1] = dx/dy0, jac[2] = dy/dx0, jac[3] = dy/dy0.
 * With warp 0 the point is x0 and the Jacobian the identity, exactly. */
ATMO_FN void terrain_fbm_point(ATMO_GLOBAL const atmo_gpu_terrain_field *f, float u, float v,
                               float *x, float *y, float *jac)
{
    float x0 = u * f->frequency_per_m, y0 = v * f->frequency_per_m;
    *x = x0;
    *y = y0;
    if (jac)
        jac[0] = 1.0f, jac[1] = 0.0f, jac[2] = 0.0f, jac[3] = 1.0f;
    if (f->warp == 0.0f)
        return;
    float amp = f->warp, fr = TERRAIN_WARP_FREQUENCY, c = TERRAIN_ROT_C, sn = TERRAIN_ROT_S;
    uint seed = f->seed + TERRAIN_WARP_SEED;
    for (int o = 0; o < TERRAIN_WARP_OCTAVES; o++) {
        float s = fr * (c * x0 - sn * y0), t = fr * (sn * x0 + c * y0);
        uint sa = seed + 2u * (uint)o, sb = sa + 1u;
        if (jac) {
            terrain_noise wa = terrain_value_noise(s, t, sa), wb = terrain_value_noise(s, t, sb);
            float k = amp * fr;
            *x += amp * wa.v;
            *y += amp * wb.v;
            /* d w / d x0 = F grad_(s,t) w R, R the octave's rotation [[c, -s], [s, c]] */
            jac[0] += k * (c * wa.dx + sn * wa.dy);
            jac[1] += k * (c * wa.dy - sn * wa.dx);
            jac[2] += k * (c * wb.dx + sn * wb.dy);
            jac[3] += k * (c * wb.dy - sn * wb.dx);
        } else {
            *x += amp * terrain_value_noise_value(s, t, sa);
            *y += amp * terrain_value_noise_value(s, t, sb);
        }
        float nc = c * TERRAIN_ROT_C - sn * TERRAIN_ROT_S; /* the next octave turns by M */
        sn = sn * TERRAIN_ROT_C + c * TERRAIN_ROT_S;
        c = nc;
        amp *= 0.5f;
        fr *= 2.0f;
    }
}

/* The eroded fBm's elevation e in [0, 1] at lattice point (x, y) and its gradient in the
 * unwarped lattice coordinates (x0, y0), jac = d(x, y)/d(x0, y0) (terrain_fbm_point). */
ATMO_FN float terrain_fbm(float x, float y, const float *jac, int octaves, uint seed, float *ex,
                          float *ey)
{
    float a = 0.0f, ax = 0.0f, ay = 0.0f, b = 1.0f, norm = 0.0f;
    float dx = 0.0f, dy = 0.0f;                             /* D_i */
    float sxx = 0.0f, sxy = 0.0f, syx = 0.0f, syy = 0.0f;   /* sum_j J_j^T H_j, row-major */
    float j00 = jac[0], j01 = jac[1], j10 = jac[2], j11 = jac[3]; /* J_i = (2M)^i J_w */
    for (int i = 0; i < octaves; i++) {
        terrain_noise n = terrain_value_noise(x, y, seed + (uint)i);
        dx += n.dx;
        dy += n.dy;
        /* J^T H: J^T = [[j00, j10], [j01, j11]] */
        sxx += j00 * n.dxx + j10 * n.dxy;
        sxy += j00 * n.dxy + j10 * n.dyy;
        syx += j01 * n.dxx + j11 * n.dxy;
        syy += j01 * n.dxy + j11 * n.dyy;
        float den = 1.0f + dx * dx + dy * dy;
        float gx = j00 * n.dx + j10 * n.dy, gy = j01 * n.dx + j11 * n.dy; /* J^T g */
        float hx = sxx * dx + sxy * dy, hy = syx * dx + syy * dy;         /* (sum J^T H) D */
        a += b * n.v / den;
        ax += b * (gx * den - 2.0f * n.v * hx) / (den * den);
        ay += b * (gy * den - 2.0f * n.v * hy) / (den * den);
        norm += b;
        b *= 0.5f;
        terrain_octave_next(&x, &y);
        terrain_octave_next(&j00, &j10);
        terrain_octave_next(&j01, &j11);
    }
    float k = TERRAIN_RELIEF / norm, th = tanhf(2.0f * k * a), slope = k * (1.0f - th * th);
    *ex = ax * slope;
    *ey = ay * slope;
    return 0.5f + 0.5f * th;
}

/* The land/sea coverage in [0, 1] at (u, v) metres and its gradient. */
ATMO_FN float terrain_coverage(ATMO_GLOBAL const atmo_gpu_terrain_field *f, float u, float v,
                               float *cu, float *cv)
{
    float x = u * f->coverage_frequency_per_m, y = v * f->coverage_frequency_per_m;
    float c = 0.0f, cx = 0.0f, cy = 0.0f, b = 1.0f, norm = 0.0f;
    float j00 = 1.0f, j01 = 0.0f, j10 = 0.0f, j11 = 1.0f;
    uint seed = f->seed + 0x51ed27u;
    for (int i = 0; i < f->coverage_octaves; i++) {
        terrain_noise n = terrain_value_noise(x, y, seed + (uint)i);
        c += b * n.v;
        cx += b * (j00 * n.dx + j10 * n.dy);
        cy += b * (j01 * n.dx + j11 * n.dy);
        norm += b;
        b *= 0.5f;
        terrain_octave_next(&x, &y);
        terrain_octave_next(&j00, &j10);
        terrain_octave_next(&j01, &j11);
    }
    float c0 = 0.5f * c / norm + 0.5f;
    float t = 1.0f - f->land_fraction;
    float s = clamp((c0 - (t - TERRAIN_COAST_HALF_WIDTH)) / (2.0f * TERRAIN_COAST_HALF_WIDTH),
                    0.0f, 1.0f);
    float ds = (s > 0.0f && s < 1.0f) ? 6.0f * s * (1.0f - s) / (2.0f * TERRAIN_COAST_HALF_WIDTH)
                                      : 0.0f;
    float k = ds * 0.5f / norm * f->coverage_frequency_per_m;
    *cu = cx * k;
    *cv = cy * k;
    return s * s * (3.0f - 2.0f * s);
}

/* terrain_fbm's elevation alone: the same sums without the Hessians and the gradient (the
 * tracer's clearance needs no normal; about half the work per octave).
 *
 * With cap_e < 1 it may stop early with an upper bound instead (*bound = 1): each octave's
 * term b_i n_i / (1 + |D_i|^2) lies in [-b_i, b_i] (|n| <= 1), so after m octaves
 * |a - a_m| <= R_m = sum_{i >= m} b_i, and since tanh has slope <= 1,
 * |e - e_m| <= k R_m (k = TERRAIN_RELIEF / sum b_i, e_m the elevation of a_m). After the
 * octaves TERRAIN_BOUND_OCTAVE_A and TERRAIN_BOUND_OCTAVE_B (4 and 7, the fastest measured:
 * docs/notes/terrain.md) it returns
 * e_m + k R_m + 1e-6 (the float rounding of the sums) when that is at most cap_e - k R_m: below
 * the cap by at least half the bound's whole uncertainty 2 k R_m, so a caller that steps by the
 * margin to the bound takes at least a third of the step the exact value allows. */
ATMO_FN float terrain_fbm_value_capped(float x, float y, int octaves, uint seed, float cap_e,
                                       int *bound)
{
    float a = 0.0f, b = 1.0f, norm = 0.0f, dx = 0.0f, dy = 0.0f;
    float last = 1.0f; /* 0.5^octaves */
    for (int i = 0; i < octaves; i++)
        last *= 0.5f;
    float total = 2.0f - 2.0f * last, k = TERRAIN_RELIEF / total;
    *bound = 0;
    for (int i = 0; i < octaves; i++) {
        float fx0 = floorf(x), fy0 = floorf(y);
        int ix = (int)fx0, iy = (int)fy0;
        float fx = x - fx0, fy = y - fy0;
        float qx = fx * fx * fx * (fx * (fx * 6.0f - 15.0f) + 10.0f);
        float qy = fy * fy * fy * (fy * (fy * 6.0f - 15.0f) + 10.0f);
        float dqx = 30.0f * fx * fx * (fx - 1.0f) * (fx - 1.0f);
        float dqy = 30.0f * fy * fy * (fy - 1.0f) * (fy - 1.0f);
        uint sd = seed + (uint)i;
        float na = terrain_lattice(ix, iy, sd), nb = terrain_lattice(ix + 1, iy, sd);
        float nc = terrain_lattice(ix, iy + 1, sd), nd = terrain_lattice(ix + 1, iy + 1, sd);
        float k1 = nb - na, k2 = nc - na, k3 = na - nb - nc + nd;
        dx += dqx * (k1 + k3 * qy);
        dy += dqy * (k2 + k3 * qx);
        a += b * (na + k1 * qx + k2 * qy + k3 * qx * qy) / (1.0f + dx * dx + dy * dy);
        norm += b;
        b *= 0.5f;
        if ((i + 1 == TERRAIN_BOUND_OCTAVE_A || i + 1 == TERRAIN_BOUND_OCTAVE_B) &&
            i + 1 < octaves && cap_e < 1.0f) {
            float rest = k * (total - norm); /* k R_m */
            float up = 0.5f + 0.5f * tanhf(2.0f * k * a) + rest + 1e-6f;
            if (up <= cap_e - rest) {
                *bound = 1;
                return up;
            }
        }
        terrain_octave_next(&x, &y);
    }
    return 0.5f + 0.5f * tanhf(2.0f * (TERRAIN_RELIEF / norm) * a);
}

ATMO_FN float terrain_fbm_value(float x, float y, int octaves, uint seed)
{
    int bound;
    return terrain_fbm_value_capped(x, y, octaves, seed, 1.0f, &bound);
}

/* terrain_coverage's value alone. */
ATMO_FN float terrain_coverage_value(ATMO_GLOBAL const atmo_gpu_terrain_field *f, float u,
                                     float v)
{
    float x = u * f->coverage_frequency_per_m, y = v * f->coverage_frequency_per_m;
    float c = 0.0f, b = 1.0f, norm = 0.0f;
    uint seed = f->seed + 0x51ed27u;
    for (int i = 0; i < f->coverage_octaves; i++) {
        float fx0 = floorf(x), fy0 = floorf(y);
        int ix = (int)fx0, iy = (int)fy0;
        float fx = x - fx0, fy = y - fy0;
        float qx = fx * fx * fx * (fx * (fx * 6.0f - 15.0f) + 10.0f);
        float qy = fy * fy * fy * (fy * (fy * 6.0f - 15.0f) + 10.0f);
        uint sd = seed + (uint)i;
        float na = terrain_lattice(ix, iy, sd), nb = terrain_lattice(ix + 1, iy, sd);
        float nc = terrain_lattice(ix, iy + 1, sd), nd = terrain_lattice(ix + 1, iy + 1, sd);
        float k1 = nb - na, k2 = nc - na, k3 = na - nb - nc + nd;
        c += b * (na + k1 * qx + k2 * qy + k3 * qx * qy);
        norm += b;
        b *= 0.5f;
        terrain_octave_next(&x, &y);
    }
    float c0 = 0.5f * c / norm + 0.5f;
    float t = 1.0f - f->land_fraction;
    float s = clamp((c0 - (t - TERRAIN_COAST_HALF_WIDTH)) / (2.0f * TERRAIN_COAST_HALF_WIDTH),
                    0.0f, 1.0f);
    return s * s * (3.0f - 2.0f * s);
}

/* terrain_height_direct's height alone. */
ATMO_FN float terrain_height_direct_value(ATMO_GLOBAL const atmo_gpu_terrain_field *f, float u,
                                          float v)
{
    float c = terrain_coverage_value(f, u, v);
    if (c <= 0.0f)
        return 0.0f;
    float x, y;
    terrain_fbm_point(f, u, v, &x, &y, 0);
    return f->max_height_m * c * terrain_fbm_value(x, y, f->octaves, f->seed);
}

/* The warp's stretch at a point: the spectral norm of its Jacobian jac = [[a, b], [c, d]]
 * (terrain_fbm_point's, row-major), its largest singular value
 *     (sqrt((a + d)^2 + (c - b)^2) + sqrt((a - d)^2 + (b + c)^2)) / 2
 * (J as a rotation-scaling plus a reflection-scaling, whose scales add; sums of squares, so
 * free of the cancellation of sqrt((T + sqrt(T^2 - 4 det^2)) / 2) where J is near conformal).
 * The slope in (u, v) is at most the stretch times the fBm's slope at the warped point. */
ATMO_FN float terrain_warp_stretch(const float *jac)
{
    float p = jac[0] + jac[3], q = jac[2] - jac[1], r = jac[0] - jac[3], w = jac[1] + jac[2];
    return 0.5f * (sqrtf(p * p + q * q) + sqrtf(r * r + w * w));
}

/* An upper bound on the height at (u, v), cheaper than the height where it is well below
 * cap_m: the coverage bounded by 1 and the fBm stopped early (terrain_fbm_value_capped), when
 * that bound is below cap_m with room to spare; else the height itself.
 * *bound: 1 for a bound, 0 for the height. stretch (may be NULL): gets the warp's stretch at
 * (u, v) (terrain_warp_stretch), from the warped point's own Jacobian. */
ATMO_FN float terrain_height_direct_capped(ATMO_GLOBAL const atmo_gpu_terrain_field *f, float u,
                                           float v, float cap_m, int *bound, float *stretch)
{
    float H = f->max_height_m, x, y, jac[4];
    terrain_fbm_point(f, u, v, &x, &y, stretch ? jac : 0);
    if (stretch)
        *stretch = terrain_warp_stretch(jac);
    if (cap_m < H && cap_m > 0.0f) {
        float e = terrain_fbm_value_capped(x, y, f->octaves, f->seed, cap_m / H, bound);
        if (*bound)
            return H * e;
    }
    *bound = 0;
    float c = terrain_coverage_value(f, u, v);
    return c <= 0.0f ? 0.0f : H * c * terrain_fbm_value(x, y, f->octaves, f->seed);
}

/* The height field h = H coverage e at (u, v) metres, evaluated directly. */
ATMO_FN terrain_height terrain_height_direct(ATMO_GLOBAL const atmo_gpu_terrain_field *f, float u,
                                             float v)
{
    float cu, cv, ex, ey;
    float c = terrain_coverage(f, u, v, &cu, &cv);
    terrain_height r;
    if (c <= 0.0f) { /* open sea: the fBm is not needed */
        r.h = 0.0f, r.du = 0.0f, r.dv = 0.0f;
        return r;
    }
    float x, y, jac[4];
    terrain_fbm_point(f, u, v, &x, &y, jac);
    float e = terrain_fbm(x, y, jac, f->octaves, f->seed, &ex, &ey);
    float H = f->max_height_m;
    r.h = H * c * e;
    r.du = H * (cu * e + c * ex * f->frequency_per_m);
    r.dv = H * (cv * e + c * ey * f->frequency_per_m);
    return r;
}

#endif
