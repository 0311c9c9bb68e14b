/* bench.h — benchmark suites run by `atmo bench` (host/cmd_bench.c dispatches). */
#ifndef ATMO_BENCH_H
#define ATMO_BENCH_H
#include <stdio.h>
#include "atmo/render.h"
#include "atmo/scene.h"
#include "atmo/status.h"

typedef struct bench_row {
    char method[32];
    char settings[64];
    double seconds;
    double error;
} bench_row;

/* Plan and render a scene on the device (default settings). */
int bench_render(const atmo_scene *s, const char *device, atmo_render_result *r, atmo_err *e);
/* RMS over pixels and channels of (a - ref) / ref. */
double bench_rms_relative(const atmo_render_result *a, const atmo_render_result *ref);
/* The relative RMS error over pixels and channels of the image x against the converged image T,
 * estimated from two references A and B of the same samples per pixel, independent of x and of
 * each other (other seeds). With R = (A + B) / 2, E sum (x - R)^2 = sum (x - T)^2 + sum Var(R)
 * and E (A - B)^2 = 2 Var(A) = 4 Var(R), so
 *     sqrt((sum (x - R)^2 - sum (A - B)^2 / 4) / sum R^2),
 * clamped at 0, estimates |x - T| / |T| with the references' own noise removed, whatever the
 * sampler. (The per-pixel standard errors from the samples' spread do not do: the path
 * tracer's camera samples are scrambled Sobol points, whose mean varies less than the spread
 * of independent samples says, so subtracting them removes too much.) */
double bench_unbiased_error(const float *x, const atmo_render_result *ref_a,
                            const atmo_render_result *ref_b);
/* The relative RMS bias of an image against a reference, each rendered twice with other seeds
 * (luminances x1, x2 and a, b of w x h pixels), over the B x B blocks of pixels none of which
 * is marked in skip (may be NULL). Per block k, with X, R the blocks' means of (x1 + x2) / 2
 * and (a + b) / 2, D = X - R, and since E D^2 = bias^2 + Var X + Var R and
 * E (x1 - x2)^2 = 4 Var X (the same for a, b), (D^2 - (x1 - x2)^2 / 4 - (a - b)^2 / 4) / R^2
 * estimates the squared relative bias beta^2 but for the noise of R in the denominator: with
 * R = T (1 + e), the expansion of 1 / R^2 meets D's own -T e and adds 4 beta Var e, which
 * (a - b)^2 / (4 R^2) estimates (a - b is independent of a + b for symmetric noise), so
 *     t_k = (D^2 - (x1 - x2)^2 / 4 - (a - b)^2 / 4) / R^2 - D (a - b)^2 / R^3
 * is the block's estimate, whatever the samplers (no per-pixel standard errors, which
 * scrambled Sobol samples overstate), to terms of the fourth order in the blocks' noise; the
 * blocks count where R is above `bright` times the mean R over the unskipped pixels. Returns sqrt(max(mean t, 0)); *se its standard
 * error from the spread of t (se of the mean t over 2 sqrt(mean t), or sqrt(se of the mean t)
 * where the mean is not above its own error); *mean_bias sum X / sum R - 1 over those blocks;
 * *blocks their count. Blocks average the noise down, so the estimate stays finite where a
 * pixel's reference is noisy (the mean of 1 / R^2 of a noisy R grows without bound). */
double bench_block_bias(const double *x1, const double *x2, const double *a, const double *b,
                        const unsigned char *skip, int w, int h, int B, double bright, double *se,
                        double *mean_bias, int *blocks);
/* DIR/SUITE.csv: method,settings,seconds,error,device. */
int bench_write_csv(const char *path, const bench_row *rows, int n, const char *device,
                    atmo_err *e);
/* A chart from a gnuplot script (atmo/gnuplot.h); where gnuplot is not installed, a note on
 * stderr and ATMO_OK, so a benchmark still leaves its CSV. */
int bench_plot(const char *svg, int width, int height, const char *script, atmo_err *e);
/* bench_plot of a script written to an open_memstream(script) stream: closes the stream, draws,
 * and frees the script. */
int bench_plot_close(FILE *script_stream, char **script, const char *svg, int width, int height,
                     atmo_err *e);
/* Log-log chart of error against seconds, one series per method, via gnuplot. */
int bench_chart(const char *csv, const char *svg, const char *title, const char *ylabel,
                const bench_row *rows, int n, atmo_err *e);
/* DIR/NAME.csv (bench_write_csv) and its chart DIR/NAME.svg (bench_chart), then "wrote ..." on
 * stdout. */
int bench_write_suite(const char *dir, const char *name, const bench_row *rows, int n,
                      const char *device, const char *title, const char *ylabel, atmo_err *e);

/* Sums of the squared sun-transmittance errors of the shadow term (host/bench/
 * bench_clouds_shadow.c) over sample points: all of them, and those in cloud. */
typedef struct bench_shadow_error {
    double sq_all, sq_cloud;
    int n_all, n_cloud;
} bench_shadow_error;
/* Adds the shadow term's errors at the marcher's sample points of the rays (r, mu, mu_s, nu)
 * of the plan's scene to *out: the light march, or the sun shadow map where the plan has one. */
int bench_clouds_shadow_error(const atmo_plan *plan, const float4 *rays, int n_rays,
                              bench_shadow_error *out, atmo_err *e);

/* `atmo bench sky` (host/bench_sky.c). */
int bench_sky(const char *dir, const char *device, int quick, atmo_err *e);
/* `atmo bench atmosphere` (host/bench_atmosphere.c). */
int bench_atmosphere(const char *dir, const char *device, const char *reference, int quick,
                     atmo_err *e);

/* `atmo bench colour`: 3-wavelength against spectral colour (host/bench_colour.c). Writes
 * DIR/colour.csv and DIR/colour.svg. */
int bench_colour(const char *dir, const char *device, int quick, atmo_err *e);

/* `atmo bench mie`: phase options against the tabulated Mie phase, and table build times
 * (host/bench_mie.c). Writes DIR/mie.csv, DIR/mie_table.csv and DIR/mie.svg. */
int bench_mie(const char *dir, int quick, atmo_err *e);

/* `atmo bench panorama`: whole-process stages of a sky panorama to EXR, warm, new atmosphere
 * and cold, 512x256 to 4096x2048 (host/bench/bench_panorama.c). Writes DIR/panorama.csv and
 * DIR/panorama.svg. */
int bench_panorama(const char *dir, const char *device, int quick, atmo_err *e);

/* `atmo bench render`: the path tracer's time to 1 % noise per thesis view (1280 x 720,
 * extrapolated from a central crop), its split between the atmosphere and the bounces, and the
 * cost of an unused feature (host/bench/bench_path.c). Writes DIR/render.csv, DIR/render.svg. */
int bench_path(const char *dir, const char *device, int quick, atmo_err *e);

/* `atmo bench terrain`: heightmap sizes and formats against direct evaluation, sphere-tracing
 * optimism and steps, exact against estimated shadows, light-shaft shortcuts, and thesis-1's
 * time (host/bench/bench_terrain.c). Writes DIR/terrain.csv, DIR/terrain.svg and
 * DIR/terrain_thesis1.csv. */
int bench_terrain(const char *dir, const char *device, int quick, atmo_err *e);

/* `atmo bench clouds`: the fBm clouds' marcher and its knobs against the Monte Carlo reference
 * on four cloud views, or (fit = 1) the fit of its multiple-scattering octaves to the reference
 * (host/bench/bench_clouds.c). Writes DIR/clouds.csv and DIR/clouds.svg, or DIR/clouds_fit.csv. */
int bench_clouds(const char *dir, const char *device, int quick, int fit, atmo_err *e);

/* `atmo bench views`: each thesis view (views: a comma-separated subset, NULL all) in the
 * default mode, two-seed noise against time at 1280 x 720 and bias against the cached
 * path-traced reference at 320 x 180 (quick: 320 x 180 and 80 x 45; noise_only: no bias row,
 * no reference) (host/bench/bench_views.c). Writes DIR/views_VIEW.csv and DIR/views_VIEW.svg
 * per view, the references to DIR/views_ref/. */
int bench_views(const char *dir, const char *device, const char *views, int quick, int noise_only,
                atmo_err *e);
/* ATMO_ERR_USAGE naming the first name of the comma-separated views that is not a thesis view
 * (NULL: all, fine). */
int bench_views_check(const char *views, atmo_err *e);

/* `atmo bench denoise`: the path tracer's error against time without and with Open Image
 * Denoise (fast, balanced, high) by samples per pixel on thesis-7 (host/bench/bench_denoise.c).
 * Writes DIR/denoise.csv and DIR/denoise.svg; without the library, its load error. */
int bench_denoise(const char *dir, const char *device, int quick, atmo_err *e);

/* `atmo bench guides`: raw, colour-alone and guided denoising (quality high) of 4-spp path-traced
 * images of the sky, terrain, limb and objects scenes at 256 x 144 (quick: 64 x 36) against a
 * reference (host/bench/bench_guides.c). Writes DIR/guides.csv and DIR/guides.svg. */
int bench_guides(const char *dir, const char *device, int quick, atmo_err *e);

#endif
