/* cmd_params.c — `atmo params`: every scene parameter with its unit, default, valid range and
 * meaning, as a table (default) or as JSON (--json, for tools). Both are printed from the
 * registry (scene.c and the feature folders), so they cannot drift from what --set and scene
 * files accept. */
#include <cjson/cJSON.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>
#include "atmo/scene.h"
#include "cli_flags.h"
#include "commands.h"

typedef struct params_args {
    int json;
} params_args;

static const cli_flag params_flags[] = {
    {.type = CLI_BOOL, .name = "--json", .offset = offsetof(params_args, json),
     .help = "print the list as JSON"},
    {.type = CLI_END},
};

static const cli_command params_cli = {
    .name = "params",
    .synopsis = "[--json]",
    .about = "List every scene parameter: key, unit, default, valid range and meaning.\n"
             "Set them with --set key=value, in a JSON scene file ({\"sun\": {\"zenith_deg\": 60}}),\n"
             "or through a preset (atmo presets).\n",
    .flags = params_flags,
};

/* The default as it would be written after --set. */
static void default_text(const atmo_param *p, char *buf, size_t n)
{
    switch (p->type) {
    case ATMO_PARAM_VEC3:
        snprintf(buf, n, "%.9g,%.9g,%.9g", p->def[0], p->def[1], p->def[2]);
        break;
    case ATMO_PARAM_VEC2:
        snprintf(buf, n, "%.9g,%.9g", p->def[0], p->def[1]);
        break;
    case ATMO_PARAM_STRING:
        snprintf(buf, n, "\"\"");
        break;
    case ATMO_PARAM_ENUM:
        snprintf(buf, n, "%s", p->names[(int)p->def[0]]);
        break;
    case ATMO_PARAM_BOOL:
        snprintf(buf, n, "%s", p->def[0] != 0 ? "true" : "false");
        break;
    default:
        snprintf(buf, n, "%.9g", p->def[0]);
    }
}

static void range_text(const atmo_param *p, char *buf, size_t n)
{
    if (p->type == ATMO_PARAM_ENUM) {
        size_t used = 0;
        buf[0] = '\0';
        for (int i = 0; p->names[i] && used < n; i++)
            used += (size_t)snprintf(buf + used, n - used, "%s%s", i ? "|" : "", p->names[i]);
    } else if (p->type == ATMO_PARAM_BOOL) {
        snprintf(buf, n, "true|false");
    } else if (p->type == ATMO_PARAM_STRING) {
        snprintf(buf, n, "text (< %d bytes)", ATMO_PARAM_STRING_MAX);
    } else {
        snprintf(buf, n, "%.15g .. %.15g%s", p->min, p->max,
                 atmo_param_components(p) > 1 ? " each" : "");
    }
}

static int print_json(void)
{
    int rc = ATMO_ERR_RUNTIME;
    char *text = NULL;
    cJSON *list = cJSON_CreateArray();
    if (!list)
        goto cleanup;
    for (int i = 0; i < atmo_param_count(); i++) {
        const atmo_param *p = atmo_param_at(i);
        cJSON *row = cJSON_CreateObject();
        if (!row || !cJSON_AddItemToArray(list, row))
            goto cleanup;
        cJSON_AddStringToObject(row, "key", p->key);
        cJSON_AddStringToObject(row, "type",
                                p->type == ATMO_PARAM_INT     ? "int"
                                : p->type == ATMO_PARAM_FLOAT ? "float"
                                : p->type == ATMO_PARAM_VEC3  ? "vec3"
                                : p->type == ATMO_PARAM_VEC2  ? "vec2"
                                : p->type == ATMO_PARAM_ENUM  ? "enum"
                                : p->type == ATMO_PARAM_STRING ? "string"
                                                              : "bool");
        cJSON_AddStringToObject(row, "unit", p->unit);
        if (p->type == ATMO_PARAM_VEC3 || p->type == ATMO_PARAM_VEC2)
            cJSON_AddItemToObject(row, "default",
                                  cJSON_CreateDoubleArray(p->def, atmo_param_components(p)));
        else if (p->type == ATMO_PARAM_STRING)
            cJSON_AddStringToObject(row, "default", "");
        else if (p->type == ATMO_PARAM_ENUM)
            cJSON_AddStringToObject(row, "default", p->names[(int)p->def[0]]);
        else if (p->type == ATMO_PARAM_BOOL)
            cJSON_AddBoolToObject(row, "default", p->def[0] != 0);
        else
            cJSON_AddNumberToObject(row, "default", p->def[0]);
        if (p->type == ATMO_PARAM_ENUM) {
            int n = 0;
            while (p->names[n])
                n++;
            cJSON_AddItemToObject(row, "values", cJSON_CreateStringArray(p->names, n));
        } else if (p->type != ATMO_PARAM_BOOL && p->type != ATMO_PARAM_STRING) {
            cJSON_AddNumberToObject(row, "min", p->min);
            cJSON_AddNumberToObject(row, "max", p->max);
        }
        cJSON_AddStringToObject(row, "help", p->help);
    }
    text = cJSON_Print(list);
    if (!text)
        goto cleanup;
    puts(text);
    rc = ATMO_OK;
cleanup:
    if (rc)
        fprintf(stderr, "atmo params: out of memory\n");
    cJSON_free(text);
    cJSON_Delete(list);
    return rc;
}

int cmd_params(int argc, char **argv)
{
    params_args a = {0};
    int rc;
    if (!cli_parse(&params_cli, &a, argc, argv, NULL, NULL, &rc))
        return rc;
    if (a.json)
        return print_json();
    printf("%-36s %-9s %-16s %-44s %s\n", "key", "unit", "default", "valid range", "meaning");
    for (int i = 0; i < atmo_param_count(); i++) {
        const atmo_param *p = atmo_param_at(i);
        char def[64], range[160];
        default_text(p, def, sizeof def);
        range_text(p, range, sizeof range);
        printf("%-36s %-9s %-16s %-44s %s\n", p->key, p->unit[0] ? p->unit : "-", def, range,
               p->help);
    }
    /* the object list is not one value but a JSON array (host/scene/scene_objects.c) */
    printf("%-36s %-9s %-16s %-44s %s\n", "objects", "m", "[]",
           "JSON array of up to 32 spheres and boxes",
           "objects: {\"type\": \"sphere\", \"center_m\": [x,y,z], \"radius_m\": r} or "
           "{\"type\": \"box\", \"min_m\": [...], \"size_m\": [...]}, each with \"albedo\" "
           "(0..1, default 0.8) and \"emission\" (W/m^2/sr/nm, default 0)");
    return ATMO_OK;
}
