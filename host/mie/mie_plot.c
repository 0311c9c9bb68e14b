/* mie_plot.c — charts drawn by gnuplot: the helper that runs it, and `atmo mie --chart`.
 *
 * mie_gnuplot_svg writes the caller's script (data inline as gnuplot datablocks, so there is one
 * file) after a preamble that selects the SVG terminal and a temporary output beside the target,
 * runs gnuplot on it without a shell (fork/exec, so no path is ever quoted for sh), and renames
 * the temporary SVG over the target (include/atmo/fileio.h): the chart is complete or absent.
 *
 * mie_chart_svg draws log10 of the 4pi-normalised P against the scattering angle, one line per
 * wavelength, with shaded angle ranges where the photometeors appear for cloud drops: corona
 * (forward diffraction rings, 0-10 deg), fog bow (130-150 deg; its maximum lies at 138-148 deg
 * for drops of a few to 50 um, mie.md) and glory (170-180 deg). */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>
#include "atmo/fileio.h"
#include "atmo/mie.h"

int mie_gnuplot_available(void)
{
    const char *path = getenv("PATH");
    if (!path)
        return 0;
    char dir[4096], exe[4200];
    while (*path) {
        size_t len = strcspn(path, ":");
        snprintf(dir, sizeof dir, "%.*s", (int)(len < sizeof dir - 1 ? len : sizeof dir - 1), path);
        snprintf(exe, sizeof exe, "%s/gnuplot", len ? dir : ".");
        if (access(exe, X_OK) == 0)
            return 1;
        path += len + (path[len] == ':');
    }
    return 0;
}

/* A path as a gnuplot single-quoted string (a quote is written twice). */
static void mie_gp_quote(FILE *f, const char *s)
{
    fputc('\'', f);
    for (; *s; s++) {
        if (*s == '\'')
            fputc('\'', f);
        fputc(*s, f);
    }
    fputc('\'', f);
}

int mie_gnuplot_svg(const char *svg, int width, int height, const char *script, atmo_err *e)
{
    char svg_tmp[ATMO_TMP_PATH_MAX], gp_path[ATMO_TMP_PATH_MAX + 8], gp_tmp[ATMO_TMP_PATH_MAX];
    if (!mie_gnuplot_available())
        return atmo_fail(e, ATMO_ERR_RUNTIME, "gnuplot not found on PATH, needed for %s; install "
                         "gnuplot-nox (setup.sh does) or leave the chart out", svg);
    atmo_tmp_path(svg, svg_tmp);
    snprintf(gp_path, sizeof gp_path, "%s.gp", svg);
    FILE *f = atmo_atomic_open(gp_path, gp_tmp, e);
    if (!f)
        return ATMO_ERR_RUNTIME;
    fprintf(f, "set terminal svg size %d,%d dynamic background rgb 'white' font 'sans,11'\n"
               "set output ", width, height);
    mie_gp_quote(f, svg_tmp);
    fprintf(f, "\n%s\nunset output\n", script);
    if (fclose(f) != 0) {
        remove(gp_tmp);
        return atmo_fail(e, ATMO_ERR_RUNTIME, "cannot write the gnuplot script %s: %s", gp_tmp,
                         strerror(errno));
    }
    int status = -1;
    pid_t pid = fork();
    if (pid == 0) {
        execlp("gnuplot", "gnuplot", gp_tmp, (char *)NULL);
        _exit(127);
    }
    if (pid > 0)
        waitpid(pid, &status, 0);
    remove(gp_tmp);
    if (pid < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        remove(svg_tmp);
        return atmo_fail(e, ATMO_ERR_RUNTIME, "gnuplot failed drawing %s (its message is above)",
                         svg);
    }
    return atmo_atomic_commit(NULL, svg_tmp, svg, e);
}

int mie_chart_svg(const char *svg, const char *title, const double *theta_deg, int n,
                  const double *P, const double *wavelength_nm, int n_wavelengths, atmo_err *e)
{
    size_t cap = 4096 + (size_t)n * (size_t)(24 + 18 * n_wavelengths);
    char *s = malloc(cap);
    if (!s)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for the chart of %d angles", n);
    char safe_title[256]; /* inside a gnuplot double-quoted string: no quotes or backslashes */
    snprintf(safe_title, sizeof safe_title, "%s", title);
    for (char *c = safe_title; *c; c++)
        if (*c == '"' || *c == '\\' || *c == '\n')
            *c = '\'';
    size_t len = (size_t)snprintf(s, cap, "$P << EOD\n");
    for (int i = 0; i < n; i++) {
        len += (size_t)snprintf(s + len, cap - len, "%.6f", theta_deg[i]);
        for (int w = 0; w < n_wavelengths; w++)
            len += (size_t)snprintf(s + len, cap - len, " %.9g", P[(size_t)w * n + i]);
        len += (size_t)snprintf(s + len, cap - len, "\n");
    }
    len += (size_t)snprintf(s + len, cap - len,
        "EOD\n"
        "set title \"%s\" noenhanced\n"
        "set xlabel 'scattering angle (deg)'\nset ylabel 'P (4pi-normalised)'\n"
        "set logscale y\nset format y '10^{%%L}'\nset xrange [0:180]\nset xtics 0,20,180\n"
        "set grid\nset key top center\n"
        "set style rect fs solid 1.0 noborder\n" /* light opaque fills behind: any SVG viewer */
        "set object 1 rect from 0,graph 0 to 10,graph 1 behind fc rgb '#fbe6c0'\n"
        "set object 2 rect from 130,graph 0 to 150,graph 1 behind fc rgb '#d6ecf8'\n"
        "set object 3 rect from 170,graph 0 to 180,graph 1 behind fc rgb '#cdeee3'\n"
        "set label 1 'corona' at 5,graph 0.96 center\n"
        "set label 2 'fog bow' at 140,graph 0.96 center\n"
        "set label 3 'glory' at 175,graph 0.90 center\n"
        "plot ", safe_title);
    for (int w = 0; w < n_wavelengths; w++)
        len += (size_t)snprintf(s + len, cap - len, "%s$P using 1:%d with lines lw 1.2 title '%g nm'",
                                w ? ", " : "", w + 2, wavelength_nm[w]);
    snprintf(s + len, cap - len, "\n");
    int rc = mie_gnuplot_svg(svg, 900, 520, s, e);
    free(s);
    return rc;
}
