/* scene_options.h — the scene options of `atmo render` and `atmo view` (scene_options.c):
 * --preset NAME, --scene FILE, --set KEY=VALUE and render's shorthands, and the scene they
 * assemble. */
#ifndef ATMO_SCENE_OPTIONS_H
#define ATMO_SCENE_OPTIONS_H
#include "atmo/scene.h"
#include "atmo/status.h"

#define SCENE_OPTIONS_MAX_SETS 256

typedef struct scene_options {
    const char *command;  /* "render", "view": the subcommand its messages name */
    int shorthands;       /* also take --width, --height, --samples, --seed, --time, --camera */
    const char *preset, *scene_file;
    const char *sets[SCENE_OPTIONS_MAX_SETS]; /* KEY=VALUE, in command-line order */
    int set_count;
    char shorthand_sets[SCENE_OPTIONS_MAX_SETS][64]; /* the shorthands written as KEY=VALUE */
} scene_options;

void scene_options_init(scene_options *o, const char *command, int shorthands);
/* argv[*i] a scene option: take it and its value (*i is left on the value) and return 1; any
 * other argument: 0. A missing value or one --set too many: the one-line message on stderr and
 * -1 (the command exits with ATMO_ERR_USAGE). */
int scene_options_take(scene_options *o, int argc, char **argv, int *i);
/* The scene: the defaults, the preset (atmo_default_preset without --preset) unless --scene was
 * given, the file (`file` if not NULL, else --scene's), the assignments in order, the rewrite of
 * output.blender (atmo_scene_for_blender; said on stderr for the first scene), validated.
 * --preset with --scene is a usage error. An animation's end scene passes its own file. */
int scene_options_scene(const scene_options *o, const char *file, atmo_scene *s, atmo_err *e);

#endif
