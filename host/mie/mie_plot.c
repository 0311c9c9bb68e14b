/* mie_plot.c — `atmo mie --chart`: the phase function drawn by gnuplot (atmo/gnuplot.h), its
 * data inline as a datablock, so there is one file.
 *
 * mie_chart_svg draws log10 of the 4pi-normalised P against the scattering angle, one line per
 * wavelength, with shaded angle ranges where the photometeors appear for cloud drops: corona
 * (forward diffraction rings, 0-10 deg), fog bow (130-150 deg; its maximum lies at 138-148 deg
 * for drops of a few to 50 um, mie.md) and glory (170-180 deg). */
#include <stdio.h>
#include <stdlib.h>
#include "atmo/gnuplot.h"
#include "atmo/mie.h"

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
    int rc = atmo_gnuplot_svg(svg, 900, 520, s, e);
    free(s);
    return rc;
}
