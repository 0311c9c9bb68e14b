/* frames.c — animations for `atmo render --frames A..B` (frames.h).
 *
 * An animation is a list of scene keys, each with its value at the first and at the last frame;
 * frame f takes v(t) = (1 - t) v0 + t v1 with t = (f - A) / (B - A), which is v0 and v1 exactly
 * at the ends. Keys come from --animate KEY=V0..V1 (any float key: the sun's zenith, the
 * camera's altitude, a cloud layer's time) or from the difference between the start scene and
 * --scene-end FILE (float and vec3 keys). Each frame's values go through the registry's checks
 * (atmo_param_store) and the scene through atmo_scene_validate before any frame is rendered. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "frames.h"

int frames_parse_range(const char *text, int *first, int *last, atmo_err *e)
{
    char tail;
    if (sscanf(text, "%d..%d%c", first, last, &tail) != 2 || *first < 1 || *last < *first ||
        *last > FRAMES_LAST)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "--frames needs A..B with 1 <= A <= B <= %d (e.g. 1..24), got '%s'",
                         FRAMES_LAST, text);
    return ATMO_OK;
}

static int add_key(frames_animation *a, const atmo_param *p, const double v0[3],
                   const double v1[3], atmo_err *e)
{
    for (int k = 0; k < a->count; k++)
        if (a->keys[k].param == p)
            return atmo_fail(e, ATMO_ERR_USAGE, "%s is animated twice; animate each key once",
                             p->key);
    if (a->count == FRAMES_MAX_KEYS)
        return atmo_fail(e, ATMO_ERR_USAGE, "more than %d animated keys", FRAMES_MAX_KEYS);
    frames_key *k = &a->keys[a->count++];
    k->param = p;
    memcpy(k->v0, v0, sizeof k->v0);
    memcpy(k->v1, v1, sizeof k->v1);
    return ATMO_OK;
}

int frames_add_animate(frames_animation *a, const char *text, atmo_err *e)
{
    char key[128];
    const char *eq = strchr(text, '=');
    const char *dots = eq ? strstr(eq, "..") : NULL;
    if (!eq || !dots || (size_t)(eq - text) >= sizeof key)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "--animate needs KEY=V0..V1 (e.g. sun.zenith_deg=60..95), got '%s'",
                         text);
    memcpy(key, text, (size_t)(eq - text));
    key[eq - text] = 0;
    const atmo_param *p = atmo_param_find(key);
    if (!p) {
        const char *near = atmo_param_closest(key);
        return atmo_fail(e, ATMO_ERR_USAGE, "--animate: unknown key '%s'%s%s%s (atmo params)",
                         key, near ? "; did you mean '" : "", near ? near : "", near ? "'?" : "");
    }
    if (p->type != ATMO_PARAM_FLOAT)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "--animate %s: only float keys move linearly (this one is %s); set it "
                         "with --set",
                         key, p->type == ATMO_PARAM_VEC3 ? "a vector: use --scene-end"
                                                          : "a count, a choice or a switch");
    char v0_text[64], v1_text[64];
    size_t n0 = (size_t)(dots - eq - 1);
    double v0[3] = {0.0, 0.0, 0.0}, v1[3] = {0.0, 0.0, 0.0};
    if (n0 >= sizeof v0_text || strlen(dots + 2) >= sizeof v1_text)
        return atmo_fail(e, ATMO_ERR_USAGE, "--animate %s: values too long in '%s'", key, text);
    memcpy(v0_text, eq + 1, n0);
    v0_text[n0] = 0;
    snprintf(v1_text, sizeof v1_text, "%s", dots + 2);
    if (!atmo_parse_decimal(v0_text, &v0[0]) || !atmo_parse_decimal(v1_text, &v1[0]))
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "--animate %s: '%s' and '%s' must be decimal numbers in %s", key,
                         v0_text, v1_text, p->unit[0] ? p->unit : "the key's unit");
    return add_key(a, p, v0, v1, e);
}

int frames_add_scene_end(frames_animation *a, const atmo_scene *start, const atmo_scene *end,
                         const char *where, atmo_err *e)
{
    for (int i = 0; i < atmo_param_count(); i++) {
        const atmo_param *p = atmo_param_at(i);
        double v0[3], v1[3];
        atmo_param_get(start, p, v0);
        atmo_param_get(end, p, v1);
        int n = atmo_param_components(p), same = 1;
        for (int c = 0; c < (n > 0 ? n : 1); c++)
            same = same && v0[c] == v1[c];
        if (p->type == ATMO_PARAM_STRING)
            same = strcmp(atmo_param_text(start, p), atmo_param_text(end, p)) == 0;
        if (same)
            continue;
        if (p->type != ATMO_PARAM_FLOAT && p->type != ATMO_PARAM_VEC2 &&
            p->type != ATMO_PARAM_VEC3)
            return atmo_fail(e, ATMO_ERR_USAGE,
                             "%s: %s differs from the start scene, but only float and vector "
                             "keys move linearly; give both scenes the same %s",
                             where, p->key, p->key);
        int rc = add_key(a, p, v0, v1, e);
        if (rc)
            return rc;
    }
    return ATMO_OK;
}

int frames_scene(const frames_animation *a, const atmo_scene *start, int frame, atmo_scene *out,
                 atmo_err *e)
{
    double t = a->last > a->first ? (double)(frame - a->first) / (a->last - a->first) : 0.0;
    char where[32];
    snprintf(where, sizeof where, "frame %d", frame);
    *out = *start;
    for (int k = 0; k < a->count; k++) {
        const frames_key *key = &a->keys[k];
        double v[3];
        char shown[96];
        for (int c = 0; c < 3; c++)
            v[c] = (1.0 - t) * key->v0[c] + t * key->v1[c];
        if (key->param->type == ATMO_PARAM_VEC3)
            snprintf(shown, sizeof shown, "%.17g,%.17g,%.17g", v[0], v[1], v[2]);
        else if (key->param->type == ATMO_PARAM_VEC2)
            snprintf(shown, sizeof shown, "%.17g,%.17g", v[0], v[1]);
        else
            snprintf(shown, sizeof shown, "%.17g", v[0]);
        int rc = atmo_param_store(out, key->param, v, shown, where, e);
        if (rc)
            return rc;
    }
    return atmo_scene_validate(out, e);
}

int frames_path(const char *path, int frame, char *out, size_t size)
{
    const char *slash = strrchr(path, '/');
    const char *dot = strrchr(path, '.');
    if (!dot || (slash && dot < slash) || dot == (slash ? slash + 1 : path))
        dot = path + strlen(path);
    int n = snprintf(out, size, "%.*s.%04d%s", (int)(dot - path), path, frame, dot);
    return n > 0 && (size_t)n < size;
}
