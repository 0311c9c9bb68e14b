/* scene.c — the scene parameter registry and the checks on every value a user can set.
 *
 * The registry has one row per field of atmo_scene (scene.h): its dotted key (the struct path),
 * type, unit, valid range, default and a one-line meaning; the scene's own rows are here, each
 * feature's in its folder (atmo/scene_params.h). Everything that reads or writes a
 * scene goes through it: the defaults, --set, presets, JSON scene files (scene_json.c), and
 * `atmo params`. Units are those of the key's name: _deg degrees, _m metres, _nm nanometres,
 * _per_m 1/m; the Rayleigh coefficient c gives beta_R(lambda) = c * lambda[um]^-4 in 1/m.
 *
 * Values are rejected, with one line naming the key, the value, the valid range and the unit:
 * unknown keys (with the closest key by Levenshtein edit distance), text that is not entirely a
 * number (strtod must consume it all), NaN and Inf, values outside [min, max] (inclusive, every
 * component of a vec3), non-integers for int keys, and enum names not in the list.
 * String keys (file paths) take any text shorter than ATMO_PARAM_STRING_MAX bytes without control
 * characters; "" means none. Vec2 keys are two numbers "x,z".
 * atmo_scene_validate adds the checks between parameters: top radius above the bottom radius,
 * ozone bottom <= peak <= top with bottom < top, and the camera not below the ground. */
#include <ctype.h>
#include <pthread.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/scene_params.h"
#include "atmo/suggest.h"

/* Enum names in the order of the ATMO_* constants of scene.h and gpu_enums.h. */
static const char *const camera_kinds[] = {"perspective", "panorama", "fisheye", NULL};
static const char *const camera_terrain_modes[] = {"off", "below", "at", NULL};
static const char *const quantity_names[] = {"radiance", "luminance", NULL};
static const char *const tonemap_names[] = {"none",           "exposure", "reinhard",
                                            "reinhard-white", "aces",     "unreal3",
                                            "uchimura",       "lottes",   NULL};
static const char *const transfer_names[] = {"srgb", "gamma22", NULL};
static const char *const denoise_names[] = {"auto", "off", "fast", "balanced", "high", NULL};
static const char *const render_modes[] = {"preview", "path", NULL};
_Static_assert(ATMO_RENDER_PATH == 1 && ATMO_CAMERA_PANORAMA == 1 && ATMO_CAMERA_FISHEYE == 2 &&
                   ATMO_QUANTITY_LUMINANCE == 1 && ATMO_TONEMAP_LOTTES == 7 &&
                   ATMO_TRANSFER_GAMMA22 == 1 && ATMO_OUTPUT_DENOISE_HIGH == 4,
               "enum name tables follow the order of the constants");

/* The scene's own rows: the image, the camera and the sun; each feature's follow from its
 * folder ... */
static const atmo_param scene_head_rows[] = {
    ROW_INT("image.width", image.width, "px", 1, 16384, 640, "image width in pixels"),
    ROW_INT("image.height", image.height, "px", 1, 16384, 360, "image height in pixels"),
    ROW_INT("image.samples", image.samples, "", 1, 1e6, 16,
            "samples per pixel (more: less noise, longer render)"),
    ROW_INT("image.seed", image.seed, "", 0, 2147483647, 0,
            "random-number seed; the same seed and scene give the same image"),
    ROW_ENUM("camera.kind", camera.kind, camera_kinds, ATMO_CAMERA_PERSPECTIVE,
             "perspective pinhole, a 360-degree equirectangular panorama (environment map, "
             "Blender's layout), or an equal-area fisheye of vertical field camera.fov_deg"),
    ROW_VEC3("camera.position_m", camera.position_m, "m", -1e9, 1e9, 0, 1.7, 0,
             "camera position in metres: Y up, origin at sea level, planet centre (0,-R,0)"),
    ROW_FLOAT("camera.pitch_deg", camera.pitch_deg, "deg", -90, 90, 0,
              "camera pitch in degrees above the horizontal (ignored by panoramas)"),
    ROW_FLOAT(
        "camera.yaw_deg", camera.yaw_deg, "deg", -3600, 3600, 0,
        "camera yaw in degrees: 0 looks along +Z, forward = (-cos p sin y, sin p, cos p cos y)"),
    ROW_FLOAT("camera.fov_deg", camera.fov_deg, "deg", 1, 179, 45,
              "vertical field of view of the perspective camera in degrees"),
    ROW_ENUM("camera.on_terrain", camera.on_terrain, camera_terrain_modes,
             ATMO_CAMERA_TERRAIN_OFF,
             "camera.position_m's y: above sea level (off), above the terrain's surface under "
             "the camera (below) or at camera.terrain_at_m (at: an object's anchor)"),
    ROW_VEC2("camera.terrain_at_m", camera.terrain_at_m, "m", -1e8, 1e8, 0, 0,
             "world X, Z of the terrain point camera.on_terrain=at measures the camera's y from"),
    ROW_FLOAT("sun.zenith_deg", sun.zenith_deg, "deg", 0, 180, 0,
              "sun zenith angle in degrees from world +Y (90 = on the horizon)"),
    ROW_FLOAT(
        "sun.azimuth_deg", sun.azimuth_deg, "deg", -3600, 3600, 0,
        "sun azimuth in degrees: direction (sin z sin a, cos z, sin z cos a); a = -yaw faces it"),
    ROW_FLOAT("sun.angular_radius_deg", sun.angular_radius_deg, "deg", 0.01, 10, 0.26786,
              "angular radius of the sun disc in degrees"),
    ROW_FLOAT("sun.irradiance_scale", sun.irradiance_scale, "", 0, 1e6, 1,
              "factor on the solar spectrum (1 = ASTM G-173 extraterrestrial)"),
};
/* ... and after the features' keys, how the scene is rendered, displayed and written */
static const atmo_param scene_tail_rows[] = {
    ROW_VEC3("render.wavelengths_nm", render.wavelengths_nm, "nm", 360, 830, 680, 550, 440,
             "the three render wavelengths in nm (R, G, B channels)"),
    ROW_INT("render.spectral_bands", render.spectral_bands, "", 0, 470, 0,
            "0: render at the three wavelengths; N >= 15: spectral mode, N bands over 360-830 nm "
            "combined through the CIE 1931 CMFs into luminance-based linear sRGB (cd/m^2)"),
    ROW_ENUM("render.quantity", render.quantity, quantity_names, ATMO_QUANTITY_RADIANCE,
             "what HDR outputs hold: spectral radiance (W/m^2/sr/nm) or luminance (cd/m^2)"),
    ROW_INT("render.view_steps", render.view_steps, "", 1, 4096, 32,
            "ray-march steps along each view ray"),
    ROW_INT("render.transmittance_width", render.transmittance_width, "", 4, 4096, 256,
            "transmittance LUT size along the view-zenith cosine"),
    ROW_INT("render.transmittance_height", render.transmittance_height, "", 4, 4096, 256,
            "transmittance LUT size along the altitude"),
    ROW_ENUM("render.mode", path.mode, render_modes, ATMO_RENDER_PREVIEW,
             "preview: primary rays with the method (objects lit by sun and sky irradiance); "
             "path: the progressive path tracer with bounces (kernels/render/path.h)"),
    ROW_FLOAT("post.exposure", post.exposure, "", 0, 1e9, 10,
              "exposure factor on the (white-balanced) radiance before tone mapping"),
    ROW_ENUM("post.tonemap", post.tonemap, tonemap_names, ATMO_TONEMAP_EXPOSURE,
             "tone-mapping operator for PNG output"),
    ROW_FLOAT("post.white_point", post.white_point, "", 1e-6, 1e9, 4,
              "white point of the reinhard-white operator (exposed units)"),
    ROW_BOOL("post.white_balance", post.white_balance, 1,
             "divide by the sun's colour so sunlight is white"),
    ROW_ENUM("post.transfer", post.transfer, transfer_names, ATMO_TRANSFER_SRGB,
             "PNG encoding curve: sRGB or a pure 2.2 gamma"),
    ROW_ENUM("output.denoise", output.denoise, denoise_names, ATMO_OUTPUT_DENOISE_AUTO,
             "Intel Open Image Denoise on the final linear image, before tone mapping: auto "
             "(PNG outputs, quality high, where the library is installed; not the preview of the "
             "air alone), "
             "off, fast, balanced or high (every output; EXR keeps the noisy image and the "
             "guides as layers)"),
    ROW_BOOL("post.flare", post.flare, 0,
             "lens flare from the sun's light in the image (perspective camera only; every "
             "output)"),
    ROW_FLOAT("post.flare_strength", post.flare_strength, "", 0, 1e3, 1,
              "lens flare brightness relative to the default lens"),
    ROW_BOOL("output.blender", output.blender, 0,
             "outputs for Blender (--blender): luminance-based linear Rec.709 RGB in cd/m^2 "
             "with the EXR chromaticities, the exposure scaled to luminance, panoramas in "
             "Blender's world orientation (docs/guide/blender.md)"),
};

#define REGISTRY_MAX 512
static const atmo_param *registry[REGISTRY_MAX];
static int registry_count;
static pthread_once_t registry_once = PTHREAD_ONCE_INIT;

static void registry_add(const atmo_param *rows, int n)
{
    for (int i = 0; i < n; i++) {
        if (registry_count == REGISTRY_MAX) {
            fprintf(stderr, "atmo: more than %d scene parameters (raise REGISTRY_MAX, a build "
                            "bug)\n",
                    REGISTRY_MAX);
            abort();
        }
        registry[registry_count++] = &rows[i];
    }
}

/* The scene's first rows, each folder's set in the order the build lists them, the scene's
 * last rows (so a saved scene reads: what is seen, what is in the world, how it is rendered). */
static void registry_build(void)
{
    registry_add(scene_head_rows, (int)(sizeof scene_head_rows / sizeof scene_head_rows[0]));
    for (const atmo_param_set *const *set = atmo_param_sets; *set; set++)
        registry_add((*set)->rows, (*set)->count);
    registry_add(scene_tail_rows, (int)(sizeof scene_tail_rows / sizeof scene_tail_rows[0]));
}

int atmo_param_count(void)
{
    pthread_once(&registry_once, registry_build);
    return registry_count;
}

const atmo_param *atmo_param_at(int i)
{
    return i >= 0 && i < atmo_param_count() ? registry[i] : NULL;
}

int atmo_param_index(const atmo_param *p)
{
    for (int i = 0; i < atmo_param_count(); i++)
        if (registry[i] == p)
            return i;
    return -1;
}

int atmo_param_components(const atmo_param *p)
{
    return p->type == ATMO_PARAM_VEC3 ? 3
           : p->type == ATMO_PARAM_VEC2 ? 2
           : p->type == ATMO_PARAM_STRING ? 0
                                         : 1;
}

/* The types stored as doubles. */
static int is_real(const atmo_param *p)
{
    return p->type == ATMO_PARAM_FLOAT || p->type == ATMO_PARAM_VEC3 ||
           p->type == ATMO_PARAM_VEC2;
}

const atmo_param *atmo_param_find(const char *key)
{
    for (int i = 0; i < atmo_param_count(); i++)
        if (strcmp(registry[i]->key, key) == 0)
            return registry[i];
    return NULL;
}

static int *int_field(atmo_scene *s, const atmo_param *p)
{
    return (int *)((char *)s + p->offset);
}

static double *double_field(atmo_scene *s, const atmo_param *p)
{
    return (double *)((char *)s + p->offset);
}

void atmo_param_get(const atmo_scene *s, const atmo_param *p, double v[3])
{
    const char *base = (const char *)s + p->offset;
    v[0] = v[1] = v[2] = 0;
    if (is_real(p))
        memcpy(v, base, (size_t)atmo_param_components(p) * sizeof(double));
    else if (p->type != ATMO_PARAM_STRING)
        v[0] = *(const int *)base;
}

const char *atmo_param_text(const atmo_scene *s, const atmo_param *p)
{
    return p->type == ATMO_PARAM_STRING ? (const char *)s + p->offset : NULL;
}

int atmo_param_store_text(atmo_scene *s, const atmo_param *p, const char *text, const char *where,
                          atmo_err *e)
{
    if (p->type != ATMO_PARAM_STRING)
        return atmo_fail(e, ATMO_ERR_USAGE, "%s (from %s) takes a number, not text", p->key,
                         where);
    size_t n = strlen(text);
    if (n >= ATMO_PARAM_STRING_MAX)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "%s = '%.40s...' (from %s) is %zu bytes long; the limit is %d (use a "
                         "shorter path)",
                         p->key, text, where, n, ATMO_PARAM_STRING_MAX - 1);
    for (size_t i = 0; i < n; i++)
        if ((unsigned char)text[i] < 0x20 || text[i] == 0x7f)
            return atmo_fail(e, ATMO_ERR_USAGE,
                             "%s (from %s) holds a control character at byte %zu; write the "
                             "text without one",
                             p->key, where, i);
    char *field = (char *)s + p->offset;
    memset(field, 0, ATMO_PARAM_STRING_MAX); /* the rest zero, so scenes compare with memcmp */
    memcpy(field, text, n);
    return ATMO_OK;
}

void atmo_scene_defaults(atmo_scene *s)
{
    memset(s, 0, sizeof *s); /* padding too, so scenes compare with memcmp */
    for (int i = 0; i < atmo_param_count(); i++) {
        const atmo_param *p = registry[i];
        if (is_real(p))
            memcpy(double_field(s, p), p->def, (size_t)atmo_param_components(p) * sizeof(double));
        else if (p->type != ATMO_PARAM_STRING) /* strings: "" from the memset */
            *int_field(s, p) = (int)p->def[0];
    }
}

const char *atmo_preset_closest(const char *name)
{
    atmo_suggest near;
    atmo_suggest_begin(&near, name);
    for (const atmo_preset *p = atmo_presets; p->name; p++)
        atmo_suggest_offer(&near, p->name);
    return atmo_suggest_result(&near);
}

const char *atmo_param_closest(const char *key)
{
    atmo_suggest near;
    atmo_suggest_begin(&near, key);
    for (int i = 0; i < atmo_param_count(); i++)
        atmo_suggest_offer(&near, registry[i]->key);
    return atmo_suggest_result(&near);
}

static int unknown_key(const char *key, const char *where, atmo_err *e)
{
    const char *near = atmo_param_closest(key);
    if (!near)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "unknown parameter '%s' (from %s); atmo params lists them all", key, where);
    return atmo_fail(
        e, ATMO_ERR_USAGE,
        "unknown parameter '%s' (from %s); did you mean '%s'? (atmo params lists them all)", key,
        where, near);
}

/* "0 .. 180 deg" */
static void range_text(const atmo_param *p, char *buf, size_t n)
{
    snprintf(buf, n, "%.15g .. %.15g%s%s%s", p->min, p->max,
             atmo_param_components(p) > 1 ? " (each)" : "", p->unit[0] ? " " : "", p->unit);
}

static void names_text(const atmo_param *p, char *buf, size_t n)
{
    size_t used = 0;
    buf[0] = '\0';
    for (const char *const *name = p->names; *name && used < n; name++)
        used += (size_t)snprintf(buf + used, n - used, "%s%s", name == p->names ? "" : ", ", *name);
}

int atmo_param_store(atmo_scene *s, const atmo_param *p, const double v[3], const char *shown,
                     const char *where, atmo_err *e)
{
    char range[128];
    int n = atmo_param_components(p);
    if (p->type == ATMO_PARAM_STRING)
        return atmo_fail(e, ATMO_ERR_USAGE, "%s = %s (from %s) must be text, not a number",
                         p->key, shown, where);
    for (int i = 0; i < n; i++) {
        if (!isfinite(v[i]))
            return atmo_fail(e, ATMO_ERR_USAGE,
                             "%s = %s (from %s) is not a finite number; give a value in %s", p->key,
                             shown, where, (range_text(p, range, sizeof range), range));
        if (p->type == ATMO_PARAM_ENUM) {
            char names[256];
            names_text(p, names, sizeof names);
            const char *near = atmo_suggest_among(shown, p->names);
            if (v[i] != floor(v[i]) || v[i] < p->min || v[i] > p->max)
                return atmo_fail(e, ATMO_ERR_USAGE,
                                 "%s = %s (from %s) is not a valid name; %s%s%suse one of: %s",
                                 p->key, shown, where, near ? "did you mean '" : "",
                                 near ? near : "", near ? "'? " : "", names);
            continue;
        }
        if (v[i] < p->min || v[i] > p->max) {
            range_text(p, range, sizeof range);
            if (p->type == ATMO_PARAM_BOOL)
                return atmo_fail(e, ATMO_ERR_USAGE,
                                 "%s = %s (from %s) is not a boolean; use true or false", p->key,
                                 shown, where);
            return atmo_fail(e, ATMO_ERR_USAGE, "%s = %s (from %s) is out of range; valid: %s",
                             p->key, shown, where, range);
        }
        if ((p->type == ATMO_PARAM_INT || p->type == ATMO_PARAM_BOOL) && v[i] != floor(v[i])) {
            range_text(p, range, sizeof range);
            return atmo_fail(e, ATMO_ERR_USAGE,
                             "%s = %s (from %s) must be a whole number; valid: integers in %s",
                             p->key, shown, where, range);
        }
    }
    if (is_real(p))
        memcpy(double_field(s, p), v, (size_t)n * sizeof(double));
    else
        *int_field(s, p) = (int)v[0];
    return ATMO_OK;
}

/* The whole of text (surrounding blanks aside) as one number; 0 when it is not one. strtod's
 * "nan" and "inf" are accepted here so that the caller reports them as not finite. */
static int parse_number(const char *text, double *out)
{
    char *end;
    errno = 0;
    while (isspace((unsigned char)*text))
        text++;
    if (!*text)
        return 0;
    *out = strtod(text, &end);
    if (end == text)
        return 0;
    while (isspace((unsigned char)*end))
        end++;
    if (*end)
        return 0;
    if (errno == ERANGE && fabs(*out) > 1.0) /* overflow: report as Inf, not as garbage */
        *out = HUGE_VAL;
    return 1;
}

int atmo_parse_decimal(const char *text, double *out)
{
    const char *c = text;
    c += *c == '-';
    /* JSON's number grammar: -?(0|[1-9][0-9]*)(.[0-9]+)?([eE][+-]?[0-9]+)?, so no blanks, '+',
     * hexadecimal, "inf"/"nan" or leading zero (which C and other readers take for octal) */
    if (!isdigit((unsigned char)*c) || (c[0] == '0' && isdigit((unsigned char)c[1])))
        return 0;
    while (isdigit((unsigned char)*c))
        c++;
    if (*c == '.') {
        if (!isdigit((unsigned char)*++c))
            return 0;
        while (isdigit((unsigned char)*c))
            c++;
    }
    if (*c == 'e' || *c == 'E') {
        c++;
        c += *c == '+' || *c == '-';
        if (!isdigit((unsigned char)*c))
            return 0;
        while (isdigit((unsigned char)*c))
            c++;
    }
    if (*c)
        return 0;
    errno = 0;
    *out = strtod(text, NULL);
    if (errno == ERANGE && fabs(*out) > 1.0) /* overflow: report as Inf, not as garbage */
        *out = HUGE_VAL;
    return 1;
}

static int parse_value(const atmo_param *p, const char *value, double v[3])
{
    switch (p->type) {
    case ATMO_PARAM_INT:
        return atmo_parse_decimal(value, &v[0]);
    case ATMO_PARAM_FLOAT:
        return parse_number(value, &v[0]);
    case ATMO_PARAM_VEC2:
    case ATMO_PARAM_VEC3: {
        int want = atmo_param_components(p);
        char buf[256];
        if (strlen(value) >= sizeof buf)
            return 0;
        strcpy(buf, value);
        char *parts[4] = {buf, NULL, NULL, NULL};
        int n = 1;
        for (char *c = buf; *c; c++)
            if (*c == ',') {
                if (n == want)
                    return 0;
                *c = '\0';
                parts[n++] = c + 1;
            }
        if (n != want)
            return 0;
        for (int i = 0; i < want; i++)
            if (!parse_number(parts[i], &v[i]))
                return 0;
        return 1;
    }
    case ATMO_PARAM_ENUM:
        for (int i = 0; p->names[i]; i++)
            if (strcmp(value, p->names[i]) == 0) {
                v[0] = i;
                return 1;
            }
        v[0] = -1; /* reported by atmo_param_store with the list of names */
        return 1;
    case ATMO_PARAM_BOOL:
        if (!strcmp(value, "true") || !strcmp(value, "1") || !strcmp(value, "yes") ||
            !strcmp(value, "on"))
            v[0] = 1;
        else if (!strcmp(value, "false") || !strcmp(value, "0") || !strcmp(value, "no") ||
                 !strcmp(value, "off"))
            v[0] = 0;
        else
            v[0] = -1; /* reported as not a boolean */
        return 1;
    case ATMO_PARAM_STRING: /* stored by atmo_param_store_text */
        return 0;
    }
    return 0;
}

int atmo_scene_set(atmo_scene *s, const char *key, const char *value, const char *where,
                   atmo_err *e)
{
    if (strcmp(key, "objects") == 0)
        return atmo_scene_set_objects(s, value, where, e);
    const atmo_param *p = atmo_param_find(key);
    if (!p)
        return unknown_key(key, where, e);
    if (p->type == ATMO_PARAM_STRING)
        return atmo_param_store_text(s, p, value, where, e);
    double v[3] = {0, 0, 0};
    if (!parse_value(p, value, v)) {
        char range[128], example[96] = "";
        range_text(p, range, sizeof range);
        if (p->type == ATMO_PARAM_VEC3) /* the default is a valid example */
            snprintf(example, sizeof example, ", e.g. %.15g,%.15g,%.15g (the default)",
                     p->def[0], p->def[1], p->def[2]);
        else if (p->type == ATMO_PARAM_VEC2)
            snprintf(example, sizeof example, ", e.g. %.15g,%.15g (the default)", p->def[0],
                     p->def[1]);
        else if (p->type == ATMO_PARAM_INT)
            snprintf(example, sizeof example, ", written as decimal digits, e.g. %.15g",
                     p->def[0]);
        return atmo_fail(e, ATMO_ERR_USAGE, "%s = '%s' (from %s) is not %s; valid: %s%s", p->key,
                         value, where,
                         p->type == ATMO_PARAM_VEC3   ? "three numbers x,y,z"
                         : p->type == ATMO_PARAM_VEC2 ? "two numbers x,z"
                         : p->type == ATMO_PARAM_INT  ? "an integer"
                                                      : "a number",
                         range, example);
    }
    return atmo_param_store(s, p, v, value, where, e);
}

int atmo_scene_assign(atmo_scene *s, const char *assignment, const char *where, atmo_err *e)
{
    const char *eq = strchr(assignment, '=');
    char key[128];
    if (!eq || eq == assignment)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "'%s' (from %s) is not key=value; write e.g. sun.zenith_deg=60",
                         assignment, where);
    size_t n = (size_t)(eq - assignment);
    if (n >= sizeof key)
        return unknown_key(assignment, where, e);
    memcpy(key, assignment, n);
    key[n] = '\0';
    return atmo_scene_set(s, key, eq + 1, where, e);
}

int atmo_scene_apply_preset(atmo_scene *s, const char *name, atmo_err *e)
{
    const atmo_preset *pr = atmo_preset_find(name);
    const char *near = pr ? NULL : atmo_preset_closest(name);
    if (near)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "unknown preset '%s' (did you mean '%s'? atmo presets lists them)", name,
                         near);
    if (!pr) {
        char names[512];
        size_t used = 0;
        names[0] = '\0';
        for (const atmo_preset *q = atmo_presets; q->name && used < sizeof names; q++)
            used += (size_t)snprintf(names + used, sizeof names - used, "%s%s",
                                     q == atmo_presets ? "" : ", ", q->name);
        return atmo_fail(e, ATMO_ERR_USAGE, "unknown preset '%s'; use one of: %s", name, names);
    }
    char where[96];
    snprintf(where, sizeof where, "preset %s", pr->name);
    for (const char *const *a = pr->settings; *a; a++) {
        int rc = atmo_scene_assign(s, *a, where, e);
        if (rc)
            return rc;
    }
    return ATMO_OK;
}

int atmo_scene_check_spectral_bands(int bands, atmo_err *e)
{
    if (bands == 0 || (bands >= ATMO_SPECTRAL_MIN_BANDS && bands <= ATMO_SPECTRAL_MAX_BANDS))
        return ATMO_OK;
    return atmo_fail(e, ATMO_ERR_USAGE,
                     "render.spectral_bands=%d: use 0 (3-wavelength mode) or %d to %d bands "
                     "over 360-830 nm",
                     bands, ATMO_SPECTRAL_MIN_BANDS, ATMO_SPECTRAL_MAX_BANDS);
}

int atmo_scene_validate(const atmo_scene *s, atmo_err *e)
{
    /* every value again, for scenes filled in by code rather than through atmo_scene_set */
    atmo_scene copy = *s;
    for (int i = 0; i < atmo_param_count(); i++) {
        const atmo_param *p = registry[i];
        double v[3];
        char shown[96];
        atmo_param_get(s, p, v);
        if (p->type == ATMO_PARAM_VEC3)
            snprintf(shown, sizeof shown, "%.9g,%.9g,%.9g", v[0], v[1], v[2]);
        else if (p->type == ATMO_PARAM_VEC2)
            snprintf(shown, sizeof shown, "%.9g,%.9g", v[0], v[1]);
        else
            snprintf(shown, sizeof shown, "%.9g", v[0]);
        const char *text = atmo_param_text(s, p);
        /* a string filled in by code may lack its terminator: check it within the field */
        if (text && !memchr(text, '\0', ATMO_PARAM_STRING_MAX))
            return atmo_fail(e, ATMO_ERR_USAGE, "%s is not terminated within %d bytes", p->key,
                             ATMO_PARAM_STRING_MAX);
        int rc = text ? atmo_param_store_text(&copy, p, text, "the scene", e)
                      : atmo_param_store(&copy, p, v, shown, "the scene", e);
        if (rc)
            return rc;
    }
    int rc = atmo_scene_check_spectral_bands(s->render.spectral_bands, e);
    if (rc || (rc = atmo_scene_check_objects(s, e)))
        return rc;
    double bottom = s->atmosphere.bottom_radius_m, top = s->atmosphere.top_radius_m;
    double oz_bottom = s->atmosphere.ozone_bottom_m, oz_peak = s->atmosphere.ozone_peak_m,
           oz_top = s->atmosphere.ozone_top_m;
    if (!(top > bottom))
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "atmosphere.top_radius_m (%.9g m) must be greater than "
                         "atmosphere.bottom_radius_m (%.9g m); raise the top or lower the bottom",
                         top, bottom);
    if (!(oz_bottom <= oz_peak && oz_peak <= oz_top && oz_bottom < oz_top))
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "ozone layer out of order: atmosphere.ozone_bottom_m (%.9g m) <= "
                         "atmosphere.ozone_peak_m (%.9g m) <= atmosphere.ozone_top_m (%.9g m) with "
                         "bottom < top is required; reorder the three altitudes",
                         oz_bottom, oz_peak, oz_top);
    if (s->dem.detail && !s->dem.file[0])
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "terrain.heightmap_detail=true adds detail below a heightmap file's "
                         "cells; set terrain.heightmap_file or the detail to false");
    const double *c = s->camera.position_m;
    if (s->camera.on_terrain != ATMO_CAMERA_TERRAIN_OFF) {
        if (!s->terrain.enabled && !s->dem.file[0])
            return atmo_fail(e, ATMO_ERR_USAGE,
                             "camera.on_terrain=%s measures the camera's height from the "
                             "terrain; set terrain.enabled=true or camera.on_terrain=off",
                             camera_terrain_modes[s->camera.on_terrain]);
        if (c[1] < 0.0)
            return atmo_fail(e, ATMO_ERR_USAGE,
                             "camera.position_m's y (%.9g m) is below the terrain's surface "
                             "with camera.on_terrain=%s; use y >= 0 (metres above it)",
                             c[1], camera_terrain_modes[s->camera.on_terrain]);
        return ATMO_OK; /* above the terrain, which lies at or above sea level */
    }
    double dy = c[1] + bottom;
    double r = sqrt(c[0] * c[0] + dy * dy + c[2] * c[2]);
    /* 1 m of slack: a camera placed at sea level must not fail on rounding */
    if (r < bottom - 1.0)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "camera.position_m (%.9g, %.9g, %.9g) is %.6g m below the ground of "
                         "radius atmosphere.bottom_radius_m = %.9g m around (0, -R, 0); raise the "
                         "camera's y",
                         c[0], c[1], c[2], bottom - r, bottom);
    return ATMO_OK;
}
