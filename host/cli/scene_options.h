/* scene_options.h — the scene options of `atmo render` and `atmo view` (scene_options.c):
 * --preset NAME, --scene FILE, --set KEY=VALUE, the shorthands of scene keys (--width,
 * --height, --samples, --seed, --time, --camera) and --blender, as a flag table (cli_flags.h) that both
 * commands include, and the scene they assemble. */
#ifndef ATMO_SCENE_OPTIONS_H
#define ATMO_SCENE_OPTIONS_H
#include "atmo/scene.h"
#include "atmo/status.h"
#include "cli_flags.h"

#define SCENE_OPTIONS_MAX_SETS 256

typedef struct scene_options {
    const char *preset, *scene_file;
    const char *sets[SCENE_OPTIONS_MAX_SETS]; /* KEY=VALUE, in command-line order */
    int set_count;
    char shorthand_sets[SCENE_OPTIONS_MAX_SETS][64]; /* the shorthands written as KEY=VALUE */
    int blender;                  /* --blender: output.blender=true after the assignments */
} scene_options;

/* The flags, their destinations in a scene_options (include them with CLI_INCLUDE at the
 * offset of the command's scene_options): --preset, --scene and --set alone, or those and the
 * shorthands. */
extern const cli_flag scene_source_flags[];
extern const cli_flag scene_option_flags[];

void scene_options_init(scene_options *o);
/* The scene: the defaults, the preset (atmo_default_preset without --preset) unless --scene was
 * given, the file (`file` if not NULL, else --scene's), the assignments in order, --blender's
 * output.blender=true, the rewrite of output.blender (atmo_scene_for_blender; said on stderr for
 * the first scene), validated.
 * --preset with --scene is a usage error. An animation's end scene passes its own file. */
int scene_options_scene(const scene_options *o, const char *file, atmo_scene *s, atmo_err *e);

#endif
