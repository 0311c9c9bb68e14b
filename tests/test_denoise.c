/* test_denoise — Intel Open Image Denoise on path-traced images (host/image/denoise.c,
 * host/render/outputs.c): the denoised 4-spp image is closer to the converged image than the
 * raw 4-spp image and keeps the edges; the guides follow OIDN's conventions.
 * labels: render slow
 *
 * Oracle 1, the converged image, estimated without bias. Each scene is rendered twice at
 * REF_SPP / 2 samples per pixel (seeds 1 and 3: the references A and B) and, independently, at
 * 4 (seed 2). With R = (A + B) / 2, for an image X independent of both,
 * E sum (X - R)^2 = sum (X - T)^2 + sum Var(R) over pixels and channels, T the converged image,
 * and E (A - B)^2 = 4 Var(R). So
 *     e(X) = sqrt((sum (X - R)^2 - sum (A - B)^2 / 4) / sum R^2)
 * is the relative RMS error of X against T, the reference's own noise removed, whatever the
 * sampler. The spread of a render's own samples (atmo_render_result.se) does not estimate
 * Var(R) here: the camera's samples are Owen-scrambled Sobol points (path_camera.h), whose
 * mean over a pixel varies less than that of independent samples, most at the silhouettes, so
 * subtracting se^2 removed too much and read the denoised errors low (the sky's guided error
 * 1.53 % with it, 2.06 % with the pair). The checks:
 *   - e(denoised, quality high, as the writes run it: the guide pass's albedo and normal,
 *     cleanAux) <= e(raw) / FACTOR_<scene>. Measured at 48 x 32 with the guide pass's 8 x 8
 *     rays per pixel (docs/guide/denoise.md): 2.42x (sky), 1.89x (terrain), 2.66x (limb),
 *     2.55x (objects); the colour alone gives 2.09x, 1.88x, 1.88x, 2.02x. Most of the raw error
 *     sits on the silhouettes (the pixel filter's 4 samples give a noisy edge coverage), where
 *     the sum is carried by about a hundred pixels: the estimate of each factor then varies by
 *     about 6 % (sqrt(2 / 300) per sum), so each FACTOR_ lies three of those (18 %) below its
 *     scene's measured factor. At this size the issue's expectation of 3x is met on the fog
 *     alone; at 256 x 144 `atmo bench guides` measures the same scenes (docs/guide/denoise.md).
 *     The fog (a cloud shell of tau about 0.1-1 along the view over the terrain scene, the
 *     sky the atmosphere's, so the path tracer marches the shell on every segment): 5.82x with
 *     the guides (6.28x colour alone). Its raw error is carried by a few bright pixels
 *     (fireflies of the 4-spp paths), so it varies more (with the former estimate, over raw
 *     seeds 2-5, from 7.51x down to 3.83x); FACTOR_FOG is the issue's expectation, 3. The
 *     terrain and fog scenes keep the default terrain without its domain warp
 *     (terrain.warp=0), the field these factors were measured on; over the warped field the
 *     fog measured 2.52x guided and 2.74x colour alone, the terrain 1.88x and 1.95x.
 *   - The guides help: e(guided) <= e(colour alone) on the sky and objects scenes (measured
 *     0.86 and 0.79 of it; the ratio's estimate varies by about 8 %), and at most 1.25 of it
 *     on the terrain, the limb and the fog, where they measured 0.99, 0.77 and 1.08 (0.91 to
 *     1.12 over the fog's four seeds with the former estimate: no worse within three of those).
 *     On the fog the clouds' share of the guides (guides.cl: transmittance-weighted) lowered
 *     the guided error to 0.84-0.90 of what guides that see through the fog gave, seed by seed.
 *   - Edges: on the band of pixels where a surface's silhouette against the sky lies (a pixel
 *     and its 8 neighbours disagree on whether the first reference's samples mostly hit a
 *     surface), the error of the denoised image does not exceed the raw image's (the same
 *     estimate on the band alone; measured guided: 19.4 % raw, 6.3 % denoised on the sky
 *     scene's horizon, 20.1 % -> 10.9 % on the planet's limb).
 * Oracle 2, closed forms, for the guides (atmo_outputs_guides_from_passes: the guide pass's)
 * of the objects scene: a pixel whose guide rays all hit the sphere has the sphere's albedo
 * (to 1e-5, the float rounding of a mean of 64 values; the box's albedo differs by 0.1 or
 * more), a normal of unit length up to its averaging (the mean of unit normals over the pixel
 * filter's reach of 1.5 px = 2.1 degrees of view, 0.22 m at 6 m, about 13 degrees of the unit
 * sphere: |n| >= cos 13 deg = 0.97, and <= 1 to float rounding) whose direction matches the
 * closed form n = (t d - c) / R at the pixel's centre within 2 degrees (tests/test_guides.c
 * checks the guides tighter, in both modes); a pixel of open sky has albedo 1 and normal 0
 * (OIDN's convention); the ground far below the horizon has normal (0, 1, 0) (a sphere of
 * 6360 km: within 1e-4). Oracle 3, exact: a denoised EXR holds what the filter gave as R, G, B
 * and the noisy image and the guides as its Blender-named layers, value for value.
 * Scenes (48 x 32 pixels, path mode): a clear sky over the planet's ground (the horizon is the
 * silhouette), procedural terrain seen from 600 m at a grazing angle under a uniform sky, the
 * planet from 2000 km (preset space: its limb against space is the silhouette), the terrain
 * under the atmosphere's sky with a thin fog shell from sea level to 300 m (cloud.enabled,
 * method single: the cloud view; its reference at FOG_REF_SPP), and a sphere and a box on the
 * ground under a uniform sky. The fBm layer is not among them: a thesis cloud view at this
 * size takes about 1 s per sample on two cores (thesis-8: 52 s for a 64-spp reference), and
 * there the filter gained little (thesis-8, 48 x 27, 4 spp against 64: 9.6 % raw, 8.95 %
 * guided, 11.3 % colour alone). Without the library the test exits 77
 * saying how to install it (setup.sh installs it, so CI runs it). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/denoise.h"
#include "atmo/image.h"
#include "atmo/outputs.h"
#include "atmo/render.h"
#include "testlib.h"
#include "testscene.h"

#define W 48
#define H 32
#define REF_SPP 128
#define RAW_SPP 4
/* the smallest factor raw / guided (quality high) each scene must reach, and the largest ratio
 * guided / colour alone it may show (measured and derived in the header) */
#define FACTOR_SKY 2.0
#define FACTOR_TERRAIN 1.55
#define FACTOR_LIMB 1.95
#define FACTOR_OBJECTS 2.1
#define FACTOR_FOG 3.0
/* the fog's reference: its march of the shell on every path segment costs about 0.2 s per
 * sample per 48 x 32 frame, so 64 samples (its own variance is subtracted all the same) */
#define FOG_REF_SPP 64
#define NO_HIT_DEPTH_M 1e10

typedef struct sums {
    double d2, var, ref2;
} sums;

static const char *const objects_keys[] = {
    "sun.zenith_deg=50", "path.sky=uniform", "path.uniform_sky=0.1,0.2,0.3",
    "camera.position_m=0,1.5,0", "camera.pitch_deg=-10",
    "objects=[{\"type\": \"sphere\", \"center_m\": [0.8, 1, 6], \"radius_m\": 1, "
    "\"albedo\": [0.7, 0.5, 0.3]}, {\"type\": \"box\", \"min_m\": [-3, 0, 7], "
    "\"size_m\": [2, 2, 2], \"albedo\": [0.3, 0.6, 0.4]}]",
    NULL};

/* Render the scene of keys at spp samples with seed, with passes and the guide pass. Exits 1
 * on failure. */
static void render_scene(const char *const *keys, int spp, int seed, atmo_render_result *r)
{
    atmo_scene s;
    test_scene_preset(&s, strncmp(keys[0], "preset=", 7) == 0 ? keys[0] + 7 : "sky-noon");
    for (int i = strncmp(keys[0], "preset=", 7) == 0; keys[i]; i++)
        test_scene_set(&s, keys[i]);
    test_scene_set(&s, "render.mode=path");
    test_scene_set(&s, "path.passes=true");
    test_scene_image(&s, W, H, spp, seed);
    atmo_plan p;
    test_plan(&s, &p);
    atmo_render_settings rs;
    atmo_render_settings_default(&rs);
    rs.guides = 1;
    atmo_err e;
    if (atmo_render(&p, &rs, r, &e)) {
        fprintf(stderr, "render failed: %s\n", e.msg);
        exit(1);
    }
    atmo_plan_free(&p);
    CHECK(r->nonfinite == 0);
}

/* The silhouette band of the reference: pixels whose 3 x 3 neighbourhood holds both pixels
 * that mostly hit a surface and pixels that mostly escape. */
static void silhouette_band(const atmo_render_result *ref, unsigned char *band)
{
    size_t pixels = (size_t)W * H;
    const float *np = ref->passes + 4 * pixels * ATMO_PATH_LIGHT_PASSES;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            int hit = 0, miss = 0;
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    int u = x + dx, v = y + dy;
                    if (u < 0 || v < 0 || u >= W || v >= H)
                        continue;
                    if (np[4 * ((size_t)v * W + u) + 3] < 0.5 * NO_HIT_DEPTH_M)
                        hit = 1;
                    else
                        miss = 1;
                }
            band[(size_t)y * W + x] = (unsigned char)(hit && miss);
        }
}

/* Sums of the unbiased error estimate of x against the reference pair over the pixels of mask
 * (all: NULL): R = (A + B) / 2 and its variance (A - B)^2 / 4 per value (the header). */
static sums error_sums(const float *x, const atmo_render_result ref[2], const unsigned char *mask)
{
    sums s = {0, 0, 0};
    for (size_t i = 0; i < (size_t)W * H; i++) {
        if (mask && !mask[i])
            continue;
        for (int c = 0; c < 3; c++) {
            double a = ref[0].rgb[3 * i + c], b = ref[1].rgb[3 * i + c], r = 0.5 * (a + b);
            double d = (double)x[3 * i + c] - r;
            s.d2 += d * d;
            s.var += 0.25 * (a - b) * (a - b);
            s.ref2 += r * r;
        }
    }
    return s;
}

static double rel_error(const float *x, const atmo_render_result ref[2], const unsigned char *mask)
{
    sums s = error_sums(x, ref, mask);
    return sqrt(fmax(s.d2 - s.var, 0.0) / s.ref2);
}

/* raw denoised as the writes do it (atmo_outputs_denoise_rgb): with guides (the guide pass's,
 * clean) or the colour alone. */
static void denoise(const atmo_render_result *raw, int quality, int guided, float *out)
{
    atmo_outputs_guides g = {0};
    float *block = NULL;
    if (guided)
        CHECK(atmo_outputs_guides_from_passes(raw, &g, &block) == 1 && g.clean && !block);
    atmo_err e;
    if (atmo_outputs_denoise_rgb(raw->rgb, W, H, guided ? &g : NULL, quality, out, &e)) {
        fprintf(stderr, "denoise failed: %s\n", e.msg);
        exit(1);
    }
}

/* The error factors of one scene; the first reference (seed 1) is left in *ref for the
 * caller. */
static void check_scene(const char *name, const char *const *keys, int ref_spp,
                        double factor_min, double guided_vs_colour_max, atmo_render_result *ref)
{
    atmo_render_result raw, pair[2];
    render_scene(keys, ref_spp / 2, 1, &pair[0]);
    render_scene(keys, ref_spp / 2, 3, &pair[1]);
    render_scene(keys, RAW_SPP, 2, &raw);
    float *out = malloc(sizeof(float) * 3 * W * H);
    unsigned char band[W * H];
    if (!out)
        exit(1);
    silhouette_band(&pair[0], band);
    int band_pixels = 0;
    for (int i = 0; i < W * H; i++)
        band_pixels += band[i];
    double e_raw = rel_error(raw.rgb, pair, NULL), b_raw = rel_error(raw.rgb, pair, band);
    double e_colour = 0.0;
    printf("%s: raw %d spp %.2f %% (silhouette band of %d pixels: %.2f %%)\n", name, RAW_SPP,
           100.0 * e_raw, band_pixels, 100.0 * b_raw);
    for (int guided = 0; guided <= 1; guided++)
        for (int q = ATMO_DENOISE_FAST; q <= ATMO_DENOISE_HIGH; q++) {
            denoise(&raw, q, guided, out);
            double e_dn = rel_error(out, pair, NULL), b_dn = rel_error(out, pair, band);
            printf("  denoised %-8s %-7s %.2f %% (%.2fx lower), band %.2f %%\n",
                   atmo_denoise_quality_name(q), guided ? "guided" : "colour", 100.0 * e_dn,
                   e_raw / e_dn, 100.0 * b_dn);
            if (!guided && q == ATMO_DENOISE_HIGH)
                e_colour = e_dn;
            if (guided && q == ATMO_DENOISE_HIGH)
                CHECK(e_dn * factor_min <= e_raw && e_dn <= e_colour * guided_vs_colour_max);
            CHECK(band_pixels > 0 && b_dn <= b_raw);
        }
    free(out);
    atmo_render_result_free(&raw);
    atmo_render_result_free(&pair[1]);
    *ref = pair[0];
}

/* Oracle 2 on the objects scene's reference (see the header). */
static void check_guides(const atmo_render_result *ref)
{
    atmo_outputs_guides g;
    float *data;
    int have = atmo_outputs_guides_from_passes(ref, &g, &data);
    CHECK(have == 1 && g.clean);
    if (have != 1)
        return;
    double forward[3], right[3], up[3], c[3] = {0.8, -0.5, 6.0};
    atmo_camera_basis(-10.0, 0.0, forward, right, up);
    double th = tan(22.5 * M_PI / 180.0), worst_angle = 0.0, worst_len = 1.0;
    int sphere = 0, sky = 0, ground = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            size_t i = (size_t)y * W + x;
            const float *a = g.albedo + 3 * i, *n = g.normal + 3 * i;
            double len = sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
            /* every sample on the sphere: its albedo, to the float rounding of the mean */
            if (fabs(a[0] - 0.7) < 1e-5 && fabs(a[1] - 0.5) < 1e-5 && fabs(a[2] - 0.3) < 1e-5) {
                double sx = (2.0 * (x + 0.5) / W - 1.0) * th * W / H;
                double sy = (1.0 - 2.0 * (y + 0.5) / H) * th, d[3], dd = 0.0, b = 0.0, f2 = 0.0;
                for (int k = 0; k < 3; k++)
                    d[k] = forward[k] + sx * right[k] + sy * up[k], dd += d[k] * d[k];
                for (int k = 0; k < 3; k++)
                    d[k] /= sqrt(dd), b -= d[k] * c[k], f2 += c[k] * c[k];
                double t = -b - sqrt(fmax(b * b - f2 + 1.0, 0.0)), dot = 0.0;
                for (int k = 0; k < 3; k++)
                    dot += (t * d[k] - c[k]) * n[k] / len;
                worst_angle = fmax(worst_angle, acos(fmin(dot, 1.0)) * 180.0 / M_PI);
                worst_len = fmin(worst_len, len);
                CHECK(len >= 0.97 && len <= 1.0 + 1e-5);
                sphere++;
            }
            if (g.depth[i] >= (float)NO_HIT_DEPTH_M) { /* every sample escapes */
                CHECK(a[0] == 1.0f && a[1] == 1.0f && a[2] == 1.0f && len == 0.0);
                sky++;
            }
            if (y == H - 1 && (x < 4 || x >= W - 4) && g.depth[i] < 10.0f) { /* near ground */
                CHECK(fabs(n[0]) < 1e-4 && fabs(n[1] - 1.0) < 1e-4 && fabs(n[2]) < 1e-4);
                ground++;
            }
        }
    printf("guides: %d sphere pixels (|n| >= %.5f, worst angle to the closed form %.2f deg), "
           "%d sky pixels, %d ground pixels\n", sphere, worst_len, worst_angle, sky, ground);
    CHECK(worst_angle <= 2.0);
    CHECK(sphere >= 20 && sky >= 20 && ground >= 4);
    free(data);
}

/* The EXR of a denoised write (atmo_outputs_write_denoised, output.denoise = fast): R, G, B
 * are the filter's output, exactly what atmo_denoise_run gives, and the layers hold the noisy
 * image and the guides exactly (the EXR stores floats losslessly). */
static void check_exr_layers(const atmo_render_result *r)
{
    const char *path = "test_denoise.exr";
    atmo_scene s;
    test_scene_preset(&s, "sky-noon");
    test_scene_set(&s, "output.denoise=fast");
    atmo_outputs_guides g;
    float *data, *want = malloc(sizeof(float) * 3 * W * H);
    CHECK(atmo_outputs_guides_from_passes(r, &g, &data) == 1 && want);
    atmo_image img = {W, H, r->rgb, NULL, 0};
    atmo_outputs_denoise info;
    atmo_err e;
    atmo_exr_file f = {0};
    int rc = atmo_outputs_write_denoised(&s, &img, &g, 4, 0, ATMO_EXR_DEFAULT, &path, 1, &info, &e);
    CHECK(rc == ATMO_OK && info.applied && info.guided && info.clean_aux &&
          info.quality == ATMO_DENOISE_FAST);
    if (rc == ATMO_OK && atmo_exr_read(path, &f, &e) == ATMO_OK) {
        denoise(r, ATMO_DENOISE_FAST, 1, want);
        static const char *const names[] = {"R", "G", "B", "Noisy Image.R", "Noisy Image.G",
                                            "Noisy Image.B", "Denoising Albedo.R",
                                            "Denoising Albedo.G", "Denoising Albedo.B",
                                            "Denoising Normal.X", "Denoising Normal.Y",
                                            "Denoising Normal.Z", "Denoising Depth.Z"};
        int mismatched = 0, denoised_differs = 0;
        for (int k = 0; k < 13; k++) {
            const float *ch = atmo_exr_channel_data(&f, names[k]);
            CHECK(ch != NULL);
            for (int i = 0; ch && i < W * H; i++) {
                int c = k % 3;
                float v = k < 3    ? want[3 * i + c]
                          : k < 6  ? r->rgb[3 * i + c]
                          : k < 9  ? g.albedo[3 * i + c]
                          : k < 12 ? g.normal[3 * i + c]
                                   : g.depth[i];
                mismatched += ch[i] != v;
                denoised_differs += k < 3 && ch[i] != r->rgb[3 * i + c];
            }
        }
        printf("EXR layers: %d values differ from what was written, the denoised R, G, B differ "
               "from the noisy image in %d of %d values\n", mismatched, denoised_differs,
               3 * W * H);
        CHECK(mismatched == 0 && denoised_differs > W * H);
    } else
        fprintf(stderr, "%s\n", e.msg);
    atmo_exr_file_free(&f);
    remove(path);
    free(want);
    free(data);
}

int main(void)
{
    test_require_opencl();
    atmo_err e;
    int rc = atmo_denoise_load(&e);
    if (rc == ATMO_ERR_USAGE) {
        printf("skipped: %s\n", e.msg);
        return 77;
    }
    CHECK(rc == ATMO_OK);
    printf("Open Image Denoise %d (%s)\n", atmo_denoise_version(), atmo_denoise_library_path());
    static const char *const sky[] = {"sun.zenith_deg=60", "camera.pitch_deg=-5", NULL};
    static const char *const limb[] = {"preset=space", NULL};
    static const char *const terrain[] = {
        "terrain.enabled=true", "terrain.warp=0", "camera.position_m=0,600,0",
        "camera.pitch_deg=-8", "sun.zenith_deg=60", "path.sky=uniform",
        "path.uniform_sky=0.05,0.08,0.12", "path.bounces=2", NULL};
    static const char *const fog[] = {
        "terrain.enabled=true", "terrain.warp=0", "camera.position_m=0,600,0",
        "camera.pitch_deg=-8", "sun.zenith_deg=60", "path.bounces=2", "cloud.enabled=true",
        "cloud.bottom_m=0", "cloud.top_m=300", "cloud.lwc_g_m3=0.0005",
        "atmosphere.method=single", NULL};
    atmo_render_result ref;
    check_scene("clear sky over the ground", sky, REF_SPP, FACTOR_SKY, 1.0, &ref);
    atmo_render_result_free(&ref);
    check_scene("terrain", terrain, REF_SPP, FACTOR_TERRAIN, 1.25, &ref);
    atmo_render_result_free(&ref);
    check_scene("the planet's limb from 2000 km", limb, REF_SPP, FACTOR_LIMB, 1.25, &ref);
    atmo_render_result_free(&ref);
    check_scene("fog over the terrain", fog, FOG_REF_SPP, FACTOR_FOG, 1.25, &ref);
    atmo_render_result_free(&ref);
    check_scene("objects", objects_keys, REF_SPP, FACTOR_OBJECTS, 1.0, &ref);
    check_guides(&ref);
    check_exr_layers(&ref);
    atmo_render_result_free(&ref);
    return test_finish();
}
