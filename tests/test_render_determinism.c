/* test_render_determinism — same seed, same device: bitwise the same image whatever the tile
 * size, the launch budget or the samples per launch; a different seed changes it.
 * labels: render kernel
 *
 * Oracle: the renderer's contract (DESIGN.md, "Random numbers"). Each render is 37 x 23 pixels
 * (no tile size divides it, so edge tiles are partial) with 7 samples per pixel, compared with
 * memcmp against the first. The scene is the default sunset with a panorama camera, so rays
 * see sky, sun, ground and horizon. Every method is checked: single, march, fast, lut (at
 * reduced table sizes, as testscene.h's test_sky_plan: the contract does not depend on them)
 * and reference (whose random walks use many dimensions per sample). The path tracer's volume
 * stage too (thesis-6 in path mode with path.clouds = volume, 13 x 9 pixels, 7 samples, three
 * variants): its walks through the layer draw from the path's streams and, for the air's
 * samples, from streams hashed from the sample point (media_walk.h), which must keep the image
 * a function of the seed. */
#include <stdlib.h>
#include <string.h>
#include "atmo/render.h"
#include "testlib.h"
#include "testscene.h"

static float *render(const atmo_plan *plan, int tile, int max_batch, double budget_ms)
{
    atmo_render_settings rs;
    atmo_render_result r;
    atmo_err e;
    atmo_render_settings_default(&rs);
    rs.tile_size = tile;
    rs.max_batch = max_batch;
    rs.launch_budget_ms = budget_ms;
    if (atmo_render(plan, &rs, &r, &e)) {
        fprintf(stderr, "render failed: %s\n", e.msg);
        exit(1);
    }
    CHECK(r.samples_min == 7 && r.samples_max == 7 && !r.interrupted);
    CHECK(r.nonfinite == 0);
    return r.rgb;
}

static void check_method(const char *method)
{
    static const char *const small_lut[] = {"lut.r_size=8",   "lut.mu_size=32",
                                            "lut.mu_s_size=8", "lut.nu_size=4",
                                            "lut.orders=2",    "lut.sphere_samples=8",
                                            "lut.steps=16"};
    atmo_scene scene;
    atmo_plan plan;
    char buf[64];
    test_scene_preset(&scene, "sky-sunset");
    snprintf(buf, sizeof buf, "atmosphere.method=%s", method);
    test_scene_set(&scene, buf);
    test_scene_set(&scene, "camera.kind=panorama");
    test_scene_set(&scene, "image.width=37");
    test_scene_set(&scene, "image.height=23");
    test_scene_set(&scene, "image.samples=7");
    test_scene_set(&scene, "render.view_steps=8");
    if (strcmp(method, "lut") == 0)
        for (size_t i = 0; i < sizeof small_lut / sizeof small_lut[0]; i++)
            test_scene_set(&scene, small_lut[i]);
    test_plan(&scene, &plan);
    plan.cache_luts = 2; /* every render after the first loads the view-independent LUTs */
    size_t bytes = sizeof(float) * 3 * 37 * 23;

    float *first = render(&plan, 64, 0, 100.0);
    struct { int tile, max_batch; double budget; } variants[] = {
        {8, 1, 100.0}, {16, 3, 100.0}, {32, 0, 1.0}, {64, 7, 1e5}, {24, 2, 5.0}};
    int same = 0, n = (int)(sizeof variants / sizeof variants[0]);
    for (int i = 0; i < n; i++) {
        float *other = render(&plan, variants[i].tile, variants[i].max_batch, variants[i].budget);
        if (memcmp(first, other, bytes) != 0)
            fprintf(stderr, "%s: tile %d, batch <= %d, budget %.0f ms differs\n", method,
                    variants[i].tile, variants[i].max_batch, variants[i].budget);
        same += memcmp(first, other, bytes) == 0;
        free(other);
    }
    CHECK(same == n);

    int finite = 1;
    for (size_t i = 0; i < 3 * 37 * 23; i++)
        finite &= isfinite(first[i]) && first[i] >= 0.0f;
    CHECK(finite);

    plan.gpu.seed = 99u; /* a different seed gives a different image */
    float *reseeded = render(&plan, 64, 0, 100.0);
    int differs = memcmp(first, reseeded, bytes) != 0;
    CHECK(differs);
    printf("%-9s %d of %d tile/batch/budget variants bitwise equal; another seed %s\n", method,
           same, n, differs ? "differs" : "is THE SAME");
    free(reseeded);
    free(first);
}

static void check_path_volume(void)
{
    atmo_scene scene;
    atmo_plan plan;
    test_scene_preset(&scene, "thesis-6");
    test_scene_set(&scene, "render.mode=path");
    test_scene_set(&scene, "path.clouds=volume");
    test_scene_set(&scene, "clouds.look=physical");
    test_scene_set(&scene, "image.width=13");
    test_scene_set(&scene, "image.height=9");
    test_scene_set(&scene, "image.samples=7");
    test_plan(&scene, &plan);
    size_t bytes = sizeof(float) * 3 * 13 * 9;
    float *first = render(&plan, 64, 0, 100.0);
    struct { int tile, max_batch; double budget; } variants[] = {
        {8, 1, 100.0}, {4, 3, 1.0}, {16, 7, 1e5}};
    int same = 0, n = (int)(sizeof variants / sizeof variants[0]), finite = 1;
    for (int i = 0; i < n; i++) {
        float *other = render(&plan, variants[i].tile, variants[i].max_batch, variants[i].budget);
        same += memcmp(first, other, bytes) == 0;
        free(other);
    }
    for (size_t i = 0; i < 3 * 13 * 9; i++)
        finite &= isfinite(first[i]) && first[i] >= 0.0f;
    CHECK(same == n);
    CHECK(finite);
    printf("path, volume clouds: %d of %d tile/batch/budget variants bitwise equal\n", same, n);
    free(first);
    atmo_plan_free(&plan);
}

int main(void)
{
    test_require_opencl();
    test_fresh_cache_dir(); /* the LUTs of this build, not an earlier one's from the cache */
    static const char *const methods[] = {"single", "march", "fast", "lut", "reference"};
    for (size_t i = 0; i < sizeof methods / sizeof methods[0]; i++)
        check_method(methods[i]);
    check_path_volume();
    return test_finish();
}
