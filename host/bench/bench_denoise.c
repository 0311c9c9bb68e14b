/* bench_denoise.c — `atmo bench denoise`: the path tracer's error against time with and without
 * Intel Open Image Denoise (atmo/denoise.h), by samples per pixel: where denoising pays.
 *
 * Scene: thesis-7 (an open box on the ground, path traced), 256 x 144 (--quick: 64 x 36),
 * rendered at 1, 2, 4, ... 64 samples per pixel (--quick: 1 to 8) with seed 2, each image then
 * denoised at quality fast, balanced and high (the colour alone, as `atmo render` does), against
 * two references of 512 samples (--quick: 64) with seeds 1 and 3.
 * Error: the relative RMS over pixels and channels against the converged image, estimated
 * without bias from the reference pair (bench_unbiased_error: their mean as the reference,
 * their difference for its own noise, which is removed). Seconds: render (kernel build and
 * precompute left out) plus the filter (device creation included). Rows: method off / fast / balanced / high, settings "N spp". */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include "atmo/bench.h"
#include "atmo/clock.h"
#include "atmo/denoise.h"
#include "atmo/scene.h"

#define BENCH_DENOISE_MAX_ROWS 32

/* The four rows (off, fast, balanced, high) of one image into rows[]. */
static int denoise_rows(const atmo_render_result *r, const atmo_render_result ref[2], int spp,
                        bench_row *rows, atmo_err *e)
{
    float *out = malloc(sizeof(float) * 3 * (size_t)r->width * r->height);
    if (!out)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for the denoised image");
    int rc = ATMO_OK;
    for (int q = -1; q <= ATMO_DENOISE_HIGH && !rc; q++) {
        bench_row *row = &rows[q + 1];
        double seconds = 0.0;
        if (q >= 0) {
            atmo_denoise_input in = {r->width, r->height, r->rgb, NULL, NULL, 0, q};
            double t0 = atmo_now_seconds();
            rc = atmo_denoise_run(&in, out, e);
            seconds = atmo_now_seconds() - t0;
        }
        snprintf(row->method, sizeof row->method, "%s", q < 0 ? "off" : atmo_denoise_quality_name(q));
        snprintf(row->settings, sizeof row->settings, "%d spp", spp);
        row->seconds = r->seconds_render + seconds;
        row->error = bench_unbiased_error(q < 0 ? r->rgb : out, &ref[0], &ref[1]);
        fprintf(stderr, "bench denoise: %-8s %3d spp %8.3fs (filter %.3fs)  error %.3e\n",
                row->method, spp, row->seconds, seconds, row->error);
    }
    free(out);
    return rc;
}

int bench_denoise(const char *dir, const char *device, int quick, atmo_err *e)
{
    atmo_scene base;
    atmo_render_result ref[2];
    int rc;
    if ((rc = atmo_denoise_load(e)))
        return rc;
    atmo_scene_defaults(&base);
    if ((rc = atmo_scene_apply_preset(&base, "thesis-7", e)))
        return rc;
    base.image.width = quick ? 64 : 256;
    base.image.height = quick ? 36 : 144;
    atmo_scene s = base;
    s.image.samples = quick ? 64 : 512;
    fprintf(stderr, "bench denoise: references (2 x %d spp)\n", s.image.samples);
    s.image.seed = 1;
    if ((rc = bench_render(&s, device, &ref[0], e)))
        return rc;
    s.image.seed = 3;
    if ((rc = bench_render(&s, device, &ref[1], e))) {
        atmo_render_result_free(&ref[0]);
        return rc;
    }
    bench_row rows[BENCH_DENOISE_MAX_ROWS];
    int n = 0;
    for (int spp = 1; spp <= (quick ? 8 : 64) && !rc; spp *= 2) {
        atmo_render_result r;
        s = base;
        s.image.samples = spp;
        s.image.seed = 2;
        if ((rc = bench_render(&s, device, &r, e)))
            break;
        rc = denoise_rows(&r, ref, spp, rows + n, e);
        n += 4;
        atmo_render_result_free(&r);
    }
    char device_name[256];
    snprintf(device_name, sizeof device_name, "%s", ref[0].device_name);
    atmo_render_result_free(&ref[0]);
    atmo_render_result_free(&ref[1]);
    if (rc)
        return rc;
    char title[512];
    snprintf(title, sizeof title, "thesis-7 path traced, %dx%d, 1-%d spp, Open Image Denoise %d.%d (%s)",
             base.image.width, base.image.height, quick ? 8 : 64, atmo_denoise_version() / 10000,
             atmo_denoise_version() / 100 % 100, device_name);
    return bench_write_suite(dir, "denoise", rows, n, device_name, title,
                             "relative RMS error (unbiased)", e);
}
