/* bench_clouds.c — `atmo bench clouds`: the fBm cloud layer's marcher (method march,
 * kernels/media/cloud_march.h) and its knobs against the Monte Carlo reference (method
 * reference, all orders), error against time, and the fit of the marcher's multiple-scattering
 * octaves to the reference.
 *
 * Views: five cloud scenes (thesis view 6 as it is; an overcast 2 km deck of density 0.4 seen
 * from below; the layer seen from 12 km above; thesis-6 under a sun 10 degrees high; thesis
 * view 5's deck from 42 km, looking down away from the sun, where the antisolar point lies at
 * 54.6 degrees below the horizon: light scattered back out of a thick deck), each with
 * six camera rays given by elevation and azimuth from the sun (sky_probe, atmo/probe.h). A
 * view's radiance is the sum over its rays of the 550 nm channel; its error is
 * sum L_march / sum L_ref - 1, and a configuration's error is the RMS of that over the views.
 * The reference: 256 paths per ray (4096 on the cheap overcast view; 64 with --quick), drawn
 * with its own seed (image.seed = BENCH_CLOUDS_REF_SEED; the marcher keeps the scene's 0), so
 * its noise is independent of the marcher's jitter and a fit cannot follow it; its own
 * error is its relative standard error (the batches' spread, summed over the rays), charted at
 * 64, 128 and 256 paths (scaled by 1 / sqrt(paths)) with the time of that many paths. The marcher: 64
 * samples per ray (its jittered march averaged; its error is its bias), charted with the time
 * of one sample of the 30 rays (one sample is an image's pixel-sample).
 *
 * The fit (Wrenninge et al. 2013's octaves, cloud_march.h): the cloud light is
 *     L = L_0 + sum_{1 <= i < N} b^i G_i(a, c)
 * with G_i the light of octave i at b = 1; G_i is measured as the difference of the marcher at
 * N = i + 1 and N = i octaves (b = 1), over a grid of a and c, and b (steps of 0.01) and N
 * (1..BENCH_CLOUDS_FIT_OCTAVES) then minimise the RMS view error in closed form. The fit's
 * values and its residual per view are printed; the grid's rows (every tenth b and each new
 * best) are written to DIR/clouds_fit.csv. Writes DIR/clouds.csv and DIR/clouds.svg, and
 * the shadow term's RMS error (bench_clouds_shadow.c) over all the marcher's sample points and
 * over those inside cloud, one series each for the light march and the shadow map, against
 * the same time per sample, to DIR/clouds_shadow.csv and DIR/clouds_shadow.svg. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/bench.h"
#include "atmo/clock.h"
#include "atmo/probe.h"

#define BENCH_CLOUDS_VIEWS 5
#define BENCH_CLOUDS_RAYS 6
#define BENCH_CLOUDS_REF_SAMPLES 256
#define BENCH_CLOUDS_MARCH_SAMPLES 64
#define BENCH_CLOUDS_FIT_OCTAVES 12
#define BENCH_CLOUDS_REF_SEED 1 /* the reference's image.seed: not the marcher's (0) */

typedef struct cloud_view {
    const char *name;
    const char *assignments[12]; /* over thesis-6, NULL-terminated */
    double elevation_deg[BENCH_CLOUDS_RAYS], azimuth_deg[BENCH_CLOUDS_RAYS];
    int ref_samples; /* the reference's paths per ray (cheap views get more) */
} cloud_view;

static const cloud_view views[BENCH_CLOUDS_VIEWS] = {
    {"thesis-6", {NULL}, {5, 15, 30, 5, 15, 30}, {30, 30, 30, 150, 150, 150}, 256},
    {"overcast",
     {"camera.position_m=0,500,0", "clouds.coverage=1", "clouds.bottom_m=1000",
      "clouds.top_m=3000", "clouds.fade_m=500", "clouds.density=0.4", NULL},
     {20, 45, 80, 20, 45, 80},
     {30, 30, 30, 150, 150, 150},
     4096},
    {"from above",
     {"camera.position_m=0,12000,0", NULL},
     {-10, -30, -60, -10, -30, -60},
     {30, 30, 30, 150, 150, 150},
     256},
    {"low sun",
     {"sun.zenith_deg=80", NULL},
     {5, 15, 30, 5, 15, 30},
     {30, 30, 30, 150, 150, 150},
     256},
    {"backscatter",
     {"camera.position_m=61950,42398,-83371", "sun.zenith_deg=35.396615", "clouds.seed=0",
      "clouds.max_distance_m=2e5", NULL},
     {-35, -45, -55, -35, -45, -55},
     {180, 180, 180, 160, 160, 160},
     256},
};

typedef struct march_config {
    const char *settings;
    const char *assignments[5];
    int shadow; /* 1: the shadow term's error is measured too (bench_clouds_shadow.c) */
} march_config;

static const march_config march_configs[] = {
    {"defaults", {NULL}, 1},
    {"octaves 0.5/0.5/0.5 x4",
     {"clouds.ms_a=0.5", "clouds.ms_b=0.5", "clouds.ms_c=0.5", "clouds.ms_octaves=4"}, 0},
    {"octaves 0.05/0.43/0.9 x12",
     {"clouds.ms_a=0.05", "clouds.ms_b=0.43", "clouds.ms_c=0.9", "clouds.ms_octaves=12"}, 0},
    {"step 300 m", {"clouds.step_m=300", NULL}, 0},
    {"step 75 m", {"clouds.step_m=75", NULL}, 0},
    {"1 light step", {"clouds.light_steps=1", NULL}, 1},
    {"2 light steps", {"clouds.light_steps=2", NULL}, 1},
    {"8 light steps", {"clouds.light_steps=8", NULL}, 1},
    {"16 light steps", {"clouds.light_steps=16", NULL}, 1},
    {"shadow map 128x16",
     {"clouds.shadow_map=true", "clouds.shadow_map_size=128", "clouds.shadow_map_levels=16",
      NULL},
     1},
    {"shadow map 256x32",
     {"clouds.shadow_map=true", "clouds.shadow_map_size=256", "clouds.shadow_map_levels=32",
      NULL},
     1},
    {"1 octave", {"clouds.ms_octaves=1", NULL}, 0},
    {"2 octaves", {"clouds.ms_octaves=2", NULL}, 0},
    {"8 octaves", {"clouds.ms_octaves=8", NULL}, 0},
    {"128 steps", {"clouds.steps=128", NULL}, 0},
};

/* A 1280 x 720 frame's pixel-samples per sample of one view's rays: a per-view cost spread
 * over a frame at one sample per pixel. */
#define BENCH_CLOUDS_FRAME_SAMPLES (1280.0 * 720.0 / BENCH_CLOUDS_RAYS)

static int view_scene(const cloud_view *v, const char *method, const char *const *extra,
                      atmo_scene *s, atmo_err *e)
{
    char buf[128];
    int rc;
    atmo_scene_defaults(s);
    if ((rc = atmo_scene_apply_preset(s, "thesis-6", e)))
        return rc;
    snprintf(buf, sizeof buf, "atmosphere.method=%s", method);
    if ((rc = atmo_scene_assign(s, buf, "bench", e)) ||
        (rc = atmo_scene_assign(s, "post.flare=false", "bench", e)))
        return rc;
    for (int i = 0; v->assignments[i]; i++)
        if ((rc = atmo_scene_assign(s, v->assignments[i], "bench", e)))
            return rc;
    for (int i = 0; extra && extra[i]; i++)
        if ((rc = atmo_scene_assign(s, extra[i], "bench", e)))
            return rc;
    return atmo_scene_validate(s, e);
}

/* The view's radiance (550 nm, summed over its rays), its standard error, the probe's seconds
 * per sample of all its rays and, unless NULL, its precompute's seconds and the shadow term's
 * errors at the marcher's sample points added to *shadow. */
static int view_radiance(const cloud_view *v, const char *method, const char *const *extra,
                         int samples, const char *device, double *L, double *se,
                         double *seconds, double *precompute, bench_shadow_error *shadow,
                         atmo_err *e)
{
    atmo_scene s;
    atmo_plan plan;
    atmo_probe probe = {0};
    int rc = view_scene(v, method, extra, &s, e);
    if (rc || (rc = atmo_plan_make(&s, &plan, e)))
        return rc;
    rc = atmo_probe_open(&probe, &plan, device, e);
    float4 rays[BENCH_CLOUDS_RAYS];
    double mean[BENCH_CLOUDS_RAYS][3], err[BENCH_CLOUDS_RAYS][3];
    double zs = s.sun.zenith_deg * M_PI / 180.0, r = plan.gpu.camera.local_up.w;
    for (int i = 0; i < BENCH_CLOUDS_RAYS; i++) {
        double el = v->elevation_deg[i] * M_PI / 180.0, az = v->azimuth_deg[i] * M_PI / 180.0;
        float4 q = {(float)r, (float)sin(el), (float)cos(zs),
                    (float)(cos(el) * sin(zs) * cos(az) + sin(el) * cos(zs))};
        rays[i] = q;
    }
    double t0 = atmo_now_seconds();
    if (!rc)
        rc = atmo_probe_rays(&probe, rays, BENCH_CLOUDS_RAYS, samples, mean, err, e);
    *seconds = (atmo_now_seconds() - t0) / samples;
    if (precompute)
        *precompute = probe.seconds_precompute;
    atmo_probe_close(&probe);
    if (!rc && shadow)
        rc = bench_clouds_shadow_error(&plan, rays, BENCH_CLOUDS_RAYS, shadow, e);
    atmo_plan_free(&plan);
    if (rc)
        return rc;
    double var = 0.0;
    *L = 0.0;
    for (int i = 0; i < BENCH_CLOUDS_RAYS; i++)
        *L += mean[i][1], var += err[i][1] * err[i][1];
    *se = sqrt(var);
    return ATMO_OK;
}

typedef struct reference_result {
    double L[BENCH_CLOUDS_VIEWS], se[BENCH_CLOUDS_VIEWS], seconds;
} reference_result;

/* The marcher's RMS relative view error with the assignments, its seconds per sample, its
 * precompute's seconds summed over the views and, unless NULL, the shadow term's errors. */
static int march_error(const char *const *extra, const reference_result *ref, const char *device,
                       double errors[BENCH_CLOUDS_VIEWS], double *rms, double *seconds,
                       double *precompute, bench_shadow_error *shadow, atmo_err *e)
{
    double sum = 0.0;
    *seconds = 0.0, *precompute = 0.0;
    for (int v = 0; v < BENCH_CLOUDS_VIEWS; v++) {
        double L, se, t, pre;
        int rc = view_radiance(&views[v], "march", extra, BENCH_CLOUDS_MARCH_SAMPLES, device, &L,
                               &se, &t, &pre, shadow, e);
        if (rc)
            return rc;
        errors[v] = L / ref->L[v] - 1.0;
        sum += errors[v] * errors[v];
        *seconds += t, *precompute += pre;
    }
    *rms = sqrt(sum / BENCH_CLOUDS_VIEWS);
    return ATMO_OK;
}

/* The octaves' fit (see the top of the file); writes DIR/clouds_fit.csv. */
static int fit_octaves(const char *dir, const reference_result *ref, const char *device,
                       int quick, atmo_err *e)
{
    static const double a_grid[] = {0.05, 0.1, 0.2, 0.35, 0.5, 0.65, 0.8};
    static const double c_grid[] = {0.4, 0.7, 0.9};
    int na = quick ? 2 : (int)(sizeof a_grid / sizeof a_grid[0]);
    int nc = quick ? 1 : (int)(sizeof c_grid / sizeof c_grid[0]);
    int N_max = quick ? 4 : BENCH_CLOUDS_FIT_OCTAVES;
    double best = INFINITY, best_a = 0, best_b = 0, best_c = 0, best_err[BENCH_CLOUDS_VIEWS];
    int best_n = 0;
    char path[4096];
    snprintf(path, sizeof path, "%s/clouds_fit.csv", dir);
    FILE *f = fopen(path, "w");
    if (!f)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "cannot write %s", path);
    fprintf(f, "a,c,octaves,b,rms_error");
    for (int v = 0; v < BENCH_CLOUDS_VIEWS; v++)
        fprintf(f, ",%s", views[v].name);
    fprintf(f, "\n");
    for (int ia = 0; ia < na; ia++)
        for (int ic = 0; ic < nc; ic++) {
            double a = quick ? a_grid[1 + 2 * ia] : a_grid[ia], c = c_grid[ic];
            double G[BENCH_CLOUDS_FIT_OCTAVES][BENCH_CLOUDS_VIEWS], prev[BENCH_CLOUDS_VIEWS];
            for (int n = 1; n <= N_max; n++) {
                char sa[48], sb[48], sc[48], so[48];
                snprintf(sa, sizeof sa, "clouds.ms_a=%.3f", a);
                snprintf(sb, sizeof sb, "clouds.ms_b=1");
                snprintf(sc, sizeof sc, "clouds.ms_c=%.3f", c);
                snprintf(so, sizeof so, "clouds.ms_octaves=%d", n);
                const char *extra[] = {sa, sb, sc, so, NULL};
                for (int v = 0; v < BENCH_CLOUDS_VIEWS; v++) {
                    double L, se, t;
                    int rc = view_radiance(&views[v], "march", extra, BENCH_CLOUDS_MARCH_SAMPLES,
                                           device, &L, &se, &t, NULL, NULL, e);
                    if (rc) {
                        fclose(f);
                        return rc;
                    }
                    G[n - 1][v] = n == 1 ? L : L - prev[v];
                    prev[v] = L;
                }
            }
            for (int n = 1; n <= N_max; n++)
                for (int ib = 0; ib <= 100; ib++) {
                    double b = ib / 100.0, sum = 0.0, err[BENCH_CLOUDS_VIEWS];
                    for (int v = 0; v < BENCH_CLOUDS_VIEWS; v++) {
                        double L = 0.0, w = 1.0;
                        for (int i = 0; i < n; i++, w *= b)
                            L += w * G[i][v];
                        err[v] = L / ref->L[v] - 1.0;
                        sum += err[v] * err[v];
                    }
                    double rms = sqrt(sum / BENCH_CLOUDS_VIEWS);
                    if (ib % 10 == 0 || rms < best) {
                        fprintf(f, "%.3f,%.3f,%d,%.2f,%.5f", a, c, n, b, rms);
                        for (int v = 0; v < BENCH_CLOUDS_VIEWS; v++)
                            fprintf(f, ",%.5f", err[v]);
                        fprintf(f, "\n");
                    }
                    if (rms < best) {
                        best = rms, best_a = a, best_b = b, best_c = c, best_n = n;
                        memcpy(best_err, err, sizeof err);
                    }
                }
            fprintf(stderr, "bench clouds: fit a %.2f c %.2f done (best so far: a %.2f b %.2f c "
                            "%.2f octaves %d, RMS %.1f %%)\n",
                    a, c, best_a, best_b, best_c, best_n, 100.0 * best);
        }
    fclose(f);
    printf("octave fit: clouds.ms_a=%.2f clouds.ms_b=%.2f clouds.ms_c=%.2f "
           "clouds.ms_octaves=%d, RMS view error %.1f %%\n",
           best_a, best_b, best_c, best_n, 100.0 * best);
    for (int v = 0; v < BENCH_CLOUDS_VIEWS; v++)
        printf("  %-10s residual %+6.1f %% (reference +- %.1f %%)\n", views[v].name,
               100.0 * best_err[v], 100.0 * ref->se[v] / ref->L[v]);
    return ATMO_OK;
}

int bench_clouds(const char *dir, const char *device, int quick, int fit, atmo_err *e)
{
    int rc, ref_samples = quick ? 64 : BENCH_CLOUDS_REF_SAMPLES;
    reference_result ref;
    char seed[48];
    snprintf(seed, sizeof seed, "image.seed=%d", BENCH_CLOUDS_REF_SEED);
    const char *ref_extra[] = {seed, NULL};
    ref.seconds = 0.0;
    for (int v = 0; v < BENCH_CLOUDS_VIEWS; v++) {
        double t;
        if ((rc = view_radiance(&views[v], "reference", ref_extra,
                                quick ? 64 : views[v].ref_samples,
                                device, &ref.L[v], &ref.se[v], &t, NULL, NULL, e)))
            return rc;
        ref.seconds += t;
        fprintf(stderr, "bench clouds: reference %-10s %.5e +- %.1f %% (%.3f s per sample)\n",
                views[v].name, ref.L[v], 100.0 * ref.se[v] / ref.L[v], t);
    }
    if (fit)
        return fit_octaves(dir, &ref, device, quick, e);
    enum { N_CONFIGS = sizeof march_configs / sizeof march_configs[0] };
    bench_row out[N_CONFIGS + 3], shadow_rows[2 * N_CONFIGS];
    int n = 0, n_shadow = 0;
    double base_precompute = 0.0;
    for (int i = 0; i < N_CONFIGS; i++) {
        if (quick && i > 0)
            break;
        double errors[BENCH_CLOUDS_VIEWS], precompute;
        bench_shadow_error shadow = {0.0, 0.0, 0, 0};
        const march_config *mc = &march_configs[i];
        bench_row *row = &out[n++];
        snprintf(row->method, sizeof row->method, "march");
        snprintf(row->settings, sizeof row->settings, "%s", mc->settings);
        if ((rc = march_error(mc->assignments, &ref, device, errors, &row->error, &row->seconds,
                              &precompute, mc->shadow ? &shadow : NULL, e)))
            return rc;
        if (i == 0)
            base_precompute = precompute;
        /* the map's build: the precompute's seconds beyond the defaults', spread over a frame */
        double build = fmax(precompute - base_precompute, 0.0);
        int has_map = strstr(mc->settings, "shadow map") != NULL;
        if (has_map)
            row->seconds += build / BENCH_CLOUDS_FRAME_SAMPLES;
        fprintf(stderr, "bench clouds: march %-18s %.4f s per sample%s, RMS error %.1f %% (",
                row->settings, row->seconds, has_map ? " (build amortised)" : "",
                100.0 * row->error);
        for (int v = 0; v < BENCH_CLOUDS_VIEWS; v++)
            fprintf(stderr, "%s%s %+.1f %%", v ? ", " : "", views[v].name, 100.0 * errors[v]);
        fprintf(stderr, ")\n");
        if (has_map)
            fprintf(stderr, "bench clouds:   map build %.2f s over the %d views (%.2f s per view), "
                            "%.2e s per sample amortised over a 1280x720 frame\n",
                    build, BENCH_CLOUDS_VIEWS, build / BENCH_CLOUDS_VIEWS,
                    build / BENCH_CLOUDS_FRAME_SAMPLES);
        if (!mc->shadow)
            continue;
        bench_row *sr = &shadow_rows[n_shadow++], *sc = &shadow_rows[n_shadow++];
        const char *term = has_map ? "shadow map" : "light march";
        snprintf(sr->method, sizeof sr->method, "%s", term);
        snprintf(sc->method, sizeof sc->method, "%s in cloud", term);
        snprintf(sr->settings, sizeof sr->settings, "%s", mc->settings);
        snprintf(sc->settings, sizeof sc->settings, "%s", mc->settings);
        sr->seconds = sc->seconds = row->seconds;
        sr->error = sqrt(shadow.sq_all / shadow.n_all);
        sc->error = sqrt(shadow.sq_cloud / fmax(shadow.n_cloud, 1));
        fprintf(stderr, "bench clouds:   sun transmittance vs the whole-chord quadrature: RMS "
                        "%.4f over %d sample points, %.4f over the %d in cloud\n",
                sr->error, shadow.n_all, sc->error, shadow.n_cloud);
    }
    /* the reference at 64, 128 and 256 paths: its relative standard error (RMS over the views)
     * scaled from this run's to that many paths, and their time */
    double sum = 0.0;
    for (int v = 0; v < BENCH_CLOUDS_VIEWS; v++) {
        double rel = ref.se[v] / ref.L[v];
        sum += rel * rel * (quick ? 64 : views[v].ref_samples) / ref_samples;
    }
    for (int paths = 64; paths <= ref_samples; paths *= 2) {
        bench_row *row = &out[n++];
        snprintf(row->method, sizeof row->method, "reference");
        snprintf(row->settings, sizeof row->settings, "%d paths", paths);
        row->seconds = ref.seconds * paths;
        row->error = sqrt(sum / BENCH_CLOUDS_VIEWS) * sqrt((double)ref_samples / paths);
    }
    if ((rc = bench_write_suite(dir, "clouds", out, n, device ? device : "default",
                                "fBm clouds: marcher knobs vs the reference (5 views x 6 rays, "
                                "550 nm); time per sample of the 30 rays",
                                "RMS relative error of the views", e)))
        return rc;
    char csv[4096], svg[4096];
    snprintf(csv, sizeof csv, "%s/clouds_shadow.csv", dir);
    snprintf(svg, sizeof svg, "%s/clouds_shadow.svg", dir);
    if ((rc = bench_write_csv(csv, shadow_rows, n_shadow, device ? device : "default", e)) ||
        (rc = bench_chart(csv, svg,
                          "fBm clouds: sun transmittance of the light march and the shadow map at the "
                          "sample points of the marcher (5 views x 6 rays); time per sample of "
                          "the 30 rays, the build of the map spread over a 1280x720 frame",
                          "RMS error of T_sun (whole chord, 550 nm)", shadow_rows, n_shadow, e)))
        return rc;
    printf("wrote %s and %s\n", csv, svg);
    return ATMO_OK;
}
