/* test_terrain_trace — sphere tracing the terrain (kernels/terrain/terrain.h) on the device
 * against a brute-force double-precision march, and its precision at planet scale.
 * labels: kernel
 *
 * Oracle: terrain_ref_hit (host/terrain/terrain_ref.c): the same height field in double,
 * marched in steps of at most 2 m (shorter near the surface, so no feature of the 130 m finest
 * octave is stepped over) and bisected to 1e-9. With eps(t) = 0.01 m + tolerance t the
 * tracer's acceptance distance and delta(t) = the float rounding bound of the height field
 * (test_terrain_noise's bound 2) plus 2e-7 t for the ray's float position, a ray is counted as
 *   - a miss: the reference hits, the tracer does not;
 *   - a pass-through: both hit, but the reference's clearance goes more than delta + 0.5 m
 *     below the surface between its hit and the tracer's (the tracer stepped over solid
 *     ground);
 *   - a false hit: the tracer hits, the reference does not, and the reference ray's smallest
 *     clearance exceeds eps + delta;
 *   - a bad hit: the double clearance at the tracer's hit point lies outside
 *     [-delta, eps + delta].
 * Rays: from a camera 300 m above thesis-1's site, 800 downward rays; 1200 grazing rays
 * (cosine to the vertical in [-0.05, 0.02]) from 2..50 m above the surface; 1000 rays that
 * skim a random surface point horizontally at 0.05..3 m, started on the line back from it
 * where that is at least 1 m above the terrain. Asserted: no miss, pass-through, false
 * or bad hit among them (at most 3 / hits at 95 % confidence for the rate), at the default
 * steps and optimism. With 8 steps the fallback resolves every downward ray (a hit within the
 * bound: never sky) and the others' errors are printed.
 *
 * Precision: one target point on the surface seen at 45 degrees from cameras 1 m, 10 m, ...,
 * 100 km and 2000 km away (each its own camera-relative frame, image 16384 px high with a 1
 * degree field, so eps(t) ~ 5e-7 t): the double clearance at the hit within [-delta, eps +
 * delta] and the hit point within (eps + delta) / |dg/dt| + 1e-6 t of the reference's, dg/dt
 * the rate the reference's clearance falls along the ray. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/plan_terrain.h"
#include "atmo/terrain_ref.h"
#include "testlib.h"
#include "testscene.h"

static const char probe_src[] =
    "__kernel void trace(__global const atmo_gpu_scene *s, ATMO_LUT_PARAMS,\n"
    "                    __global const float4 *o, __global const float4 *d,\n"
    "                    __global float4 *out, uint n) {\n"
    "  uint i = get_global_id(0); if (i >= n) return;\n"
    "  float t = 0.0f; int used = 0;\n"
    "  int hit = terrain_trace(s, heightmap, o[i].xyz, d[i].xyz, 0.0f, d[i].w, s->terrain.steps,\n"
    "                          &t, &used);\n"
    "  out[i] = (float4)(hit ? t : -1.0f, (float)used, 0.0f, 0.0f);\n"
    "}\n";

#define SITE_X 23796.0
#define SITE_Z 16636.0
#define N_DOWN 800
#define N_GRAZE 1200
#define N_SKIM 1000
#define N_RAYS (N_DOWN + N_GRAZE + N_SKIM)
#define REF_STEP_M 2.0

static double urand(unsigned *state)
{
    *state = *state * 1664525u + 1013904223u;
    return (*state >> 8) / 16777216.0;
}

typedef struct ray {
    double o[3], d[3]; /* camera-relative origin (float-rounded) and unit direction */
    double t_max;
} ray;

typedef struct setup {
    atmo_scene scene;
    atmo_plan plan;
    double cam[3];
} setup;

static double R_m;

static void plan_at(setup *u, const double cam[3], const char *extra1, const char *extra2)
{
    char buf[160];
    test_scene_preset(&u->scene, "sky-noon");
    test_scene_set(&u->scene, "atmosphere.method=single");
    test_scene_set(&u->scene, "terrain.enabled=true");
    test_scene_set(&u->scene, "terrain.seed=46");
    snprintf(buf, sizeof buf, "camera.position_m=%.17g,%.17g,%.17g", cam[0], cam[1], cam[2]);
    test_scene_set(&u->scene, buf);
    if (extra1)
        test_scene_set(&u->scene, extra1);
    if (extra2)
        test_scene_set(&u->scene, extra2);
    test_plan(&u->scene, &u->plan);
    memcpy(u->cam, cam, sizeof u->cam);
    R_m = u->scene.atmosphere.bottom_radius_m;
}

/* The surface point above planar (x, z) and its vertical, world coordinates. */
static void surface_point(const atmo_gpu_terrain_field *f, double sea, double x, double z,
                          double p[3], double n[3])
{
    double h = fmax(terrain_ref_height(f, x, z, NULL, NULL), sea);
    double rho2 = (x * x + z * z) / (R_m * R_m);
    n[0] = x / R_m, n[1] = sqrt(1 - rho2), n[2] = z / R_m;
    for (int k = 0; k < 3; k++)
        p[k] = n[k] * (R_m + h) - (k == 1 ? R_m : 0);
}

static void make_ray(ray *r, const double cam[3], const double origin_world[3], const double d[3],
                     double t_max)
{
    double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    float df[3];
    for (int k = 0; k < 3; k++)
        df[k] = (float)(d[k] / len);
    len = sqrt((double)df[0] * df[0] + (double)df[1] * df[1] + (double)df[2] * df[2]);
    for (int k = 0; k < 3; k++) {
        r->o[k] = (double)(float)(origin_world[k] - cam[k]);
        r->d[k] = (double)df[k] / len;
    }
    r->t_max = t_max;
}

/* Runs the probe over the rays: out[i] = (t or -1, steps used). */
static void run_trace(atmo_cl *cl, cl_program prog, const atmo_plan *p, const ray *rays, int n,
                      float4 *out)
{
    cl_int err;
    float4 *o = calloc((size_t)n, sizeof *o), *d = calloc((size_t)n, sizeof *d);
    for (int i = 0; i < n; i++) {
        o[i].x = (float)rays[i].o[0], o[i].y = (float)rays[i].o[1], o[i].z = (float)rays[i].o[2];
        d[i].x = (float)rays[i].d[0], d[i].y = (float)rays[i].d[1], d[i].z = (float)rays[i].d[2];
        d[i].w = (float)rays[i].t_max;
    }
    cl_mem scene = clCreateBuffer(cl->context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                                  sizeof p->gpu, (void *)&p->gpu, &err);
    cl_mem luts[ATMO_PLAN_MAX_BUFFERS];
    test_precompute(cl, prog, scene, p, luts);
    cl_mem bo = test_cl_buffer(cl, sizeof *o * (size_t)n, o);
    cl_mem bd = test_cl_buffer(cl, sizeof *d * (size_t)n, d);
    cl_mem bout = test_cl_buffer(cl, sizeof *out * (size_t)n, NULL);
    cl_kernel k = clCreateKernel(prog, "trace", &err);
    clSetKernelArg(k, 0, sizeof scene, &scene);
    int a = test_bind_buffers(k, luts);
    cl_uint nn = (cl_uint)n;
    clSetKernelArg(k, a++, sizeof bo, &bo);
    clSetKernelArg(k, a++, sizeof bd, &bd);
    clSetKernelArg(k, a++, sizeof bout, &bout);
    clSetKernelArg(k, a++, sizeof nn, &nn);
    test_cl_run_1d(cl, k, (size_t)n);
    test_cl_read(cl, bout, sizeof *out * (size_t)n, out);
    clReleaseKernel(k);
    clReleaseMemObject(bout);
    clReleaseMemObject(bd);
    clReleaseMemObject(bo);
    test_release_luts(luts);
    clReleaseMemObject(scene);
    free(o);
    free(d);
}

static double delta_m(const atmo_gpu_terrain_field *f, double L, const double w[3], double t)
{
    double eps = ldexp(1.0, -24) * f->octaves;
    double reach = fmax(fmax(fabs(w[0]), fabs(w[2])), 1000.0);
    return 4.0 * (L * eps * reach + eps * (double)f->max_height_m) + 2e-7 * t;
}

static void world_at(const setup *u, const ray *r, double t, double w[3])
{
    for (int k = 0; k < 3; k++)
        w[k] = u->cam[k] + r->o[k] + t * r->d[k];
}

typedef struct tally {
    int hits, misses, through, false_hits, bad, ref_hits;
    double worst_clear, mean_steps;
} tally;

static tally judge(const setup *u, const ray *rays, int n, const float4 *out, int verbose)
{
    const atmo_gpu_terrain *tr = &u->plan.gpu.terrain;
    double L = atmo_terrain_slope_bound(&tr->field), sea = tr->sea_level_m;
    tally y;
    memset(&y, 0, sizeof y);
    for (int i = 0; i < n; i++) {
        const ray *r = &rays[i];
        double o[3], t_ref = 0, min_clear = INFINITY;
        world_at(u, r, 0.0, o);
        int ref = terrain_ref_hit(&tr->field, R_m, sea, o, r->d, r->t_max, REF_STEP_M, &t_ref,
                                  &min_clear);
        int hit = out[i].x >= 0.0f;
        double t = out[i].x, w[3];
        y.ref_hits += ref;
        y.hits += hit;
        y.mean_steps += out[i].y / n;
        if (ref && !hit) {
            y.misses++;
            if (verbose)
                fprintf(stderr, "  ray %d: missed a hit at %.3f m\n", i, t_ref);
            continue;
        }
        if (!hit)
            continue;
        world_at(u, r, t, w);
        double eps = 0.01 + (double)tr->tolerance * t, delta = delta_m(&tr->field, L, w, t);
        double g = terrain_ref_clearance(&tr->field, R_m, sea, w);
        y.worst_clear = fmax(y.worst_clear, g > 0 ? g / (eps + delta) : -g / delta);
        if (g < -delta || g > eps + delta) {
            y.bad++;
            if (verbose)
                fprintf(stderr, "  ray %d: hit at %.3f m has clearance %.4f m (eps %.3f, delta "
                                "%.3f)\n", i, t, g, eps, delta);
        }
        if (!ref && min_clear > eps + delta) {
            y.false_hits++;
            if (verbose)
                fprintf(stderr, "  ray %d: hit at %.3f m, reference clears by %.3f m\n", i, t,
                        min_clear);
        }
        if (ref && t > t_ref) { /* how deep the reference goes between the two hits */
            double deepest = 0;
            for (int k = 1; k < 64; k++) {
                double q[3];
                world_at(u, r, t_ref + (t - t_ref) * k / 64.0, q);
                deepest = fmin(deepest, terrain_ref_clearance(&tr->field, R_m, sea, q));
            }
            if (deepest < -(delta + 0.5)) {
                y.through++;
                if (verbose)
                    fprintf(stderr, "  ray %d: passed %.3f m deep through the terrain (hits "
                                    "%.3f / %.3f m)\n", i, -deepest, t_ref, t);
            }
        }
    }
    return y;
}

int main(void)
{
    test_require_opencl();
    atmo_cl cl;
    test_cl_open(&cl);
    setup u;
    double cam[3] = {SITE_X, 0.0, SITE_Z}, p[3], n[3];
    plan_at(&u, cam, NULL, NULL); /* for the field */
    const atmo_gpu_terrain_field f = u.plan.gpu.terrain.field;
    surface_point(&f, 0.0, SITE_X, SITE_Z, p, n);
    atmo_plan_free(&u.plan);
    for (int k = 0; k < 3; k++)
        cam[k] = p[k] + 300.0 * n[k];
    plan_at(&u, cam, NULL, NULL);
    cl_program prog = test_plan_program(&cl, &u.plan, probe_src);

    ray *rays = calloc(N_RAYS, sizeof *rays);
    float4 *out = calloc(N_RAYS, sizeof *out);
    unsigned rng = 777u;
    for (int i = 0; i < N_RAYS; i++) {
        double o[3], d[3], t_max;
        if (i < N_DOWN) { /* from the camera, down */
            double mu = -0.02 - 0.98 * urand(&rng), phi = 2 * M_PI * urand(&rng);
            double s = sqrt(1 - mu * mu);
            memcpy(o, cam, sizeof o);
            d[0] = s * cos(phi), d[1] = mu, d[2] = s * sin(phi);
            t_max = 20000.0;
        } else {
            double x = SITE_X + (urand(&rng) - 0.5) * 4000, z = SITE_Z + (urand(&rng) - 0.5) * 4000;
            double q[3], m[3], phi = 2 * M_PI * urand(&rng);
            surface_point(&f, 0.0, x, z, q, m);
            /* a horizontal unit vector at q */
            double e1[3] = {cos(phi), 0, sin(phi)}, k = e1[0] * m[0] + e1[1] * m[1] + e1[2] * m[2];
            for (int c = 0; c < 3; c++)
                e1[c] -= k * m[c];
            double len = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
            if (i < N_DOWN + N_GRAZE) {
                double above = 2 + 48 * urand(&rng), mu = -0.05 + 0.07 * urand(&rng);
                for (int c = 0; c < 3; c++) {
                    o[c] = q[c] + above * m[c];
                    d[c] = e1[c] / len * sqrt(1 - mu * mu) + mu * m[c];
                }
                t_max = 8000.0;
            } else { /* started where the line back from q is above the terrain */
                double above = 0.05 + 2.95 * urand(&rng), back = 3000.0;
                for (int c = 0; c < 3; c++)
                    d[c] = e1[c] / len;
                do {
                    back *= 0.7;
                    for (int c = 0; c < 3; c++)
                        o[c] = q[c] + above * m[c] - back * d[c];
                } while (back > 1.0 && terrain_ref_clearance(&f, R_m, 0.0, o) < 1.0);
                t_max = back + 3000.0;
            }
        }
        make_ray(&rays[i], cam, o, d, t_max);
    }
    static const char *const names[3] = {"downward", "grazing", "ridge-skimming"};
    const int first[4] = {0, N_DOWN, N_DOWN + N_GRAZE, N_RAYS};

    run_trace(&cl, prog, &u.plan, rays, N_RAYS, out);
    int all_hits = 0, all_bad = 0;
    for (int g = 0; g < 3; g++) {
        tally y = judge(&u, rays + first[g], first[g + 1] - first[g], out + first[g], 1);
        printf("default (steps %d, optimism %.2f): %-14s %4d rays, %4d hits (reference %4d): "
               "%d misses, %d pass-throughs, %d false, %d bad; worst clearance %.3f of its "
               "bound; %.1f steps per ray\n",
               u.plan.gpu.terrain.steps, (double)u.plan.gpu.terrain.optimism, names[g],
               first[g + 1] - first[g], y.hits, y.ref_hits, y.misses, y.through, y.false_hits,
               y.bad, y.worst_clear, y.mean_steps);
        all_hits += y.ref_hits;
        all_bad += y.misses + y.through + y.false_hits + y.bad;
    }
    CHECK(all_bad == 0);
    printf("  %d errors in %d reference hits: rate < %.2g at 95 %% confidence\n", all_bad,
           all_hits, 3.0 / all_hits);
    atmo_plan_free(&u.plan);

    /* the fallback: 8 steps */
    plan_at(&u, cam, "terrain.steps=8", NULL);
    run_trace(&cl, prog, &u.plan, rays, N_RAYS, out);
    for (int g = 0; g < 3; g++) {
        tally y = judge(&u, rays + first[g], first[g + 1] - first[g], out + first[g], 0);
        printf("8 steps + fallback: %-14s %4d hits (reference %4d): %d misses, %d "
               "pass-throughs, %d false, %d bad; %.1f steps per ray\n",
               names[g], y.hits, y.ref_hits, y.misses, y.through, y.false_hits, y.bad,
               y.mean_steps);
        if (g == 0)
            CHECK(y.misses == 0 && y.through == 0 && y.bad == 0);
    }
    atmo_plan_free(&u.plan);

    /* precision: one target, cameras from 1 m to 2000 km away at 45 degrees */
    double target[3], tn[3];
    surface_point(&f, 0.0, SITE_X + 1234.5, SITE_Z - 987.25, target, tn);
    double east[3] = {tn[1], -tn[0], 0}, el = hypot(east[0], east[1]);
    static const double dist[] = {1, 10, 100, 1e3, 1e4, 1e5, 2e6};
    for (size_t k = 0; k < sizeof dist / sizeof dist[0]; k++) {
        double c[3], d[3];
        for (int i = 0; i < 3; i++) {
            d[i] = -(tn[i] + east[i] / el) / sqrt(2.0);
            c[i] = target[i] - dist[k] * sqrt(2.0) * d[i] * 0.5 * sqrt(2.0);
        }
        plan_at(&u, c, "image.height=16384", "camera.fov_deg=1");
        ray r;
        make_ray(&r, c, c, d, 2.0 * dist[k] + 1e4);
        float4 res;
        run_trace(&cl, prog, &u.plan, &r, 1, &res);
        const atmo_gpu_terrain *tr = &u.plan.gpu.terrain;
        double L = atmo_terrain_slope_bound(&tr->field);
        /* the reference from where the ray comes below the highest terrain */
        double start = fmax(0.0, dist[k] - 6000.0), o[3], t_ref, mc;
        world_at(&u, &r, start, o);
        int ref = terrain_ref_hit(&tr->field, R_m, 0.0, o, r.d, dist[k] + 1e4 - start, REF_STEP_M,
                                  &t_ref, &mc);
        t_ref += start;
        double w[3], wr[3], a[3], b[3];
        world_at(&u, &r, res.x, w);
        world_at(&u, &r, t_ref, wr);
        world_at(&u, &r, t_ref - 0.5, a);
        world_at(&u, &r, t_ref + 0.5, b);
        double rate = fabs(terrain_ref_clearance(&tr->field, R_m, 0.0, b) -
                           terrain_ref_clearance(&tr->field, R_m, 0.0, a));
        double t = res.x, eps = 0.01 + (double)tr->tolerance * t;
        double delta = delta_m(&tr->field, L, w, t);
        double g = terrain_ref_clearance(&tr->field, R_m, 0.0, w);
        double err = sqrt((w[0] - wr[0]) * (w[0] - wr[0]) + (w[1] - wr[1]) * (w[1] - wr[1]) +
                          (w[2] - wr[2]) * (w[2] - wr[2]));
        double bound = (eps + delta) / fmax(rate, 0.05) + 1e-6 * t;
        CHECK(ref && res.x >= 0.0f);
        CHECK(g >= -delta && g <= eps + delta);
        CHECK(err <= bound);
        printf("camera %8.0f m from the target: hit %.4f m from the reference's (bound %.3f), "
               "clearance %+.4f m (eps %.3f, delta %.3f)\n",
               dist[k], err, bound, g, eps, delta);
        atmo_plan_free(&u.plan);
    }
    free(rays);
    free(out);
    clReleaseProgram(prog);
    atmo_cl_close(&cl);
    return test_finish();
}
