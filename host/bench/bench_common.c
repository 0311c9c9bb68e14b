/* bench_common.c — what the benchmark suites share (atmo/bench.h): rendering a scene, the
 * RMS relative difference of two images, the CSV and the gnuplot chart of error against time. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/bench.h"
#include "atmo/fileio.h"
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

int bench_chart(const char *csv, const char *svg, const char *title, const char *ylabel,
                const bench_row *rows, int n, atmo_err *e)
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
               "set xlabel 'seconds'\nset ylabel '%s'\nset grid\n"
               "set key outside right\nset title '%s'\n",
            svg_tmp, ylabel, title);
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

