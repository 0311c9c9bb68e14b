/* test_clouds_shadow_map — the fBm cloud layer's sun shadow map (kernels/clouds/cloud_shadow_map.h,
 * its pass cloud_shadow_map.cl; the lookup and the node points in host builds of the headers,
 * the map from the device's pass). Scene: thesis-6 (the sun 28 degrees high) with method march
 * and clouds.shadow_map, the marcher's far plane at 20 km so the map's cells are small.
 * labels: kernel render
 *
 * Oracle: D_fine, a double-precision midpoint quadrature of the density integral toward the
 * sun (cloud_layer.h's clouds_density, host build, bitwise the device's: test_cloud_noise) over
 * the whole chord from the point to the layer's top, FINE_STEPS uniform steps, the points and
 * their altitudes computed in double from the point's double-precision position; its own error
 * is taken as |D_fine - D_half| / 3 (D_half: half the steps; the midpoint rule's error falls 4
 * times per halving, so that difference is 3 times it).
 *   - nodes: at NODES random nodes of the device's map, the node's point rebuilt in double
 *     (the gnomonic frame of the file's top) and its rule (clouds.shadow_map_steps steps
 *     growing as (i/n)^2, midpoints) evaluated in double must match the node within the
 *     float rounding of its float sum and sample points: ROUND_REL of the sum of |d dt| plus
 *     the density's change over the sample points' rounding (their coordinates' ulp at the
 *     chord's scale and half an ulp of the node's float radius, which moves every sample's
 *     altitude, times the density's Lipschitz bound, printed) over the chord; the rule's
 *     error against D_fine (its step error) is printed for the default clouds and the smooth
 *     ones;
 *   - lookups, smooth clouds (one octave of 50 km features, no warp, a coverage field constant
 *     over the region: D is smooth on the cells' scale): at LOOKUPS random points in and below
 *     the layer, |D_map - D_fine| must stay below the trilinear interpolation's bound
 *         sum_a h_a^2 / 8 max |d^2 D / d a^2|
 *     (h_a the cell's edges along gnomonic X, Z and altitude), with the curvature per axis
 *     taken as CURVATURE_MARGIN times the largest second difference of D_fine along the
 *     cell's 4 edges of that axis (at their ends and midpoints), plus the largest error of the
 *     cell's 8 nodes against D_fine and D_fine's own error; the transmittance's error is at
 *     most extinction times that. RMS and worst |T_map - T_fine| are printed; for the default
 *     clouds they are printed at this resolution (the bench, atmo bench clouds, charts them);
 *   - a point outside the map (beyond its horizontal extent) gets the light march bit for bit;
 *   - the pass run twice gives the same map bit for bit; renders (16 x 12, 2 samples) with the
 *     map at tile sizes 8 and 64 are bitwise the same and hold no NaN/Inf (test_render);
 *   - a map over ATMO_CLOUDS_SHADOW_MAP_MAX_BYTES is refused with a usage error (exit 2). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "common/compat.h"
#include "common/geometry.h"
#include "clouds/cloud_shadow_map.h"
#include "media/ray.h"
#include "atmo/plan_clouds.h"
#include "testlib.h"
#include "testscene.h"

#define FINE_STEPS 2048
#define NODES 256
#define LOOKUPS 128
#define ROUND_REL 1e-5          /* 48-256 float additions of positive terms: n 2^-24 < 2e-5 */
#define CURVATURE_MARGIN 2.0    /* the cell's largest curvature over that of its edges */

typedef struct map_case {
    atmo_plan plan;
    float *map;
    size_t nodes;
    double R, E, r_c, bottom, top, k; /* k: the green extinction per unit density */
} map_case;

/* The double-precision frame of a camera-relative point at gnomonic (X, Z) and altitude h. */
static void point_at(const map_case *m, const clouds_grid_frame *f, double X, double Z, double h,
                     double p[3], double dir[3])
{
    double R = m->R, n = sqrt(X * X + R * R + Z * Z);
    const float *ax = &f->ax.x, *ay = &f->ay.x, *az = &f->az.x;
    for (int a = 0; a < 3; a++) {
        dir[a] = (X * ax[a] + R * ay[a] + Z * az[a]) / n;
        p[a] = (R + h) * dir[a] - m->r_c * ay[a];
    }
}

static double density_at(const atmo_gpu_scene *s, const double x[3], double h)
{
    return clouds_density(&s->clouds, v3((float)x[0], (float)x[1], (float)x[2]), (float)h);
}

/* The altitude of p + t dir (dir unit, mu_s its cosine to the vertical at p of radius r). */
static double altitude(double R, double r, double mu_s, double t)
{
    double rt = sqrt(r * r + 2.0 * r * mu_s * t + t * t);
    return (t * (t + 2.0 * r * mu_s) + (r - R) * (r + R)) / (rt + R);
}

/* D over [0, chord to the top] from p (radius r, sun cosine mu_s) by n uniform midpoint steps;
 * from below the layer the chord starts where the ray enters it. */
static double fine_depth(const map_case *m, const double p[3], double h, double mu_s, int n)
{
    const atmo_gpu_scene *s = &m->plan.gpu;
    double R = m->R, r = R + h, top = R + m->top, bottom = R + m->bottom;
    const float *sun = &s->sun_direction.x;
    double t0 = h < m->bottom ? -r * mu_s + sqrt(r * r * mu_s * mu_s - r * r + bottom * bottom)
                              : 0.0;
    double t1 = -r * mu_s + sqrt(r * r * mu_s * mu_s - r * r + top * top);
    double dt = (t1 - t0) / n, D = 0.0;
    for (int j = 0; j < n; j++) {
        double t = t0 + (j + 0.5) * dt, x[3];
        for (int a = 0; a < 3; a++)
            x[a] = p[a] + t * sun[a];
        D += density_at(s, x, altitude(R, r, mu_s, t)) * dt;
    }
    return D;
}

/* The node's rule (clouds_sun_density_steps with jitter 1/2, whole chord) in double; *abs_sum
 * the sum of |d dt|, *chord its length. */
static double rule_depth(const map_case *m, const double p[3], double h, double mu_s, int n,
                         double *abs_sum, double *chord)
{
    const atmo_gpu_scene *s = &m->plan.gpu;
    double R = m->R, r = R + h, top = R + m->top;
    const float *sun = &s->sun_direction.x;
    double len = fmax(-r * mu_s + sqrt(r * r * mu_s * mu_s - r * r + top * top), 0.0), D = 0.0;
    *abs_sum = 0.0, *chord = len;
    for (int i = 0; i < n; i++) {
        double x0 = (double)i / n, x1 = (double)(i + 1) / n;
        double dt = len * (x1 * x1 - x0 * x0), t = len * x0 * x0 + 0.5 * dt, x[3];
        for (int a = 0; a < 3; a++)
            x[a] = p[a] + t * sun[a];
        double d = density_at(s, x, altitude(R, r, mu_s, t));
        D += d * dt, *abs_sum += fabs(d) * dt;
    }
    return D;
}

static float uniform(uint i, uint d) { return rng_uniform(7u, i, 0u, d); }

static void open_case(map_case *m, const char *const *sets, atmo_cl *cl, int twice)
{
    atmo_scene sc;
    test_scene_preset(&sc, "thesis-6");
    test_scene_set(&sc, "atmosphere.method=march");
    test_scene_set(&sc, "image.width=8");
    test_scene_set(&sc, "image.height=8");
    test_scene_set(&sc, "clouds.max_distance_m=20000");
    test_scene_set(&sc, "clouds.shadow_map=true");
    for (int i = 0; sets[i]; i++)
        test_scene_set(&sc, sets[i]);
    test_plan(&sc, &m->plan);
    const atmo_gpu_scene *s = &m->plan.gpu;
    cl_program prog = test_plan_program(cl, &m->plan, "");
    cl_mem scene = test_cl_buffer(cl, sizeof m->plan.gpu, &m->plan.gpu);
    cl_mem luts[ATMO_PLAN_MAX_BUFFERS] = {0};
    int n = s->clouds.shadow_map_size;
    m->nodes = (size_t)n * (size_t)n * (size_t)s->clouds.shadow_map_levels;
    m->map = malloc(sizeof(float) * m->nodes);
    CHECK(m->map != NULL);
    test_precompute(cl, prog, scene, &m->plan, luts);
    test_cl_read(cl, test_plan_buffer(&m->plan, luts, "clouds_shadow_map"),
                 sizeof(float) * m->nodes, m->map);
    if (twice) {
        cl_mem again[ATMO_PLAN_MAX_BUFFERS] = {0};
        float *map2 = malloc(sizeof(float) * m->nodes);
        CHECK(map2 != NULL);
        test_precompute(cl, prog, scene, &m->plan, again);
        test_cl_read(cl, test_plan_buffer(&m->plan, again, "clouds_shadow_map"),
                     sizeof(float) * m->nodes, map2);
        CHECK(memcmp(m->map, map2, sizeof(float) * m->nodes) == 0);
        free(map2);
        test_release_luts(again);
    }
    test_release_luts(luts);
    clReleaseMemObject(scene);
    clReleaseProgram(prog);
    m->R = s->atmosphere.bottom_radius;
    m->E = clouds_shadow_map_extent(s);
    m->r_c = s->camera.local_up.w;
    m->bottom = s->clouds.bottom_m, m->top = s->clouds.top_m;
    m->k = s->clouds.extinction.y;
}

/* A Lipschitz bound on the density (1/m), as cloud_majorant.h's (b) bounds the noise: value
 * noise moves by at most 15/8 per lattice unit and axis, so the shape fBm by 15/8 f sum_i a_i
 * 2^i / sum_i a_i per metre (f its largest base frequency), times 1 + the warp's slope
 * (warp_m 2 15/8 f/4 per axis), the coverage by C 15/8 f_c (4 octaves: 4 / 1.875) plus the
 * fade's 1.5 / fade_m; times density x sharpness ((cov - fbm)^(sharpness - 1) <= 1 for
 * sharpness >= 1) and sqrt(3) for the axes. */
static double density_lipschitz(const atmo_gpu_clouds *c)
{
    double sum = 0.0, norm = 0.0, amp = 1.0, scale = 1.0;
    for (int i = 0; i < c->octaves; i++)
        sum += amp * scale, norm += amp, amp *= 0.5, scale *= 2.0;
    double f = fmax(c->frequency.x, fmax(c->frequency.y, c->frequency.z));
    double shape = 1.875 * f * sum / norm * (1.0 + c->warp_m * 2.0 * 1.875 * 0.25 * f * sqrt(3.0));
    double cover = 3.0 * 1.875 * c->frequency.w * 4.0 / 1.875 + 1.5 / c->fade_m;
    return c->density * c->sharpness * (shape + cover) * sqrt(3.0);
}

/* The nodes against their rule in double (a failure count) and the rule against D_fine. */
static int check_nodes(const map_case *m, const char *what)
{
    const atmo_gpu_scene *s = &m->plan.gpu;
    clouds_grid_frame f = clouds_grid_frame_make(s);
    int n = s->clouds.shadow_map_size, L = s->clouds.shadow_map_levels, bad = 0;
    double G = density_lipschitz(&s->clouds), worst = 0.0, sq = 0.0, worst_step = 0.0;
    double sq_step = 0.0, scale = 0.0;
    for (int q = 0; q < NODES; q++) {
        int i = (int)(uniform((uint)q, 0) * n) % n, k = (int)(uniform((uint)q, 1) * n) % n;
        int j = (int)(uniform((uint)q, 2) * L) % L;
        double X = -m->E + 2.0 * m->E * i / (n - 1), Z = -m->E + 2.0 * m->E * k / (n - 1);
        double h = m->bottom + (m->top - m->bottom) * j / (L - 1), p[3], dir[3], abs_sum, chord;
        point_at(m, &f, X, Z, h, p, dir);
        double mu_s = dir[0] * s->sun_direction.x + dir[1] * s->sun_direction.y +
                      dir[2] * s->sun_direction.z;
        double rule = rule_depth(m, p, h, mu_s, s->clouds.shadow_map_steps, &abs_sum, &chord);
        double node = m->map[((size_t)j * n + k) * n + i];
        /* the float sample points: coordinates up to |p| + chord, 2 ulp each, and the node's
         * own point (the gnomonic frame in float), as many again; their altitudes: the node's
         * radius R + h in float (half an ulp of it) shifts them all */
        double round_point = 4.0 * (sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) + chord) *
                                 ldexp(1.0, -24) +
                             0.5 * ldexp(1.0, ilogb(m->R + h) - 23);
        double tol = ROUND_REL * abs_sum + G * round_point * chord;
        double err = fabs(node - rule);
        if (err > tol && bad++ < 3)
            printf("%s node (%d, %d, %d): %.6g m, its rule in double %.6g m, tolerance %.3g m\n",
                   what, i, j, k, node, rule, tol);
        worst = fmax(worst, err / fmax(tol, 1e-30)), sq += err * err;
        double fine = fine_depth(m, p, h, mu_s, FINE_STEPS);
        worst_step = fmax(worst_step, fabs(node - fine));
        sq_step += (node - fine) * (node - fine), scale += fine * fine;
    }
    printf("%s: %d nodes, RMS |node - its rule in double| %.3g m (worst %.2f of its tolerance, "
           "Lipschitz %.3g 1/m); the %d-step rule against D_fine: RMS %.3g m, worst %.3g m, RMS "
           "D_fine %.3g m\n",
           what, NODES, sqrt(sq / NODES), worst, G, s->clouds.shadow_map_steps,
           sqrt(sq_step / NODES), worst_step, sqrt(scale / NODES));
    return bad;
}

/* D_fine at gnomonic (X, Z) and altitude h, and its error estimate. */
static double fine_at(const map_case *m, const clouds_grid_frame *f, double X, double Z, double h,
                      double *err)
{
    const atmo_gpu_scene *s = &m->plan.gpu;
    double p[3], dir[3];
    point_at(m, f, X, Z, h, p, dir);
    double mu_s =
        dir[0] * s->sun_direction.x + dir[1] * s->sun_direction.y + dir[2] * s->sun_direction.z;
    double D = fine_depth(m, p, h, mu_s, FINE_STEPS);
    if (err)
        *err = fabs(D - fine_depth(m, p, h, mu_s, FINE_STEPS / 2)) / 3.0;
    return D;
}

/* The trilinear bound at a point of cell (i, j, k) (see the top of the file). */
static double trilinear_bound(const map_case *m, const clouds_grid_frame *f, int i, int j, int k)
{
    const atmo_gpu_scene *s = &m->plan.gpu;
    int n = s->clouds.shadow_map_size, L = s->clouds.shadow_map_levels;
    double hx = 2.0 * m->E / (n - 1), hv = (m->top - m->bottom) / (L - 1);
    double x0 = -m->E + hx * i, z0 = -m->E + hx * k, v0 = m->bottom + hv * j;
    double curv[3] = {0.0, 0.0, 0.0}, node_err = 0.0, e;
    for (int b = 0; b < 2; b++)
        for (int c = 0; c < 2; c++) {
            double ends[3][3][3]; /* axis, which (lo, mid, hi), the point (X, Z, h) */
            for (int w = 0; w < 3; w++) {
                double t = 0.5 * w;
                double pts[3][3] = {{x0 + hx * t, z0 + hx * b, v0 + hv * c},
                                    {x0 + hx * b, z0 + hx * t, v0 + hv * c},
                                    {x0 + hx * b, z0 + hx * c, v0 + hv * t}};
                memcpy(ends[0][w], pts[0], sizeof pts[0]);
                memcpy(ends[1][w], pts[1], sizeof pts[1]);
                memcpy(ends[2][w], pts[2], sizeof pts[2]);
            }
            const double h_a[3] = {hx, hx, hv};
            for (int a = 0; a < 3; a++) {
                double D[3];
                for (int w = 0; w < 3; w++)
                    D[w] = fine_at(m, f, ends[a][w][0], ends[a][w][1], ends[a][w][2], NULL);
                double second = fabs(D[0] - 2.0 * D[1] + D[2]) / (0.25 * h_a[a] * h_a[a]);
                curv[a] = fmax(curv[a], second);
            }
        }
    for (int c = 0; c < 8; c++) {
        int di = c & 1, dj = (c >> 1) & 1, dk = c >> 2;
        double D = fine_at(m, f, x0 + hx * di, z0 + hx * dk, v0 + hv * dj, &e);
        double node = m->map[((size_t)(j + dj) * n + (k + dk)) * n + (i + di)];
        node_err = fmax(node_err, fabs(node - D) + e);
    }
    return CURVATURE_MARGIN * (hx * hx * (curv[0] + curv[1]) + hv * hv * curv[2]) / 8.0 +
           node_err;
}

/* Lookups at random points in and below the layer against D_fine; with `bounded` each must
 * lie within the trilinear bound (a failure count). */
static int check_lookups(const map_case *m, const char *what, int bounded)
{
    const atmo_gpu_scene *s = &m->plan.gpu;
    clouds_grid_frame f = clouds_grid_frame_make(s);
    int n = s->clouds.shadow_map_size, L = s->clouds.shadow_map_levels, bad = 0;
    double hx = 2.0 * m->E / (n - 1), hv = (m->top - m->bottom) / (L - 1);
    double sq = 0.0, worst = 0.0, worst_ratio = 0.0;
    for (int q = 0; q < LOOKUPS; q++) {
        double X = (uniform((uint)q, 10) * 1.8 - 0.9) * m->E;
        double Z = (uniform((uint)q, 11) * 1.8 - 0.9) * m->E;
        /* a quarter below the layer (the terrain's and the low air's shadows) */
        double h = q % 4 == 0 ? uniform((uint)q, 12) * m->bottom
                              : m->bottom + uniform((uint)q, 12) * (m->top - m->bottom);
        double p[3], dir[3], e;
        point_at(m, &f, X, Z, h, p, dir);
        medium_point pt;
        pt.p = v3((float)p[0], (float)p[1], (float)p[2]);
        pt.r = (float)(m->R + h), pt.h = (float)h, pt.mu = 1.0f;
        double mu_s =
            dir[0] * s->sun_direction.x + dir[1] * s->sun_direction.y + dir[2] * s->sun_direction.z;
        pt.mu_s = (float)mu_s;
        double D_map = clouds_shadow_map_density(s, m->map, &pt);
        double D = fine_at(m, &f, X, Z, h, &e);
        double dT = fabs(exp(-m->k * D_map) - exp(-m->k * D));
        sq += dT * dT, worst = fmax(worst, dT);
        if (!bounded)
            continue;
        /* the cell: from below the layer, the one where the sun's ray enters it */
        double Xc = X, Zc = Z, hc = h;
        if (h < m->bottom) {
            double r = m->R + h, A = m->R + m->bottom;
            double t = -r * mu_s + sqrt(r * r * mu_s * mu_s - r * r + A * A), x[3];
            for (int a = 0; a < 3; a++)
                x[a] = p[a] + m->r_c * (&f.ay.x)[a] + t * (&s->sun_direction.x)[a];
            double vy = x[0] * f.ay.x + x[1] * f.ay.y + x[2] * f.ay.z;
            Xc = m->R * (x[0] * f.ax.x + x[1] * f.ax.y + x[2] * f.ax.z) / vy;
            Zc = m->R * (x[0] * f.az.x + x[1] * f.az.y + x[2] * f.az.z) / vy;
            hc = m->bottom;
        }
        int i = (int)((Xc + m->E) / hx), k = (int)((Zc + m->E) / hx), j = (int)((hc - m->bottom) / hv);
        i = i < n - 2 ? i : n - 2, k = k < n - 2 ? k : n - 2, j = j < L - 2 ? j : L - 2;
        double bound = trilinear_bound(m, &f, i, j, k) + e;
        double ratio = fabs(D_map - D) / bound;
        worst_ratio = fmax(worst_ratio, ratio);
        if (ratio > 1.0 && bad++ < 3)
            printf("%s lookup at (%.0f, %.0f, %.0f m): D map %.6g m, D_fine %.6g m, bound %.3g m\n",
                   what, X, Z, h, D_map, D, bound);
    }
    printf("%s: map %d x %d x %d (cells %.0f x %.0f m), %d lookups: |T_map - T_fine| RMS %.4f, "
           "worst %.4f",
           what, n, L, n, hx, hv, LOOKUPS, sqrt(sq / LOOKUPS), worst);
    if (bounded)
        printf("; worst |D_map - D_fine| %.2f of its trilinear bound", worst_ratio);
    printf("\n");
    return bad;
}

/* A point beyond the map's horizontal extent takes the light march. */
static void check_fallback(const map_case *m)
{
    const atmo_gpu_scene *s = &m->plan.gpu;
    clouds_grid_frame f = clouds_grid_frame_make(s);
    double p[3], dir[3], h = 0.5 * (m->bottom + m->top);
    point_at(m, &f, 1.5 * m->E, 0.0, h, p, dir);
    medium_point q;
    q.p = v3((float)p[0], (float)p[1], (float)p[2]);
    q.r = (float)(m->R + h), q.h = (float)h, q.mu = 1.0f;
    q.mu_s = (float)(dir[0] * s->sun_direction.x + dir[1] * s->sun_direction.y +
                     dir[2] * s->sun_direction.z);
    float march = clouds_sun_density(s, &q, clouds_point_jitter(q.p, s->clouds.seed));
    CHECK(clouds_shadow_map_density(s, m->map, &q) == march);
}

static void check_renders(void)
{
    atmo_scene sc;
    test_scene_preset(&sc, "thesis-6");
    test_scene_set(&sc, "atmosphere.method=march");
    test_scene_set(&sc, "image.width=16");
    test_scene_set(&sc, "image.height=12");
    test_scene_set(&sc, "image.samples=2");
    test_scene_set(&sc, "clouds.steps=64");
    test_scene_set(&sc, "clouds.max_distance_m=20000");
    test_scene_set(&sc, "clouds.shadow_map=true");
    test_scene_set(&sc, "clouds.shadow_map_size=32");
    test_scene_set(&sc, "clouds.shadow_map_levels=8");
    test_scene_set(&sc, "clouds.shadow_map_steps=16");
    test_image a = test_render(&sc, 8, 1), b = test_render(&sc, 64, 64);
    CHECK(memcmp(a.mean, b.mean, sizeof(float) * 3 * 16 * 12) == 0);
    test_image_free(&a);
    test_image_free(&b);

    atmo_plan p;
    atmo_err e;
    test_scene_set(&sc, "clouds.shadow_map_size=4096");
    test_scene_set(&sc, "clouds.shadow_map_levels=16");
    CHECK(atmo_plan_make(&sc, &p, &e) == ATMO_ERR_USAGE);
    printf("refused: %s\n", e.msg);
}

int main(void)
{
    atmo_cl cl;
    test_cl_open(&cl);
    int bad = 0;
    static const char *const smooth[] = {
        "clouds.octaves=1",           "clouds.warp_m=0",         "clouds.coverage_scale_m=1e8",
        "clouds.coverage=1",          "clouds.sharpness=1",      "clouds.density=0.5",
        "clouds.frequency_per_m=2e-5,4e-5,2e-5",                 "clouds.shadow_map_size=64",
        "clouds.shadow_map_levels=16", "clouds.shadow_map_steps=128", NULL};
    static const char *const defaults[] = {"clouds.shadow_map_size=96",
                                           "clouds.shadow_map_levels=24", NULL};
    map_case m;
    open_case(&m, smooth, &cl, 1);
    bad += check_nodes(&m, "smooth clouds");
    bad += check_lookups(&m, "smooth clouds", 1);
    free(m.map);
    atmo_plan_free(&m.plan);
    open_case(&m, defaults, &cl, 0);
    bad += check_nodes(&m, "default clouds");
    check_lookups(&m, "default clouds", 0);
    check_fallback(&m);
    free(m.map);
    atmo_plan_free(&m.plan);
    CHECK(bad == 0);
    check_renders();
    atmo_cl_close(&cl);
    return test_finish();
}
