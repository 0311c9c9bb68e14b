/* terrain_detail.h — the procedural fBm's detail below a digital elevation model's cells
 * (terrain.heightmap_detail): the octaves of the height fBm (noise.h) whose lattice is finer
 * than the cells, added to the heightmap's resampled heights by the lookups of terrain.h.
 *
 * The fBm's octave i samples value noise at p_i = (2 M)^i f (u, v) (lattice period
 * P_i = 1 / (f 2^i) metres, M the octave rotation) with weight 0.5^i. Value noise of period P
 * varies on wavelengths of 2 P and longer (its lattice's Nyquist wavelength), so the octaves
 * i0 .. i0 + K - 1 with 2 P_i <= C, C the cell size the DEM is drawn at (the larger of the
 * file's cell and the heightmap's texel, plan_terrain.c), hold no structure the cells
 * already resolve; their leak to longer wavelengths is white noise of the lattice, whose mean
 * over a cell of side C has variance at most A_i^2 / 3 (P_i / C)^2 (the interpolation weights
 * sum to 1 and each is at most (P_i / C)^2 after averaging; the lattice values are independent
 * with variance 1/3): tests/test_dem_detail.c checks that bound. The sum is
 *     d(u, v) = sum_{i = i0}^{i0 + K - 1} A_i n_i(p_i),   A_i = A_{i0} 0.5^(i - i0),
 * plain value noise without the erosion term (the DEM's own slopes are not the fBm's), with
 * A_{i0} = detail_amplitude_m (the fBm's own gain: H relief / sum b 0.5^i0, noise.h's slope
 * of the elevation times the octave weight). Its gradient is exact:
 *     grad d = sum_i A_i J_i^T grad n_i,   J_i = (2 M)^i f,
 * so |d| <= A_{i0} (2 - 2^(1 - K)) (|n| <= 1) and |grad d| <= K A_{i0} 2^i0 f (15/4)
 * (each octave as in plan_terrain.c's slope bound, A_i 2^i constant): the tracer's shell and
 * slope bound include both. Octave i hashes with seed + i, as in the fBm. Float precision: the
 * lattice coordinates reach f 2^(i0 + K) |u|, about 3e4 over a 30 m DEM 30 km from the origin,
 * rounded to ~1e-3 of a lattice cell: millimetres of the detail's height. */
#ifndef ATMO_TERRAIN_DETAIL_H
#define ATMO_TERRAIN_DETAIL_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "terrain/noise.h"
#include "atmo/gpu_terrain.h"
#endif

/* The largest value of |d| (see the top of the file), m. */
ATMO_FN float terrain_detail_bound_m(ATMO_GLOBAL const atmo_gpu_terrain_field *f)
{
    float sum = 0.0f, a = f->detail_amplitude_m;
    for (int k = 0; k < f->detail_octaves; k++, a *= 0.5f)
        sum += a;
    return sum;
}

/* The lattice point of octave i0 at (u, v) metres and, with jac non-NULL, the Jacobian's
 * columns (jac[0], jac[2]) and (jac[1], jac[3]) of J_i0 = (2 M)^i0 f. */
ATMO_FN void terrain_detail_start(ATMO_GLOBAL const atmo_gpu_terrain_field *f, float u, float v,
                                  float *x, float *y, float *jac)
{
    *x = u * f->frequency_per_m;
    *y = v * f->frequency_per_m;
    if (jac)
        jac[0] = f->frequency_per_m, jac[1] = 0.0f, jac[2] = 0.0f, jac[3] = f->frequency_per_m;
    for (int i = 0; i < f->detail_octave0; i++) {
        terrain_octave_next(x, y);
        if (jac) {
            terrain_octave_next(&jac[0], &jac[2]);
            terrain_octave_next(&jac[1], &jac[3]);
        }
    }
}

/* The detail d at (u, v) metres and its gradient in (u, v). */
ATMO_FN terrain_height terrain_detail_height(ATMO_GLOBAL const atmo_gpu_terrain_field *f, float u,
                                             float v)
{
    float x, y, j[4], a = f->detail_amplitude_m;
    terrain_height r;
    r.h = 0.0f, r.du = 0.0f, r.dv = 0.0f;
    terrain_detail_start(f, u, v, &x, &y, j);
    for (int k = 0; k < f->detail_octaves; k++, a *= 0.5f) {
        terrain_noise n = terrain_value_noise(x, y, f->seed + (uint)(f->detail_octave0 + k));
        r.h += a * n.v;
        r.du += a * (j[0] * n.dx + j[2] * n.dy);
        r.dv += a * (j[1] * n.dx + j[3] * n.dy);
        terrain_octave_next(&x, &y);
        terrain_octave_next(&j[0], &j[2]);
        terrain_octave_next(&j[1], &j[3]);
    }
    return r;
}

/* The detail d alone (the tracer's clearance). */
ATMO_FN float terrain_detail_value(ATMO_GLOBAL const atmo_gpu_terrain_field *f, float u, float v)
{
    float x, y, a = f->detail_amplitude_m, d = 0.0f;
    terrain_detail_start(f, u, v, &x, &y, 0);
    for (int k = 0; k < f->detail_octaves; k++, a *= 0.5f) {
        d += a * terrain_value_noise(x, y, f->seed + (uint)(f->detail_octave0 + k)).v;
        terrain_octave_next(&x, &y);
    }
    return d;
}

#endif
