/* cloud_majorant.h — the fBm cloud layer's majorant grid: a coarse 3-D grid of bounds on the
 * layer's density over the region around the camera, and the walk of a ray through its cells,
 * so that delta, spectral and ratio tracking (tracking.h) take tentative points at the rate of
 * the cloud that is there instead of the layer's global bound everywhere.
 *
 * The grid's frame (clouds_grid_frame_make) is the tangent frame at the camera's foot F (the
 * point of the ground sphere below the camera): y along the local vertical, x and z horizontal.
 * Its box spans [-E, E] in x and z, E = min(clouds.max_distance_m, CLOUDS_GRID_EXTENT_MAX x R),
 * and in y from the layer's bottom where it has sunk lowest, at the box's corners (horizontal
 * distance rho = sqrt(2) E: y_lo = (A - R) - rho^2 / (sqrt(A^2 - rho^2) + A), A = R + bottom),
 * to the layer's top (the plane y = top touches the sphere of radius R + top at F, so every
 * point above it is above the layer). CLOUDS_GRID_NX x NY x NZ cells.
 *
 * A cell's bound (clouds_grid_cell_bound) is analytic and conservative over the cell's box grown
 * by CLOUDS_GRID_MARGIN_M on every side (more than the float rounding of the points the walk
 * evaluates), from the density's form (cloud_layer.h)
 *     d = density max(c - fbm_N, 0)^sharpness,  c = field(x) fade(h),
 *     field = clamp(C (fbm_4(f_c x) - 1/2) + coverage, 0, 1):
 *   - fbm_N >= 0, so d <= density (field_max fade_max)^sharpness;
 *   - fade is a smoothstep of min(h - bottom, top - h) / fade_m, concave in h before the
 *     smoothstep, so over the box's altitudes [h_lo, h_hi] it is largest at the layer's middle
 *     altitude clamped into them; the altitudes come from the box's nearest and farthest points
 *     to the planet centre, h = (r^2 - R^2) / (r + R) (no cancellation at 6360 km), widened by
 *     CLOUDS_GRID_ALTITUDE_MARGIN_M;
 *   - field is increasing in fbm_4, so field_max = clamp(C (n_max - 1/2) + coverage, 0, 1) for
 *     any bound n_max of fbm_4 over the box; the smaller of two bounds is used:
 *     (a) value noise is a convex combination of the 8 lattice values around its point (the
 *     quintic fade's weights lie in [0, 1]), so over a box it is at most the largest lattice
 *     value of the lattice points of the cells the box touches; octave i samples its lattice
 *     at the turned point (2 R)^i R f_c x + o_i (cloud_noise.h's octave rotation R), so the
 *     cell's box (centre +- its half-size, world axes) maps into the axis-aligned box of that
 *     octave's lattice centred on the centre's turned point with half-size 2^i |R^(i+1)| f_c
 *     ext (the bounding box of the turned box: |M| the entries' absolute values), grown for
 *     the coordinates' rounding; an octave whose box holds more than CLOUDS_GRID_LATTICE_MAX
 *     lattice points is bounded by 1: n_max = sum_i a_i v_i,max / sum_i a_i;
 *     (b) Lipschitz: along each lattice axis the trilinear blend's derivative is s'(f) times a
 *     blend of differences of values in [0, 1), and |s'(f)| = 30 f^2 (1 - f)^2 <= 15/8 per
 *     lattice unit, so between the centre's turned point and any other point of the same
 *     lattice box octave i moves by at most 15/8 times the box's half-size summed over the
 *     three axes, H_i: n_max = fbm_4(centre) + 15/8 sum_i a_i H_i / sum_i a_i (+ 1e-5 for the
 *     rounding of the centre's value). The coverage field's features are hundreds of km
 *     wide, so (b) is within a few hundredths of the field over a cell of a few km.
 * The bound is multiplied by 1 + 1e-4 for the rounding of the kernels' powf and products (a few
 * ulp). The shape fBm's lower bound (it would need the warp's reach, 3 km, around each box) is
 * not used: the bound is the coverage the cell may hold, which is zero over the clear regions
 * and small near the layer's bottom and top, where the walk then takes no or few points.
 *
 * The walk (clouds_grid_begin, clouds_grid_segment) is Amanatides & Woo's 3-D DDA (1987) in the
 * grid's frame: the ray's parameter range inside the box by the slab method, then cell by cell
 * the distances to the next x, y and z boundaries; each segment returns its cell's bound. Before
 * and after the box (and for a ray that misses it) it returns -1: the caller uses the layer's
 * global bound there. Units: metres, density as cloud_layer.h's (extinction = density x
 * clouds.extinction). */
#ifndef ATMO_CLOUDS_CLOUD_MAJORANT_H
#define ATMO_CLOUDS_CLOUD_MAJORANT_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "clouds/cloud_layer.h"
#include "clouds/cloud_noise.h"
#include "atmo/gpu_types.h"
#endif

#define CLOUDS_GRID_NX 128
#define CLOUDS_GRID_NY 32
#define CLOUDS_GRID_NZ 128
#define CLOUDS_GRID_EXTENT_MAX 0.1f        /* of the ground radius: 636 km on Earth */
#define CLOUDS_GRID_MARGIN_M 16.0f         /* each cell's bound covers its box grown by this */
#define CLOUDS_GRID_ALTITUDE_MARGIN_M 16.0f
#define CLOUDS_GRID_LATTICE_MAX 512        /* lattice points per octave and cell, else bound 1 */
#define CLOUDS_GRID_LATTICE_MARGIN 1e-3f   /* lattice units, relative above |y|_1 = 100: the
                                              rounding of the noise's coordinates (a few 1e-6
                                              relative, clouds_grid_lattice_margin) */
#define CLOUDS_GRID_ROUNDING 1.0001f

typedef struct clouds_grid_frame {
    vec3 corner;     /* camera-relative position of the box's corner (cell 0, 0, 0), m */
    vec3 ax, ay, az; /* unit axes: horizontal, vertical (up at the foot), horizontal */
    vec3 cell;       /* the cells' edges along ax, ay, az, m */
    vec3 low;        /* the corner's coordinates relative to the foot F along ax, ay, az, m */
} clouds_grid_frame;

/* The grid's frame for the scene's camera and layer (the same on host and device). */
ATMO_FN clouds_grid_frame clouds_grid_frame_make(ATMO_GLOBAL const atmo_gpu_scene *s)
{
    ATMO_GLOBAL const atmo_gpu_clouds *c = &s->clouds;
    clouds_grid_frame f;
    float R = s->atmosphere.bottom_radius;
    vec3 up = v3_from4(s->camera.local_up);
    vec3 x = v3_sub(v3(1.0f, 0.0f, 0.0f), v3_scale(up, up.x));
    if (v3_dot(x, x) < 1e-6f) /* up along the world's x axis */
        x = v3_sub(v3(0.0f, 0.0f, 1.0f), v3_scale(up, up.z));
    f.ax = v3_normalize(x);
    f.ay = up;
    f.az = v3_cross(f.ax, up);
    float E = fminf(c->max_distance_m, CLOUDS_GRID_EXTENT_MAX * R);
    float A = R + c->bottom_m, rho2 = 2.0f * E * E;
    float y_lo = c->bottom_m - rho2 / (sqrtf(A * A - rho2) + A);
    f.low = v3(-E, y_lo, -E);
    f.cell = v3(2.0f * E / (float)CLOUDS_GRID_NX, (c->top_m - y_lo) / (float)CLOUDS_GRID_NY,
                2.0f * E / (float)CLOUDS_GRID_NZ);
    vec3 foot = v3_scale(up, R - s->camera.local_up.w);
    f.corner = v3_add(foot, v3_add(v3_add(v3_scale(f.ax, -E), v3_scale(f.ay, y_lo)),
                                   v3_scale(f.az, -E)));
    return f;
}

/* The altitude of a point at horizontal distance^2 q2 from the foot's vertical and height y
 * above the foot: (r^2 - R^2) / (r + R) with r^2 = q2 + (R + y)^2. */
ATMO_FN float clouds_grid_altitude(float R, float q2, float y)
{
    float r = sqrtf(q2 + (R + y) * (R + y));
    return (q2 + y * (y + 2.0f * R)) / (r + R);
}

/* |v| per component. */
ATMO_FN vec3 clouds_grid_abs(vec3 v)
{
    return v3(fabsf(v.x), fabsf(v.y), fabsf(v.z));
}

/* How far the rounding of noise_fbm's coordinates may move a lattice coordinate of a point y of
 * an octave's lattice: f_c x and each of the (at most CLOUDS_COVERAGE_OCTAVES) turns by R round
 * by a few ulp of |y| (3 products and 2 sums of terms at most |y|: 3.1e-7 |y| per turn, 1.3e-6
 * |y| after four, 2.6e-6 |y| between two points), under CLOUDS_GRID_LATTICE_MARGIN
 * (1 + 1e-2 |y|_1). */
ATMO_FN float clouds_grid_lattice_margin(vec3 y)
{
    return CLOUDS_GRID_LATTICE_MARGIN * (1.0f + 1e-2f * (fabsf(y.x) + fabsf(y.y) + fabsf(y.z)));
}

/* The largest lattice value (cloud_noise.h) over the lattice points of the cells that the noise
 * coordinates in [lo, hi] touch; 1 when they are more than CLOUDS_GRID_LATTICE_MAX. */
ATMO_FN float clouds_grid_lattice_max(vec3 lo, vec3 hi, uint seed)
{
    int i0 = (int)floorf(lo.x), j0 = (int)floorf(lo.y), l0 = (int)floorf(lo.z);
    int i1 = (int)floorf(hi.x) + 1, j1 = (int)floorf(hi.y) + 1, l1 = (int)floorf(hi.z) + 1;
    if ((i1 - i0 + 1) * (j1 - j0 + 1) * (l1 - l0 + 1) > CLOUDS_GRID_LATTICE_MAX)
        return 1.0f;
    float m = 0.0f;
    for (int l = l0; l <= l1; l++)
        for (int j = j0; j <= j1; j++)
            for (int i = i0; i <= i1; i++)
                m = fmaxf(m, noise_lattice(i, j, l, seed));
    return m;
}

/* A bound on the coverage fBm (clouds_coverage_field's fbm_4) over the world noise points
 * centre +- ext: the smaller of (a) and (b) (see the top of the file). Octave i of the fBm at
 * the noise point u = f_c x is value noise at y_i + o_i, y_i = (2 R)^i R u (cloud_noise.h); over
 * the box u_c +- E (u_c = f_c centre, E = f_c ext) y_i lies in the axis-aligned box
 * y_i(u_c) +- 2^i |R^(i+1)| E, |M| the entries' absolute values (each coordinate of M d is a
 * sum of M's entries times d's, |d| <= E). R^(i+1)'s columns are the unit vectors turned i + 1
 * times by noise_rotate, in float (a relative 1e-6 off the exact product, under the factor
 * 1.0001 on E); the box is grown by clouds_grid_lattice_margin for the rounding of the noise's
 * coordinates. */
ATMO_FN float clouds_grid_coverage_fbm_bound(ATMO_GLOBAL const atmo_gpu_clouds *c, vec3 centre,
                                            vec3 ext)
{
    float sum = 0.0f, slope = 0.0f, norm = 0.0f, amp = 1.0f, scale = 1.0f;
    uint seed = c->seed ^ 0x5bd1e995u;
    vec3 u = v3_scale(centre, c->frequency.w), e = v3_scale(ext, c->frequency.w * 1.0001f);
    vec3 y = noise_rotate(u);
    vec3 cx = noise_rotate(v3(1.0f, 0.0f, 0.0f)), cy = noise_rotate(v3(0.0f, 1.0f, 0.0f));
    vec3 cz = noise_rotate(v3(0.0f, 0.0f, 1.0f));
    for (int i = 0; i < CLOUDS_COVERAGE_OCTAVES; i++) {
        vec3 mid = noise_octave_point(y, i);
        float m = clouds_grid_lattice_margin(mid);
        vec3 hw = v3_add(v3_scale(v3_add(v3_add(v3_scale(clouds_grid_abs(cx), e.x),
                                                  v3_scale(clouds_grid_abs(cy), e.y)),
                                           v3_scale(clouds_grid_abs(cz), e.z)),
                                    scale),
                           v3(m, m, m));
        sum += amp * clouds_grid_lattice_max(v3_sub(mid, hw), v3_add(mid, hw), seed + (uint)i);
        slope += amp * (hw.x + hw.y + hw.z);
        norm += amp;
        amp *= 0.5f;
        scale *= 2.0f;
        y = noise_rotate(v3_scale(y, 2.0f));
        cx = noise_rotate(cx), cy = noise_rotate(cy), cz = noise_rotate(cz);
    }
    /* (b): the fBm at the centre plus, per octave, its slope bound 15/8 per lattice unit along
     * each of its axes times its box's half-size (1e-5 for the rounding of the centre's value) */
    float n = noise_fbm(u, CLOUDS_COVERAGE_OCTAVES, seed);
    return fminf(sum / norm, n + 1.875f * slope / norm * 1.0001f + 1e-5f);
}

/* The bound on the density over cell (i, j, k) of the grid (see the top of the file). */
ATMO_FN float clouds_grid_cell_bound(ATMO_GLOBAL const atmo_gpu_scene *s,
                                     const clouds_grid_frame *f, int i, int j, int k)
{
    ATMO_GLOBAL const atmo_gpu_clouds *c = &s->clouds;
    float R = s->atmosphere.bottom_radius, m = CLOUDS_GRID_MARGIN_M;
    vec3 lo = v3_add(f->low, v3_mul(v3((float)i, (float)j, (float)k), f->cell));
    vec3 hi = v3_add(lo, f->cell);
    lo = v3_sub(lo, v3(m, m, m));
    hi = v3_add(hi, v3(m, m, m));
    /* the altitudes: nearest and farthest points to the centre, at (0, -R, 0) from the foot */
    float nx = clamp(0.0f, lo.x, hi.x), nz = clamp(0.0f, lo.z, hi.z);
    float fx = fmaxf(fabsf(lo.x), fabsf(hi.x)), fz = fmaxf(fabsf(lo.z), fabsf(hi.z));
    float h_lo = clouds_grid_altitude(R, nx * nx + nz * nz, lo.y) - CLOUDS_GRID_ALTITUDE_MARGIN_M;
    float h_hi = clouds_grid_altitude(R, fx * fx + fz * fz, hi.y) + CLOUDS_GRID_ALTITUDE_MARGIN_M;
    if (h_hi <= c->bottom_m || h_lo >= c->top_m)
        return 0.0f;
    float fade = clouds_fade(c, clamp(0.5f * (c->bottom_m + c->top_m), h_lo, h_hi));
    if (fade <= 0.0f)
        return 0.0f;
    /* the box in world noise coordinates: its centre plus its axis-aligned half-size */
    vec3 mid = v3_scale(v3_add(lo, hi), 0.5f), size = v3_scale(v3_sub(hi, lo), 0.5f);
    vec3 centre = v3_add(v3_add(v3_from4(c->origin), f->corner),
                         v3_add(v3_add(v3_scale(f->ax, mid.x - f->low.x),
                                       v3_scale(f->ay, mid.y - f->low.y)),
                                v3_scale(f->az, mid.z - f->low.z)));
    vec3 ext = v3_add(v3_add(v3_scale(v3(fabsf(f->ax.x), fabsf(f->ax.y), fabsf(f->ax.z)), size.x),
                             v3_scale(v3(fabsf(f->ay.x), fabsf(f->ay.y), fabsf(f->ay.z)), size.y)),
                      v3_scale(v3(fabsf(f->az.x), fabsf(f->az.y), fabsf(f->az.z)), size.z));
    float n = clouds_grid_coverage_fbm_bound(c, centre, ext);
    float field = clamp(CLOUDS_COVERAGE_CONTRAST * (n - 0.5f) + c->coverage, 0.0f, 1.0f);
    float cov = field * fade;
    return cov > 0.0f ? c->density * powf(cov, c->sharpness) * CLOUDS_GRID_ROUNDING : 0.0f;
}

/* A ray's walk through the grid's cells. */
typedef struct clouds_grid_walk {
    float t_in, t_out;     /* the ray's parameter range inside the box (t_in > t_out: none) */
    vec3 t_next, t_delta;  /* distance to the next boundary per axis; between boundaries */
    int i, j, k;           /* the current cell */
    int di, dj, dk;        /* the steps per axis (+-1, 0) */
} clouds_grid_walk;

/* One axis of the slab test and of the DDA's start: o, d the ray's coordinate and direction
 * along it in the box (from its corner), n cells of edge e. */
ATMO_FN void clouds_grid_axis(float o, float d, float e, int n, float *t0, float *t1)
{
    float L = e * (float)n;
    if (d == 0.0f) {
        if (o < 0.0f || o > L)
            *t0 = INFINITY, *t1 = -INFINITY;
        return;
    }
    float a = -o / d, b = (L - o) / d;
    *t0 = fmaxf(*t0, fminf(a, b));
    *t1 = fminf(*t1, fmaxf(a, b));
}

ATMO_FN int clouds_grid_start(float o, float d, float e, int n, float t, float *t_next,
                              float *t_delta, int *step)
{
    int c = clamp((int)floorf((o + d * t) / e), 0, n - 1);
    if (d > 0.0f) {
        *t_next = ((float)(c + 1) * e - o) / d, *t_delta = e / d, *step = 1;
    } else if (d < 0.0f) {
        *t_next = ((float)c * e - o) / d, *t_delta = -e / d, *step = -1;
    } else {
        *t_next = INFINITY, *t_delta = INFINITY, *step = 0;
    }
    return c;
}

/* The walk of the ray origin + t dir (camera-relative, dir unit) for t in [0, end]. */
ATMO_FN clouds_grid_walk clouds_grid_begin(const clouds_grid_frame *f, vec3 origin, vec3 dir,
                                           float end)
{
    clouds_grid_walk w;
    vec3 r = v3_sub(origin, f->corner);
    vec3 o = v3(v3_dot(r, f->ax), v3_dot(r, f->ay), v3_dot(r, f->az));
    vec3 d = v3(v3_dot(dir, f->ax), v3_dot(dir, f->ay), v3_dot(dir, f->az));
    w.t_in = 0.0f, w.t_out = end;
    clouds_grid_axis(o.x, d.x, f->cell.x, CLOUDS_GRID_NX, &w.t_in, &w.t_out);
    clouds_grid_axis(o.y, d.y, f->cell.y, CLOUDS_GRID_NY, &w.t_in, &w.t_out);
    clouds_grid_axis(o.z, d.z, f->cell.z, CLOUDS_GRID_NZ, &w.t_in, &w.t_out);
    w.i = w.j = w.k = 0;
    w.di = w.dj = w.dk = 0;
    w.t_next = w.t_delta = v3(INFINITY, INFINITY, INFINITY);
    if (w.t_in >= w.t_out)
        return w;
    /* the entry cell (clamped: the entry face's coordinate rounds to either side) */
    float nx, ny, nz, ex, ey, ez;
    w.i = clouds_grid_start(o.x, d.x, f->cell.x, CLOUDS_GRID_NX, w.t_in, &nx, &ex, &w.di);
    w.j = clouds_grid_start(o.y, d.y, f->cell.y, CLOUDS_GRID_NY, w.t_in, &ny, &ey, &w.dj);
    w.k = clouds_grid_start(o.z, d.z, f->cell.z, CLOUDS_GRID_NZ, w.t_in, &nz, &ez, &w.dk);
    w.t_next = v3(nx, ny, nz);
    w.t_delta = v3(ex, ey, ez);
    return w;
}

/* The segment of the ray that starts at t: its end in *seg_end and its density bound, the
 * current cell's, or -1 outside the box (before it: up to t_in; after it: to infinity). */
ATMO_FN float clouds_grid_segment(clouds_grid_walk *w, ATMO_GLOBAL const float *grid, float t,
                                  float *seg_end)
{
    if (w->t_in >= w->t_out || t >= w->t_out) {
        *seg_end = INFINITY;
        return -1.0f;
    }
    if (t < w->t_in) {
        *seg_end = w->t_in;
        return -1.0f;
    }
    /* cells the walk has passed (a boundary at or before t) are stepped over */
    for (;;) {
        float next = fminf(w->t_next.x, fminf(w->t_next.y, w->t_next.z));
        if (next > t || next >= w->t_out)
            break;
        if (w->t_next.x <= next)
            w->i += w->di, w->t_next.x += w->t_delta.x;
        else if (w->t_next.y <= next)
            w->j += w->dj, w->t_next.y += w->t_delta.y;
        else
            w->k += w->dk, w->t_next.z += w->t_delta.z;
    }
    if (w->i < 0 || w->i >= CLOUDS_GRID_NX || w->j < 0 || w->j >= CLOUDS_GRID_NY || w->k < 0 ||
        w->k >= CLOUDS_GRID_NZ) { /* rounding at the box's faces: the ray has left it */
        *seg_end = INFINITY;
        w->t_out = t;
        return -1.0f;
    }
    *seg_end = fminf(w->t_out, fminf(w->t_next.x, fminf(w->t_next.y, w->t_next.z)));
    return grid[(w->k * CLOUDS_GRID_NY + w->j) * CLOUDS_GRID_NX + w->i];
}

#endif
