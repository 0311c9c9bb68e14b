/* scene_json.c — scene files: JSON in, JSON out, through the parameter registry.
 *
 * A scene file is a JSON object whose keys are the registry's dotted keys, nested by their
 * dots ({"sun": {"zenith_deg": 60}}); dotted keys at the top level ({"sun.zenith_deg": 60}) are
 * read too. Values: numbers for int and float keys, [x, y, z] for vec3, [x, z] for vec2, a name
 * string for enums, true/false for booleans, a string for string keys (file paths). Keys not in the file keep the values already in the scene
 * (the caller starts from the defaults or a preset); unknown keys, duplicates and values of the
 * wrong JSON type are errors naming the key and the file.
 *
 * The key "objects" holds the object list, an array (scene_objects.c); saving writes it after
 * the registry's keys when the scene has objects. Saving writes every key, nested, in registry order, each number with the fewest significant
 * digits (15 to 17) that read back exactly, so save -> load restores the scene bit for bit (a
 * render of the saved scene reproduces the image) and a second save gives the same text. */
#include <cjson/cJSON.h>
#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include "atmo/fileio.h"
#include "atmo/scene.h"

#define SCENE_FILE_MAX (16 << 20) /* a scene is a few kB; refuse anything absurd */

/* The whole file as a string; the buffer grows by doubling so pipes (--scene /dev/stdin) work. */
static char *read_file(const char *path, size_t *length, atmo_err *e)
{
    char *text = NULL;
    size_t used = 0, cap = 4096;
    FILE *f = fopen(path, "rb");
    if (!f) {
        atmo_fail(e, ATMO_ERR_USAGE, "cannot read scene file '%s': %s (check the path)", path,
                  strerror(errno));
        goto cleanup;
    }
    for (;;) {
        char *grown = realloc(text, cap + 1);
        if (!grown) {
            atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory reading '%s'", path);
            goto fail;
        }
        text = grown;
        used += fread(text + used, 1, cap - used, f);
        if (used < cap)
            break;
        if (cap >= SCENE_FILE_MAX) {
            atmo_fail(e, ATMO_ERR_USAGE, "scene file '%s' is larger than 16 MiB; is it a scene?",
                      path);
            goto fail;
        }
        cap *= 2;
    }
    if (ferror(f)) {
        atmo_fail(e, ATMO_ERR_USAGE, "scene file '%s' could not be read: %s", path,
                  strerror(errno));
        goto fail;
    }
    text[used] = '\0';
    *length = used;
    goto cleanup;
fail:
    free(text);
    text = NULL;
cleanup:
    if (f)
        fclose(f);
    return text;
}

/* The line of the first NUL character of the text's JSON strings, written raw or as the
 * escape \u0000 (cJSON would end the string there and read a shorter name), or 0 if none. */
static int nul_line(const char *text, size_t length)
{
    int line = 1, in_string = 0;
    for (size_t i = 0; i < length; i++) {
        char c = text[i];
        if (c == '\0')
            return line;
        line += c == '\n';
        if (!in_string) {
            in_string = c == '"';
        } else if (c == '"') {
            in_string = 0;
        } else if (c == '\\' && i + 1 < length) {
            if (length - i >= 6 && memcmp(text + i + 1, "u0000", 5) == 0)
                return line;
            i++; /* the escaped character */
        }
    }
    return 0;
}

/* One JSON value into parameter p. */
static int store_json(atmo_scene *s, const atmo_param *p, const cJSON *item, const char *path,
                        atmo_err *e)
{
    double v[3] = {0, 0, 0};
    char shown[128];
    const char *expected = NULL;
    switch (p->type) {
    case ATMO_PARAM_INT:
    case ATMO_PARAM_FLOAT:
        if (!cJSON_IsNumber(item))
            expected = "a number";
        else
            v[0] = item->valuedouble;
        break;
    case ATMO_PARAM_VEC2:
    case ATMO_PARAM_VEC3: {
        int n = atmo_param_components(p);
        const char *want = n == 3 ? "an array of 3 numbers" : "an array of 2 numbers";
        if (!cJSON_IsArray(item) || cJSON_GetArraySize(item) != n)
            expected = want;
        for (int i = 0; !expected && i < n; i++) {
            const cJSON *c = cJSON_GetArrayItem(item, i);
            if (!cJSON_IsNumber(c))
                expected = want;
            else
                v[i] = c->valuedouble;
        }
        break;
    }
    case ATMO_PARAM_STRING:
        if (!cJSON_IsString(item))
            expected = "a string";
        else
            return atmo_param_store_text(s, p, item->valuestring, path, e);
        break;
    case ATMO_PARAM_ENUM:
        if (!cJSON_IsString(item)) {
            expected = "a name string";
            break;
        }
        v[0] = -1; /* not a valid name unless found */
        for (int i = 0; p->names[i]; i++)
            if (strcmp(item->valuestring, p->names[i]) == 0)
                v[0] = i;
        snprintf(shown, sizeof shown, "'%s'", item->valuestring);
        return atmo_param_store(s, p, v, shown, path, e);
    case ATMO_PARAM_BOOL:
        if (!cJSON_IsBool(item))
            expected = "true or false";
        else
            v[0] = cJSON_IsTrue(item) ? 1 : 0;
        break;
    }
    if (expected) {
        char *text = cJSON_PrintUnformatted(item);
        int rc =
            atmo_fail(e, ATMO_ERR_USAGE, "%s = %.60s (from %s) has the wrong type: expected %s",
                      p->key, text ? text : "?", path, expected);
        cJSON_free(text);
        return rc;
    }
    if (p->type == ATMO_PARAM_VEC3)
        snprintf(shown, sizeof shown, "[%.17g, %.17g, %.17g]", v[0], v[1], v[2]);
    else if (p->type == ATMO_PARAM_VEC2)
        snprintf(shown, sizeof shown, "[%.17g, %.17g]", v[0], v[1]);
    else
        snprintf(shown, sizeof shown, "%.17g", v[0]);
    return atmo_param_store(s, p, v, shown, path, e);
}

/* Duplicate keys: cJSON keeps both members of {"a": 1, "a": 2} and a lookup sees the first, so
 * every object of the tree is searched for a key given twice among its members; path grows with
 * the keys and [indices] on the way down ("objects[1].type"). */
static int find_duplicate(const cJSON *node, char *path, size_t size, size_t len)
{
    int index = 0;
    for (const cJSON *item = node->child; item; item = item->next, index++) {
        if (cJSON_IsObject(node))
            for (const cJSON *before = node->child; before != item; before = before->next)
                if (strcmp(before->string, item->string) == 0) {
                    snprintf(path + len, size - len, "%s%s", len ? "." : "", item->string);
                    return 1;
                }
        int n = cJSON_IsObject(node)
                    ? snprintf(path + len, size - len, "%s%s", len ? "." : "", item->string)
                    : snprintf(path + len, size - len, "[%d]", index);
        size_t next = n > 0 && (size_t)n < size - len ? len + (size_t)n : size - 1;
        if ((cJSON_IsObject(item) || cJSON_IsArray(item)) && find_duplicate(item, path, size, next))
            return 1;
        path[len] = 0;
    }
    return 0;
}

int atmo_json_check_duplicates(const cJSON *root, const char *prefix, const char *where,
                               atmo_err *e)
{
    char path[512];
    int n = snprintf(path, sizeof path, "%s", prefix);
    if (!find_duplicate(root, path, sizeof path, n > 0 && (size_t)n < sizeof path ? (size_t)n : 0))
        return ATMO_OK;
    return atmo_fail(e, ATMO_ERR_USAGE, "%s: the key '%s' is given twice; keep one of the two",
                     where, path);
}

/* Why cJSON stopped at `at`: a NaN or Infinity literal, nesting beyond cJSON's limit, or a
 * plain syntax error. */
static void syntax_error(const char *text, const char *at, const char *path, atmo_err *e)
{
    int line = 1, depth = 0, in_string = 0;
    for (const char *c = text; at && c < at && *c; c++) {
        line += *c == '\n';
        if (in_string)
            in_string = !(*c == '"' && c[-1] != '\\');
        else if (*c == '"')
            in_string = 1;
        else
            depth += (*c == '{' || *c == '[') - (*c == '}' || *c == ']');
    }
    const char *word = at;
    while (word && (*word == ' ' || *word == '\t' || *word == '\n' || *word == '\r' ||
                    *word == ':' || *word == ',' || *word == '-' || *word == '['))
        word++;
    int word_len = 0;
    while (word && word_len < 16 && isalpha((unsigned char)word[word_len]))
        word_len++;
    if (word && (strncasecmp(word, "nan", 3) == 0 || strncasecmp(word, "inf", 3) == 0))
        atmo_fail(e, ATMO_ERR_USAGE,
                  "%s: near line %d, '%.*s' is not a JSON number (JSON has no NaN or Infinity); "
                  "give a finite number",
                  path, line, word_len, word);
    else if (depth >= CJSON_NESTING_LIMIT)
        atmo_fail(e, ATMO_ERR_USAGE,
                  "%s: near line %d the JSON is nested more than %d levels deep; a scene needs "
                  "three", path, line, CJSON_NESTING_LIMIT);
    else
        atmo_fail(e, ATMO_ERR_USAGE,
                  "%s: JSON syntax error near line %d; check for a missing comma, quote or brace "
                  "there", path, line);
}

/* 1 when key names a group of parameters ("sun" of "sun.zenith_deg"). */
static int param_group(const char *key)
{
    size_t n = strlen(key);
    for (int i = 0; i < atmo_param_count(); i++) {
        const atmo_param *p = atmo_param_at(i);
        if (strncmp(p->key, key, n) == 0 && p->key[n] == '.')
            return 1;
    }
    return 0;
}

/* The members of object `obj`, whose keys are prefixed by `prefix` ("" at the top). */
static int load_object(atmo_scene *s, const cJSON *obj, const char *prefix, const char *path,
                         unsigned char *seen, atmo_err *e)
{
    const cJSON *item;
    cJSON_ArrayForEach(item, obj)
    {
        char key[256];
        if ((size_t)snprintf(key, sizeof key, "%s%s", prefix, item->string) >= sizeof key)
            return atmo_fail(e, ATMO_ERR_USAGE,
                             "key '%.60s...' in %s is too long to be a parameter", key, path);
        const atmo_param *p = atmo_param_find(key);
        if (strcmp(key, "objects") == 0) { /* the object list (scene_objects.c) */
            char *text = cJSON_PrintUnformatted(item);
            int rc = text ? atmo_scene_set_objects(s, text, path, e)
                          : atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory reading '%s'", path);
            cJSON_free(text);
            if (rc)
                return rc;
        } else if (p) {
            size_t index = (size_t)atmo_param_index(p);
            if (seen[index])
                return atmo_fail(e, ATMO_ERR_USAGE,
                                 "%s appears twice in %s; keep one of the two values", key, path);
            seen[index] = 1;
            int rc = store_json(s, p, item, path, e);
            if (rc)
                return rc;
        } else if (cJSON_IsObject(item)) {
            char sub[256];
            if ((size_t)snprintf(sub, sizeof sub, "%s.", key) >= sizeof sub)
                return atmo_fail(e, ATMO_ERR_USAGE, "key '%.60s...' in %s is too long", key, path);
            int rc = load_object(s, item, sub, path, seen, e);
            if (rc)
                return rc;
        } else if (param_group(key)) {
            char *text = cJSON_PrintUnformatted(item);
            int rc = atmo_fail(e, ATMO_ERR_USAGE,
                               "'%s' in %s is a group of parameters and needs an object such as "
                               "{\"%s\": {...}}, got %.40s (atmo params lists its keys)",
                               key, path, item->string, text ? text : "another value");
            cJSON_free(text);
            return rc;
        } else {
            const char *near = atmo_param_closest(key);
            return atmo_fail(e, ATMO_ERR_USAGE,
                             "unknown parameter '%s' (from %s); %s%s%s(atmo params lists them all)",
                             key, path, near ? "did you mean '" : "", near ? near : "",
                             near ? "'? " : "");
        }
    }
    return ATMO_OK;
}

int atmo_scene_load_json_text(atmo_scene *s, const char *text, size_t length, const char *path,
                              atmo_err *e)
{
    int rc = ATMO_OK;
    cJSON *root = NULL;
    unsigned char *seen = NULL;
    int bad_line = nul_line(text, length);
    if (bad_line) {
        rc = atmo_fail(e, ATMO_ERR_USAGE,
                       "%s: a NUL character (\\u0000 or a zero byte) near line %d; scene files "
                       "hold names and numbers, which never contain one",
                       path, bad_line);
        goto cleanup;
    }
    const char *end = NULL;
    root = cJSON_ParseWithOpts(text, &end, 1);
    if (!root) { /* cJSON stops where the text stops being JSON */
        syntax_error(text, end ? end : cJSON_GetErrorPtr(), path, e);
        rc = ATMO_ERR_USAGE;
        goto cleanup;
    }
    if ((rc = atmo_json_check_duplicates(root, "", path, e)))
        goto cleanup;
    if (!cJSON_IsObject(root)) {
        rc = atmo_fail(
            e, ATMO_ERR_USAGE,
            "%s: a scene file must be a JSON object such as {\"sun\": {\"zenith_deg\": 60}}", path);
        goto cleanup;
    }
    seen = calloc((size_t)atmo_param_count(), 1);
    if (!seen) {
        rc = atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory reading '%s'", path);
        goto cleanup;
    }
    rc = load_object(s, root, "", path, seen, e);
cleanup:
    free(seen);
    cJSON_Delete(root);
    return rc;
}

int atmo_scene_load_json(atmo_scene *s, const char *path, atmo_err *e)
{
    size_t length = 0;
    char *text = read_file(path, &length, e);
    if (!text)
        return ATMO_ERR_USAGE;
    int rc = atmo_scene_load_json_text(s, text, length, path, e);
    free(text);
    return rc;
}

/* A JSON number that reads back as exactly x: the shortest of 15, 16 or 17 significant digits
 * that strtod returns unchanged. (cJSON's own printer accepts 15 digits when they read back
 * within an epsilon, which can lose the last bit.) */
static cJSON *exact_number(double x)
{
    char buf[40];
    for (int digits = 15; digits <= 17; digits++) {
        snprintf(buf, sizeof buf, "%.*g", digits, x);
        if (strtod(buf, NULL) == x)
            break;
    }
    return cJSON_CreateRaw(buf);
}

/* The object for the group part of key ("sun" of "sun.zenith_deg"), created on first use. */
static cJSON *json_group(cJSON *root, const char *key, const char **leaf)
{
    cJSON *obj = root;
    const char *start = key;
    for (const char *dot; obj && (dot = strchr(start, '.')); start = dot + 1) {
        char name[128];
        snprintf(name, sizeof name, "%.*s", (int)(dot - start), start);
        cJSON *child = cJSON_GetObjectItemCaseSensitive(obj, name);
        if (!child)
            child = cJSON_AddObjectToObject(obj, name);
        obj = child;
    }
    *leaf = start;
    return obj;
}

char *atmo_scene_to_json(const atmo_scene *s)
{
    char *out = NULL, *printed = NULL;
    cJSON *root = cJSON_CreateObject();
    if (!root)
        goto cleanup;
    for (int k = 0; k < atmo_param_count(); k++) {
        const atmo_param *p = atmo_param_at(k);
        const char *leaf;
        cJSON *obj = json_group(root, p->key, &leaf);
        double v[3];
        atmo_param_get(s, p, v);
        cJSON *item = NULL;
        switch (p->type) {
        case ATMO_PARAM_INT:
        case ATMO_PARAM_FLOAT:
            item = exact_number(v[0]);
            break;
        case ATMO_PARAM_VEC2:
        case ATMO_PARAM_VEC3:
            item = cJSON_CreateArray();
            for (int c = 0; item && c < atmo_param_components(p); c++) {
                cJSON *x = exact_number(v[c]);
                if (!x || !cJSON_AddItemToArray(item, x)) {
                    cJSON_Delete(x);
                    cJSON_Delete(item);
                    item = NULL;
                }
            }
            break;
        case ATMO_PARAM_ENUM: {
            int i = (int)v[0], n = 0;
            while (p->names[n])
                n++;
            /* an out-of-range enum (a scene filled in by code) is written as "?" and will be
             * rejected on loading, rather than crashing here */
            item = cJSON_CreateString(i >= 0 && i < n ? p->names[i] : "?");
            break;
        }
        case ATMO_PARAM_BOOL:
            item = cJSON_CreateBool(v[0] != 0);
            break;
        case ATMO_PARAM_STRING:
            item = cJSON_CreateString(atmo_param_text(s, p));
            break;
        }
        if (!obj || !item || !cJSON_AddItemToObject(obj, leaf, item)) {
            cJSON_Delete(item);
            goto cleanup;
        }
    }
    if (s->objects.count > 0) { /* the object list, after the registry's keys */
        char *text = atmo_scene_objects_json(s);
        cJSON *list = text ? cJSON_Parse(text) : NULL;
        free(text);
        if (!list || !cJSON_AddItemToObject(root, "objects", list)) {
            cJSON_Delete(list);
            goto cleanup;
        }
    }
    printed = cJSON_Print(root);
    if (!printed)
        goto cleanup;
    size_t n = strlen(printed);
    out = malloc(n + 2);
    if (out) {
        memcpy(out, printed, n);
        out[n] = '\n';
        out[n + 1] = '\0';
    }
cleanup:
    cJSON_free(printed);
    cJSON_Delete(root);
    return out;
}

int atmo_scene_save_json(const atmo_scene *s, const char *path, atmo_err *e)
{
    char *text = atmo_scene_to_json(s);
    if (!text)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory writing the scene to '%s'", path);
    int rc = atmo_write_text_file(path, text, e);
    free(text);
    return rc;
}
