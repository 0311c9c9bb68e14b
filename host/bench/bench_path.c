/* bench_path.c — `atmo bench render`: the path tracer's time to a noise level per thesis view,
 * the split of its time between components, and what planning only the features a scene has
 * saves (atmo/bench.h).
 *
 * Time to noise: each view renders in path mode with a 1 % noise target (the session's
 * per-tile relative standard error, atmo/session.h; at most 4096 samples) on the central crop
 * of its 1280 x 720 frame: a perspective image's central crop of 1/k of its width and height
 * is the image of the same camera with tan(fov'/2) = tan(fov/2) / k, so the crop has the
 * full frame's pixels, and the full frame's time is extrapolated as the crop's times k^2
 * (the centre stands for the frame: views whose corners are harder converge later there).
 * Split: the time per sample at a fixed count (8) of the full path, of the same path in the
 * uniform test world (no atmosphere method called: the rest is the atmosphere's share), and
 * with no bounces (N_b = 0: the bounces' share). Features: the same render with one object
 * added far behind the camera (the objects feature compiled in and tested on every ray but
 * never seen) against the scene as it is; for a view with objects, the other way round is
 * not possible without changing the image, so its row is the cost of its own objects.
 * Rows: method = view, settings = what was measured, seconds, error = the noise reached
 * (time to noise) or the seconds per megapixel-sample (split, features). Writes
 * DIR/render.csv and the chart DIR/render.svg. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "atmo/bench.h"
#include "atmo/plan.h"

#define BENCH_CROP 16 /* the crop's share of the frame's width and height: 80 x 45 */

static int preset_scene(const char *name, int w, int h, int crop, atmo_scene *s, atmo_err *e)
{
    atmo_scene_defaults(s);
    int rc = atmo_scene_apply_preset(s, name, e);
    if (rc)
        return rc;
    s->path.mode = ATMO_RENDER_PATH;
    s->image.width = w;
    s->image.height = h;
    s->camera.fov_deg =
        2.0 * atan(tan(0.5 * s->camera.fov_deg * M_PI / 180.0) / crop) * 180.0 / M_PI;
    return ATMO_OK;
}

/* Render s with a noise target (0: none) and the given sample count; seconds of rendering. */
static int timed(const atmo_scene *s, const char *device, double noise, double *seconds,
                 atmo_render_result *out, atmo_err *e)
{
    atmo_plan plan;
    atmo_render_settings rs;
    int rc = atmo_plan_make_cached(s, 1, 1, &plan, e);
    if (rc)
        return rc;
    atmo_render_settings_default(&rs);
    rs.device = device;
    rs.tile_size = 16;
    rs.noise_target = noise;
    rc = atmo_render(&plan, &rs, out, e);
    atmo_plan_free(&plan);
    if (!rc)
        *seconds = out->seconds_render;
    return rc;
}

int bench_path(const char *dir, const char *device, int quick, atmo_err *e)
{
    static const char *const views[] = {"thesis-1", "thesis-6", "thesis-7"};
    int n_views = quick ? 1 : 3, crop = quick ? 32 : BENCH_CROP;
    int w = 1280 / crop, h = 720 / crop;
    double noise = quick ? 0.1 : 0.01;
    bench_row rows[32];
    int n = 0, rc = ATMO_OK;
    for (int v = 0; v < n_views && !rc; v++) {
        const char *name = quick ? "thesis-7" : views[v];
        atmo_scene s;
        atmo_render_result r;
        double sec;
        if ((rc = preset_scene(name, w, h, crop, &s, e)))
            break;
        s.image.samples = 4096;
        if ((rc = timed(&s, device, noise, &sec, &r, e)))
            break;
        double full = sec * crop * crop;
        printf("%s: %.0f%% noise on the central %dx%d crop in %.2f s (%d to %d samples per "
               "pixel); 1280x720 extrapolated: %.1f s\n",
               name, 100.0 * noise, w, h, sec, r.samples_min, r.samples_max, full);
        atmo_render_result_free(&r);
        bench_row t = {"", "", full, noise};
        snprintf(t.method, sizeof t.method, "%s", name);
        snprintf(t.settings, sizeof t.settings, "time to %g%% noise 1280x720 (crop x%d)",
                 100.0 * noise, crop * crop);
        rows[n++] = t;

        /* the split, at 8 samples per pixel */
        struct { const char *what; int uniform, bounces0, extra_object; } parts[] = {
            {"full path", 0, 0, 0}, {"no atmosphere (uniform world)", 1, 0, 0},
            {"no bounces (N_b = 0)", 0, 1, 0}, {"with an unseen object", 0, 0, 1}};
        double base = 0.0;
        for (int k = 0; k < 4 && !rc; k++) {
            atmo_scene q = s;
            q.image.samples = 8;
            if (parts[k].uniform)
                q.path.sky = ATMO_PATH_SKY_UNIFORM;
            if (parts[k].bounces0)
                q.path.bounces = 0;
            if (parts[k].extra_object) {
                char obj[160];
                snprintf(obj, sizeof obj,
                         "[{\"type\": \"sphere\", \"center_m\": [%.3f, %.3f, %.3f], "
                         "\"radius_m\": 0.5}]",
                         s.camera.position_m[0], s.camera.position_m[1] + 1e4,
                         s.camera.position_m[2]);
                if (q.objects.count > 0)
                    continue; /* a view with objects has the feature already */
                if ((rc = atmo_scene_set_objects(&q, obj, "bench", e)))
                    break;
            }
            if ((rc = timed(&q, device, 0.0, &sec, &r, e)))
                break;
            atmo_render_result_free(&r);
            double per = sec / (8.0 * w * h * 1e-6); /* seconds per megapixel-sample */
            if (k == 0)
                base = per;
            printf("  %-30s %.3f s per megapixel-sample (%+.0f%% of the full path)\n",
                   parts[k].what, per, 100.0 * (per / base - 1.0));
            bench_row b = {"", "", sec, per};
            snprintf(b.method, sizeof b.method, "%s", name);
            snprintf(b.settings, sizeof b.settings, "%s", parts[k].what);
            rows[n++] = b;
        }
    }
    if (rc)
        return rc;
    char csv[1024], svg[1024];
    snprintf(csv, sizeof csv, "%s/render.csv", dir);
    snprintf(svg, sizeof svg, "%s/render.svg", dir);
    if ((rc = bench_write_csv(csv, rows, n, device ? device : "default", e)))
        return rc;
    return bench_chart(csv, svg, "path tracer: time and its parts",
                       "noise reached / seconds per megapixel-sample", rows, n, e);
}
