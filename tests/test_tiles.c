/* test_tiles — the tile scheduler's merged launches: within the budget, far fewer launches, and
 * bitwise the same image as one launch per tile.
 * labels: unit render kernel
 *
 * 1. The scheduler alone (atmo/tiles.h, no device). Oracle: a linear cost model, under which
 *    the adapted work per launch is exact: a launch of p pixel-samples takes p * 1e-4 ms
 *    (0.21 s for one sample of 2048 x 1024, what `fast` takes on this machine). A 2048 x 1024
 *    image with 64-pixel tiles is driven to 4 samples per pixel with a 100 ms budget. Checked:
 *    every launch is a rectangle of whole tiles inside the image, each holding as many samples
 *    as the launch's first sample index (so each pixel's samples arrive in order, none twice);
 *    the launched pixel-samples add up to exactly W x H x 4; no launch takes more than the
 *    budget under the model; and the merging needs fewer than 1/20 of the 2048 launches that
 *    one tile per launch (max_tiles = 1, batch <= 1) takes, which the same run counts.
 * 2. Renders. Oracle: the renderer's contract that the per-pixel sums are built in sample order
 *    (DESIGN.md, "Random numbers"), so merging tiles cannot change a bit. `fast` (its sky-view
 *    LUT for camera rays, the march for the others) at 37 x 23 pixels (no tile size divides
 *    it) and 5 samples, rendered with one tile per launch (max_tiles = 1) and with merged launches at tile sizes 8 and 16, batches bounded or not and
 *    budgets of 1 ms and 1e5 ms: every image equal with memcmp to the one-tile-per-launch image,
 *    and the 1e5 ms merged render made fewer launches than the one-tile-per-launch render. */
#include <stdlib.h>
#include <string.h>
#include "atmo/render.h"
#include "atmo/tiles.h"
#include "testlib.h"
#include "testscene.h"

#define MODEL_MS_PER_PIXEL_SAMPLE 1e-4

/* Drive a scheduler to `target` samples under the cost model; returns the launch count, or -1
 * when a check failed (the CHECKs say which). */
static int simulate(int width, int height, int size, int target, double budget_ms, int max_batch,
                    int max_tiles, double *worst_ms)
{
    atmo_tiles t;
    atmo_err e;
    atmo_tile l;
    if (atmo_tiles_init(&t, width, height, size, &e))
        return -1;
    int launches = 0, ok = 1;
    double pixel_samples = 0.0;
    *worst_ms = 0.0;
    while (atmo_tiles_next(&t, target, &l) && launches < 1000000) {
        int column = l.index % t.columns, row = l.index / t.columns;
        ok &= l.tiles_across >= 1 && l.tiles_down >= 1 && column + l.tiles_across <= t.columns &&
              (row + l.tiles_down) * t.columns <= t.count;
        ok &= l.x == column * size && l.y == row * size && l.x + l.w <= width &&
              l.y + l.h <= height && l.w > 0 && l.h > 0;
        for (int r = 0; ok && r < l.tiles_down; r++)
            for (int c = 0; c < l.tiles_across; c++)
                ok &= t.samples[l.index + r * t.columns + c] == l.sample_begin;
        ok &= l.sample_count >= 1 && l.samples == l.sample_begin + l.sample_count &&
              l.samples <= target;
        double ms = MODEL_MS_PER_PIXEL_SAMPLE * l.w * l.h * l.sample_count;
        *worst_ms = ms > *worst_ms ? ms : *worst_ms;
        pixel_samples += (double)l.w * l.h * l.sample_count;
        atmo_tiles_done(&t, &l, ms, budget_ms, max_batch, max_tiles);
        launches++;
    }
    int min, max;
    atmo_tiles_range(&t, &min, &max);
    CHECK(ok);
    CHECK(min == target && max == target);
    CHECK(pixel_samples == (double)width * height * target);
    atmo_tiles_free(&t);
    return ok && min == target && max == target ? launches : -1;
}

static void check_scheduler(void)
{
    double worst, worst_single, worst_uneven;
    int merged = simulate(2048, 1024, 64, 4, 100.0, 0, 0, &worst);
    int single = simulate(2048, 1024, 64, 4, 100.0, 1, 1, &worst_single);
    CHECK(single == 4 * 512);
    CHECK(merged > 0 && merged * 20 < single);
    CHECK(worst <= 100.0 * (1.0 + 1e-12));
    int uneven = simulate(1000, 333, 64, 3, 7.0, 0, 0, &worst_uneven);
    CHECK(uneven > 0 && worst_uneven <= 7.0 * (1.0 + 1e-12));
    printf("1. 2048x1024, 4 samples: %d merged launches (longest %.1f ms of 100 under the model) "
           "against %d with one tile per launch; 1000x333 at 7 ms: %d launches, longest %.2f ms\n",
           merged, worst, single, uneven, worst_uneven);
}

static float *render(const atmo_plan *plan, int tile, int max_batch, int max_tiles,
                     double budget_ms, int *launches)
{
    atmo_render_settings rs;
    atmo_render_result r;
    atmo_err e;
    atmo_render_settings_default(&rs);
    rs.tile_size = tile;
    rs.max_batch = max_batch;
    rs.max_tiles = max_tiles;
    rs.launch_budget_ms = budget_ms;
    if (atmo_render(plan, &rs, &r, &e)) {
        fprintf(stderr, "render failed: %s\n", e.msg);
        exit(1);
    }
    CHECK(r.samples_min == 5 && r.samples_max == 5 && r.nonfinite == 0);
    *launches = r.launches;
    return r.rgb;
}

static void check_renders(const char *method)
{
    atmo_scene scene;
    atmo_plan plan;
    char buf[64];
    test_scene_preset(&scene, "sky-sunset");
    snprintf(buf, sizeof buf, "atmosphere.method=%s", method);
    test_scene_set(&scene, buf);
    test_scene_set(&scene, "camera.kind=panorama");
    test_scene_set(&scene, "image.width=37");
    test_scene_set(&scene, "image.height=23");
    test_scene_set(&scene, "image.samples=5");
    test_scene_set(&scene, "render.view_steps=8");
    test_plan(&scene, &plan);
    size_t bytes = sizeof(float) * 3 * 37 * 23;
    int single_launches, launches, same = 0, fewer = 0;
    float *single = render(&plan, 8, 1, 1, 100.0, &single_launches);
    struct { int tile, max_batch; double budget; } variants[] = {
        {8, 0, 1e5}, {8, 2, 1.0}, {16, 0, 1.0}, {16, 3, 1e5}};
    int n = (int)(sizeof variants / sizeof variants[0]);
    for (int i = 0; i < n; i++) {
        float *merged = render(&plan, variants[i].tile, variants[i].max_batch, 0,
                               variants[i].budget, &launches);
        int equal = memcmp(single, merged, bytes) == 0;
        if (!equal)
            fprintf(stderr, "%s: merged launches, tile %d, batch <= %d, budget %g ms differ\n",
                    method, variants[i].tile, variants[i].max_batch, variants[i].budget);
        same += equal;
        if (i == 0)
            fewer = launches < single_launches;
        if (i == 0)
            printf("2. %-5s one tile per launch: %d launches; merged at 1e5 ms: %d\n", method,
                   single_launches, launches);
        free(merged);
    }
    CHECK(same == n);
    CHECK(fewer);
    printf("   %-5s %d of %d merged variants bitwise equal to one tile per launch\n", method, same,
           n);
    free(single);
    atmo_plan_free(&plan);
}

int main(void)
{
    check_scheduler();
    test_require_opencl();
    check_renders("fast");
    return test_finish();
}
