/* test_render_determinism — same seed, same device: bitwise the same image whatever the tile
 * size, the launch budget or the samples per launch; a different seed changes it.
 * labels: render kernel
 *
 * Oracle: the renderer's contract (DESIGN.md, "Random numbers"). Each render is 37 x 23 pixels
 * (no tile size divides it, so edge tiles are partial) with 7 samples per pixel, compared with
 * memcmp against the first. The scene is the default sunset with a panorama camera, so rays
 * see sky, sun, ground and horizon. */
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

int main(void)
{
    test_require_opencl();
    atmo_scene scene;
    atmo_plan plan;
    test_scene_preset(&scene, "sky-sunset");
    test_scene_set(&scene, "camera.kind=panorama");
    test_scene_set(&scene, "image.width=37");
    test_scene_set(&scene, "image.height=23");
    test_scene_set(&scene, "image.samples=7");
    test_scene_set(&scene, "render.view_steps=8");
    test_plan(&scene, &plan);
    size_t bytes = sizeof(float) * 3 * 37 * 23;

    float *first = render(&plan, 64, 0, 100.0);
    struct { int tile, max_batch; double budget; } variants[] = {
        {8, 1, 100.0}, {16, 3, 100.0}, {32, 0, 1.0}, {64, 7, 1e5}, {24, 2, 5.0}};
    for (size_t i = 0; i < sizeof variants / sizeof variants[0]; i++) {
        float *other = render(&plan, variants[i].tile, variants[i].max_batch, variants[i].budget);
        if (memcmp(first, other, bytes) != 0)
            fprintf(stderr, "tile %d, batch <= %d, budget %.0f ms differs\n", variants[i].tile,
                    variants[i].max_batch, variants[i].budget);
        CHECK(memcmp(first, other, bytes) == 0);
        free(other);
    }

    int finite = 1;
    for (size_t i = 0; i < 3 * 37 * 23; i++)
        finite &= isfinite(first[i]) && first[i] >= 0.0f;
    CHECK(finite);

    plan.gpu.seed = 99u; /* a different seed gives a different image */
    float *reseeded = render(&plan, 64, 0, 100.0);
    CHECK(memcmp(first, reseeded, bytes) != 0);
    free(reseeded);
    free(first);
    return test_finish();
}
