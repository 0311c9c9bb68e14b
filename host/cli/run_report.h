/* run_report.h — the JSON run report that `atmo render --report` and `atmo merge --report`
 * write (run_report.c): one object whose first members say what wrote it and the scene it
 * rendered, the command adding its own members after them, and last the files it wrote;
 * written out as one file that is complete or absent (atmo_write_text_file). */
#ifndef ATMO_RUN_REPORT_H
#define ATMO_RUN_REPORT_H
#include <cjson/cJSON.h>
#include "atmo/scene.h"
#include "atmo/status.h"

/* A new report: {"software": "atmo VERSION", "scene": the scene's JSON (null if it cannot be
 * made)}; NULL when out of memory. */
cJSON *run_report_new(const atmo_scene *s);

/* Close the report with "outputs": the n_out files the command wrote, print it with a final
 * newline to path and free it (also on failure). */
int run_report_write(cJSON *root, const char *const *outputs, int n_out, const char *path,
                     atmo_err *e);

#endif
