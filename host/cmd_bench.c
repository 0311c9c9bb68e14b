/* cmd_bench.c — `atmo bench SUITE --output DIR`: error against time for each method's knobs.
 *
 * A suite renders one view with several settings and a reference of much higher quality, and
 * writes DIR/SUITE.csv (method, settings, seconds, error, device) and DIR/SUITE.svg, a log-log
 * chart of error against time drawn by gnuplot (when installed; otherwise the CSV alone, and it
 * says so). Seconds are precompute plus render time; kernel builds are timed apart by the
 * renderer and left out (the reference render builds and caches the program first).
 *
 * Suites:
 *   sky   the single-scattering sky (panorama 256 x 128, sun zenith 80 deg, 4 samples per pixel)
 *         for view-ray steps 4..128 (LUT 256 x 64) and transmittance LUT sizes 16 x 4 .. 512 x 128
 *         (64 steps), against 1024 steps and a 1024 x 256 LUT at 16 samples per pixel.
 *         Error: the RMS over pixels of the relative difference of the three channels. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "atmo/bench.h"
#include "atmo/fileio.h"
#include "atmo/plan.h"
#include "atmo/render.h"
#include "atmo/scene.h"
#include "commands.h"

static const char bench_usage[] =
    "usage: atmo bench SUITE [--output DIR] [--device N|NAME] [--quick]\n"
    "\n"
    "Measures error against a high-quality reference and time for each setting of a method,\n"
    "and writes DIR/SUITE.csv and the chart DIR/SUITE.svg (gnuplot). DIR defaults to bench/.\n"
    "--quick runs fewer settings (for tests).\n"
    "\n"
    "suites:\n"
    "  sky   single-scattering sky: view-ray steps and transmittance LUT size\n"
    "  mie   cloud phase options against the tabulated Mie phase; phase table build time\n";

typedef struct bench_row {
    char method[32];
    char settings[64];
    double seconds;
    double error;
} bench_row;

static int __bench_render(const atmo_scene *s, const char *device, atmo_render_result *r,
                          atmo_err *e)
{
    atmo_plan plan;
    atmo_render_settings rs;
    int rc = atmo_plan_make(s, &plan, e);
    if (rc)
        return rc;
    atmo_render_settings_default(&rs);
    rs.device = device;
    return atmo_render(&plan, &rs, r, e);
}

static double __rms_relative(const atmo_render_result *a, const atmo_render_result *ref)
{
    size_t n = (size_t)a->width * a->height * 3;
    double sum = 0.0;
    for (size_t i = 0; i < n; i++) {
        double d = ((double)a->rgb[i] - (double)ref->rgb[i]) / fmax(fabs((double)ref->rgb[i]), 1e-30);
        sum += d * d;
    }
    return sqrt(sum / (double)n);
}

static int __write_csv(const char *path, const bench_row *rows, int n, const char *device,
                       atmo_err *e)
{
    char tmp[ATMO_TMP_PATH_MAX];
    FILE *f = atmo_atomic_open(path, tmp, e);
    if (!f)
        return ATMO_ERR_RUNTIME;
    fprintf(f, "method,settings,seconds,error,device\n");
    for (int i = 0; i < n; i++)
        fprintf(f, "%s,%s,%.6f,%.6e,\"%s\"\n", rows[i].method, rows[i].settings, rows[i].seconds,
                rows[i].error, device);
    return atmo_atomic_commit(f, tmp, path, e);
}

/* Draw the chart with gnuplot: one series per method, log-log. */
static int __chart(const char *csv, const char *svg, const char *title, const bench_row *rows,
                   int n, atmo_err *e)
{
    if (system("command -v gnuplot >/dev/null 2>&1") != 0) {
        fprintf(stderr, "atmo bench: gnuplot not found; wrote the CSV only (apt-get install "
                        "gnuplot-nox for the chart)\n");
        return ATMO_OK;
    }
    char script_path[ATMO_TMP_PATH_MAX + 8], svg_tmp[ATMO_TMP_PATH_MAX];
    snprintf(script_path, sizeof script_path, "%s.gp", svg);
    atmo_tmp_path(svg, svg_tmp);
    FILE *f = fopen(script_path, "w");
    if (!f)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "cannot write %s: %s", script_path, strerror(errno));
    fprintf(f, "set terminal svg size 800,500 dynamic background rgb 'white'\n"
               "set output '%s'\nset datafile separator ','\nset logscale xy\n"
               "set xlabel 'seconds'\nset ylabel 'RMS relative error'\nset grid\n"
               "set key outside right\nset title '%s'\n",
            svg_tmp, title);
    const char *methods[16];
    int nm = 0;
    for (int i = 0; i < n; i++) {
        int seen = 0;
        for (int j = 0; j < nm; j++)
            seen |= strcmp(methods[j], rows[i].method) == 0;
        if (!seen && nm < 16)
            methods[nm++] = rows[i].method;
    }
    fprintf(f, "plot ");
    for (int j = 0; j < nm; j++)
        fprintf(f, "%s'%s' using (strcol(1) eq '%s' ? $3 : 1/0):4:2 with linespoints title '%s', "
                   "'' using (strcol(1) eq '%s' ? $3 : 1/0):4:2 with labels offset 1,0.5 font ',8' "
                   "notitle",
                j ? ", " : "", csv, methods[j], methods[j], methods[j]);
    fprintf(f, "\n");
    fclose(f);
    char cmd[3 * ATMO_TMP_PATH_MAX];
    snprintf(cmd, sizeof cmd, "gnuplot '%s'", script_path);
    int status = system(cmd);
    remove(script_path);
    if (status != 0) {
        remove(svg_tmp);
        return atmo_fail(e, ATMO_ERR_RUNTIME, "gnuplot failed drawing %s", svg);
    }
    return atmo_atomic_commit(NULL, svg_tmp, svg, e);
}

static int __bench_sky(const char *dir, const char *device, int quick, atmo_err *e)
{
    atmo_scene base;
    int rc;
    atmo_scene_defaults(&base);
    if ((rc = atmo_scene_apply_preset(&base, "sky-sunset", e)) ||
        (rc = atmo_scene_assign(&base, "camera.kind=panorama", "bench", e)) ||
        (rc = atmo_scene_assign(&base, "sun.zenith_deg=80", "bench", e)))
        return rc;
    base.image.width = quick ? 64 : 256;
    base.image.height = quick ? 32 : 128;
    base.image.samples = 4;

    atmo_scene ref = base;
    ref.render.view_steps = quick ? 256 : 1024;
    ref.render.transmittance_width = 1024;
    ref.render.transmittance_height = 256;
    ref.image.samples = 16;
    atmo_render_result r_ref;
    fprintf(stderr, "bench sky: reference (%d steps, LUT 1024x256, 16 spp)\n", ref.render.view_steps);
    if ((rc = __bench_render(&ref, device, &r_ref, e)))
        return rc;

    static const int steps[] = {4, 8, 16, 32, 64, 128};
    static const int luts[][2] = {{16, 4}, {32, 8}, {64, 16}, {128, 32}, {256, 64}, {512, 128}};
    int n_steps = quick ? 3 : 6, n_luts = quick ? 2 : 6;
    bench_row rows[16];
    int n = 0;
    for (int pass = 0; pass < 2; pass++) {
        int count = pass == 0 ? n_steps : n_luts;
        for (int i = 0; i < count && !rc; i++) {
            atmo_scene s = base;
            bench_row *row = &rows[n];
            if (pass == 0) {
                s.render.view_steps = steps[i];
                snprintf(row->method, sizeof row->method, "view-steps");
                snprintf(row->settings, sizeof row->settings, "%d", steps[i]);
            } else {
                s.render.view_steps = 64;
                s.render.transmittance_width = luts[i][0];
                s.render.transmittance_height = luts[i][1];
                snprintf(row->method, sizeof row->method, "lut-size");
                snprintf(row->settings, sizeof row->settings, "%dx%d", luts[i][0], luts[i][1]);
            }
            atmo_render_result r;
            if ((rc = __bench_render(&s, device, &r, e)))
                break;
            row->seconds = r.seconds_precompute + r.seconds_render;
            row->error = __rms_relative(&r, &r_ref);
            fprintf(stderr, "bench sky: %-10s %-8s %8.4fs  error %.3e\n", row->method,
                    row->settings, row->seconds, row->error);
            atmo_render_result_free(&r);
            n++;
        }
    }
    char device_name[256];
    snprintf(device_name, sizeof device_name, "%s", r_ref.device_name);
    atmo_render_result_free(&r_ref);
    if (rc)
        return rc;
    char csv[4096], svg[4096];
    snprintf(csv, sizeof csv, "%s/sky.csv", dir);
    snprintf(svg, sizeof svg, "%s/sky.svg", dir);
    if ((rc = __write_csv(csv, rows, n, device_name, e)))
        return rc;
    char title[512];
    snprintf(title, sizeof title, "single-scattering sky, 256x128 panorama, 4 spp (%s)",
             device_name);
    if ((rc = __chart(csv, svg, title, rows, n, e)))
        return rc;
    printf("wrote %s and %s\n", csv, svg);
    return ATMO_OK;
}

int cmd_bench(int argc, char **argv)
{
    const char *suite = NULL, *dir = "bench", *device = NULL;
    int quick = 0;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            printf("%s", bench_usage);
            return ATMO_OK;
        } else if (strcmp(argv[i], "--quick") == 0)
            quick = 1;
        else if ((strcmp(argv[i], "--output") == 0 || strcmp(argv[i], "--device") == 0) &&
                 i + 1 < argc) {
            if (argv[i][2] == 'o')
                dir = argv[++i];
            else
                device = argv[++i];
        } else if (argv[i][0] != '-' && !suite)
            suite = argv[i];
        else {
            fprintf(stderr, "atmo bench: unexpected argument '%s' (atmo bench --help)\n", argv[i]);
            return ATMO_ERR_USAGE;
        }
    }
    if (!suite) {
        fprintf(stderr, "atmo bench: name a suite (sky, mie); atmo bench --help\n");
        return ATMO_ERR_USAGE;
    }
    if (strcmp(suite, "sky") != 0 && strcmp(suite, "mie") != 0) {
        fprintf(stderr, "atmo bench: unknown suite '%s' (suites: sky, mie)\n", suite);
        return ATMO_ERR_USAGE;
    }
    if (mkdir(dir, 0755) != 0 && errno != EEXIST) {
        fprintf(stderr, "atmo bench: cannot create output directory '%s': %s\n", dir,
                strerror(errno));
        return ATMO_ERR_USAGE;
    }
    atmo_err e;
    int rc = strcmp(suite, "mie") == 0 ? bench_mie(dir, quick, &e) : __bench_sky(dir, device, quick, &e);
    if (rc)
        fprintf(stderr, "atmo bench: %s\n", e.msg);
    return rc;
}
