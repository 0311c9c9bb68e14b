/* scene_options.c — the scene options that `atmo render` and `atmo view` share
 * (scene_options.h), so both read a scene from the command line alike and say the same things
 * about it.
 *
 * The options: --preset NAME or --scene FILE (they exclude each other), --set KEY=VALUE
 * (repeatable, applied in command-line order), and for render the shorthands --width,
 * --height, --samples, --seed, --time, --camera and --denoise, each kept as the assignment it
 * stands for (image.width=N, ..., clouds.time_s=S, camera.kind=K, output.denoise=Q) in its place
 * among the --set options.
 * A shorthand's value is at most SHORTHAND_MAX_CHARS characters (the longest any key takes);
 * a longer one is refused as a bad value. The scene is then the defaults, the preset or the
 * file, the assignments, validated (atmo/scene.h), before any work. */
#include <stdio.h>
#include <string.h>
#include "scene_options.h"

#define SHORTHAND_MAX_CHARS 40

static const struct {
    const char *option, *key;
} shorthand_keys[] = {
    {"--width", "image.width"},     {"--height", "image.height"}, {"--samples", "image.samples"},
    {"--seed", "image.seed"},       {"--time", "clouds.time_s"}, {"--camera", "camera.kind"},
    {"--denoise", "output.denoise"},
};

void scene_options_init(scene_options *o, const char *command, int shorthands)
{
    memset(o, 0, sizeof *o);
    o->command = command;
    o->shorthands = shorthands;
}

int scene_options_take(scene_options *o, int argc, char **argv, int *i)
{
    const char *a = argv[*i], *key = NULL;
    int n_short = (int)(sizeof shorthand_keys / sizeof shorthand_keys[0]);
    for (int k = 0; o->shorthands && k < n_short; k++)
        if (strcmp(a, shorthand_keys[k].option) == 0)
            key = shorthand_keys[k].key;
    if (!key && strcmp(a, "--preset") != 0 && strcmp(a, "--scene") != 0 && strcmp(a, "--set") != 0)
        return 0;
    if (*i + 1 >= argc) {
        fprintf(stderr, "atmo %s: %s needs a value (atmo %s --help)\n", o->command, a, o->command);
        return -1;
    }
    const char *v = argv[++*i];
    if (key) {
        if (o->set_count == SCENE_OPTIONS_MAX_SETS || strlen(v) > SHORTHAND_MAX_CHARS) {
            fprintf(stderr, "atmo %s: bad value '%s' for %s\n", o->command, v, a);
            return -1;
        }
        char *text = o->shorthand_sets[o->set_count];
        snprintf(text, sizeof o->shorthand_sets[0], "%s=%s", key, v);
        o->sets[o->set_count++] = text;
    } else if (strcmp(a, "--set") == 0) {
        if (o->set_count == SCENE_OPTIONS_MAX_SETS) {
            fprintf(stderr, "atmo %s: more than %d --set options\n", o->command,
                    SCENE_OPTIONS_MAX_SETS);
            return -1;
        }
        o->sets[o->set_count++] = v;
    } else if (strcmp(a, "--preset") == 0) {
        o->preset = v;
    } else {
        o->scene_file = v;
    }
    return 1;
}

int scene_options_scene(const scene_options *o, const char *file, atmo_scene *s, atmo_err *e)
{
    if (o->preset && o->scene_file)
        return atmo_fail(e, ATMO_ERR_USAGE, "--preset and --scene exclude each other; pick one");
    int rc = ATMO_OK;
    atmo_scene_defaults(s);
    if (!o->scene_file)
        rc = atmo_scene_apply_preset(s, o->preset ? o->preset : atmo_default_preset, e);
    if (!file)
        file = o->scene_file;
    if (!rc && file)
        rc = atmo_scene_load_json(s, file, e);
    for (int i = 0; i < o->set_count && !rc; i++)
        rc = atmo_scene_assign(s, o->sets[i], "--set", e);
    return rc ? rc : atmo_scene_validate(s, e);
}
