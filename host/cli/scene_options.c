/* scene_options.c — the scene options that `atmo render` and `atmo view` share
 * (scene_options.h), so both read a scene from the command line alike and say the same things
 * about it.
 *
 * The options: --preset NAME or --scene FILE (they exclude each other), --set KEY=VALUE
 * (repeatable, applied in command-line order), and the shorthands --width, --height,
 * --samples, --seed, --time, --camera and --denoise, each checked against its key's type and range in
 * the scene's registry (cli_flags.c) and kept as the assignment it stands for (image.width=N,
 * ..., clouds.time_s=S, camera.kind=K,
 * output.denoise=Q) in its place among the --set options. A shorthand's
 * value is at most SHORTHAND_MAX_CHARS characters (the longest any key takes); a longer one
 * is refused as a bad value. --blender stands for output.blender=true, set after the
 * assignments; atmo_scene_for_blender then rewrites the scene for it, saying on stderr what it
 * changed. The scene is then the defaults, the preset or the file, the assignments, validated
 * (atmo/scene.h), before any work. */
#include <stddef.h>
#include <stdio.h>
#include <string.h>
#include "scene_options.h"

#define SHORTHAND_MAX_CHARS 40

static int take_set(void *args, const cli_flag *f, const char *v, atmo_err *e)
{
    scene_options *o = args;
    if (o->set_count == SCENE_OPTIONS_MAX_SETS)
        return atmo_fail(e, ATMO_ERR_USAGE, "more than %d --set options", SCENE_OPTIONS_MAX_SETS);
    (void)f;
    o->sets[o->set_count++] = v;
    return ATMO_OK;
}

static int take_shorthand(void *args, const cli_flag *f, const char *v, atmo_err *e)
{
    scene_options *o = args;
    if (o->set_count == SCENE_OPTIONS_MAX_SETS || strlen(v) > SHORTHAND_MAX_CHARS)
        return atmo_fail(e, ATMO_ERR_USAGE, "bad value '%s' for %s", v, f->name);
    char *text = o->shorthand_sets[o->set_count];
    snprintf(text, sizeof o->shorthand_sets[0], "%s=%s", f->key, v);
    o->sets[o->set_count++] = text;
    return ATMO_OK;
}

#define SHORTHAND(flag, t, k, text)                                                            \
    {.type = t, .name = flag, .key = k, .take = take_shorthand, .help = text}

const cli_flag scene_source_flags[] = {
    {.type = CLI_STRING, .name = "--preset", .metavar = "NAME",
     .offset = offsetof(scene_options, preset), .def_var = &atmo_default_preset,
     .help = "a built-in scene (atmo presets lists them)"},
    {.type = CLI_PATH, .name = "--scene", .offset = offsetof(scene_options, scene_file),
     .def = "none: the preset", .help = "a JSON scene file instead of a preset (atmo params lists every key)"},
    {.type = CLI_STRING, .name = "--set", .metavar = "KEY=VALUE", .take = take_set, .def = "none",
     .help = "override one parameter, e.g. --set sun.zenith_deg=60 (repeatable;\n"
             "applied in command-line order)"},
    {.type = CLI_END},
};

const cli_flag scene_option_flags[] = {
    {.type = CLI_INCLUDE, .include = scene_source_flags},
    SHORTHAND("--width", CLI_INT, "image.width", "image width in pixels (image.width)"),
    SHORTHAND("--height", CLI_INT, "image.height", "image height in pixels (image.height)"),
    SHORTHAND("--samples", CLI_INT, "image.samples",
              "samples per pixel; the most any tile gets (image.samples)"),
    SHORTHAND("--seed", CLI_INT, "image.seed", "random seed (image.seed)"),
    SHORTHAND("--time", CLI_FLOAT, "clouds.time_s",
              "seconds of cloud motion with the wind (clouds.time_s)"),
    SHORTHAND("--camera", CLI_ENUM, "camera.kind", "projection (camera.kind)"),
    SHORTHAND("--denoise", CLI_ENUM, "output.denoise",
              "Intel Open Image Denoise before tone mapping: auto (PNG outputs, high,\n"
              "where installed; not the preview of the air alone), off, fast, balanced,\n"
              "high (every output)\n"
              "(output.denoise)"),
    {.type = CLI_BOOL, .name = "--blender", .offset = offsetof(scene_options, blender),
     .help = "outputs for Blender (output.blender=true): linear Rec.709\n"
             "RGB in cd/m^2 (render.quantity=luminance, post.exposure\n"
             "x 1e-5), panoramas in Blender's world orientation\n"
             "(camera.yaw_deg=-90); docs/guide/blender.md"},
    {.type = CLI_END},
};

void scene_options_init(scene_options *o) { memset(o, 0, sizeof *o); }

int scene_options_scene(const scene_options *o, const char *file, atmo_scene *s, atmo_err *e)
{
    if (o->preset && o->scene_file)
        return atmo_fail(e, ATMO_ERR_USAGE, "--preset and --scene exclude each other; pick one");
    int rc = ATMO_OK, end_scene = file != NULL;
    atmo_scene_defaults(s);
    if (!o->scene_file)
        rc = atmo_scene_apply_preset(s, o->preset ? o->preset : atmo_default_preset, e);
    if (!file)
        file = o->scene_file;
    if (!rc && file)
        rc = atmo_scene_load_json(s, file, e);
    for (int i = 0; i < o->set_count && !rc; i++)
        rc = atmo_scene_assign(s, o->sets[i], "--set", e);
    if (o->blender)
        s->output.blender = 1;
    char changes[256];
    if (!rc && atmo_scene_for_blender(s, changes, sizeof changes) > 0 && !end_scene)
        fprintf(stderr, "atmo: for Blender: %s\n", changes);
    return rc ? rc : atmo_scene_validate(s, e);
}
