/* bench_sky.c — `atmo bench sky`: the single-scattering sky for several view-ray step counts
 * and transmittance LUT sizes (panorama 256 x 128, sun zenith 80 deg, 4 samples per pixel),
 * against 1024 steps and a 1024 x 256 LUT with the same samples and seed, so that the random
 * offsets are shared and the difference is the discretisation error, not noise (method single:
 * the default method, fast, would not march with these steps). The LUT rows march with the
 * reference's steps, so their error is the LUT's alone.
 * Error: the RMS over pixels of the relative difference of the three channels; seconds:
 * precompute + render (kernel builds are timed apart and left out). */
#include <stdio.h>
#include <string.h>
#include "atmo/bench.h"
#include "atmo/scene.h"

int bench_sky(const char *dir, const char *device, int quick, atmo_err *e)
{
    atmo_scene base;
    int rc;
    atmo_scene_defaults(&base);
    if ((rc = atmo_scene_apply_preset(&base, "sky-sunset", e)) ||
        (rc = atmo_scene_assign(&base, "camera.kind=panorama", "bench", e)) ||
        (rc = atmo_scene_assign(&base, "atmosphere.method=single", "bench", e)) ||
        (rc = atmo_scene_assign(&base, "sun.zenith_deg=80", "bench", e)))
        return rc;
    base.image.width = quick ? 64 : 256;
    base.image.height = quick ? 32 : 128;
    base.image.samples = 4;

    atmo_scene ref = base;
    ref.render.view_steps = quick ? 256 : 1024;
    ref.render.transmittance_width = 1024;
    ref.render.transmittance_height = 256;
    atmo_render_result r_ref;
    fprintf(stderr, "bench sky: reference (%d steps, LUT 1024x256)\n", ref.render.view_steps);
    if ((rc = bench_render(&ref, device, &r_ref, e)))
        return rc;

    static const int steps[] = {4, 8, 16, 32, 64, 128};
    static const int luts[][2] = {{16, 4}, {32, 8}, {64, 16}, {128, 32}, {256, 64}, {512, 128}};
    int n_steps = quick ? 3 : 6, n_luts = quick ? 2 : 6;
    bench_row rows[16];
    int n = 0;
    for (int pass = 0; pass < 2; pass++) {
        int count = pass == 0 ? n_steps : n_luts;
        for (int i = 0; i < count && !rc; i++) {
            atmo_scene s = base;
            bench_row *row = &rows[n];
            if (pass == 0) {
                s.render.view_steps = steps[i];
                snprintf(row->method, sizeof row->method, "view-steps");
                snprintf(row->settings, sizeof row->settings, "%d", steps[i]);
            } else {
                s.render.view_steps = ref.render.view_steps; /* the LUT's error alone */
                s.render.transmittance_width = luts[i][0];
                s.render.transmittance_height = luts[i][1];
                snprintf(row->method, sizeof row->method, "lut-size");
                snprintf(row->settings, sizeof row->settings, "%dx%d", luts[i][0], luts[i][1]);
            }
            atmo_render_result r;
            if ((rc = bench_render(&s, device, &r, e)))
                break;
            row->seconds = r.seconds_precompute + r.seconds_render;
            row->error = bench_rms_relative(&r, &r_ref);
            fprintf(stderr, "bench sky: %-10s %-8s %8.4fs  error %.3e\n", row->method,
                    row->settings, row->seconds, row->error);
            atmo_render_result_free(&r);
            n++;
        }
    }
    char device_name[256];
    snprintf(device_name, sizeof device_name, "%s", r_ref.device_name);
    atmo_render_result_free(&r_ref);
    if (rc)
        return rc;
    char title[512];
    snprintf(title, sizeof title, "single-scattering sky, 256x128 panorama, 4 spp (%s)",
             device_name);
    return bench_write_suite(dir, "sky", rows, n, device_name, title, "RMS relative error", e);
}

