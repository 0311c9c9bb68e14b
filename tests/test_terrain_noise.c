/* test_terrain_noise — the terrain's height field (kernels/terrain/noise.h) and the heightmap
 * pass (kernels/terrain/heightmap.cl).
 * labels: kernel
 *
 * Oracles:
 *  1. The analytic gradient of the eroded fBm (with the coverage field) in double precision
 *     (host/terrain/terrain_ref.c) against central differences of the same double function,
 *     step 1e-3 m: the difference's truncation error is h^2/6 |h'''| ~ 1e-6 |grad| (third
 *     derivatives at most ~ 1/cell^2 of the gradient, cells >= 130 m), its rounding error
 *     1e-16 H / 1e-3 m ~ 4e-10: bound 1e-6 + 1e-5 |grad| (absolute, per component). Points where
 *     the elevation saturates (the clamp's kink) or the coast's smoothstep ends lie within
 *     1e-3 m of a kink with probability ~1e-7 and are not excluded.
 *  2. The kernels' float height (the same header compiled on the host, and the heightmap pass on
 *     the device) against the double reference: the float rounding of the octave coordinates,
 *     relative ~ i 2^-24 at octave i, moves the point by about N 2^-24 |u| metres, the height by
 *     the slope bound L times that; the sums add ~ N 2^-24 H. Bound
 *        4 (L N 2^-24 max(|u|, |v|, 1 km) + N 2^-24 H)
 *     (the factor 4 for the rounding of the lattice fractions and the erosion's quotient), and
 *     for the gradient 4 L N 2^-24 (|u| / cell_9 + 1) (cell_9 = the finest octave's period).
 *  3. The heightmap pass writes the texel centres' heights (and, in the derivatives format, the
 *     gradient) within bound 2, and two runs give bitwise the same buffer.
 *  4. The float format's lookup between texels (terrain_height_at) against the bilinear
 *     interpolation, in double, of the double reference at the four surrounding texel centres:
 *     bound 2 at those centres plus 1e-6 H for the interpolation's own rounding. Its distance
 *     to the true field (the interpolation error, which the detail below a texel sets) is
 *     printed, not asserted: atmo bench terrain charts it.
 *  5. A host-supplied height grid (atmo_plan_terrain_base; 33 x 33 samples of a smooth
 *     surface over the heightmap's square, detail 0.25): each texel against the grid's bilinear
 *     interpolation in double plus 0.25 times the double fBm, within bound 2 plus 1e-6 of the
 *     grid's heights (the interpolation's float rounding).
 *  6. The tracer's slope L (plan_terrain.c: the sampled envelope of the eroded fBm's slopes,
 *     not the sum of the octaves' bounds, times the domain warp's bound on ||J||) above every
 *     slope of the double reference at 2^16 land points of the 120 km square around the
 *     thesis' sites, for the default field (seed 46 here) with the default warp and without
 *     one, and the thesis presets' mountains (seed 7, first octave 1e-4 /m, no warp, as the
 *     presets set; and with the default warp); the largest measured is printed as a fraction
 *     of L.
 *  7. The tracer's local bound under the domain warp (plan_terrain.c): at every one of 2^16
 *     land points of the same square the double reference's slope at most stretch_slope times
 *     the warp's stretch ||J|| there (terrain_ref_warp_stretch), and between 2^16 pairs of
 *     points up to 4 km apart the stretch changing by at most the closed-form rate
 *     slope_growth / (2 stretch_slope) per metre (value noise's Hessian bound; | ||A|| - ||B|| |
 *     <= ||A - B||); the largest measured fractions are printed. The kernels' float stretch
 *     (terrain_height_direct_capped's) against the double one: the float lattice point is off
 *     by about 4 |x0| 2^-24 cells, which moves the stretch by the rate times that, plus 1e-5
 *     for the Jacobian's own rounding.
 * The field of 1 to 5 is the default one, so it has the domain warp (noise.h): its derivatives
 * (the warp's Jacobian by the chain rule) against the differences, and its float evaluation
 * against the double one. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/plan_terrain.h"
#include "atmo/terrain_ref.h"
#include "terrain/terrain.h"
#include "testlib.h"
#include "testscene.h"

#define MAP 64
#define EXTENT 8192.0

static double urand(unsigned *state)
{
    *state = *state * 1664525u + 1013904223u;
    return (*state >> 8) / 16777216.0;
}

static void terrain_plan(int format, atmo_plan *p)
{
    atmo_scene s;
    char buf[64];
    test_scene_preset(&s, "sky-noon");
    test_scene_set(&s, "atmosphere.method=single");
    test_scene_set(&s, "terrain.enabled=true");
    test_scene_set(&s, "terrain.seed=46");
    snprintf(buf, sizeof buf, "terrain.heightmap_size=%d", MAP);
    test_scene_set(&s, buf);
    snprintf(buf, sizeof buf, "terrain.heightmap_extent_m=%g", EXTENT);
    test_scene_set(&s, buf);
    test_scene_set(&s, format ? "terrain.heightmap_format=derivatives" : "terrain.heightmap_format=float");
    test_plan(&s, p);
}

static double float_bound(const atmo_gpu_terrain_field *f, double L, double u, double v)
{
    double eps = ldexp(1.0, -24) * f->octaves;
    double reach = fmax(fmax(fabs(u), fabs(v)), 1000.0);
    return 4.0 * (L * eps * reach + eps * (double)f->max_height_m);
}

static double grad_bound(const atmo_gpu_terrain_field *f, double L, double u, double v)
{
    double cell = 1.0 / ((double)f->frequency_per_m * pow(2.0, f->octaves - 1));
    double eps = ldexp(1.0, -24) * f->octaves;
    return 4.0 * L * eps * (fmax(fabs(u), fabs(v)) / cell + 1.0);
}

/* 6: the largest slope of the double reference over 2^16 land points around the thesis'
 * sites, as a fraction of the plan's slope L (seed, first octave) */
static double slope_fraction(const char *seed, const char *frequency, const char *warp)
{
    atmo_scene s;
    atmo_plan p;
    test_scene_preset(&s, "sky-noon");
    test_scene_set(&s, "atmosphere.method=single");
    test_scene_set(&s, "terrain.enabled=true");
    test_scene_set(&s, seed);
    test_scene_set(&s, frequency);
    test_scene_set(&s, warp);
    test_plan(&s, &p);
    const atmo_gpu_terrain_field *f = &p.gpu.terrain.field;
    double L = atmo_terrain_slope_bound(f), worst = 0.0;
    unsigned rng = 2024u;
    for (int i = 0; i < 65536; i++) {
        double u = 23796.0 + (2 * urand(&rng) - 1) * 60000.0;
        double v = 16636.0 + (2 * urand(&rng) - 1) * 60000.0, g[2], c;
        terrain_ref_height(f, u, v, g, &c);
        if (c > 0.0)
            worst = fmax(worst, hypot(g[0], g[1]));
    }
    printf("%s, %s, %s: largest sampled slope %.3f, %.3f of the tracer's L %.3f\n", seed,
           frequency, warp, worst, worst / L, L);
    atmo_plan_free(&p);
    return worst / L;
}

/* 7: the local bound under the warp on the default field (seed 46, 3e-5 /m, warp A) */
static void check_local_bound(const char *warp)
{
    atmo_scene s;
    atmo_plan p;
    test_scene_preset(&s, "sky-noon");
    test_scene_set(&s, "atmosphere.method=single");
    test_scene_set(&s, "terrain.enabled=true");
    test_scene_set(&s, "terrain.seed=46");
    test_scene_set(&s, warp);
    test_plan(&s, &p);
    const atmo_gpu_terrain_field *f = &p.gpu.terrain.field;
    double Ls = atmo_terrain_stretch_slope(f), growth = atmo_terrain_slope_growth(f);
    double rate = growth / (2.0 * Ls), fr = (double)f->frequency_per_m; /* stretch per metre */
    double worst_slope = 0.0, worst_rate = 0.0, worst_float = 0.0, worst_float_m = 0.0;
    unsigned rng = 777u;
    CHECK(Ls > 0.0 && growth > 0.0);
    for (int i = 0; i < 65536; i++) {
        double u = 23796.0 + (2 * urand(&rng) - 1) * 60000.0;
        double v = 16636.0 + (2 * urand(&rng) - 1) * 60000.0, g[2], c;
        double stretch = terrain_ref_warp_stretch(f, u, v);
        terrain_ref_height(f, u, v, g, &c);
        if (c > 0.0)
            worst_slope = fmax(worst_slope, hypot(g[0], g[1]) / (Ls * stretch));
        double delta = 4000.0 * urand(&rng), phi = 2.0 * M_PI * urand(&rng);
        double moved = terrain_ref_warp_stretch(f, u + delta * cos(phi), v + delta * sin(phi));
        if (delta > 0.0)
            worst_rate = fmax(worst_rate, fabs(moved - stretch) / (rate * delta));
        /* the float stretch at the float point, far out too */
        double reach = i % 2 ? 3e6 : 6e4;
        double uf = (double)(float)((2 * urand(&rng) - 1) * reach);
        double vf = (double)(float)((2 * urand(&rng) - 1) * reach);
        int bound;
        float sf;
        terrain_height_direct_capped(f, (float)uf, (float)vf, -1.0f, &bound, &sf);
        double ref = terrain_ref_warp_stretch(f, uf, vf);
        double tol = rate / fr * 4.0 * fmax(fmax(fabs(uf), fabs(vf)) * fr, 1.0) * ldexp(1.0, -24) +
                     1e-5;
        worst_float = fmax(worst_float, fabs((double)sf - ref) / tol);
        worst_float_m = fmax(worst_float_m, fabs((double)sf - ref));
    }
    printf("%s: slope over stretch_slope ||J||: largest %.3f; stretch's change over its bound "
           "%.3g per m: largest %.3f; float stretch off the double by %.3g (%.3f of its bound)\n",
           warp, worst_slope, rate, worst_rate, worst_float_m, worst_float);
    CHECK(worst_slope < 1.0);
    CHECK(worst_rate <= 1.0);
    CHECK(worst_float <= 1.0);
    atmo_plan_free(&p);
}

int main(void)
{
    atmo_plan plan;
    terrain_plan(0, &plan);
    const atmo_gpu_terrain_field *f = &plan.gpu.terrain.field;
    double L = atmo_terrain_slope_bound(f);
    unsigned rng = 12345u;

    /* 1 and 2: random points from the origin out to 3000 km */
    double worst_fd = 0, worst_h = 0, worst_h_rel = 0, worst_g = 0, max_slope = 0;
    for (int i = 0; i < 4000; i++) {
        double reach = i < 2000 ? 5e4 : 3e6;
        double u = (2 * urand(&rng) - 1) * reach, v = (2 * urand(&rng) - 1) * reach;
        double g[2], step = 1e-3;
        double h = terrain_ref_height(f, u, v, g, NULL);
        double hx = (terrain_ref_height(f, u + step, v, NULL, NULL) -
                     terrain_ref_height(f, u - step, v, NULL, NULL)) / (2 * step);
        double hz = (terrain_ref_height(f, u, v + step, NULL, NULL) -
                     terrain_ref_height(f, u, v - step, NULL, NULL)) / (2 * step);
        double slope = hypot(g[0], g[1]);
        max_slope = fmax(max_slope, slope);
        double fd = fmax(fabs(hx - g[0]), fabs(hz - g[1]));
        worst_fd = fmax(worst_fd, fd / (1e-6 + 1e-5 * slope));
        CHECK(fd <= 1e-6 + 1e-5 * slope);

        terrain_height hf = terrain_height_direct(f, (float)u, (float)v);
        /* the float point is the rounded one: compare at the point the kernel evaluates */
        double uf = (double)(float)u, vf = (double)(float)v;
        double hr = terrain_ref_height(f, uf, vf, g, NULL);
        double bound = float_bound(f, L, u, v), gb = grad_bound(f, L, u, v);
        worst_h = fmax(worst_h, fabs((double)hf.h - hr));
        worst_h_rel = fmax(worst_h_rel, fabs((double)hf.h - hr) / bound);
        worst_g = fmax(worst_g, fmax(fabs((double)hf.du - g[0]), fabs((double)hf.dv - g[1])) / gb);
        CHECK(fabs((double)hf.h - hr) <= bound);
        CHECK(fabs((double)hf.du - g[0]) <= gb && fabs((double)hf.dv - g[1]) <= gb);
        (void)h;
    }
    printf("gradient vs finite differences: worst %.3f of its bound; float vs double height: "
           "worst %.3g m (%.3f of its bound), gradient %.3f of its bound; largest slope %.3f "
           "(slope bound %.3f)\n",
           worst_fd, worst_h, worst_h_rel, worst_g, max_slope, L);
    CHECK(slope_fraction("terrain.seed=46", "terrain.frequency_per_m=3e-5", "terrain.warp=1.25") <
          1.0);
    CHECK(slope_fraction("terrain.seed=46", "terrain.frequency_per_m=3e-5", "terrain.warp=0") <
          1.0);
    CHECK(slope_fraction("terrain.seed=7", "terrain.frequency_per_m=1e-4", "terrain.warp=0") < 1.0);
    CHECK(slope_fraction("terrain.seed=7", "terrain.frequency_per_m=1e-4", "terrain.warp=1.25") <
          1.0);
    check_local_bound("terrain.warp=1.25");
    check_local_bound("terrain.warp=4");

    /* 3 and 4: the heightmap pass in both formats */
    test_require_opencl();
    atmo_cl cl;
    test_cl_open(&cl);
    for (int format = 0; format < 2; format++) {
        atmo_plan p;
        terrain_plan(format, &p);
        cl_program prog = test_plan_program(&cl, &p, "");
        cl_int err;
        cl_mem scene = clCreateBuffer(cl.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                                      sizeof p.gpu, &p.gpu, &err);
        CHECK(err == CL_SUCCESS);
        cl_mem luts[ATMO_PLAN_MAX_BUFFERS], again[ATMO_PLAN_MAX_BUFFERS];
        test_precompute(&cl, prog, scene, &p, luts);
        test_precompute(&cl, prog, scene, &p, again);
        int stride = format ? 3 : 1;
        size_t bytes = sizeof(float) * (size_t)stride * MAP * MAP;
        float *map = malloc(bytes), *map2 = malloc(bytes);
        test_cl_read(&cl, test_plan_buffer(&p, luts, "heightmap"), bytes, map);
        test_cl_read(&cl, test_plan_buffer(&p, again, "heightmap"), bytes, map2);
        CHECK(memcmp(map, map2, bytes) == 0);
        double worst = 0, worst_interp = 0, texel = EXTENT / MAP;
        const atmo_gpu_terrain_field *pf = &p.gpu.terrain.field;
        for (int j = 0; j < MAP; j++)
            for (int i = 0; i < MAP; i++) {
                double u = (double)(float)(-0.5 * EXTENT + (i + 0.5) * texel);
                double v = (double)(float)(-0.5 * EXTENT + (j + 0.5) * texel);
                double g[2], h = terrain_ref_height(pf, u, v, g, NULL);
                double bound = float_bound(pf, L, u, v), gb = grad_bound(pf, L, u, v);
                const float *t = map + stride * (j * MAP + i);
                worst = fmax(worst, fabs(t[0] - h) / bound);
                CHECK(fabs(t[0] - h) <= bound);
                if (format)
                    CHECK(fabs(t[1] - g[0]) <= gb && fabs(t[2] - g[1]) <= gb);
            }
        if (!format) { /* bilinear between texel centres */
            double rms = 0;
            int n_interp = 500;
            for (int k = 0; k < n_interp; k++) {
                float u = (float)((urand(&rng) - 0.5) * (EXTENT - 2 * texel));
                float v = (float)((urand(&rng) - 0.5) * (EXTENT - 2 * texel));
                terrain_height got = terrain_height_at(pf, map, u, v);
                double gx = (u + 0.5 * EXTENT) / texel - 0.5, gy = (v + 0.5 * EXTENT) / texel - 0.5;
                double i0 = floor(gx), j0 = floor(gy), fx = gx - i0, fy = gy - j0, c[2][2];
                for (int a = 0; a < 2; a++)
                    for (int b = 0; b < 2; b++)
                        c[a][b] = terrain_ref_height(
                            pf, (double)(float)(-0.5 * EXTENT + (i0 + a + 0.5) * texel),
                            (double)(float)(-0.5 * EXTENT + (j0 + b + 0.5) * texel), NULL, NULL);
                double want = (1 - fy) * ((1 - fx) * c[0][0] + fx * c[1][0]) +
                              fy * ((1 - fx) * c[0][1] + fx * c[1][1]);
                double bound = float_bound(pf, L, u, v) + 1e-6 * (double)pf->max_height_m;
                worst_interp = fmax(worst_interp, fabs(got.h - want) / bound);
                CHECK(fabs(got.h - want) <= bound);
                double truth = terrain_ref_height(pf, u, v, NULL, NULL);
                rms += (got.h - truth) * (got.h - truth);
            }
            printf("bilinear lookups worst %.3f of their bound; interpolation error of %.0f m "
                   "texels: rms %.2f m\n", worst_interp, texel, sqrt(rms / n_interp));
        }
        printf("heightmap %s %dx%d over %.0f m: texels worst %.3f of the float bound, "
               "bitwise repeatable %s\n",
               format ? "height+derivatives" : "float", MAP, MAP, EXTENT, worst,
               memcmp(map, map2, bytes) == 0 ? "yes" : "NO");
        free(map);
        free(map2);
        test_release_luts(luts);
        test_release_luts(again);
        clReleaseMemObject(scene);
        clReleaseProgram(prog);
        atmo_plan_free(&p);
    }
    /* 5: a height grid under the heightmap */
    {
        atmo_plan p;
        terrain_plan(0, &p);
        enum { G = 33 };
        static float grid[G * G];
        double x0 = -0.5 * EXTENT, dx = EXTENT / (G - 1);
        for (int j = 0; j < G; j++)
            for (int i = 0; i < G; i++)
                grid[j * G + i] = (float)(1000.0 + 300.0 * sin((x0 + i * dx) / 1500.0) *
                                                       cos((x0 + j * dx) / 1100.0));
        atmo_err e;
        CHECK(atmo_plan_terrain_base(&p, grid, G, G, x0, x0, dx, dx, 0.25, &e) == ATMO_OK);
        cl_program prog = test_plan_program(&cl, &p, "");
        cl_int err;
        cl_mem scene = clCreateBuffer(cl.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                                      sizeof p.gpu, &p.gpu, &err);
        cl_mem luts[ATMO_PLAN_MAX_BUFFERS];
        test_precompute(&cl, prog, scene, &p, luts);
        float *map = malloc(sizeof(float) * MAP * MAP);
        test_cl_read(&cl, test_plan_buffer(&p, luts, "heightmap"), sizeof(float) * MAP * MAP, map);
        const atmo_gpu_terrain_field *pf = &p.gpu.terrain.field;
        double worst = 0, texel = EXTENT / MAP;
        for (int j = 0; j < MAP; j++)
            for (int i = 0; i < MAP; i++) {
                double u = (double)(float)(-0.5 * EXTENT + (i + 0.5) * texel);
                double v = (double)(float)(-0.5 * EXTENT + (j + 0.5) * texel);
                double gx = (u - x0) / dx, gz = (v - x0) / dx;
                int a = (int)gx, b = (int)gz;
                double fx = gx - a, fz = gz - b;
                double want = (1 - fz) * ((1 - fx) * grid[b * G + a] + fx * grid[b * G + a + 1]) +
                              fz * ((1 - fx) * grid[(b + 1) * G + a] + fx * grid[(b + 1) * G + a + 1]);
                want += 0.25 * terrain_ref_height(pf, u, v, NULL, NULL);
                double bound = float_bound(pf, L, u, v) + 1e-6 * 1300.0;
                worst = fmax(worst, fabs(map[j * MAP + i] - want) / bound);
                CHECK(fabs(map[j * MAP + i] - want) <= bound);
            }
        printf("height grid under the heightmap: texels worst %.3f of their bound\n", worst);
        free(map);
        test_release_luts(luts);
        clReleaseMemObject(scene);
        clReleaseProgram(prog);
        atmo_plan_free(&p);
    }
    atmo_cl_close(&cl);
    atmo_plan_free(&plan);
    return test_finish();
}
