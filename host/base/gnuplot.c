/* gnuplot.c — running gnuplot for a chart (atmo/gnuplot.h).
 *
 * atmo_gnuplot_svg writes the caller's script after a preamble that selects the SVG terminal and a
 * temporary output beside the target, runs gnuplot on it without a shell (fork/exec, so no path is
 * ever quoted for sh; inside the script a path is a single-quoted gnuplot string with its quotes
 * doubled), and renames the temporary SVG over the target (atmo/fileio.h). */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>
#include "atmo/fileio.h"
#include "atmo/gnuplot.h"

int atmo_gnuplot_available(void)
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
static void gp_quote(FILE *f, const char *s)
{
    fputc('\'', f);
    for (; *s; s++) {
        if (*s == '\'')
            fputc('\'', f);
        fputc(*s, f);
    }
    fputc('\'', f);
}

int atmo_gnuplot_svg(const char *svg, int width, int height, const char *script, atmo_err *e)
{
    char svg_tmp[ATMO_TMP_PATH_MAX], gp_path[ATMO_TMP_PATH_MAX + 8], gp_tmp[ATMO_TMP_PATH_MAX];
    if (!atmo_gnuplot_available())
        return atmo_fail(e, ATMO_ERR_RUNTIME, "gnuplot not found on PATH, needed for %s; install "
                         "gnuplot-nox (setup.sh does) or leave the chart out", svg);
    atmo_tmp_path(svg, svg_tmp);
    snprintf(gp_path, sizeof gp_path, "%s.gp", svg);
    FILE *f = atmo_atomic_open(gp_path, gp_tmp, e);
    if (!f)
        return ATMO_ERR_RUNTIME;
    fprintf(f, "set terminal svg size %d,%d dynamic background rgb 'white' font 'sans,11'\n"
               "set output ", width, height);
    gp_quote(f, svg_tmp);
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
