/* test_path_clouds — the path tracer's scattering events in the fBm cloud layer (path.clouds =
 * volume: kernels/render/volume_stage.h, kernels/media/media_walk.h, kernels/render/path.h).
 * labels: render kernel stat slow
 *
 * 1. Furnace (oracle: closed form). The uniform test world (path.sky = uniform: no air, no
 *    planet, no ground; the sun off) with the cloud layer of albedo 1 (clouds.albedo = 1 with
 *    clouds.extinction_per_m > 0: the same sigma_t in every channel) under a uniform sky of
 *    radiance L_u = (1, 0.5, 0.25): scattering without absorption keeps a uniform radiance field
 *    uniform, so every pixel's expected radiance is L_u, whatever the clouds' shape and the
 *    number of scatterings. The camera sits above a heterogeneous layer (coverage 0.7, optical
 *    depths up to ~10), looking down through it; for the Mie table, Henyey-Greenstein and
 *    Jendersie-d'Eon phases the image mean must lie within 4.4 standard errors of L_u (two-sided
 *    p ~ 1e-5, from the per-pixel standard errors, pixels independent), and the standard error
 *    must be positive in every channel: without a scattering event every sample would be L_u
 *    exactly, so a positive error shows that the paths scatter in the clouds.
 * 2. Agreement with the unbiased reference (oracle: atmosphere.method = reference in preview,
 *    which tracks the same layer through its own walk, method_reference.h). A layer whose noise
 *    is stretched flat (frequencies 1e-8 /m, coverage features 1e8 m: horizontally uniform over
 *    the scene, so the preview's box and the path tracer's Gaussian pixel footprints see the same
 *    medium), 1-2 km, albedo 0.95, Henyey-Greenstein with the cumulus table's g, the air off,
 *    the planet's ground (albedo 0.3) below, the sun at 30 degrees; the camera above it looking
 *    down, 6 x 6 pixels at 512 samples. Each pixel's mean from path mode (path.clouds = volume,
 *    sun and sky NEE on, Russian roulette) and from the reference agree within a z-test on the
 *    two standard errors (each the session's, from the per-pixel second moments of
 *    independent samples): |z| < 4.4 in every pixel and channel (36 x 3 tests: family-wise
 *    p ~ 1e-3), and the image means within 4.4 of each other (their standard error is ~3 %;
 *    the Mie table's forward peak makes both estimators' error ~10 times larger at equal
 *    samples, so it is left to the furnace).
 * 3. Determinism and finiteness (oracle: the renderer's contract). The furnace's scene with the
 *    sun on (ratio-tracked shadows) rendered with tiles of 16 and one launch per sample and with
 *    tiles of 3 and no batch bound is bitwise the same, every pixel finite and non-negative,
 *    no dropped sample. The same (finite, non-negative, nothing dropped) over a sweep with the
 *    atmosphere (method single) and the default layer: density 0 and 1e4 (optical depths of
 *    1e5), coverage 0 and 1, the sun below the horizon, the camera inside a cloud, above the
 *    layer and in space (1000 km), 4 x 4 pixels at 2 samples each. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "testlib.h"
#include "testscene.h"

static void set(atmo_scene *s, const char *fmt, double v)
{
    char buf[128];
    snprintf(buf, sizeof buf, fmt, v);
    test_scene_set(s, buf);
}

static void furnace_scene(atmo_scene *s)
{
    test_scene_preset(s, "sky-noon");
    test_scene_set(s, "render.mode=path");
    test_scene_set(s, "path.sky=uniform");
    test_scene_set(s, "path.ground=false");
    test_scene_set(s, "path.uniform_sky=1,0.5,0.25");
    test_scene_set(s, "sun.irradiance_scale=0");
    test_scene_set(s, "clouds.enabled=true");
    test_scene_set(s, "path.clouds=volume");
    test_scene_set(s, "path.volume_bounces=4096"); /* roulette ends the paths, not the cap */
    test_scene_set(s, "clouds.bottom_m=1000");
    test_scene_set(s, "clouds.top_m=2000");
    test_scene_set(s, "clouds.fade_m=300");
    test_scene_set(s, "clouds.coverage=0.7");
    test_scene_set(s, "clouds.extinction_per_m=0.005");
    test_scene_set(s, "clouds.albedo=1");
    test_scene_set(s, "camera.position_m=0,2500,0");
    test_scene_set(s, "camera.pitch_deg=-30");
    test_scene_set(s, "camera.fov_deg=90");
    test_scene_set(s, "image.width=10");
    test_scene_set(s, "image.height=10");
}

static void test_furnace(void)
{
    static const double L[3] = {1.0, 0.5, 0.25};
    static const char *const phases[] = {"mie", "hg", "jendersie-deon"};
    for (int k = 0; k < 3; k++) {
        atmo_scene s;
        char buf[64];
        furnace_scene(&s);
        snprintf(buf, sizeof buf, "clouds.phase=%s", phases[k]);
        test_scene_set(&s, buf);
        test_scene_set(&s, "image.samples=128");
        test_image im = test_render(&s, 64, 0);
        int n = im.w * im.h;
        for (int c = 0; c < 3; c++) {
            double sum = 0.0, var = 0.0;
            for (int i = 0; i < n; i++) {
                sum += im.mean[3 * i + c];
                var += (double)im.se[3 * i + c] * im.se[3 * i + c];
            }
            double mean = sum / n, se = sqrt(var) / n, z = se > 0.0 ? (mean - L[c]) / se : 0.0;
            printf("furnace phase %s channel %d: mean %.5f want %.5f, z = %+.2f, se %.2g "
                   "relative\n",
                   phases[k], c, mean, L[c], z, se / L[c]);
            CHECK(se > 0.0);
            CHECK(fabs(z) < 4.4);
        }
        test_image_free(&im);
    }
}

#define AGREE_SAMPLES 512

static void agreement_scene(atmo_scene *s)
{
    test_scene_preset(s, "sky-noon");
    test_scene_set(s, "atmosphere.rayleigh_coefficient=0");
    test_scene_set(s, "atmosphere.mie_extinction_per_m=0");
    test_scene_set(s, "atmosphere.ozone_column_du=0");
    test_scene_set(s, "atmosphere.ground_albedo=0.3");
    test_scene_set(s, "atmosphere.method=reference");
    test_scene_flat_cloud_view(s);
    test_scene_set(s, "image.width=6");
    test_scene_set(s, "image.height=6");
}

static void test_agreement(void)
{
    atmo_scene ref, path;
    agreement_scene(&ref);
    set(&ref, "image.samples=%g", AGREE_SAMPLES);
    agreement_scene(&path);
    test_scene_set(&path, "render.mode=path");
    test_scene_set(&path, "path.clouds=volume");
    set(&path, "image.samples=%g", AGREE_SAMPLES);
    test_image a = test_render(&ref, 64, 0), b = test_render(&path, 64, 0);
    double z_max;
    int bad = test_image_agree("agreement", "reference", &a, "path volume", &b, 4.4, &z_max);
    printf("agreement: %d of %d pixel-channels with |z| >= 4.4 (largest |z| %.2f)\n", bad,
           3 * a.w * a.h, z_max);
    CHECK(bad == 0);
    test_image_free(&a);
    test_image_free(&b);
}

static void test_determinism(void)
{
    atmo_scene s;
    furnace_scene(&s);
    test_scene_set(&s, "sun.irradiance_scale=1");
    test_scene_set(&s, "sun.zenith_deg=40");
    test_scene_set(&s, "image.samples=3");
    test_image a = test_render(&s, 16, 1), b = test_render(&s, 3, 0);
    size_t bytes = sizeof(float) * 3 * 10 * 10;
    CHECK(memcmp(a.mean, b.mean, bytes) == 0);
    int finite = 1;
    for (int i = 0; i < 3 * 10 * 10; i++)
        finite &= isfinite(a.mean[i]) && a.mean[i] >= 0.0f;
    CHECK(finite);
    printf("determinism: tiles 16/3, batches 1/any %s; finite and non-negative: %s\n",
           memcmp(a.mean, b.mean, bytes) == 0 ? "bitwise equal" : "DIFFER", finite ? "yes" : "NO");
    test_image_free(&a);
    test_image_free(&b);
}

static void test_sweep(void)
{
    static const char *const cases[][2] = {
        {"clouds.density=0", "camera.pitch_deg=20"},
        {"clouds.density=1e4", "camera.pitch_deg=20"},
        {"clouds.coverage=0", "camera.pitch_deg=20"},
        {"clouds.coverage=1", "camera.pitch_deg=20"},
        {"sun.zenith_deg=100", "camera.pitch_deg=20"},
        {"camera.position_m=0,4000,0", "clouds.coverage=1"},
        {"camera.position_m=0,9000,0", "camera.pitch_deg=-40"},
        {"camera.position_m=0,1e6,0", "camera.pitch_deg=-90"},
    };
    int n = (int)(sizeof cases / sizeof cases[0]), bad_cases = 0;
    for (int k = 0; k < n; k++) {
        atmo_scene s;
        test_scene_preset(&s, "sky-afternoon");
        test_scene_set(&s, "render.mode=path");
        test_scene_set(&s, "atmosphere.method=single");
        test_scene_set(&s, "render.view_steps=8");
        test_scene_set(&s, "clouds.enabled=true");
        test_scene_set(&s, "path.clouds=volume");
        test_scene_set(&s, "image.width=4");
        test_scene_set(&s, "image.height=4");
        test_scene_set(&s, "image.samples=2");
        test_scene_set(&s, cases[k][0]);
        test_scene_set(&s, cases[k][1]);
        test_image im = test_render(&s, 16, 0);
        int ok = 1;
        for (int i = 0; i < 3 * 16; i++)
            ok &= isfinite(im.mean[i]) && im.mean[i] >= 0.0f;
        bad_cases += !ok;
        if (!ok)
            printf("sweep: %s %s: a pixel not finite or negative\n", cases[k][0], cases[k][1]);
        test_image_free(&im);
    }
    printf("sweep: %d of %d configurations finite and non-negative\n", n - bad_cases, n);
    CHECK(bad_cases == 0);
}

int main(void)
{
    test_require_opencl();
    test_furnace();
    test_agreement();
    test_determinism();
    test_sweep();
    return test_finish();
}
