/* test_path_furnace — the path tracer (kernels/render/path.h) in worlds whose answer is known
 * in closed form, and its determinism.
 * labels: render kernel stat slow
 *
 * 1. Furnace (oracle: closed form). A white Lambertian sphere (albedo 1, radius 5 m, 10 m in
 *    front of the camera, filling the 10 x 10 frame) under a uniform sky of radiance
 *    L = (1, 0.5, 0.25) with no air, no sun, no ground (path.sky = uniform,
 *    sun.irradiance_scale = 0, path.ground = false) reflects exactly L: every bounce off a convex sphere escapes, and the BSDF's
 *    weight is the albedo, 1. BSDF sampling alone (path.sky_nee = false) returns L in every
 *    sample (zero variance; checked to float rounding, 1e-6 relative); with sky sampling and
 *    MIS the estimator is unbiased with variance: the image mean must lie within 4.4 standard
 *    errors (two-sided p ~ 1e-5; from the per-pixel standard errors of the second moments,
 *    pixels independent) of L, and its standard error must be positive (a test that can fail
 *    both ways). With N_s = 3 secondary rays the same.
 * 2. The sphere with the light inside (pbrt's furnace variant; oracle: closed form). The camera
 *    at the centre of a sphere of radius 2 m with emission L_e = (1, 2, 3) and albedo a = 0.5,
 *    the sky black: a path sees L_e at each of its vertices, weighted a^k, so with N_b
 *    reflections (the camera ray's hit, then each reflection's continuation hit)
 *        L = L_e sum_{k=0}^{N_b} a^k,
 *    N_b = 20 with Russian roulette from event 3 (unbiased): the image mean within 4.4
 *    standard errors of that; and N_b = 2 without roulette, 1.75 L_e, where every sample
 *    equals it (the enclosure catches every ray: zero variance, 1e-6).
 * 3. Determinism (oracle: the renderer's contract). A path-traced scene with the atmosphere
 *    (method single), the ground and two objects, 16 x 12 pixels at 3 samples, rendered with
 *    tiles of 16 and one launch per sample, and with tiles of 5 and no batch bound, is bitwise
 *    the same; every pixel finite and non-negative, no dropped sample; another seed differs. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "testlib.h"
#include "testscene.h"

/* z of the image mean of channel c against want; *rel_spread the largest |pixel/want - 1| */
static double image_z(const test_image *im, int c, double want, double *rel_spread,
                      double *se_out)
{
    double sum = 0.0, var = 0.0, spread = 0.0;
    int n = im->w * im->h;
    for (int i = 0; i < n; i++) {
        sum += im->mean[3 * i + c];
        var += (double)im->se[3 * i + c] * im->se[3 * i + c];
        spread = fmax(spread, fabs(im->mean[3 * i + c] / want - 1.0));
    }
    double mean = sum / n, se = sqrt(var) / n;
    *rel_spread = spread;
    *se_out = se;
    return se > 0.0 ? (mean - want) / se : (mean == want ? 0.0 : INFINITY);
}

static void base_scene(atmo_scene *s)
{
    test_scene_preset(s, "sky-noon");
    test_scene_set(s, "render.mode=path");
    test_scene_set(s, "path.sky=uniform");
    test_scene_set(s, "path.ground=false");
    test_scene_set(s, "sun.irradiance_scale=0"); /* the uniform world's sun off */
    test_scene_set(s, "camera.position_m=0,100,0");
    test_scene_set(s, "camera.pitch_deg=0");
    test_scene_set(s, "image.width=10");
    test_scene_set(s, "image.height=10");
}

static void test_furnace(void)
{
    static const double L[3] = {1.0, 0.5, 0.25};
    struct { int sky_nee, secondary, samples; } cases[] = {{0, 1, 4}, {1, 1, 64}, {1, 3, 32}};
    for (int k = 0; k < 3; k++) {
        atmo_scene s;
        char buf[96];
        base_scene(&s);
        test_scene_set(&s, "path.uniform_sky=1,0.5,0.25");
        test_scene_set(&s, "objects=[{\"type\": \"sphere\", \"center_m\": [0, 100, 10], "
                           "\"radius_m\": 5, \"albedo\": [1, 1, 1]}]");
        snprintf(buf, sizeof buf, "path.sky_nee=%s", cases[k].sky_nee ? "true" : "false");
        test_scene_set(&s, buf);
        snprintf(buf, sizeof buf, "path.secondary=%d", cases[k].secondary);
        test_scene_set(&s, buf);
        snprintf(buf, sizeof buf, "image.samples=%d", cases[k].samples);
        test_scene_set(&s, buf);
        test_image im = test_render(&s, 64, 0);
        for (int c = 0; c < 3; c++) {
            double spread, se, z = image_z(&im, c, L[c], &spread, &se);
            printf("furnace sky_nee=%d N_s=%d channel %d: z = %+.2f, se %.2g, pixel spread "
                   "%.2g\n",
                   cases[k].sky_nee, cases[k].secondary, c, z, se / L[c], spread);
            if (cases[k].sky_nee) {
                CHECK(fabs(z) < 4.4);
                CHECK(se > 0.0);
            } else {
                CHECK(spread < 1e-6);
            }
        }
        test_image_free(&im);
    }
}

static void test_enclosure(void)
{
    static const double Le[3] = {1.0, 2.0, 3.0};
    struct { int bounces, rr, samples; } cases[] = {{20, 3, 64}, {2, 64, 2}};
    for (int k = 0; k < 2; k++) {
        atmo_scene s;
        char buf[96];
        base_scene(&s);
        test_scene_set(&s, "path.uniform_sky=0,0,0");
        test_scene_set(&s, "objects=[{\"type\": \"sphere\", \"center_m\": [0, 100, 0], "
                           "\"radius_m\": 2, \"albedo\": [0.5, 0.5, 0.5], \"emission\": [1, 2, 3]}]");
        snprintf(buf, sizeof buf, "path.bounces=%d", cases[k].bounces);
        test_scene_set(&s, buf);
        snprintf(buf, sizeof buf, "path.rr_bounce=%d", cases[k].rr);
        test_scene_set(&s, buf);
        snprintf(buf, sizeof buf, "image.samples=%d", cases[k].samples);
        test_scene_set(&s, buf);
        test_image im = test_render(&s, 64, 0);
        double series = 0.0;
        for (int j = 0; j <= cases[k].bounces; j++)
            series += pow(0.5, j);
        for (int c = 0; c < 3; c++) {
            double spread, se, z = image_z(&im, c, Le[c] * series, &spread, &se);
            printf("enclosure N_b=%d rr from %d channel %d: want %.6f, z = %+.2f, se %.2g, "
                   "spread %.2g\n",
                   cases[k].bounces, cases[k].rr, c, Le[c] * series, z, se / (Le[c] * series),
                   spread);
            if (cases[k].rr <= cases[k].bounces) {
                CHECK(fabs(z) < 4.4);
                CHECK(se > 0.0);
            } else {
                CHECK(spread < 1e-6);
            }
        }
        test_image_free(&im);
    }
}

static void test_determinism(void)
{
    atmo_scene s;
    test_scene_preset(&s, "sky-afternoon");
    test_scene_set(&s, "render.mode=path");
    test_scene_set(&s, "atmosphere.method=single");
    test_scene_set(&s, "render.view_steps=8");
    test_scene_set(&s, "camera.pitch_deg=-10");
    test_scene_set(&s, "image.width=16");
    test_scene_set(&s, "image.height=12");
    test_scene_set(&s, "image.samples=3");
    test_scene_set(&s, "objects=[{\"type\": \"sphere\", \"center_m\": [0, 1, 6], \"radius_m\": 1},"
                       "{\"type\": \"box\", \"min_m\": [1, 0, 5], \"size_m\": [1, 2, 1], "
                       "\"albedo\": [0.1, 0.1, 0.9], \"emission\": [0.5, 0, 0]}]");
    test_image a = test_render(&s, 16, 1), b = test_render(&s, 5, 0);
    size_t bytes = sizeof(float) * 3 * 16 * 12;
    CHECK(memcmp(a.mean, b.mean, bytes) == 0);
    int finite = 1;
    for (int i = 0; i < 3 * 16 * 12; i++)
        finite &= isfinite(a.mean[i]) && a.mean[i] >= 0.0f;
    CHECK(finite);
    s.image.seed = 5;
    test_image c = test_render(&s, 16, 0);
    CHECK(memcmp(a.mean, c.mean, bytes) != 0);
    printf("determinism: tiles 16/5, batches 1/any %s; another seed %s\n",
           memcmp(a.mean, b.mean, bytes) == 0 ? "bitwise equal" : "DIFFER",
           memcmp(a.mean, c.mean, bytes) != 0 ? "differs" : "is THE SAME");
    test_image_free(&a);
    test_image_free(&b);
    test_image_free(&c);
}

int main(void)
{
    test_require_opencl();
    test_furnace();
    test_enclosure();
    test_determinism();
    return test_finish();
}
