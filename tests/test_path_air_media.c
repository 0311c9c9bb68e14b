/* test_path_air_media — the path tracer with the air as its volume medium (path.air = medium)
 * where the air lights the ground and a cloud layer, against the unbiased reference method.
 * labels: render kernel stat slow
 *
 * Oracle: atmosphere.method = reference in preview (kernels/atmosphere/method_reference.h: the
 * Monte Carlo walk of its own through the air, the ground sphere as a Lambertian reflector and
 * the tracked cloud layer; all orders). Both renderers estimate the same radiance: the air
 * (Rayleigh, aerosols, ozone), the planet's Lambertian ground and, in the second case, the
 * cloud layer, all orders of scattering and reflection.
 *   1. Ground through the air: the sky-noon preset with ground albedo 0.3, the sun at zenith 45
 *      degrees, the camera 1000 m up looking down (pitch -45, field of view 20 degrees: the
 *      horizon out of the frame), 6 x 6 pixels.
 *   2. Air, clouds and ground together: the same air over a horizontally uniform layer (its
 *      noise stretched flat, as test_path_clouds's agreement scene: 1-2 km, coverage 1,
 *      extinction 0.002 /m, albedo 0.95, Henyey-Greenstein), the camera at 3000 m looking down
 *      through it (pitch -50), the sun at zenith 30; path.clouds = volume.
 *   3. From space: the camera 200 km up (above the atmosphere's top at 60 km), looking down at
 *      pitch -70 with a field of view of 10 degrees, the sun at zenith 40: the walk's start
 *      outside the air, its end at the ground, the air's bound on a ray that enters from above.
 * The medium's horizontal uniformity makes the preview's box footprint and the path tracer's
 * Gaussian one see the same radiance up to the curvature across a 3.3-degree pixel, which is
 * far below the noise. Each pixel's means agree within a z-test on the two standard errors
 * (each the session's, from the per-pixel second moments of independent samples,
 * path.sampler = random): |z| < 4.4 in every pixel and channel (36 x 3 tests per case:
 * family-wise p ~ 1e-3), and the image means (standard error ~0.3-1 %) within |z| < 4.4.
 * The path tracer runs with path.air_collisions = 0 in case 1 and 4 in cases 2 and 3, so the
 * floor on the walk's collisions (render/path.h's path_flight) is checked with the layer (whose
 * inside thins the air's sun estimates by roulette) and on a walk that starts above the air. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "testlib.h"
#include "testscene.h"

#define SAMPLES 1024

static void ground_scene(atmo_scene *s)
{
    test_scene_preset(s, "sky-noon");
    test_scene_set(s, "atmosphere.ground_albedo=0.3");
    test_scene_set(s, "sun.zenith_deg=45");
    test_scene_set(s, "camera.position_m=0,1000,0");
    test_scene_set(s, "camera.pitch_deg=-45");
    test_scene_set(s, "camera.fov_deg=20");
    test_scene_image(s, 6, 6, SAMPLES, 3);
}

static void cloud_scene(atmo_scene *s)
{
    test_scene_preset(s, "sky-noon");
    test_scene_set(s, "atmosphere.ground_albedo=0.3");
    test_scene_flat_cloud_view(s);
    test_scene_image(s, 6, 6, SAMPLES, 5);
}

static void space_scene(atmo_scene *s)
{
    test_scene_preset(s, "sky-noon");
    test_scene_set(s, "atmosphere.ground_albedo=0.3");
    test_scene_set(s, "sun.zenith_deg=40");
    test_scene_set(s, "camera.position_m=0,200000,0");
    test_scene_set(s, "camera.pitch_deg=-70");
    test_scene_set(s, "camera.fov_deg=10");
    test_scene_image(s, 6, 6, SAMPLES, 9);
}

/* Scene `make` rendered by the reference method in preview and by the path tracer with the air
 * as its medium (and the layer as its volume where there is one), compared pixel by pixel. */
static void agreement(const char *name, void (*make)(atmo_scene *), int collisions)
{
    char key[64];
    atmo_scene ref, path;
    make(&ref);
    test_scene_set(&ref, "atmosphere.method=reference");
    make(&path);
    test_scene_set(&path, "render.mode=path");
    test_scene_set(&path, "path.air=medium");
    test_scene_set(&path, "path.sampler=random");
    test_scene_set(&path, "path.bounces=16"); /* ground albedo 0.3: 0.3^16 of the light left */
    snprintf(key, sizeof key, "path.air_collisions=%d", collisions);
    test_scene_set(&path, key);
    if (path.clouds.enabled)
        test_scene_set(&path, "path.clouds=volume");
    test_image a = test_render(&ref, 0, 0), b = test_render(&path, 0, 0);
    double z_max;
    int bad = test_image_agree(name, "reference", &a, "path.air=medium", &b, 4.4, &z_max);
    printf("%s: %d of %d pixel-channels with |z| >= 4.4 (largest |z| %.2f)\n", name, bad,
           3 * a.w * a.h, z_max);
    CHECK(bad == 0);
    test_image_free(&a);
    test_image_free(&b);
}

int main(void)
{
    atmo_cl cl;
    test_cl_open(&cl); /* exits 77 without OpenCL */
    atmo_cl_close(&cl);
    agreement("ground", ground_scene, 0);
    agreement("clouds", cloud_scene, 4);
    agreement("space", space_scene, 4);
    return test_finish();
}
