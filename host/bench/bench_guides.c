/* bench_guides.c — `atmo bench guides`: what the denoiser's albedo and normal guides buy, at a
 * resolution where Open Image Denoise sees whole features, on the scenes of
 * tests/test_denoise.c.
 *
 * Scenes (path mode): a clear sky over the planet's ground (its horizon is the silhouette),
 * procedural terrain from 600 m at a grazing angle under a uniform sky, the planet's limb from
 * 2000 km (preset space), and a sphere and a box on the ground under a uniform sky. Each is
 * rendered at 256 x 144 (--quick: 64 x 36) with RAW_SPP samples per pixel (seed 2) and the
 * guide pass, and, independently, twice at REF_SPP (--quick: REF_SPP_QUICK; seeds 1 and 4) as
 * the reference pair.
 * Rows per scene (settings = the scene): `raw`, `colour` (quality high on the colour alone) and
 * `guided` (quality high with the guide pass's albedo and normal, cleanAux: what `atmo render
 * --denoise high` does), each error the unbiased relative RMS against the converged image
 * (bench_unbiased_error: the reference's own variance removed), and `raw 64` (an
 * independent MANY_SPP render, seed 3): what sixteen times the samples give without the
 * filter. Seconds: the render (kernel build and precompute left out) plus, for the denoised
 * rows, the filter and, for `guided`, the guide pass.
 *
 * test_denoise asserts the factors raw / guided at 48 x 32, where a handful of silhouette
 * pixels carry the error; this bench charts them where the filter has context. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include "atmo/bench.h"
#include "atmo/clock.h"
#include "atmo/denoise.h"
#include "atmo/outputs.h"
#include "atmo/scene.h"

#define RAW_SPP 4
#define MANY_SPP 64
#define REF_SPP 64
#define REF_SPP_QUICK 16
#define GUIDES_SCENES 4
#define GUIDES_ROWS 4 /* per scene: raw, colour, guided, raw at MANY_SPP */

typedef struct guides_scene {
    const char *name;
    const char *preset;
    const char *keys[10];
} guides_scene;

static const guides_scene guides_scenes[GUIDES_SCENES] = {
    {"sky", "sky-noon", {"sun.zenith_deg=60", "camera.pitch_deg=-5", NULL}},
    {"terrain", "sky-noon",
     {"terrain.enabled=true", "terrain.warp=0", "camera.position_m=0,600,0",
      "camera.pitch_deg=-8", "sun.zenith_deg=60", "path.sky=uniform",
      "path.uniform_sky=0.05,0.08,0.12", "path.bounces=2", NULL}},
    {"limb", "space", {NULL}},
    {"objects", "sky-noon",
     {"sun.zenith_deg=50", "path.sky=uniform", "path.uniform_sky=0.1,0.2,0.3",
      "camera.position_m=0,1.5,0", "camera.pitch_deg=-10",
      "objects=[{\"type\": \"sphere\", \"center_m\": [0.8, 1, 6], \"radius_m\": 1, "
      "\"albedo\": [0.7, 0.5, 0.3]}, {\"type\": \"box\", \"min_m\": [-3, 0, 7], "
      "\"size_m\": [2, 2, 2], \"albedo\": [0.3, 0.6, 0.4]}]",
      NULL}},
};

/* Render scene c at w x h, spp samples, seed, in path mode, with (guides) the guide pass. */
static int guides_render(const guides_scene *c, int w, int h, int spp, int seed, int guides,
                         const char *device, atmo_render_result *r, atmo_err *e)
{
    atmo_scene s;
    atmo_plan plan;
    atmo_render_settings rs;
    int rc;
    atmo_scene_defaults(&s);
    if ((rc = atmo_scene_apply_preset(&s, c->preset, e)))
        return rc;
    for (int i = 0; c->keys[i] && !rc; i++)
        rc = atmo_scene_assign(&s, c->keys[i], "bench guides", e);
    if (!rc)
        rc = atmo_scene_assign(&s, "render.mode=path", "bench guides", e);
    if (rc)
        return rc;
    s.image.width = w;
    s.image.height = h;
    s.image.samples = spp;
    s.image.seed = seed;
    if ((rc = atmo_plan_make(&s, &plan, e)))
        return rc;
    atmo_render_settings_default(&rs);
    rs.device = device;
    rs.guides = guides;
    rc = atmo_render(&plan, &rs, r, e);
    atmo_plan_free(&plan);
    return rc;
}

/* The rows raw, colour and guided of one scene into rows[0..2]. */
static int guides_rows(const guides_scene *c, const atmo_render_result *raw,
                       const atmo_render_result ref[2], bench_row *rows, atmo_err *e)
{
    int w = raw->width, h = raw->height, rc = ATMO_OK;
    float *out = malloc(sizeof(float) * 3 * (size_t)w * h), *block = NULL;
    atmo_outputs_guides g = {0};
    if (!out)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for the denoised image");
    if (atmo_outputs_guides_from_passes(raw, &g, &block) != 1 || !g.clean) {
        rc = atmo_fail(e, ATMO_ERR_RUNTIME, "bench guides: %s has no clean guides", c->name);
        goto done;
    }
    static const char *const methods[3] = {"raw", "colour", "guided"};
    for (int k = 0; k < 3 && !rc; k++) {
        double t0 = atmo_now_seconds(), filter = 0.0;
        if (k > 0) {
            rc = atmo_outputs_denoise_rgb(raw->rgb, w, h, k == 2 ? &g : NULL, ATMO_DENOISE_HIGH,
                                          out, e);
            filter = atmo_now_seconds() - t0;
        }
        bench_row *row = &rows[k];
        snprintf(row->method, sizeof row->method, "%s", methods[k]);
        snprintf(row->settings, sizeof row->settings, "%s", c->name);
        row->seconds = raw->seconds_render + filter + (k == 2 ? raw->seconds_guides : 0.0);
        row->error = bench_unbiased_error(k == 0 ? raw->rgb : out, &ref[0], &ref[1]);
        fprintf(stderr, "bench guides: %-8s %-6s %8.3fs  error %.3e\n", c->name, row->method,
                row->seconds, row->error);
    }
done:
    free(block);
    free(out);
    return rc;
}

int bench_guides(const char *dir, const char *device, int quick, atmo_err *e)
{
    int w = quick ? 64 : 256, h = quick ? 36 : 144, ref_spp = quick ? REF_SPP_QUICK : REF_SPP;
    bench_row rows[GUIDES_ROWS * GUIDES_SCENES];
    char device_name[256] = "";
    int rc, n = 0;
    if ((rc = atmo_denoise_load(e)))
        return rc;
    for (int i = 0; i < GUIDES_SCENES && !rc; i++) {
        const guides_scene *c = &guides_scenes[i];
        atmo_render_result ref[2], raw;
        fprintf(stderr, "bench guides: %s, references (2 x %d spp)\n", c->name, ref_spp);
        if ((rc = guides_render(c, w, h, ref_spp, 1, 0, device, &ref[0], e)))
            break;
        if ((rc = guides_render(c, w, h, ref_spp, 4, 0, device, &ref[1], e))) {
            atmo_render_result_free(&ref[0]);
            break;
        }
        if (!(rc = guides_render(c, w, h, RAW_SPP, 2, 1, device, &raw, e))) {
            rc = guides_rows(c, &raw, ref, rows + n, e);
            snprintf(device_name, sizeof device_name, "%s", raw.device_name);
            atmo_render_result_free(&raw);
        }
        if (!rc && !(rc = guides_render(c, w, h, MANY_SPP, 3, 0, device, &raw, e))) {
            bench_row *row = &rows[n + 3];
            snprintf(row->method, sizeof row->method, "raw %d", MANY_SPP);
            snprintf(row->settings, sizeof row->settings, "%s", c->name);
            row->seconds = raw.seconds_render;
            row->error = bench_unbiased_error(raw.rgb, &ref[0], &ref[1]);
            fprintf(stderr, "bench guides: %-8s %-6s %8.3fs  error %.3e\n", c->name,
                    row->method, row->seconds, row->error);
            atmo_render_result_free(&raw);
        }
        n += GUIDES_ROWS;
        atmo_render_result_free(&ref[0]);
        atmo_render_result_free(&ref[1]);
    }
    if (rc)
        return rc;
    char title[512];
    snprintf(title, sizeof title,
             "denoised %d spp against 2 x %d spp, %dx%d, path traced: raw, colour alone, guided, raw 64 spp "
             "(Open Image Denoise %d.%d, quality high; %s)",
             RAW_SPP, ref_spp, w, h, atmo_denoise_version() / 10000,
             atmo_denoise_version() / 100 % 100, device_name);
    return bench_write_suite(dir, "guides", rows, n, device_name, title,
                             "relative RMS error (unbiased)", e);
}
