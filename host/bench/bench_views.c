/* bench_views.c — `atmo bench views`: each thesis view in the default mode, noise against time at
 * its frame size, and its bias against the path-traced reference at a reduced size (atmo/bench.h).
 *
 * Noise: the view renders twice at each sample count (seeds 1 and 2) in the default mode
 * (the preset as it is: render.mode preview unless the preset says path); with Y_a, Y_b the
 * luminances (Bruneton's radiance-to-luminance constants, p = -3) and Y = (Y_a + Y_b) / 2, the
 * noise of one render is the two-seed estimate
 *     noise = sqrt(mean over P of (Y_a - Y_b)^2 / (2 Y^2)),
 * P the pixels with Y above 1 % of the image's mean Y. Its time is the render's build,
 * precompute and render seconds with warm caches (a 16 x 9 render of the view runs first).
 * Bias: the default mode at the reduced size with many samples against the reference there
 * (render.mode path, path.clouds volume where the view has clouds, and the air all orders
 * without the default mode's approximations: atmosphere.method reference, or where the view
 * has terrain, which that method does not trace, path.air medium), each rendered with seeds 1
 * and 2, the pixels that see the sun's disc left out with VIEWS_DISC_MARGIN around them (the
 * default render's disc guide: the direct beam, not the transport the two methods differ in,
 * and in the path tracer a firefly wherever its pixel filter reaches the disc). The bias is
 * bench_block_bias's (atmo/bench.h): the relative RMS of the difference over 4 x 4 blocks of
 * pixels, with both images' noise taken out by the two seeds, and its standard error; the
 * mean bias (the ratio of the images' means over those blocks, minus 1) and the reference's
 * own two-seed noise per pixel are printed beside it. The per-pixel ratio with a noisy
 * reference in its denominator would not do: a 32-sample path-traced sunset has 30 % noise per
 * pixel, and that ratio read 135 % for a view whose means differ by 16 %. The references are
 * cached in
 * DIR/views_ref/VIEW_WxH_Nspp_seedS.pfm: delete the files to render them anew after a change
 * to the renderer.
 * Sizes: 1280 x 720 at 1, 2, 4, 8, 16 samples, bias at 320 x 180 (default mode and reference
 * 64 samples each, twice); --quick: 320 x 180 at 1, 2, bias at 80 x 45 (16 and 32 samples).
 * --noise-only: the noise rows alone, no reference (which takes minutes to hours a view).
 * Writes DIR/views_VIEW.csv and the chart DIR/views_VIEW.svg (noise and bias against seconds,
 * with the goal lines: 2 % noise, 5 % bias, 120 s). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include "atmo/bench.h"
#include "atmo/colour.h"
#include "atmo/image.h"
#include "atmo/plan.h"

#define VIEWS_NOISE_GOAL 0.02
#define VIEWS_BIAS_GOAL 0.05
#define VIEWS_TIME_GOAL_S 120.0
#define VIEWS_BRIGHT 0.01 /* pixels above this fraction of the mean luminance count */
#define VIEWS_BIAS_BLOCK 4 /* the bias's blocks of pixels, per side */
#define VIEWS_DISC_MARGIN 2 /* pixels around the sun's disc left out of the bias */

typedef struct views_sizes {
    int w, h, ref_w, ref_h, ref_samples, converged_samples, n_samples;
    int samples[5];
} views_sizes;

static const views_sizes views_full = {1280, 720, 320, 180, 64, 64, 5, {1, 2, 4, 8, 16}};
static const views_sizes views_quick = {320, 180, 80, 45, 32, 16, 2, {1, 2}};

static const char *const bench_view_names[] = {"thesis-1", "thesis-2", "thesis-3", "thesis-4", "thesis-5",
                                        "thesis-6", "thesis-7", "thesis-8", "thesis-9", NULL};

static int view_scene(const char *name, int w, int h, int samples, int seed, int reference,
                      atmo_scene *s, atmo_err *e)
{
    int rc;
    atmo_scene_defaults(s);
    if ((rc = atmo_scene_apply_preset(s, name, e)))
        return rc;
    s->image.width = w, s->image.height = h, s->image.samples = samples, s->image.seed = seed;
    /* the air of the reference: method reference's walk, or with terrain (which that method
     * does not trace) the path tracer's own walk through the air as a medium */
    const char *air = s->terrain.enabled ? "path.air=medium" : "atmosphere.method=reference";
    if (reference &&
        ((rc = atmo_scene_assign(s, "render.mode=path", "bench", e)) ||
         (rc = atmo_scene_assign(s, air, "bench", e)) ||
         (s->clouds.enabled && (rc = atmo_scene_assign(s, "path.clouds=volume", "bench", e)))))
        return rc;
    return atmo_scene_validate(s, e);
}

/* Renders s; *seconds: its build, precompute and render seconds. guides: the denoiser's
 * guides too (r->guides; their pass is not counted in *seconds). */
static int views_render(const atmo_scene *s, const char *device, int guides,
                        atmo_render_result *r, double *seconds, atmo_err *e)
{
    atmo_plan plan;
    atmo_render_settings rs;
    int rc = atmo_plan_make_cached(s, 1, 1, &plan, e);
    if (rc)
        return rc;
    atmo_render_settings_default(&rs);
    rs.device = device;
    rs.guides = guides;
    rc = atmo_render(&plan, &rs, r, e);
    atmo_plan_free(&plan);
    if (!rc)
        *seconds = r->seconds_build + r->seconds_precompute + r->seconds_render;
    return rc;
}

/* Luminance of n pixels of radiance rgb, and their mean. */
static double views_luminance(const atmo_scene *s, const float *rgb, size_t n, double *Y)
{
    double k[3], mean = 0.0;
    atmo_luminance_factors(s->render.wavelengths_nm, -3.0, k);
    for (size_t i = 0; i < n; i++) {
        double L[3] = {rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2]};
        Y[i] = atmo_luminance_from_radiance(k, L);
        mean += Y[i] / (double)n;
    }
    return mean;
}

/* The two-seed noise of one render (the top of the file). */
static double views_noise(const double *Ya, const double *Yb, size_t n)
{
    double mean = 0.0, sum = 0.0;
    size_t used = 0;
    for (size_t i = 0; i < n; i++)
        mean += 0.5 * (Ya[i] + Yb[i]) / (double)n;
    for (size_t i = 0; i < n; i++) {
        double Y = 0.5 * (Ya[i] + Yb[i]), d = Ya[i] - Yb[i];
        if (Y > VIEWS_BRIGHT * mean)
            sum += d * d / (2.0 * Y * Y), used++;
    }
    return used ? sqrt(sum / (double)used) : 0.0;
}

/* The cached reference of the view rendered with `seed` (the top of the file): its radiance,
 * rendered and written when the file is missing; *seconds its render's seconds (0 when read). */
static int views_reference(const char *dir, const char *name, const views_sizes *z, int seed,
                           const char *device, float **rgb, double *seconds, atmo_err *e)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/views_ref", dir);
    if (mkdir(path, 0755) != 0 && errno != EEXIST)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "mkdir %s: %s", path, strerror(errno));
    snprintf(path, sizeof path, "%s/views_ref/%s_%dx%d_%dspp_seed%d.pfm", dir, name, z->ref_w,
             z->ref_h, z->ref_samples, seed);
    atmo_image a = {0};
    atmo_err ignored = {{0}};
    *seconds = 0.0;
    if (atmo_image_read_pfm(path, &a, &ignored) == ATMO_OK && a.width == z->ref_w &&
        a.height == z->ref_h) {
        *rgb = a.rgb;
        return ATMO_OK;
    }
    atmo_image_free(&a);
    atmo_scene s;
    atmo_render_result r;
    int rc = view_scene(name, z->ref_w, z->ref_h, z->ref_samples, seed, 1, &s, e);
    if (rc || (rc = views_render(&s, device, 0, &r, seconds, e)))
        return rc;
    fprintf(stderr, "bench views: %s reference (path traced, %d spp, %dx%d, seed %d) in %.1f s\n",
            name, z->ref_samples, z->ref_w, z->ref_h, seed, *seconds);
    atmo_image img = {z->ref_w, z->ref_h, r.rgb, NULL, 0};
    if ((rc = atmo_image_write_pfm(path, &img, e))) {
        atmo_render_result_free(&r);
        return rc;
    }
    *rgb = r.rgb;
    r.rgb = NULL;
    atmo_render_result_free(&r);
    return ATMO_OK;
}

/* The pixels within VIEWS_DISC_MARGIN of one whose disc guide (w x h) sees the sun's disc:
 * the disc's own pixels and those the pixel filters of the two renders spread it to (the
 * path tracer's reaches the next pixel; the guide's 4 x 4 rays can miss a disc that covers
 * part of a pixel). */
static void views_disc_mask(const float *guide, int w, int h, unsigned char *mask)
{
    memset(mask, 0, (size_t)w * h);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            if (!(guide[(size_t)y * w + x] > 0.0f))
                continue;
            for (int v = y - VIEWS_DISC_MARGIN; v <= y + VIEWS_DISC_MARGIN; v++)
                for (int u = x - VIEWS_DISC_MARGIN; u <= x + VIEWS_DISC_MARGIN; u++)
                    if (u >= 0 && v >= 0 && u < w && v < h)
                        mask[(size_t)v * w + u] = 1;
        }
}

/* The luminances of the view at the reference's size, seeds 1 and 2, into Y[0], Y[1]: the
 * references (reference 1) or the default mode converged, whose pixels that see the sun's disc
 * (its guide) are marked in disc; *seconds the default mode's mean render seconds. */
static int views_pair(const char *dir, const char *name, const views_sizes *z, int reference,
                      const char *device, double *Y[2], unsigned char *disc, double *seconds,
                      atmo_err *e)
{
    size_t n = (size_t)z->ref_w * z->ref_h;
    *seconds = 0.0;
    for (int k = 0; k < 2; k++) {
        atmo_scene s;
        atmo_render_result r = {0};
        float *ref = NULL;
        double t = 0.0;
        int rc = view_scene(name, z->ref_w, z->ref_h,
                            reference ? z->ref_samples : z->converged_samples, k + 1, reference,
                            &s, e);
        if (!rc && reference)
            rc = views_reference(dir, name, z, k + 1, device, &ref, &t, e);
        else if (!rc)
            rc = views_render(&s, device, k == 0, &r, &t, e);
        if (rc)
            return rc;
        views_luminance(&s, reference ? ref : r.rgb, n, Y[k]);
        if (!reference && k == 0)
            views_disc_mask(r.guides + 7 * n, z->ref_w, z->ref_h, disc); /* after albedo,
                                                                         normal, depth */
        if (!reference)
            *seconds += 0.5 * t;
        free(ref);
        atmo_render_result_free(&r);
    }
    return ATMO_OK;
}

/* The bias row: the default mode converged at the reference's size against the reference,
 * both twice (the top of the file); *ref_noise the reference's own two-seed noise per pixel. */
static int views_bias_row(const char *dir, const char *name, const views_sizes *z,
                          const char *device, bench_row *row, double *ref_noise, atmo_err *e)
{
    size_t n = (size_t)z->ref_w * z->ref_h;
    double *Y[2] = {malloc(n * sizeof(double)), malloc(n * sizeof(double))};
    double *Yref[2] = {malloc(n * sizeof(double)), malloc(n * sizeof(double))};
    unsigned char *disc = calloc(n, 1);
    double seconds, ref_seconds, se, mean_bias;
    int blocks, rc = !Y[0] || !Y[1] || !Yref[0] || !Yref[1] || !disc
                         ? atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory")
                         : ATMO_OK;
    if (rc || (rc = views_pair(dir, name, z, 1, device, Yref, NULL, &ref_seconds, e)) ||
        (rc = views_pair(dir, name, z, 0, device, Y, disc, &seconds, e)))
        goto cleanup;
    size_t sun = 0;
    for (size_t i = 0; i < n; i++)
        sun += disc[i];
    *ref_noise = views_noise(Yref[0], Yref[1], n);
    snprintf(row->method, sizeof row->method, "bias");
    snprintf(row->settings, sizeof row->settings, "%d spp %dx%d vs path traced %d spp",
             z->converged_samples, z->ref_w, z->ref_h, z->ref_samples);
    row->seconds = seconds;
    row->error = bench_block_bias(Y[0], Y[1], Yref[0], Yref[1], disc, z->ref_w, z->ref_h,
                                  VIEWS_BIAS_BLOCK, VIEWS_BRIGHT, &se, &mean_bias, &blocks);
    fprintf(stderr, "bench views: %s bias %.2f %% (standard error %.2f %%) over %d blocks of %d x "
                    "%d pixels, %zu pixels at the sun's disc left out; mean %+.2f %%; the "
                    "reference's own noise %.2f %% per pixel\n",
            name, 100.0 * row->error, 100.0 * se, blocks, VIEWS_BIAS_BLOCK, VIEWS_BIAS_BLOCK, sun,
            100.0 * mean_bias, 100.0 * *ref_noise);
cleanup:
    free(Y[0]);
    free(Y[1]);
    free(Yref[0]);
    free(Yref[1]);
    free(disc);
    return rc;
}

/* One noise row: the view at `samples` with seeds 1 and 2. */
static int views_noise_row(const char *name, const views_sizes *z, int samples,
                           const char *device, bench_row *row, atmo_err *e)
{
    size_t n = (size_t)z->w * z->h;
    double *Y[2] = {malloc(n * sizeof(double)), malloc(n * sizeof(double))}, seconds[2];
    int rc = !Y[0] || !Y[1] ? atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory") : ATMO_OK;
    for (int k = 0; k < 2 && !rc; k++) {
        atmo_scene s;
        atmo_render_result r;
        if ((rc = view_scene(name, z->w, z->h, samples, k + 1, 0, &s, e)) ||
            (rc = views_render(&s, device, 0, &r, &seconds[k], e)))
            break;
        views_luminance(&s, r.rgb, n, Y[k]);
        atmo_render_result_free(&r);
    }
    if (!rc) {
        snprintf(row->method, sizeof row->method, "noise");
        snprintf(row->settings, sizeof row->settings, "%d spp %dx%d", samples, z->w, z->h);
        row->seconds = 0.5 * (seconds[0] + seconds[1]);
        row->error = views_noise(Y[0], Y[1], n);
    }
    free(Y[0]);
    free(Y[1]);
    return rc;
}

/* The view's chart: noise and bias against seconds with the goal lines. */
static int views_chart(const char *csv, const char *svg, const char *name, const bench_row *rows,
                       int n, const char *what, atmo_err *e)
{
    char *script = NULL;
    size_t size = 0;
    double x_lo = VIEWS_TIME_GOAL_S, x_hi = VIEWS_TIME_GOAL_S, y_lo = VIEWS_NOISE_GOAL,
           y_hi = VIEWS_BIAS_GOAL;
    for (int i = 0; i < n; i++) {
        x_lo = fmin(x_lo, rows[i].seconds), x_hi = fmax(x_hi, rows[i].seconds);
        if (rows[i].error > 0.0)
            y_lo = fmin(y_lo, rows[i].error), y_hi = fmax(y_hi, rows[i].error);
    }
    FILE *f = open_memstream(&script, &size);
    if (!f)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for the chart script of %s", svg);
    fprintf(f,
            "set datafile separator ','\nset logscale xy\nset grid\nset key outside right\n"
            "set xlabel 'seconds (build + precompute + render, warm caches)'\n"
            "set ylabel 'relative RMS of luminance'\n"
            "set title '%s, default mode: %s'\n"
            "set xrange [%g:%g]\nset yrange [%g:%g]\n"
            "set arrow from %g, graph 0 to %g, graph 1 nohead dt 2 lc rgb 'black'\n"
            "set label '%g s' at %g, graph 0.95 offset 0.5,0\n"
            "plot '%s' using (strcol(1) eq 'noise' ? $3 : 1/0):4:2 with linespoints pt 7 "
            "title 'noise', '' using (strcol(1) eq 'noise' ? $3 : 1/0):4:2 with labels offset "
            "1,0.5 font ',8' notitle, '' using (strcol(1) eq 'bias' ? $3 : 1/0):4:2 with points "
            "pt 5 ps 1.5 title 'bias', '' using (strcol(1) eq 'bias' ? $3 : 1/0):4:2 with labels "
            "offset 1,-0.7 font ',8' notitle, %g with lines dt 2 lc rgb 'blue' title 'noise goal "
            "%g %%', %g with lines dt 2 lc rgb 'red' title 'bias goal %g %%'\n",
            name, what, 0.5 * x_lo, 2.0 * x_hi, 0.5 * y_lo, 2.0 * y_hi,
            VIEWS_TIME_GOAL_S, VIEWS_TIME_GOAL_S, VIEWS_TIME_GOAL_S, VIEWS_TIME_GOAL_S, csv,
            VIEWS_NOISE_GOAL, 100.0 * VIEWS_NOISE_GOAL, VIEWS_BIAS_GOAL, 100.0 * VIEWS_BIAS_GOAL);
    return bench_plot_close(f, &script, svg, 900, 500, e);
}

static int views_one(const char *dir, const char *name, const views_sizes *z, const char *device,
                     int noise_only, atmo_err *e)
{
    bench_row rows[8];
    int n = 0, rc = ATMO_OK;
    double ref_noise = NAN, seconds;
    atmo_scene warm;
    atmo_render_result r;
    /* a small render first: the kernel and LUT caches warm, so no row pays the build */
    if ((rc = view_scene(name, 16, 9, 1, 1, 0, &warm, e)) ||
        (rc = views_render(&warm, device, 0, &r, &seconds, e)))
        return rc;
    atmo_render_result_free(&r);
    for (int i = 0; i < z->n_samples && !rc; i++) {
        if ((rc = views_noise_row(name, z, z->samples[i], device, &rows[n], e)))
            break;
        fprintf(stderr, "bench views: %s %s: %.2f s, noise %.2f %%\n", name, rows[n].settings,
                rows[n].seconds, 100.0 * rows[n].error);
        n++;
    }
    if (!rc && !noise_only && !(rc = views_bias_row(dir, name, z, device, &rows[n], &ref_noise, e)))
        n++;
    if (rc)
        return rc;
    char csv[4096], svg[4096], device_note[512], what[160];
    snprintf(csv, sizeof csv, "%s/views_%s.csv", dir, name);
    snprintf(svg, sizeof svg, "%s/views_%s.svg", dir, name);
    if (noise_only) {
        snprintf(device_note, sizeof device_note, "%s; noise only (no reference)",
                 device ? device : "default");
        snprintf(what, sizeof what, "two-seed noise (no reference rendered)");
    } else {
        snprintf(device_note, sizeof device_note, "%s; reference noise %.4f",
                 device ? device : "default", ref_noise);
        snprintf(what, sizeof what,
                 "two-seed noise and bias against the path-traced reference (its own noise "
                 "%.1f %%)",
                 100.0 * ref_noise);
    }
    if ((rc = bench_write_csv(csv, rows, n, device_note, e)) ||
        (rc = views_chart(csv, svg, name, rows, n, what, e)))
        return rc;
    printf("wrote %s and %s\n", csv, svg);
    return ATMO_OK;
}

int bench_views_check(const char *views, atmo_err *e)
{
    if (!views)
        return ATMO_OK;
    char list[512];
    snprintf(list, sizeof list, "%s", views);
    for (char *save = NULL, *v = strtok_r(list, ",", &save); v; v = strtok_r(NULL, ",", &save)) {
        int known = 0;
        for (const char *const *p = bench_view_names; *p; p++)
            known |= strcmp(*p, v) == 0;
        if (!known)
            return atmo_fail(e, ATMO_ERR_USAGE,
                             "--views: unknown view '%s' (the views: thesis-1 ... thesis-9, "
                             "comma-separated)", v);
    }
    return ATMO_OK;
}

int bench_views(const char *dir, const char *device, const char *views, int quick, int noise_only,
                atmo_err *e)
{
    int rc = bench_views_check(views, e);
    if (rc)
        return rc;
    const views_sizes *z = quick ? &views_quick : &views_full;
    char list[512];
    snprintf(list, sizeof list, "%s",
             views ? views : "thesis-1,thesis-2,thesis-3,thesis-4,thesis-5,thesis-6,thesis-7,"
                             "thesis-8,thesis-9");
    for (char *save = NULL, *v = strtok_r(list, ",", &save); v && !rc;
         v = strtok_r(NULL, ",", &save))
        rc = views_one(dir, v, z, device, noise_only, e);
    return rc;
}
