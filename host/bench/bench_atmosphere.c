/* bench_atmosphere.c — `atmo bench atmosphere`: every atmosphere method and its knobs, error
 * against the Monte Carlo reference against time.
 *
 * Error: the rows of the stored reference table (tests/data/reference_sky.csv: all orders, camera
 * at the ground, sun zenith 0..80 deg, views from the zenith to 5 deg above the horizon toward,
 * across and away from the sun, standard error <= 0.3 %) are evaluated with the method through
 * sky_probe (1024 samples per view for the ray-marching methods, which averages their random
 * march offset away so the error is the method's bias; 64 for the LUT methods, whose lookups
 * are deterministic; the reference method gets the sample count of its setting, so its points
 * show Monte Carlo noise), and the error is the largest |L / L_ref - 1| over rows and channels. Sun zenith 90 deg rows are reported by the tests, not charted.
 * Time: precompute + render of a 512 x 256 panorama at 1 sample per pixel (the reference at its
 * own sample count) with the sun at 60 deg, kernels already built (builds are timed apart).
 * The 2048 x 1024 panorama costs 16 times the render part. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/bench.h"
#include "atmo/features.h"
#include "atmo/probe.h"

#define BENCH_MAX_ROWS 256

typedef struct reference_row {
    double sun_zenith, view_zenith, view_azimuth;
    double L[3];
} reference_row;

typedef struct bench_config {
    const char *method;
    const char *settings;         /* shown in the chart */
    const char *assignments[4];   /* --set style, NULL-terminated */
    int probe_samples;            /* samples per view for the error */
    int image_samples;            /* samples per pixel for the timing */
    int quick;                    /* also run with --quick */
} bench_config;

static const bench_config bench_configs[] = {
    {"single", "8 steps", {"render.view_steps=8"}, 1024, 1, 1},
    {"single", "32 steps", {"render.view_steps=32"}, 1024, 1, 0},
    {"march", "8 steps", {"render.view_steps=8"}, 1024, 1, 1},
    {"march", "16 steps", {"render.view_steps=16"}, 1024, 1, 0},
    {"march", "32 steps", {"render.view_steps=32"}, 1024, 1, 0},
    {"march", "64 steps", {"render.view_steps=64"}, 1024, 1, 0},
    {"fast", "default", {NULL}, 64, 1, 1},
    {"lut", "2 orders", {"lut.orders=2"}, 64, 1, 0},
    {"lut", "4 orders", {"lut.orders=4"}, 64, 1, 0},
    {"lut", "8 orders", {"lut.orders=8"}, 64, 1, 0},
    {"reference", "16 spp", {NULL}, 64, 16, 0},
    {"reference", "128 spp", {NULL}, 128, 128, 0},
};

/* Rows with sun zenith <= 80 deg of the reference CSV (comment lines start with '#'). */
static int read_reference(const char *path, reference_row *rows, int *n, atmo_err *e)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "cannot read the reference table '%s' (run from the source tree, or give "
                         "--reference FILE)", path);
    char line[1024];
    *n = 0;
    while (fgets(line, sizeof line, f) && *n < BENCH_MAX_ROWS) {
        reference_row r;
        double samples;
        if (line[0] == '#' ||
            sscanf(line, "%lf,%lf,%lf,%lf,%lf,%lf,%lf", &r.sun_zenith, &r.view_zenith,
                   &r.view_azimuth, &samples, &r.L[0], &r.L[1], &r.L[2]) != 7)
            continue;
        if (r.sun_zenith <= 80.0)
            rows[(*n)++] = r;
    }
    fclose(f);
    return *n ? ATMO_OK
              : atmo_fail(e, ATMO_ERR_USAGE, "no rows in the reference table '%s'", path);
}

static int config_scene(const bench_config *c, double sun_zenith, atmo_scene *s, atmo_err *e)
{
    char buf[64];
    int rc;
    atmo_scene_defaults(s);
    if ((rc = atmo_scene_apply_preset(s, "sky-noon", e)))
        return rc;
    snprintf(buf, sizeof buf, "atmosphere.method=%s", c->method);
    if ((rc = atmo_scene_assign(s, buf, "bench", e)))
        return rc;
    snprintf(buf, sizeof buf, "sun.zenith_deg=%g", sun_zenith);
    if ((rc = atmo_scene_assign(s, buf, "bench", e)))
        return rc;
    for (int i = 0; i < 4 && c->assignments[i]; i++)
        if ((rc = atmo_scene_assign(s, c->assignments[i], "bench", e)))
            return rc;
    return ATMO_OK;
}

/* Largest relative error of the method over the reference rows. */
static int config_error(const bench_config *c, const reference_row *rows, int n,
                          const char *device, double *worst, atmo_err *e)
{
    *worst = 0.0;
    const atmo_feature *method = atmo_feature_find(c->method);
    int per_sun = method && method->luts_follow_view;
    for (int start = 0; start < n;) {
        /* one probe session for all rows, or one per sun zenith where the LUTs hold one sun */
        int end = start;
        while (end < n && (!per_sun || rows[end].sun_zenith == rows[start].sun_zenith))
            end++;
        atmo_scene s;
        atmo_plan plan;
        atmo_probe probe = {0};
        int rc = config_scene(c, rows[start].sun_zenith, &s, e);
        if (!rc)
            rc = atmo_plan_make(&s, &plan, e);
        if (!rc)
            rc = atmo_probe_open(&probe, &plan, device, e);
        float4 rays[BENCH_MAX_ROWS];
        double mean[BENCH_MAX_ROWS][3];
        double r = plan.gpu.camera.local_up.w;
        for (int i = start; i < end && !rc; i++) {
            double ts = rows[i].sun_zenith * M_PI / 180, tv = rows[i].view_zenith * M_PI / 180;
            double pv = rows[i].view_azimuth * M_PI / 180;
            float4 q = {(float)r, (float)cos(tv), (float)cos(ts),
                        (float)(sin(tv) * sin(ts) * cos(pv) + cos(tv) * cos(ts))};
            rays[i - start] = q;
        }
        if (!rc)
            rc = atmo_probe_rays(&probe, rays, end - start, c->probe_samples, mean, NULL, e);
        atmo_probe_close(&probe);
        if (rc)
            return rc;
        for (int i = start; i < end; i++)
            for (int k = 0; k < 3; k++)
                *worst = fmax(*worst, fabs(mean[i - start][k] / rows[i].L[k] - 1.0));
        start = end;
    }
    return ATMO_OK;
}

int bench_atmosphere(const char *dir, const char *device, const char *reference, int quick,
                     atmo_err *e)
{
    static reference_row rows[BENCH_MAX_ROWS];
    int n_rows, rc;
    if ((rc = read_reference(reference, rows, &n_rows, e)))
        return rc;
    bench_row out[sizeof bench_configs / sizeof bench_configs[0]];
    int n = 0;
    char device_name[256] = "?";
    for (size_t i = 0; i < sizeof bench_configs / sizeof bench_configs[0]; i++) {
        const bench_config *c = &bench_configs[i];
        if (quick && !c->quick)
            continue;
        atmo_scene s;
        atmo_plan plan;
        if ((rc = config_scene(c, 60.0, &s, e)))
            return rc;
        if (atmo_plan_make(&s, &plan, e) == ATMO_ERR_USAGE && strstr(e->msg, "not implemented")) {
            fprintf(stderr, "bench atmosphere: %s is not built yet; skipped\n", c->method);
            continue;
        }
        bench_row *row = &out[n];
        snprintf(row->method, sizeof row->method, "%s", c->method);
        snprintf(row->settings, sizeof row->settings, "%s", c->settings);
        if ((rc = config_error(c, rows, n_rows, device, &row->error, e)))
            return rc;
        s.camera.kind = ATMO_CAMERA_PANORAMA;
        s.image.width = quick ? 128 : 512;
        s.image.height = quick ? 64 : 256;
        s.image.samples = c->image_samples;
        atmo_render_result r;
        if ((rc = bench_render(&s, device, &r, e)))
            return rc;
        row->seconds = r.seconds_precompute + r.seconds_render;
        snprintf(device_name, sizeof device_name, "%s", r.device_name);
        fprintf(stderr, "bench atmosphere: %-9s %-9s %8.3fs (precompute %.3fs)  worst error %.2f %%\n",
                row->method, row->settings, row->seconds, r.seconds_precompute, 100.0 * row->error);
        atmo_render_result_free(&r);
        n++;
    }
    char title[512];
    snprintf(title, sizeof title,
             "sky radiance vs Monte Carlo reference, sun zenith 0-80 deg; time: 512x256 panorama (%s)",
             device_name);
    return bench_write_suite(dir, "atmosphere", out, n, device_name, title,
                             "worst relative error", e);
}
