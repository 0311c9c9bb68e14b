/* bench_clouds.c — `atmo bench clouds`: the fBm cloud layer's marcher (method march,
 * kernels/clouds/cloud_march.h) and its knobs against the Monte Carlo reference (method
 * reference, all orders), error against time, and the fit of the marcher's multiple-scattering
 * octaves to the reference.
 *
 * Views: six cloud scenes (thesis view 6 as it is; an overcast 2 km deck of density 0.4 seen
 * from below; the layer seen from 12 km above; thesis-6 under a sun 10 degrees high; thesis
 * view 5's deck from 42 km, looking down away from the sun, where the antisolar point lies at
 * 54.6 degrees below the horizon: light scattered back out of a thick deck; thesis view 9's
 * sunset without its terrain: the cloud field (seed 5) from 37 km under a sun 2.5 degrees high,
 * looking 10-16 degrees down toward the sun and 15 degrees beside it onto clouds lit from
 * behind, scattering angles of 8-20 degrees, where no other view looks), each with
 * six camera rays given by elevation and azimuth from the sun (sky_probe, atmo/probe.h). A
 * view's radiance is the sum over its rays of the 550 nm channel; its error is
 * sum L_march / sum L_ref - 1, and a configuration's error is the RMS of that over the views.
 * A seventh view is held out: measured and charted for every configuration, but neither
 * fitted nor in the RMS. It is thesis view 8's without its terrain: from 5.8 km, inside the
 * layer, 28-44 degrees down onto the face of a near cloud turned away from a sun 9.8 degrees
 * high (scattering angles of 42-54 degrees), where the octaves and the diffuse orders that the
 * six views fit give 1.7 times the reference's light (docs/bench/README.md, "Thesis views"
 * and "The build-up").
 * The reference: 256 paths per ray (4096 on the cheap overcast view, 2048 on the sunset, whose
 * forward-peaked light is noisier; 64 with --quick), drawn
 * with its own seed (image.seed = BENCH_CLOUDS_REF_SEED; the marcher keeps the scene's 0), so
 * its noise is independent of the marcher's jitter and a fit cannot follow it; its own
 * error is its relative standard error (the batches' spread, summed over the rays), charted at
 * 64, 128 and 256 paths (scaled by 1 / sqrt(paths)) with the time of that many paths. The marcher: 64
 * samples per ray (its jittered march averaged; its error is its bias), charted with the time
 * of one sample of the 36 rays (one sample is an image's pixel-sample).
 *
 * The fit (Wrenninge et al. 2013's octaves and the diffuse orders, cloud_march.h): the cloud
 * light is
 *     L = L_0 + sum_{1 <= i < N} b^i G_i(a, c) + d G_d
 * with G_i the light of octave i at b = 1 and G_d the diffuse orders' at d = 1; G_i is measured
 * as the difference of the marcher at N = i + 1 and N = i octaves (b = 1, d = 0), G_d as the
 * difference of one octave at d = 1 and d = 0 (it depends on none of a, c, N), over a grid of a
 * and c; b (steps of 0.01) and N (1..BENCH_CLOUDS_FIT_OCTAVES) then minimise the RMS view error,
 * d in closed form for each (least squares, steps of 0.01, 0..BENCH_CLOUDS_FIT_D_MAX). The fit's
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

#define BENCH_CLOUDS_VIEWS 7
#define BENCH_CLOUDS_FIT_VIEWS 6 /* the first six: fitted and in the RMS; the rest held out */
#define BENCH_CLOUDS_RAYS 6
#define BENCH_CLOUDS_REF_SAMPLES 256
#define BENCH_CLOUDS_MARCH_SAMPLES 64
#define BENCH_CLOUDS_FIT_OCTAVES 6
#define BENCH_CLOUDS_FIT_D_MAX 20.0
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
    {"sunset",
     {"camera.position_m=18181,37415,3431", "sun.zenith_deg=87.476967",
      "sun.azimuth_deg=-150.985019", "clouds.seed=5", "clouds.max_distance_m=4e5", NULL},
     {-10, -12, -14, -10, -14, -16},
     {0, 0, 0, 15, 15, 15},
     2048},
    {"near cloud",
     {"camera.position_m=7866,5837,-143910", "sun.zenith_deg=81.435892",
      "sun.azimuth_deg=-170.007181", "clouds.seed=55", "clouds.max_distance_m=1e5", NULL},
     {-43.74, -40.09, -34.2, -37.22, -30.67, -27.69},
     {7.55, 20.65, 26.26, 10.73, 13.39, 23.83},
     4096},
};

typedef struct march_config {
    const char *settings;
    const char *assignments[6];
    int shadow; /* 1: the shadow term's error is measured too (bench_clouds_shadow.c) */
} march_config;

static const march_config march_configs[] = {
    {"defaults", {NULL}, 1},
    {"octaves 0.05/0.48/0.9 x4, no diffuse",
     {"clouds.ms_a=0.05", "clouds.ms_b=0.48", "clouds.ms_c=0.9", "clouds.ms_octaves=4",
      "clouds.ms_d=0"},
     0},
    {"octaves 0.5/0.5/0.5 x4, no diffuse",
     {"clouds.ms_a=0.5", "clouds.ms_b=0.5", "clouds.ms_c=0.5", "clouds.ms_octaves=4",
      "clouds.ms_d=0"},
     0},
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
    {"no diffuse orders", {"clouds.ms_d=0", NULL}, 0},
    {"1 octave", {"clouds.ms_octaves=1", NULL}, 0},
    {"4 octaves", {"clouds.ms_octaves=4", NULL}, 0},
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

/* The marcher's relative error of every view with the assignments, their RMS over the fitted
 * views, its seconds per sample and its precompute's seconds summed over the fitted views and,
 * unless NULL, the shadow term's errors (at the sample points of every view). */
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
        if (v < BENCH_CLOUDS_FIT_VIEWS) {
            sum += errors[v] * errors[v];
            *seconds += t, *precompute += pre;
        }
    }
    *rms = sqrt(sum / BENCH_CLOUDS_FIT_VIEWS);
    return ATMO_OK;
}

/* The marcher's view radiances at b = 1 with N octaves of factors a, c and the diffuse weight d. */
static int fit_radiances(double a, double c, int n, double d, const char *device,
                         double L[BENCH_CLOUDS_VIEWS], atmo_err *e)
{
    char sa[48], sc[48], so[48], sd[48];
    snprintf(sa, sizeof sa, "clouds.ms_a=%.3f", a);
    snprintf(sc, sizeof sc, "clouds.ms_c=%.3f", c);
    snprintf(so, sizeof so, "clouds.ms_octaves=%d", n);
    snprintf(sd, sizeof sd, "clouds.ms_d=%.3f", d);
    const char *extra[] = {sa, "clouds.ms_b=1", sc, so, sd, NULL};
    for (int v = 0; v < BENCH_CLOUDS_VIEWS; v++) {
        double se, t;
        int rc = view_radiance(&views[v], "march", extra, BENCH_CLOUDS_MARCH_SAMPLES, device,
                               &L[v], &se, &t, NULL, NULL, e);
        if (rc)
            return rc;
    }
    return ATMO_OK;
}

/* The diffuse weight (steps of 0.01 in [0, BENCH_CLOUDS_FIT_D_MAX]) that minimises the RMS of
 * the fitted views' errors x_v + d y_v, x_v the error without it and y_v its light over the
 * reference; the errors of every view at it to err[], the fitted views' RMS returned. */
static double fit_diffuse(const double x[BENCH_CLOUDS_VIEWS], const double y[BENCH_CLOUDS_VIEWS],
                          double *d, double err[BENCH_CLOUDS_VIEWS])
{
    double xy = 0.0, yy = 0.0, sum = 0.0;
    for (int v = 0; v < BENCH_CLOUDS_FIT_VIEWS; v++)
        xy += x[v] * y[v], yy += y[v] * y[v];
    *d = yy > 0.0 ? round(fmin(fmax(-xy / yy, 0.0), BENCH_CLOUDS_FIT_D_MAX) * 100.0) / 100.0 : 0.0;
    for (int v = 0; v < BENCH_CLOUDS_VIEWS; v++) {
        err[v] = x[v] + *d * y[v];
        if (v < BENCH_CLOUDS_FIT_VIEWS)
            sum += err[v] * err[v];
    }
    return sqrt(sum / BENCH_CLOUDS_FIT_VIEWS);
}

/* The octaves' and the diffuse term's fit (see the top of the file); writes
 * DIR/clouds_fit.csv. */
static int fit_octaves(const char *dir, const reference_result *ref, const char *device,
                       int quick, atmo_err *e)
{
    static const double a_grid[] = {0.05, 0.1, 0.2, 0.35};
    static const double c_grid[] = {0.5, 0.7, 0.9};
    int na = quick ? 2 : (int)(sizeof a_grid / sizeof a_grid[0]);
    int nc = quick ? 1 : (int)(sizeof c_grid / sizeof c_grid[0]);
    int N_max = quick ? 3 : BENCH_CLOUDS_FIT_OCTAVES;
    double best = INFINITY, best_a = 0, best_b = 0, best_c = 0, best_d = 0;
    double best_err[BENCH_CLOUDS_VIEWS], L_single[BENCH_CLOUDS_VIEWS], G_d[BENCH_CLOUDS_VIEWS];
    int best_n = 0, rc;
    /* the diffuse term's light at d = 1: independent of a, c and N */
    if ((rc = fit_radiances(a_grid[0], c_grid[0], 1, 0.0, device, L_single, e)) ||
        (rc = fit_radiances(a_grid[0], c_grid[0], 1, 1.0, device, G_d, e)))
        return rc;
    for (int v = 0; v < BENCH_CLOUDS_VIEWS; v++)
        G_d[v] -= L_single[v];
    char path[4096];
    snprintf(path, sizeof path, "%s/clouds_fit.csv", dir);
    FILE *f = fopen(path, "w");
    if (!f)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "cannot write %s", path);
    fprintf(f, "a,c,octaves,b,d,rms_error");
    for (int v = 0; v < BENCH_CLOUDS_VIEWS; v++)
        fprintf(f, ",%s", views[v].name);
    fprintf(f, "\n");
    for (int ia = 0; ia < na; ia++)
        for (int ic = 0; ic < nc; ic++) {
            double a = quick ? a_grid[1 + 2 * ia] : a_grid[ia], c = c_grid[ic];
            double G[BENCH_CLOUDS_FIT_OCTAVES][BENCH_CLOUDS_VIEWS], prev[BENCH_CLOUDS_VIEWS] = {0};
            for (int n = 1; n <= N_max; n++) {
                double L[BENCH_CLOUDS_VIEWS];
                if (n == 1)
                    memcpy(L, L_single, sizeof L);
                else if ((rc = fit_radiances(a, c, n, 0.0, device, L, e))) {
                    fclose(f);
                    return rc;
                }
                for (int v = 0; v < BENCH_CLOUDS_VIEWS; v++) {
                    G[n - 1][v] = n == 1 ? L[v] : L[v] - prev[v];
                    prev[v] = L[v];
                }
            }
            for (int n = 1; n <= N_max; n++)
                for (int ib = 0; ib <= 100; ib++) {
                    double b = ib / 100.0, d, x[BENCH_CLOUDS_VIEWS], y[BENCH_CLOUDS_VIEWS];
                    double err[BENCH_CLOUDS_VIEWS];
                    for (int v = 0; v < BENCH_CLOUDS_VIEWS; v++) {
                        double L = 0.0, w = 1.0;
                        for (int i = 0; i < n; i++, w *= b)
                            L += w * G[i][v];
                        x[v] = L / ref->L[v] - 1.0;
                        y[v] = G_d[v] / ref->L[v];
                    }
                    double rms = fit_diffuse(x, y, &d, err);
                    if (ib % 10 == 0 || rms < best) {
                        fprintf(f, "%.3f,%.3f,%d,%.2f,%.2f,%.5f", a, c, n, b, d, rms);
                        for (int v = 0; v < BENCH_CLOUDS_VIEWS; v++)
                            fprintf(f, ",%.5f", err[v]);
                        fprintf(f, "\n");
                    }
                    if (rms < best) {
                        best = rms, best_a = a, best_b = b, best_c = c, best_d = d, best_n = n;
                        memcpy(best_err, err, sizeof err);
                    }
                }
            fprintf(stderr, "bench clouds: fit a %.2f c %.2f done (best so far: a %.2f b %.2f c "
                            "%.2f octaves %d d %.2f, RMS %.1f %%)\n",
                    a, c, best_a, best_b, best_c, best_n, best_d, 100.0 * best);
        }
    fclose(f);
    printf("octave fit: clouds.ms_a=%.2f clouds.ms_b=%.2f clouds.ms_c=%.2f "
           "clouds.ms_octaves=%d clouds.ms_d=%.2f, RMS view error %.1f %%\n",
           best_a, best_b, best_c, best_n, best_d, 100.0 * best);
    for (int v = 0; v < BENCH_CLOUDS_VIEWS; v++)
        printf("  %-10s residual %+6.1f %% (reference +- %.1f %%)%s\n", views[v].name,
               100.0 * best_err[v], 100.0 * ref->se[v] / ref->L[v],
               v < BENCH_CLOUDS_FIT_VIEWS ? "" : ", held out");
    return ATMO_OK;
}

/* The Monte Carlo reference of every view (ref_samples paths each; 64 with quick). */
static int measure_reference(const char *device, int quick, reference_result *ref, atmo_err *e)
{
    char seed[48];
    snprintf(seed, sizeof seed, "image.seed=%d", BENCH_CLOUDS_REF_SEED);
    const char *ref_extra[] = {seed, NULL};
    ref->seconds = 0.0;
    for (int v = 0; v < BENCH_CLOUDS_VIEWS; v++) {
        double t;
        int rc = view_radiance(&views[v], "reference", ref_extra,
                               quick ? 64 : views[v].ref_samples, device, &ref->L[v], &ref->se[v],
                               &t, NULL, NULL, e);
        if (rc)
            return rc;
        if (v < BENCH_CLOUDS_FIT_VIEWS)
            ref->seconds += t;
        fprintf(stderr, "bench clouds: reference %-10s %.5e +- %.1f %% (%.3f s per sample)\n",
                views[v].name, ref->L[v], 100.0 * ref->se[v] / ref->L[v], t);
    }
    return ATMO_OK;
}

/* One marcher configuration against the reference: its row (time per sample, the map's build
 * spread over a frame where it has one, RMS error of the fitted views), a row per held-out view
 * in held[] (the same time, that view's |error|), and with a shadow measurement its two rows
 * of the sun transmittance's error (all sample points, those in cloud) in shadow_rows[*n_shadow]
 * onward. *base_precompute: the first configuration's precompute, the defaults'. */
static int march_row(const march_config *mc, int first, const reference_result *ref,
                     const char *device, double *base_precompute, bench_row *row,
                     bench_row *held, bench_row *shadow_rows, int *n_shadow, atmo_err *e)
{
    double errors[BENCH_CLOUDS_VIEWS], precompute;
    bench_shadow_error shadow = {0.0, 0.0, 0, 0};
    snprintf(row->method, sizeof row->method, "march");
    snprintf(row->settings, sizeof row->settings, "%s", mc->settings);
    int rc = march_error(mc->assignments, ref, device, errors, &row->error, &row->seconds,
                         &precompute, mc->shadow ? &shadow : NULL, e);
    if (rc)
        return rc;
    if (first)
        *base_precompute = precompute;
    /* the map's build: the precompute's seconds beyond the defaults', spread over a frame */
    double build = fmax(precompute - *base_precompute, 0.0);
    int has_map = strstr(mc->settings, "shadow map") != NULL;
    if (has_map)
        row->seconds += build / BENCH_CLOUDS_FRAME_SAMPLES;
    fprintf(stderr, "bench clouds: march %-18s %.4f s per sample%s, RMS error %.1f %% (",
            row->settings, row->seconds, has_map ? " (build amortised)" : "",
            100.0 * row->error);
    for (int v = 0; v < BENCH_CLOUDS_VIEWS; v++)
        fprintf(stderr, "%s%s%s %+.1f %%", v ? ", " : "",
                v == BENCH_CLOUDS_FIT_VIEWS ? "held out: " : "", views[v].name,
                100.0 * errors[v]);
    fprintf(stderr, ")\n");
    for (int v = BENCH_CLOUDS_FIT_VIEWS; v < BENCH_CLOUDS_VIEWS; v++) {
        bench_row *h = &held[v - BENCH_CLOUDS_FIT_VIEWS];
        snprintf(h->method, sizeof h->method, "march (%s)", views[v].name);
        snprintf(h->settings, sizeof h->settings, "%s", mc->settings);
        h->seconds = row->seconds;
        h->error = fabs(errors[v]);
    }
    if (has_map)
        fprintf(stderr, "bench clouds:   map build %.2f s over the %d views (%.2f s per view), "
                        "%.2e s per sample amortised over a 1280x720 frame\n",
                build, BENCH_CLOUDS_FIT_VIEWS, build / BENCH_CLOUDS_FIT_VIEWS,
                build / BENCH_CLOUDS_FRAME_SAMPLES);
    if (!mc->shadow)
        return ATMO_OK;
    bench_row *sr = &shadow_rows[(*n_shadow)++], *sc = &shadow_rows[(*n_shadow)++];
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
    return ATMO_OK;
}

/* The reference's rows at 64, 128 ... ref_samples paths into out: its relative standard error
 * (RMS over the views) scaled from this run's to that many paths, and their time. Returns how
 * many. */
static int reference_rows(const reference_result *ref, int quick, int ref_samples, bench_row *out)
{
    double sum = 0.0;
    int n = 0;
    for (int v = 0; v < BENCH_CLOUDS_FIT_VIEWS; v++) {
        double rel = ref->se[v] / ref->L[v];
        sum += rel * rel * (quick ? 64 : views[v].ref_samples) / ref_samples;
    }
    for (int paths = 64; paths <= ref_samples; paths *= 2) {
        bench_row *row = &out[n++];
        snprintf(row->method, sizeof row->method, "reference");
        snprintf(row->settings, sizeof row->settings, "%d paths", paths);
        row->seconds = ref->seconds * paths;
        row->error = sqrt(sum / BENCH_CLOUDS_FIT_VIEWS) * sqrt((double)ref_samples / paths);
    }
    return n;
}

/* The sun transmittance's rows as clouds_shadow.csv and its chart. */
static int write_shadow_chart(const char *dir, const bench_row *rows, int n, const char *device,
                              atmo_err *e)
{
    char csv[4096], svg[4096];
    snprintf(csv, sizeof csv, "%s/clouds_shadow.csv", dir);
    snprintf(svg, sizeof svg, "%s/clouds_shadow.svg", dir);
    int rc = bench_write_csv(csv, rows, n, device ? device : "default", e);
    if (!rc)
        rc = bench_chart(csv, svg,
                         "fBm clouds: sun transmittance of the light march and the shadow map at the "
                         "sample points of the marcher (7 views x 6 rays); time per sample of "
                         "the 36 rays of the six fitted, the build of the map spread over a "
                         "1280x720 frame",
                         "RMS error of T_sun (whole chord, 550 nm)", rows, n, e);
    if (!rc)
        printf("wrote %s and %s\n", csv, svg);
    return rc;
}

int bench_clouds(const char *dir, const char *device, int quick, int fit, atmo_err *e)
{
    int rc, ref_samples = quick ? 64 : BENCH_CLOUDS_REF_SAMPLES;
    reference_result ref;
    if ((rc = measure_reference(device, quick, &ref, e)))
        return rc;
    if (fit)
        return fit_octaves(dir, &ref, device, quick, e);
    enum {
        N_CONFIGS = sizeof march_configs / sizeof march_configs[0],
        N_HELD = BENCH_CLOUDS_VIEWS - BENCH_CLOUDS_FIT_VIEWS
    };
    bench_row out[N_CONFIGS * (1 + N_HELD) + 3], held[N_CONFIGS * N_HELD];
    bench_row shadow_rows[2 * N_CONFIGS];
    int n = 0, n_held = 0, n_shadow = 0;
    double base_precompute = 0.0;
    for (int i = 0; i < N_CONFIGS && !(quick && i > 0); i++, n_held += N_HELD)
        if ((rc = march_row(&march_configs[i], i == 0, &ref, device, &base_precompute, &out[n++],
                            &held[n_held], shadow_rows, &n_shadow, e)))
            return rc;
    for (int i = 0; i < n_held; i++)
        out[n++] = held[i];
    n += reference_rows(&ref, quick, ref_samples, &out[n]);
    if ((rc = bench_write_suite(dir, "clouds", out, n, device ? device : "default",
                                "fBm clouds: marcher knobs vs the reference (6 views x 6 rays, "
                                "550 nm; a seventh, held out, charted alone); time per sample "
                                "of the 36 rays",
                                "relative error: RMS over the six views, or the held-out "
                                "view alone",
                                e)))
        return rc;
    return write_shadow_chart(dir, shadow_rows, n_shadow, device, e);
}
