/* run_report.c — the run reports' common frame (run_report.h). */
#include <stdlib.h>
#include <string.h>
#include "atmo/fileio.h"
#include "run_report.h"

cJSON *run_report_new(const atmo_scene *s)
{
    cJSON *root = cJSON_CreateObject();
    if (!root)
        return NULL;
    char *scene_text = atmo_scene_to_json(s);
    cJSON *scene = scene_text ? cJSON_Parse(scene_text) : NULL;
    free(scene_text);
    cJSON_AddStringToObject(root, "software", "atmo " ATMO_VERSION);
    cJSON_AddItemToObject(root, "scene", scene ? scene : cJSON_CreateNull());
    return root;
}

int run_report_write(cJSON *root, const char *const *outputs, int n_out, const char *path,
                     atmo_err *e)
{
    cJSON *list = root ? cJSON_AddArrayToObject(root, "outputs") : NULL;
    for (int i = 0; list && i < n_out; i++)
        cJSON_AddItemToArray(list, cJSON_CreateString(outputs[i]));
    char *text = root ? cJSON_Print(root) : NULL;
    cJSON_Delete(root);
    size_t len = text ? strlen(text) : 0;
    char *with_newline = text ? malloc(len + 2) : NULL;
    int rc = with_newline ? ATMO_OK
                          : atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory writing the report '%s'",
                                      path);
    if (with_newline) {
        memcpy(with_newline, text, len);
        memcpy(with_newline + len, "\n", 2);
        rc = atmo_write_text_file(path, with_newline, e);
    }
    free(with_newline);
    free(text);
    return rc;
}
