/* gnuplot.h — charts drawn by gnuplot (host/base/gnuplot.c).
 *
 * A chart is a gnuplot script of plot commands, its data inline as datablocks or read from a CSV
 * that is already written. atmo_gnuplot_svg puts the SVG terminal and a temporary output in front
 * of it, runs gnuplot without a shell and renames the temporary over the target, so the chart is
 * complete or absent. */
#ifndef ATMO_GNUPLOT_H
#define ATMO_GNUPLOT_H

#include "atmo/status.h"

/* 1 when a gnuplot executable is on PATH. */
int atmo_gnuplot_available(void);
/* Run the script into svg (width x height pixels), written atomically; the terminal and the output
 * are set here. ATMO_ERR_RUNTIME when gnuplot is missing or fails. */
int atmo_gnuplot_svg(const char *svg, int width, int height, const char *script, atmo_err *e);

#endif
