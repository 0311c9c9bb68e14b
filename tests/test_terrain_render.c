/* test_terrain_render — images with terrain: finite everywhere, and the same bits for any
 * tile size.
 * labels: render slow
 *
 * Oracles: IEEE finiteness (no output may hold NaN or Inf, and the render kernel's count of
 * dropped non-finite samples must be 0) and bitwise equality (the random numbers depend on
 * (seed, pixel, sample, dimension) only and the terrain on nothing random, so the image must be
 * identical for any tile size and batch).
 *  1. A sweep of cameras — 1 m above the thesis site's ground, 50 m inside a mountain, exactly
 *     on a sea that covers the planet (land fraction 0), 100 km up and 2000 km up — and suns
 *     30, 89 and 100 degrees from the zenith (the last below the horizon), with methods march
 *     (the terrain through the integrator's surface) and fast (through the terrain render
 *     stage), 8x8 pixels looking down 30 degrees, thesis-1 without its clouds (which method
 *     fast does not render).
 *  2. thesis-1 (its clouds included) with method march at 24x16 pixels, 2 samples: tiles of 8,
 *     16 and 24 pixels and batches of 1 and 2 samples give bitwise the same image. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/render.h"
#include "atmo/terrain_ref.h"
#include "testlib.h"
#include "testscene.h"

static float *render(const atmo_plan *plan, int tile, int max_batch, unsigned *nonfinite)
{
    atmo_render_settings rs;
    atmo_render_result r;
    atmo_err e;
    atmo_render_settings_default(&rs);
    rs.tile_size = tile;
    rs.max_batch = max_batch;
    if (atmo_render(plan, &rs, &r, &e)) {
        fprintf(stderr, "render failed: %s\n", e.msg);
        exit(1);
    }
    *nonfinite = r.nonfinite;
    return r.rgb;
}

/* World y of the terrain's surface above (x, z). */
static double surface_y(const atmo_plan *p, double x, double z)
{
    double R = p->atmosphere.bottom_radius_m;
    double h = fmax(terrain_ref_height(&p->gpu.terrain.field, x, z, NULL, NULL), 0.0);
    return sqrt(1 - (x * x + z * z) / (R * R)) * (R + h) - R;
}

int main(void)
{
    test_require_opencl();
    static const char *const methods[] = {"march", "fast"};
    static const char *const suns[] = {"sun.zenith_deg=30", "sun.zenith_deg=89",
                                       "sun.zenith_deg=100"};
    atmo_scene s;
    atmo_plan base;
    test_scene_preset(&s, "thesis-1");
    test_plan(&s, &base);
    double x = 23796, z = 16636, ground = surface_y(&base, x, z);
    atmo_plan_free(&base);
    char cams[5][96];
    snprintf(cams[0], sizeof cams[0], "camera.position_m=%.3f,%.6f,%.3f", x, ground + 1.0, z);
    snprintf(cams[1], sizeof cams[1], "camera.position_m=%.3f,%.6f,%.3f", x, ground - 50.0, z);
    snprintf(cams[2], sizeof cams[2], "camera.position_m=0,0,0");
    snprintf(cams[3], sizeof cams[3], "camera.position_m=%.3f,1e5,%.3f", x, z);
    snprintf(cams[4], sizeof cams[4], "camera.position_m=%.3f,2e6,%.3f", x, z);
    int renders = 0, clean = 0;
    for (int m = 0; m < 2; m++)
        for (int c = 0; c < 5; c++)
            for (int k = 0; k < 3; k++) {
                char buf[64];
                test_scene_preset(&s, "thesis-1");
                test_scene_set(&s, "clouds.enabled=false");
                snprintf(buf, sizeof buf, "atmosphere.method=%s", methods[m]);
                test_scene_set(&s, buf);
                test_scene_set(&s, cams[c]);
                test_scene_set(&s, suns[k]);
                test_scene_set(&s, "camera.pitch_deg=-30");
                test_scene_set(&s, "image.width=8");
                test_scene_set(&s, "image.height=8");
                test_scene_set(&s, "image.samples=1");
                test_scene_set(&s, "render.view_steps=8");
                if (c == 2)
                    test_scene_set(&s, "terrain.land_fraction=0");
                atmo_plan p;
                test_plan(&s, &p);
                p.cache_luts = 2;
                unsigned bad;
                float *img = render(&p, 64, 0, &bad);
                int finite = bad == 0;
                for (int i = 0; i < 8 * 8 * 3; i++)
                    finite &= isfinite(img[i]) && img[i] >= 0.0f;
                if (!finite)
                    fprintf(stderr, "  %s, %s, %s: non-finite or negative output (%u dropped)\n",
                            methods[m], cams[c], suns[k], bad);
                CHECK(finite);
                renders++, clean += finite;
                free(img);
                atmo_plan_free(&p);
            }
    printf("sweep: %d of %d renders finite and non-negative\n", clean, renders);

    test_scene_preset(&s, "thesis-1");
    test_scene_set(&s, "atmosphere.method=march");
    test_scene_set(&s, "image.width=24");
    test_scene_set(&s, "image.height=16");
    test_scene_set(&s, "image.samples=2");
    test_scene_set(&s, "render.view_steps=8");
    atmo_plan p;
    test_plan(&s, &p);
    p.cache_luts = 2;
    unsigned bad;
    float *first = render(&p, 24, 0, &bad);
    size_t bytes = sizeof(float) * 3 * 24 * 16;
    static const int tiles[][2] = {{8, 1}, {16, 2}, {24, 1}};
    int same = 0;
    for (int i = 0; i < 3; i++) {
        float *other = render(&p, tiles[i][0], tiles[i][1], &bad);
        same += memcmp(first, other, bytes) == 0;
        free(other);
    }
    CHECK(same == 3);
    printf("thesis-1 with terrain: %d of 3 tile/batch variants bitwise equal\n", same);
    free(first);
    atmo_plan_free(&p);
    return test_finish();
}
