/* run_report.h — the JSON run report that `atmo render --report` and `atmo merge --report`
 * write (run_report.c): one object whose first members say what wrote it and the scene it
 * rendered, the command adding its own members after them, written out as one file that is
 * complete or absent (atmo_write_text_file). */
#ifndef ATMO_RUN_REPORT_H
#define ATMO_RUN_REPORT_H
#include <cjson/cJSON.h>
#include "atmo/scene.h"
#include "atmo/status.h"

/* A new report: {"software": "atmo VERSION", "scene": the scene's JSON (null if it cannot be
 * made)}; NULL when out of memory. */
cJSON *run_report_new(const atmo_scene *s);

/* Print the report with a final newline to path and free it (also on failure). */
int run_report_write(cJSON *root, const char *path, atmo_err *e);

#endif
