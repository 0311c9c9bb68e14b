/* bench_common.c — what the benchmark suites share (atmo/bench.h): rendering a scene, the
 * RMS relative difference of two images, the CSV and the gnuplot chart of error against time. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/bench.h"
#include "atmo/fileio.h"
#include "atmo/gnuplot.h"
#include "atmo/plan.h"

int bench_render(const atmo_scene *s, const char *device, atmo_render_result *r, atmo_err *e)
{
    atmo_plan plan;
    atmo_render_settings rs;
    int rc = atmo_plan_make(s, &plan, e);
    if (rc)
        return rc;
    atmo_render_settings_default(&rs);
    rs.device = device;
    rc = atmo_render(&plan, &rs, r, e);
    atmo_plan_free(&plan);
    return rc;
}

double bench_rms_relative(const atmo_render_result *a, const atmo_render_result *ref)
{
    size_t n = (size_t)a->width * a->height * 3;
    double sum = 0.0;
    for (size_t i = 0; i < n; i++) {
        double d = ((double)a->rgb[i] - (double)ref->rgb[i]) / fmax(fabs((double)ref->rgb[i]), 1e-30);
        sum += d * d;
    }
    return sqrt(sum / (double)n);
}

double bench_unbiased_error(const float *x, const atmo_render_result *ref_a,
                            const atmo_render_result *ref_b)
{
    double d2 = 0.0, var = 0.0, ref2 = 0.0;
    for (size_t i = 0; i < 3 * (size_t)ref_a->width * ref_a->height; i++) {
        double a = ref_a->rgb[i], b = ref_b->rgb[i], r = 0.5 * (a + b), d = (double)x[i] - r;
        d2 += d * d;
        var += 0.25 * (a - b) * (a - b);
        ref2 += r * r;
    }
    return sqrt(fmax(d2 - var, 0.0) / fmax(ref2, 1e-300));
}

/* The means of B x B block (bx, by) of the four images into m[4]; 0 if a pixel is skipped. */
static int bench_block_means(const double *const img[4], const unsigned char *skip, int w, int bx,
                             int by, int B, double m[4])
{
    for (int k = 0; k < 4; k++)
        m[k] = 0.0;
    for (int y = by * B; y < (by + 1) * B; y++)
        for (int x = bx * B; x < (bx + 1) * B; x++) {
            size_t i = (size_t)y * w + x;
            if (skip && skip[i])
                return 0;
            for (int k = 0; k < 4; k++)
                m[k] += img[k][i] / (double)(B * B);
        }
    return 1;
}

double bench_block_bias(const double *x1, const double *x2, const double *a, const double *b,
                        const unsigned char *skip, int w, int h, int B, double bright, double *se,
                        double *mean_bias, int *blocks)
{
    const double *const img[4] = {x1, x2, a, b};
    double ref_mean = 0.0, sum_x = 0.0, sum_r = 0.0, sum_t = 0.0, sum_t2 = 0.0, m[4];
    size_t used = 0;
    for (size_t i = 0; i < (size_t)w * h; i++)
        if (!skip || !skip[i])
            ref_mean += 0.5 * (a[i] + b[i]), used++;
    ref_mean /= used ? (double)used : 1.0;
    int k = 0;
    for (int by = 0; by < h / B; by++)
        for (int bx = 0; bx < w / B; bx++) {
            if (!bench_block_means(img, skip, w, bx, by, B, m))
                continue;
            double X = 0.5 * (m[0] + m[1]), R = 0.5 * (m[2] + m[3]);
            if (!(R > bright * ref_mean))
                continue;
            double D = X - R, dr = m[2] - m[3];
            double t = (D * D - 0.25 * (m[0] - m[1]) * (m[0] - m[1]) - 0.25 * dr * dr) / (R * R) -
                       D * dr * dr / (R * R * R);
            sum_t += t, sum_t2 += t * t, sum_x += X, sum_r += R, k++;
        }
    *blocks = k;
    *mean_bias = sum_r > 0.0 ? sum_x / sum_r - 1.0 : 0.0;
    double mean = k ? sum_t / k : 0.0;
    double se_mean = k > 1 ? sqrt(fmax(sum_t2 / k - mean * mean, 0.0) / (k - 1)) : (double)INFINITY;
    *se = mean > se_mean ? se_mean / (2.0 * sqrt(mean)) : sqrt(se_mean);
    return sqrt(fmax(mean, 0.0));
}

int bench_write_csv(const char *path, const bench_row *rows, int n, const char *device,
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

int bench_plot(const char *svg, int width, int height, const char *script, atmo_err *e)
{
    if (!atmo_gnuplot_available()) {
        fprintf(stderr, "atmo bench: gnuplot not found; wrote the CSV only (apt-get install "
                        "gnuplot-nox for the chart %s)\n", svg);
        return ATMO_OK;
    }
    return atmo_gnuplot_svg(svg, width, height, script, e);
}

int bench_plot_close(FILE *script_stream, char **script, const char *svg, int width, int height,
                     atmo_err *e)
{
    int closed = fclose(script_stream) == 0;
    int rc = closed ? bench_plot(svg, width, height, *script, e)
                    : atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for the chart script of %s", svg);
    free(*script);
    *script = NULL;
    return rc;
}

int bench_chart(const char *csv, const char *svg, const char *title, const char *ylabel,
                const bench_row *rows, int n, atmo_err *e)
{
    char *script = NULL;
    size_t size = 0;
    FILE *f = open_memstream(&script, &size);
    if (!f)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for the chart script of %s", svg);
    fprintf(f, "set datafile separator ','\nset logscale xy\n"
               "set xlabel 'seconds'\nset ylabel '%s'\nset grid\n"
               "set key outside right\nset title '%s'\n",
            ylabel, title);
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
    int rc = bench_plot_close(f, &script, svg, 800, 500, e);
    return rc;
}

int bench_write_suite(const char *dir, const char *name, const bench_row *rows, int n,
                      const char *device, const char *title, const char *ylabel, atmo_err *e)
{
    char csv[4096], svg[4096];
    int rc;
    snprintf(csv, sizeof csv, "%s/%s.csv", dir, name);
    snprintf(svg, sizeof svg, "%s/%s.svg", dir, name);
    if ((rc = bench_write_csv(csv, rows, n, device, e)) ||
        (rc = bench_chart(csv, svg, title, ylabel, rows, n, e)))
        return rc;
    printf("wrote %s and %s\n", csv, svg);
    return ATMO_OK;
}
