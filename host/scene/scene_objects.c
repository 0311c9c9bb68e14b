/* scene_objects.c — the scene's object list: spheres and axis-aligned boxes, read from and
 * written as a JSON array, with the same one-line errors as every other key (scene.c).
 *
 * An element is {"type": "sphere", "center_m": [x, y, z], "radius_m": r, "albedo": [r, g, b],
 * "emission": [r, g, b]} or {"type": "box", "min_m": [x, y, z], "size_m": [sx, sy, sz], ...}:
 * world metres (Y up, origin at sea level), albedo the Lambertian reflectance in 0..1 per render
 * wavelength (default 0.8), emission the emitted spectral radiance in W m^-2 sr^-1 nm^-1
 * (default 0). "on_terrain": true places the object on the terrain: the y of its
 * anchor (a sphere's centre, a box's min) is then metres above the terrain's surface, taken at
 * world (x, z) = "terrain_at_m": [x, z] when given (one point for a group of objects, so they
 * keep their relative heights), else at the sphere's centre or the centre of the box's base;
 * the plan takes the height the renderer draws there, procedural or a DEM
 * (host/features/terrain/plan_terrain.c). on_terrain needs the terrain (terrain.enabled or
 * terrain.heightmap_file); terrain_at_m needs on_terrain. The geometry's members are
 * required; a member that does not belong to the
 * element's type, a duplicate, a wrong JSON type, a non-finite or out-of-range number is an
 * error naming objects[i].member, the source and the valid range. The array comes in through
 * the key "objects" of a scene file, of --set (objects='[...]') and of a preset. Saving writes
 * every number with the fewest digits (15 to 17) that read back exactly, like scene_json.c. */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/scene.h"

#define OBJECT_COORD_MAX_M 1e9 /* like camera.position_m */

typedef struct member {
    const char *name;
    int types;      /* bit mask of the ATMO_OBJECT_* it belongs to */
    int components; /* 1 or 3 */
    double min, max;
    int required;
} member;

#define SPHERE (1 << ATMO_OBJECT_SPHERE)
#define BOX (1 << ATMO_OBJECT_BOX)
static const member members[] = {
    {"center_m", SPHERE, 3, -OBJECT_COORD_MAX_M, OBJECT_COORD_MAX_M, 1},
    {"radius_m", SPHERE, 1, 1e-6, 1e7, 1},
    {"min_m", BOX, 3, -OBJECT_COORD_MAX_M, OBJECT_COORD_MAX_M, 1},
    {"size_m", BOX, 3, 1e-6, 1e7, 1},
    {"albedo", SPHERE | BOX, 3, 0.0, 1.0, 0},
    {"emission", SPHERE | BOX, 3, 0.0, 1e9, 0},
};
enum { MEMBER_COUNT = (int)(sizeof members / sizeof members[0]) };
static const char *const type_names[] = {"sphere", "box", NULL};

static double *member_field(atmo_object *o, int m)
{
    switch (m) {
    case 0: return o->center_m;
    case 1: return &o->radius_m;
    case 2: return o->min_m;
    case 3: return o->size_m;
    case 4: return o->albedo;
    default: return o->emission;
    }
}

static void object_defaults(atmo_object *o, int type)
{
    memset(o, 0, sizeof *o);
    o->type = type;
    for (int c = 0; c < 3; c++)
        o->albedo[c] = 0.8;
}

static int range_error(int i, const member *m, double v, const char *where, atmo_err *e)
{
    return atmo_fail(e, ATMO_ERR_USAGE,
                     "objects[%d].%s = %.9g (from %s) is out of range; valid: %.9g .. %.9g%s", i,
                     m->name, v, where, m->min, m->max, m->components == 3 ? " (each)" : "");
}

/* One element of the array into *o. */
static int parse_object(const cJSON *item, int i, const char *where, atmo_object *o,
                        atmo_err *e)
{
    if (!cJSON_IsObject(item))
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "objects[%d] (from %s) is not an object; write e.g. {\"type\": "
                         "\"sphere\", \"center_m\": [0, 1, 5], \"radius_m\": 1}",
                         i, where);
    const cJSON *type = cJSON_GetObjectItemCaseSensitive(item, "type");
    int t = -1;
    for (int k = 0; type && cJSON_IsString(type) && type_names[k]; k++)
        if (strcmp(type->valuestring, type_names[k]) == 0)
            t = k;
    if (t < 0)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "objects[%d] (from %s) needs \"type\": \"sphere\" or \"box\"", i, where);
    object_defaults(o, t);
    unsigned seen = 0;
    const cJSON *c;
    cJSON_ArrayForEach(c, item)
    {
        if (strcmp(c->string, "type") == 0)
            continue;
        if (strcmp(c->string, "on_terrain") == 0) {
            if (!cJSON_IsBool(c))
                return atmo_fail(e, ATMO_ERR_USAGE,
                                 "objects[%d].on_terrain (from %s) has the wrong type: expected "
                                 "true or false", i, where);
            o->on_terrain = cJSON_IsTrue(c);
            continue;
        }
        if (strcmp(c->string, "terrain_at_m") == 0) {
            int ok = cJSON_IsArray(c) && cJSON_GetArraySize(c) == 2;
            for (int k = 0; ok && k < 2; k++) {
                const cJSON *x = cJSON_GetArrayItem(c, k);
                ok = cJSON_IsNumber(x) && isfinite(x->valuedouble) &&
                     fabs(x->valuedouble) <= OBJECT_COORD_MAX_M;
                if (ok)
                    o->terrain_at_m[k] = x->valuedouble;
            }
            if (!ok)
                return atmo_fail(e, ATMO_ERR_USAGE,
                                 "objects[%d].terrain_at_m (from %s) must be an array of 2 numbers "
                                 "(world x, z in metres) within +-%.9g", i, where,
                                 OBJECT_COORD_MAX_M);
            o->has_terrain_at = 1;
            continue;
        }
        int m = 0;
        while (m < MEMBER_COUNT && strcmp(members[m].name, c->string) != 0)
            m++;
        if (m == MEMBER_COUNT || !(members[m].types & (1 << t)))
            return atmo_fail(e, ATMO_ERR_USAGE,
                             "objects[%d].%s (from %s) is not a member of a %s; a sphere has "
                             "center_m, radius_m, a box min_m, size_m, both albedo, emission, "
                             "on_terrain, terrain_at_m",
                             i, c->string, where, type_names[t]);
        if (seen & (1u << m))
            return atmo_fail(e, ATMO_ERR_USAGE,
                             "objects[%d].%s appears twice (from %s); keep one of the two", i,
                             c->string, where);
        seen |= 1u << m;
        const member *mm = &members[m];
        double v[3];
        int ok = mm->components == 1 ? cJSON_IsNumber(c)
                                     : cJSON_IsArray(c) && cJSON_GetArraySize(c) == 3;
        for (int k = 0; ok && k < mm->components; k++) {
            const cJSON *x = mm->components == 1 ? c : cJSON_GetArrayItem(c, k);
            ok = cJSON_IsNumber(x);
            if (ok)
                v[k] = x->valuedouble;
        }
        if (!ok)
            return atmo_fail(e, ATMO_ERR_USAGE,
                             "objects[%d].%s (from %s) has the wrong type: expected %s", i,
                             mm->name, where,
                             mm->components == 1 ? "a number" : "an array of 3 numbers");
        for (int k = 0; k < mm->components; k++)
            if (!isfinite(v[k]) || v[k] < mm->min || v[k] > mm->max)
                return range_error(i, mm, v[k], where, e);
        memcpy(member_field(o, m), v, (size_t)mm->components * sizeof(double));
    }
    for (int m = 0; m < MEMBER_COUNT; m++)
        if (members[m].required && (members[m].types & (1 << t)) && !(seen & (1u << m)))
            return atmo_fail(e, ATMO_ERR_USAGE, "objects[%d] (a %s, from %s) needs %s", i,
                             type_names[t], where, members[m].name);
    if (o->has_terrain_at && !o->on_terrain)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "objects[%d].terrain_at_m (from %s) needs \"on_terrain\": true; add it "
                         "or remove terrain_at_m", i, where);
    return ATMO_OK;
}

int atmo_scene_set_objects(atmo_scene *s, const char *json, const char *where, atmo_err *e)
{
    int rc = ATMO_OK;
    cJSON *root = cJSON_Parse(json);
    if (!root || !cJSON_IsArray(root)) {
        rc = atmo_fail(e, ATMO_ERR_USAGE,
                       "objects (from %s) is not a JSON array; write e.g. objects='[{\"type\": "
                       "\"sphere\", \"center_m\": [0, 1, 5], \"radius_m\": 1}]'",
                       where);
        goto cleanup;
    }
    if ((rc = atmo_json_check_duplicates(root, "objects", where, e)))
        goto cleanup;
    int n = cJSON_GetArraySize(root);
    if (n > ATMO_MAX_OBJECTS) {
        rc = atmo_fail(e, ATMO_ERR_USAGE, "objects (from %s) has %d elements; at most %d", where,
                       n, ATMO_MAX_OBJECTS);
        goto cleanup;
    }
    atmo_object list[ATMO_MAX_OBJECTS];
    for (int i = 0; i < n; i++)
        if ((rc = parse_object(cJSON_GetArrayItem(root, i), i, where, &list[i], e)))
            goto cleanup;
    memset(&s->objects, 0, sizeof s->objects);
    memcpy(s->objects.list, list, (size_t)n * sizeof list[0]);
    s->objects.count = n;
cleanup:
    cJSON_Delete(root);
    return rc;
}

int atmo_scene_check_objects(const atmo_scene *s, atmo_err *e)
{
    if (s->objects.count < 0 || s->objects.count > ATMO_MAX_OBJECTS)
        return atmo_fail(e, ATMO_ERR_USAGE, "the scene has %d objects; 0 to %d are allowed",
                         s->objects.count, ATMO_MAX_OBJECTS);
    for (int i = 0; i < s->objects.count; i++) {
        atmo_object o = s->objects.list[i];
        if (o.type != ATMO_OBJECT_SPHERE && o.type != ATMO_OBJECT_BOX)
            return atmo_fail(e, ATMO_ERR_USAGE, "objects[%d] has no valid type (sphere or box)",
                             i);
        for (int m = 0; m < MEMBER_COUNT; m++) {
            if (!(members[m].types & (1 << o.type)))
                continue;
            const double *v = member_field(&o, m);
            for (int k = 0; k < members[m].components; k++)
                if (!isfinite(v[k]) || v[k] < members[m].min || v[k] > members[m].max)
                    return range_error(i, &members[m], v[k], "the scene", e);
        }
        if (o.on_terrain && !s->terrain.enabled && !s->dem.file[0])
            return atmo_fail(e, ATMO_ERR_USAGE,
                             "objects[%d].on_terrain needs the terrain; set terrain.enabled=true "
                             "or remove on_terrain", i);
        if (o.has_terrain_at && !o.on_terrain)
            return atmo_fail(e, ATMO_ERR_USAGE,
                             "objects[%d].terrain_at_m needs on_terrain; set it or remove "
                             "terrain_at_m", i);
    }
    return ATMO_OK;
}

/* A JSON number that reads back as exactly x (as scene_json.c writes them). */
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

static int add_member(cJSON *obj, const member *m, const double *v)
{
    cJSON *item = m->components == 1 ? exact_number(v[0]) : cJSON_CreateArray();
    for (int k = 0; item && m->components == 3 && k < 3; k++) {
        cJSON *x = exact_number(v[k]);
        if (!x || !cJSON_AddItemToArray(item, x)) {
            cJSON_Delete(x);
            cJSON_Delete(item);
            item = NULL;
        }
    }
    if (item && cJSON_AddItemToObject(obj, m->name, item))
        return 1;
    cJSON_Delete(item);
    return 0;
}

char *atmo_scene_objects_json(const atmo_scene *s)
{
    char *out = NULL;
    cJSON *root = cJSON_CreateArray();
    for (int i = 0; root && i < s->objects.count; i++) {
        atmo_object o = s->objects.list[i];
        cJSON *obj = cJSON_CreateObject();
        int ok = obj && cJSON_AddItemToArray(root, obj) &&
                 cJSON_AddStringToObject(obj, "type", type_names[o.type]) != NULL;
        for (int m = 0; ok && m < MEMBER_COUNT; m++)
            if (members[m].types & (1 << o.type))
                ok = add_member(obj, &members[m], member_field(&o, m));
        if (ok && o.on_terrain)
            ok = cJSON_AddTrueToObject(obj, "on_terrain") != NULL;
        if (ok && o.has_terrain_at) {
            cJSON *at = cJSON_CreateArray(), *x = NULL;
            for (int k = 0; at && k < 2; k++)
                if (!(x = exact_number(o.terrain_at_m[k])) || !cJSON_AddItemToArray(at, x)) {
                    cJSON_Delete(x);
                    cJSON_Delete(at);
                    at = NULL;
                }
            ok = at && cJSON_AddItemToObject(obj, "terrain_at_m", at);
            if (!ok)
                cJSON_Delete(at);
        }
        if (!ok)
            goto cleanup;
    }
    if (root)
        out = cJSON_PrintUnformatted(root);
cleanup:
    cJSON_Delete(root);
    return out;
}
