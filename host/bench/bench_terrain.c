/* bench_terrain.c — `atmo bench terrain`: the terrain's shortcuts, each error against time.
 *
 * thesis-1 here is the preset without its clouds (the terrain's costs alone), in method fast
 * unless a row names another.
 * Rows (DIR/terrain.csv, chart DIR/terrain.svg; DIR/terrain_thesis1.csv for the timings):
 *   heightmap-float N, heightmap-derivatives N, heightmap-half N, direct: the height field's
 *     RMS error in metres
 *     against the double-precision reference (host/terrain/terrain_ref.c) at 4000 random points
 *     of the heightmap's square (65.5 km, the thesis site inside it) — for a heightmap, the
 *     bilinear interpolation of its texels (the reference at the texel centres: the pass writes
 *     those within float rounding, test_terrain_noise; the half format their rounding to half,
 *     bitwise as the pass stores them, test_terrain_half), for direct the kernels' float fBm
 *     compiled on the host; the settings name the device memory. Seconds: precompute + render
 *     of thesis-1 at 64x36, 1 sample, method single, without shadows or shafts, on the device.
 *     The normals' RMS angle error (degrees) is the second row of each size ("-normal").
 *   optimism W, steps N: sphere tracing (the kernels' tracer compiled on the host) of 600
 *     grazing rays from 2..50 m above the thesis site, against the brute-force double march:
 *     error = (misses + pass-throughs + bad hits) / reference hits (test_terrain_trace's
 *     classes), seconds = host time of the 600 traces.
 *   shadow-exact N, shadow-estimate: the visible fraction of the sun disc at 300 surface
 *     points at thesis-1's sun (2.3 degrees high) against exact shadows with 64 rays; error =
 *     RMS difference, seconds = host time.
 *   shafts, shafts away: thesis-1 at 96x54, 1 sample, method march, as it is and turned away
 *     from the sun (yaw + 180 degrees), with no light-shaft shortcut (the exact march, every
 *     sample asks the terrain), each of the six alone (kernels/terrain/terrain_shafts.h), the
 *     default set and all six: RMS relative difference from the exact march, and CPU seconds of
 *     the render (the process's, its device threads included: load on the machine does not
 *     stretch it; less those of the same render at 1x1 pixel, what does not grow with
 *     pixels); also DIR/terrain_shafts.csv and its chart DIR/terrain_shafts.svg.
 * terrain_thesis1.csv: thesis-1's render time per sample at 320x180 (64x36 with --quick),
 * scaled to 1280x720 by the pixel count, wall seconds of the render and net CPU seconds (as
 * for the shafts rows; idle, the 2 cores take about half the CPU seconds in wall time), in
 * preview (the preset without its clouds in method fast, 4 shadow rays, the default shortcuts)
 * and quality (method
 * march, 16 shadow rays), built
 * up from the sky alone: the terrain without shadows or shafts, with the surface's shadows,
 * with exact shafts, with the default shortcuts. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "atmo/bench.h"
#include "atmo/clock.h"
#include "atmo/plan.h"
#include "atmo/plan_terrain.h"
#include "atmo/scene.h"
#include "atmo/terrain_ref.h"
#include "terrain/terrain.h"

#define SITE_X 23796.0
#define SITE_Z 16636.0
#define MAX_ROWS 80

static double urand(unsigned *state)
{
    *state = *state * 1664525u + 1013904223u;
    return (*state >> 8) / 16777216.0;
}

static int set(atmo_scene *s, const char *kv, atmo_err *e)
{
    return atmo_scene_assign(s, kv, "bench", e);
}

/* thesis-1 without its clouds, in method fast: the terrain's costs alone */
static int thesis(atmo_scene *s, atmo_err *e)
{
    int rc;
    atmo_scene_defaults(s);
    if ((rc = atmo_scene_apply_preset(s, "thesis-1", e)) ||
        (rc = set(s, "clouds.enabled=false", e)))
        return rc;
    return set(s, "atmosphere.method=fast", e);
}

/* The bilinear heightmap of N texels over the extent (the reference at the centres, rounded to
 * float or with `half` to a half float as the pass stores it). */
static double map_height(const atmo_gpu_terrain_field *f, int n, double u, double v, int deriv,
                         int half, double *du, double *dv)
{
    double E = (double)f->heightmap_extent_m, d = E / n;
    double gx = (u + 0.5 * E) / d - 0.5, gy = (v + 0.5 * E) / d - 0.5;
    double i0 = floor(gx), j0 = floor(gy), fx = gx - i0, fy = gy - j0, h = 0, a = 0, b = 0;
    for (int di = 0; di < 2; di++)
        for (int dj = 0; dj < 2; dj++) {
            double g[2], w = (di ? fx : 1 - fx) * (dj ? fy : 1 - fy);
            double x = -0.5 * E + (i0 + di + 0.5) * d, z = -0.5 * E + (j0 + dj + 0.5) * d;
            float t = (float)terrain_ref_height(f, x, z, g, NULL);
            h += w * (double)(half ? terrain_half_to_float(terrain_half_from_float(t)) : t);
            a += w * g[0], b += w * g[1];
        }
    if (!deriv) { /* central differences one texel apart, as terrain.h takes them */
        double hxp = map_height(f, n, u + d, v, 1, half, NULL, NULL);
        double hxm = map_height(f, n, u - d, v, 1, half, NULL, NULL);
        double hzp = map_height(f, n, u, v + d, 1, half, NULL, NULL);
        double hzm = map_height(f, n, u, v - d, 1, half, NULL, NULL);
        a = (hxp - hxm) / (2 * d), b = (hzp - hzm) / (2 * d);
    }
    if (du)
        *du = a, *dv = b;
    return h;
}

static double angle_deg(double a0, double b0, double a1, double b1)
{
    double n0[3] = {-a0, 1, -b0}, n1[3] = {-a1, 1, -b1};
    double c = (n0[0] * n1[0] + n0[1] * n1[1] + n0[2] * n1[2]) /
               sqrt((n0[0] * n0[0] + 1 + n0[2] * n0[2]) * (n1[0] * n1[0] + 1 + n1[2] * n1[2]));
    return acos(fmin(c, 1.0)) * 180.0 / M_PI;
}

/* precompute: whether the seconds include the precompute passes (the heightmap's) */
static int timed_render(const atmo_scene *s, const char *device, int precompute, double *seconds,
                        atmo_render_result *out, atmo_err *e)
{
    atmo_render_result r;
    int rc = bench_render(s, device, &r, e);
    if (rc)
        return rc;
    *seconds = (precompute ? r.seconds_precompute : 0.0) + r.seconds_render;
    if (out)
        *out = r;
    else
        atmo_render_result_free(&r);
    return ATMO_OK;
}

static int heightmaps(const char *device, int quick, bench_row *rows, int *n, atmo_err *e)
{
    static const int sizes[] = {256, 1024, 4096};
    int count = quick ? 2 : 3, rc;
    static const char *const names[] = {"heightmap-float", "heightmap-derivatives",
                                        "heightmap-half"};
    for (int fmt = -1; fmt <= ATMO_TERRAIN_FORMAT_HALF; fmt++)
        for (int k = 0; k < (fmt < 0 ? 1 : count); k++) {
            atmo_scene s;
            if ((rc = thesis(&s, e)) || (rc = set(&s, "atmosphere.method=single", e)) ||
                (rc = set(&s, "terrain.shadow=none", e)) ||
                (rc = set(&s, "terrain.shadow_far_m=1", e)))
                return rc;
            s.image.width = 64, s.image.height = 36, s.image.samples = 1;
            s.terrain.heightmap_size = fmt < 0 ? 0 : sizes[k];
            s.terrain.heightmap_format = fmt < 0 ? 0 : fmt;
            atmo_plan p;
            if ((rc = atmo_plan_make(&s, &p, e)))
                return rc;
            atmo_gpu_terrain_field f = p.gpu.terrain.field;
            atmo_plan_free(&p);
            double seconds;
            fprintf(stderr, "bench terrain: heightmap %d format %d\n", s.terrain.heightmap_size, fmt);
            if ((rc = timed_render(&s, device, 1, &seconds, NULL, e)))
                return rc;
            unsigned rng = 5u;
            double sum = 0, sum_a = 0;
            int m = quick ? 500 : 4000;
            for (int i = 0; i < m; i++) {
                double E = (double)f.heightmap_extent_m;
                double u = (urand(&rng) - 0.5) * 0.95 * E, v = (urand(&rng) - 0.5) * 0.95 * E;
                double g[2], h = terrain_ref_height(&f, u, v, g, NULL), got, a, b;
                if (fmt < 0) {
                    terrain_height t = terrain_height_direct(&f, (float)u, (float)v);
                    got = t.h, a = t.du, b = t.dv;
                } else {
                    got = map_height(&f, s.terrain.heightmap_size, u, v,
                                     fmt == ATMO_TERRAIN_FORMAT_DERIVATIVES,
                                     fmt == ATMO_TERRAIN_FORMAT_HALF, &a, &b);
                }
                sum += (got - h) * (got - h);
                double ang = angle_deg(a, b, g[0], g[1]);
                sum_a += ang * ang;
            }
            size_t bytes = (size_t)s.terrain.heightmap_size * s.terrain.heightmap_size *
                           (fmt == ATMO_TERRAIN_FORMAT_DERIVATIVES ? 12
                            : fmt == ATMO_TERRAIN_FORMAT_HALF      ? 2
                                                                   : 4);
            for (int r = 0; r < 2; r++) {
                bench_row *row = &rows[(*n)++];
                snprintf(row->method, sizeof row->method, "%s%s",
                         fmt < 0 ? "direct" : names[fmt],
                         r ? "-normal" : "");
                snprintf(row->settings, sizeof row->settings, "%d texels %.1f MiB",
                         s.terrain.heightmap_size, bytes / 1048576.0);
                row->seconds = seconds;
                row->error = sqrt((r ? sum_a : sum) / m);
            }
        }
    return ATMO_OK;
}

typedef struct trace_set {
    double o[600][3], d[600][3];
    int ref[600];
    double t_ref[600];
} trace_set;

static int tracing(int quick, bench_row *rows, int *n, atmo_err *e)
{
    atmo_scene s;
    atmo_plan p;
    int rc;
    if ((rc = thesis(&s, e)) || (rc = atmo_plan_make(&s, &p, e)))
        return rc;
    double R = s.atmosphere.bottom_radius_m, *cam = s.camera.position_m;
    atmo_gpu_scene g = p.gpu;
    atmo_plan_free(&p);
    trace_set *ts = malloc(sizeof *ts);
    if (!ts)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory");
    int m = quick ? 150 : 600;
    unsigned rng = 31u;
    fprintf(stderr, "bench terrain: %d reference rays\n", m);
    for (int i = 0; i < m; i++) {
        double x = SITE_X + (urand(&rng) - 0.5) * 4000, z = SITE_Z + (urand(&rng) - 0.5) * 4000;
        double h = terrain_ref_height(&g.terrain.field, x, z, NULL, NULL);
        double nv[3] = {x / R, sqrt(1 - (x * x + z * z) / (R * R)), z / R};
        double above = 2 + 48 * urand(&rng), mu = -0.05 + 0.07 * urand(&rng);
        double phi = 2 * M_PI * urand(&rng), e1[3] = {cos(phi), 0, sin(phi)};
        double k = e1[0] * nv[0] + e1[2] * nv[2], len = 0, w[3];
        for (int c = 0; c < 3; c++)
            e1[c] -= k * nv[c], len += e1[c] * e1[c];
        for (int c = 0; c < 3; c++) {
            w[c] = nv[c] * (R + h + above) - (c == 1 ? R : 0);
            ts->d[i][c] = (double)(float)(e1[c] / sqrt(len) * sqrt(1 - mu * mu) + mu * nv[c]);
            ts->o[i][c] = (double)(float)(w[c] - cam[c]);
        }
        double wo[3], mc;
        for (int c = 0; c < 3; c++)
            wo[c] = cam[c] + ts->o[i][c];
        ts->ref[i] = terrain_ref_hit(&g.terrain.field, R, 0.0, wo, ts->d[i], 8000.0, 2.0,
                                     &ts->t_ref[i], &mc);
    }
    static const double omegas[] = {1, 1.5, 2, 3, 4, 6, 8};
    static const int steps[] = {16, 32, 64, 128, 300};
    for (int pass = 0; pass < 2; pass++)
        for (int k = 0; k < (pass ? 5 : 7); k++) {
            atmo_gpu_scene gs = g;
            if (pass)
                gs.terrain.steps = steps[k];
            else
                gs.terrain.optimism = (float)omegas[k];
            int hits = 0, bad = 0;
            double t0 = atmo_now_seconds();
            for (int i = 0; i < m; i++) {
                float tf;
                vec3 o = v3((float)ts->o[i][0], (float)ts->o[i][1], (float)ts->o[i][2]);
                vec3 d = v3((float)ts->d[i][0], (float)ts->d[i][1], (float)ts->d[i][2]);
                int hit = terrain_trace(&gs, NULL, o, d, 0.0f, 8000.0f, gs.terrain.steps, &tf, 0);
                double t = (double)tf;
                hits += ts->ref[i];
                if (ts->ref[i] && !hit) {
                    bad++;
                } else if (hit) {
                    double w[3];
                    for (int c = 0; c < 3; c++)
                        w[c] = cam[c] + ts->o[i][c] + t * ts->d[i][c];
                    double gclr = terrain_ref_clearance(&g.terrain.field, R, 0.0, w);
                    double eps = 0.01 + (double)gs.terrain.tolerance * t;
                    bad += gclr < -0.5 || gclr > eps + 0.5 ||
                           (ts->ref[i] && t > ts->t_ref[i] + 5.0 + 1e-3 * ts->t_ref[i]);
                }
            }
            bench_row *row = &rows[(*n)++];
            snprintf(row->method, sizeof row->method, pass ? "steps" : "optimism");
            snprintf(row->settings, sizeof row->settings, pass ? "%.0f (optimism 3)" : "%.1f (300 steps)",
                     pass ? (double)steps[k] : omegas[k]);
            row->seconds = atmo_now_seconds() - t0;
            row->error = hits ? (double)bad / hits : 0.0;
        }
    free(ts);
    return ATMO_OK;
}

static int shadows(int quick, bench_row *rows, int *n, atmo_err *e)
{
    atmo_scene s;
    atmo_plan p;
    int rc;
    if ((rc = thesis(&s, e)) || (rc = atmo_plan_make(&s, &p, e)))
        return rc;
    double R = s.atmosphere.bottom_radius_m, *cam = s.camera.position_m;
    atmo_gpu_scene g = p.gpu;
    atmo_plan_free(&p);
    int m = quick ? 60 : 300;
    vec3 *pts = malloc(sizeof *pts * (size_t)m);
    float *exact = malloc(sizeof *exact * (size_t)m);
    if (!pts || !exact) {
        free(pts), free(exact);
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory");
    }
    unsigned rng = 77u;
    for (int i = 0; i < m; i++) {
        double x = SITE_X + (urand(&rng) - 0.5) * 8000, z = SITE_Z + (urand(&rng) - 0.5) * 8000;
        double h = terrain_ref_height(&g.terrain.field, x, z, NULL, NULL) + 0.2;
        double nv[3] = {x / R, sqrt(1 - (x * x + z * z) / (R * R)), z / R}, w[3];
        for (int c = 0; c < 3; c++)
            w[c] = nv[c] * (R + h) - (c == 1 ? R : 0) - cam[c];
        pts[i] = v3((float)w[0], (float)w[1], (float)w[2]);
    }
    atmo_gpu_scene gs = g;
    gs.terrain.shadow = ATMO_TERRAIN_SHADOW_EXACT;
    gs.terrain.shadow_rays = 64;
    fprintf(stderr, "bench terrain: exact shadows with 64 rays at %d points\n", m);
    for (int i = 0; i < m; i++)
        exact[i] = terrain_sun_visible(&gs, NULL, pts[i], 0.0f);
    static const int counts[] = {1, 4, 16};
    for (int k = 0; k < 4; k++) {
        gs = g;
        gs.terrain.shadow = k < 3 ? ATMO_TERRAIN_SHADOW_EXACT : ATMO_TERRAIN_SHADOW_ESTIMATE;
        gs.terrain.shadow_rays = k < 3 ? counts[k] : 1;
        double t0 = atmo_now_seconds(), sum = 0;
        for (int i = 0; i < m; i++) {
            double d = terrain_sun_visible(&gs, NULL, pts[i], 0.0f) - exact[i];
            sum += d * d;
        }
        bench_row *row = &rows[(*n)++];
        snprintf(row->method, sizeof row->method, k < 3 ? "shadow-exact" : "shadow-estimate");
        snprintf(row->settings, sizeof row->settings, k < 3 ? "%d rays" : "%d march",
                 k < 3 ? counts[k] : 1);
        row->seconds = atmo_now_seconds() - t0;
        row->error = sqrt(sum / m);
    }
    free(pts);
    free(exact);
    return ATMO_OK;
}

/* Seconds of CPU time of the whole process (its OpenCL device threads included on PoCL): a
 * measure of work that the machine's other load does not stretch. */
static double cpu_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* A render and its CPU seconds, less those of the same scene at 1x1 pixel (the plan, the
 * session's opening and its cached kernels and precomputes: what does not grow with the
 * pixels). The kernels and caches are already filled by a first render of the scene. */
static int cpu_render(const atmo_scene *s, const char *device, double *cpu,
                      atmo_render_result *out, atmo_err *e)
{
    atmo_scene one = *s;
    one.image.width = one.image.height = 1;
    double wall, c0 = cpu_seconds();
    int rc = timed_render(&one, device, 0, &wall, NULL, e);
    if (rc)
        return rc;
    double c1 = cpu_seconds();
    rc = timed_render(s, device, 0, &wall, out, e);
    *cpu = (cpu_seconds() - c1) - (c1 - c0);
    return rc;
}

/* The shortcut sets of the shafts rows: none (the exact march, the reference), each alone,
 * the default and all six. */
static const int shaft_sets[] = {0,
                                 ATMO_TERRAIN_SHAFT_BELOW_HORIZON,
                                 ATMO_TERRAIN_SHAFT_SURFACE,
                                 ATMO_TERRAIN_SHAFT_SPARSE,
                                 ATMO_TERRAIN_SHAFT_START,
                                 ATMO_TERRAIN_SHAFT_REST,
                                 ATMO_TERRAIN_SHAFT_FAR,
                                 ATMO_TERRAIN_SHAFT_DEFAULT,
                                 ATMO_TERRAIN_SHAFT_ALL};
static const char *const shaft_names[] = {"exact march",  "(1) below horizon", "(2) surface",
                                          "(3) sparse",   "(4) start",         "(5) rest",
                                          "(6) far",      "default",           "all six"};
#define SHAFT_SETS ((int)(sizeof shaft_sets / sizeof shaft_sets[0]))

/* The views of the shafts rows: thesis-1 as it is (toward the low sun), and turned round, away
 * from it (where shortcuts 3 and 5 apply). */
static const char *const shaft_views[] = {"camera.yaw_deg=-550", "camera.yaw_deg=-370"};
static const char *const shaft_view_names[] = {"thesis-1", "thesis-1 away from the sun"};
#define SHAFT_VIEWS 2

static int shafts(const char *device, int quick, bench_row *rows, int *n, bench_row *own,
                  atmo_err *e)
{
    int rc;
    double seconds;
    for (int v = 0; v < SHAFT_VIEWS; v++) {
        atmo_render_result ref;
        for (int k = 0; k < SHAFT_SETS; k++) {
            atmo_scene s;
            if ((rc = thesis(&s, e)) || (rc = set(&s, "atmosphere.method=march", e)) ||
                (rc = set(&s, shaft_views[v], e)))
                return rc;
            s.image.width = quick ? 24 : 96, s.image.height = quick ? 14 : 54;
            s.image.samples = 1;
            s.terrain.shafts = shaft_sets[k];
            fprintf(stderr, "bench terrain: %s, shafts %d\n", shaft_view_names[v], shaft_sets[k]);
            atmo_render_result r;
            if (k == 0) { /* compiles the kernels and fills the caches outside the timing */
                atmo_scene warm = s;
                warm.image.width = warm.image.height = 1;
                if ((rc = timed_render(&warm, device, 0, &seconds, NULL, e)))
                    return rc;
            }
            if ((rc = cpu_render(&s, device, &seconds, &r, e)))
                return rc;
            bench_row *row = &rows[(*n)++];
            snprintf(row->method, sizeof row->method, v ? "shafts away" : "shafts");
            snprintf(row->settings, sizeof row->settings, "%s (%d)", shaft_names[k],
                     shaft_sets[k]);
            row->seconds = seconds;
            if (k == 0) {
                ref = r;
                row->error = 0.0;
            } else {
                row->error = bench_rms_relative(&r, &ref);
                atmo_render_result_free(&r);
            }
            own[v * SHAFT_SETS + k] = *row;
            snprintf(own[v * SHAFT_SETS + k].method, sizeof row->method, "%s",
                     shaft_view_names[v]);
            snprintf(own[v * SHAFT_SETS + k].settings, sizeof row->settings, "%s",
                     shaft_names[k]);
        }
        atmo_render_result_free(&ref);
    }
    return ATMO_OK;
}

/* thesis-1 per sample at 1280x720, from a render at w x h scaled by the pixel count: preview
 * (the preset without its clouds, method fast, 4 shadow rays, the default shortcuts) and
 * quality (method march,
 * 16 shadow rays, the shafts' exact march), each built up from the
 * sky alone to everything, so the differences say where the time goes. Seconds: the render's
 * wall clock and its net CPU seconds (two rows), the view's precomputes (fast's sky-view LUT)
 * apart. */
static int thesis_time(const char *dir, const char *device, int quick, const char *dev_name,
                       atmo_err *e)
{
    static const char *const parts[] = {"sky only", "terrain without shadows or shafts",
                                        "terrain + surface shadows",
                                        "terrain + shadows + exact shafts (no shortcut)",
                                        "terrain + shadows + default shafts"};
    enum { PARTS = 5 };
    bench_row rows[4 * PARTS];
    int rc, w = quick ? 64 : 320, h = quick ? 36 : 180, m = 0;
    double scale = (1280.0 * 720.0) / (w * h);
    for (int quality = 0; quality < 2; quality++)
        for (int k = 0; k < PARTS; k++) {
            atmo_scene s;
            if ((rc = thesis(&s, e)))
                return rc;
            if (quality && ((rc = set(&s, "atmosphere.method=march", e)) ||
                            (rc = set(&s, "terrain.shadow_rays=16", e))))
                return rc;
            if (quality && k == PARTS - 1)
                continue; /* quality keeps the exact shortcuts */
            s.image.width = w, s.image.height = h, s.image.samples = 1;
            if (k == 0)
                s.terrain.enabled = 0;
            if (k == 1)
                s.terrain.shadow = ATMO_TERRAIN_SHADOW_NONE;
            if (k <= 2)
                s.terrain.shadow_far_m = 1.0, s.terrain.shafts = ATMO_TERRAIN_SHAFT_FAR;
            if (k == 3)
                s.terrain.shafts = 0;
            if (k == 4)
                s.terrain.shafts = ATMO_TERRAIN_SHAFT_DEFAULT;
            atmo_scene warm = s;
            warm.image.width = warm.image.height = 1;
            double seconds, cpu;
            fprintf(stderr, "bench terrain: thesis-1 %s, %s\n", quality ? "quality" : "preview",
                    parts[k]);
            if ((rc = timed_render(&warm, device, 0, &seconds, NULL, e)))
                return rc;
            atmo_render_result r;
            if ((rc = cpu_render(&s, device, &cpu, &r, e)))
                return rc;
            seconds = r.seconds_render;
            double pre = r.seconds_precompute;
            atmo_render_result_free(&r);
            const char *mode = quality ? "quality" : "preview";
            for (int c = 0; c < 2; c++) {
                bench_row *row = &rows[m++];
                snprintf(row->method, sizeof row->method, "thesis-1 %s %s", mode,
                         c ? "cpu" : "wall");
                snprintf(row->settings, sizeof row->settings, "%s", parts[k]);
                row->seconds = (c ? cpu : seconds) * scale;
                row->error = 0.0;
            }
            printf("thesis-1 %s, %s: %.1f s wall, %.1f CPU s per sample at 1280x720 (measured "
                   "at %dx%d); view precompute %.2f s\n",
                   mode, parts[k], seconds * scale, cpu * scale, w, h, pre);
        }
    char path[4096];
    snprintf(path, sizeof path, "%s/terrain_thesis1.csv", dir);
    return bench_write_csv(path, rows, m, dev_name, e);
}

int bench_terrain(const char *dir, const char *device, int quick, atmo_err *e)
{
    bench_row rows[MAX_ROWS], shaft_rows[SHAFT_VIEWS * SHAFT_SETS];
    int n = 0, rc;
    if ((rc = heightmaps(device, quick, rows, &n, e)) || (rc = tracing(quick, rows, &n, e)) ||
        (rc = shadows(quick, rows, &n, e)) ||
        (rc = shafts(device, quick, rows, &n, shaft_rows, e)))
        return rc;
    for (int i = 0; i < n; i++)
        printf("%-24s %-28s %10.4f s  error %.4g\n", rows[i].method, rows[i].settings,
               rows[i].seconds, rows[i].error);
    const char *dev_name = device ? device : "default";
    char csv[4096], svg[4096];
    snprintf(csv, sizeof csv, "%s/terrain.csv", dir);
    snprintf(svg, sizeof svg, "%s/terrain.svg", dir);
    if ((rc = bench_write_csv(csv, rows, n, dev_name, e)) ||
        (rc = bench_chart(csv, svg, "terrain: error against time (heightmap m or deg, tracing "
                                    "error rate, shadow RMS, shafts RMS relative)",
                          "error", rows, n, e)))
        return rc;
    /* the shortcuts: one series per view, each point a shortcut set (the exact march, error
     * 0, and shortcuts exact in a view fall off the log axis; the CSV has them) */
    for (int v = 0; v < SHAFT_VIEWS; v++)
        for (int k = 1; k < SHAFT_SETS; k++) {
            const bench_row *r = &shaft_rows[v * SHAFT_SETS + k];
            printf("shafts, %s: %-18s %.2fx the exact march's speed, RMS relative %.4g\n",
                   shaft_view_names[v], shaft_names[k],
                   shaft_rows[v * SHAFT_SETS].seconds / r->seconds, r->error);
        }
    snprintf(csv, sizeof csv, "%s/terrain_shafts.csv", dir);
    snprintf(svg, sizeof svg, "%s/terrain_shafts.svg", dir);
    if ((rc = bench_write_csv(csv, shaft_rows, SHAFT_VIEWS * SHAFT_SETS, dev_name, e)) ||
        (rc = bench_chart(csv, svg, "light-shaft shortcuts: RMS relative error against the "
                                    "exact march, and CPU seconds (96x54, method march)",
                          "RMS relative error", shaft_rows, SHAFT_VIEWS * SHAFT_SETS, e)))
        return rc;
    return thesis_time(dir, device, quick, dev_name, e);
}
