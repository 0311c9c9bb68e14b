/* cmd_presets.c — `atmo presets`: the built-in scenes (scene_presets.c) with what each shows;
 * `atmo presets NAME` prints the settings a preset applies over the defaults, in the
 * key=value form that --set takes. */
#include <stdio.h>
#include <string.h>
#include "atmo/scene.h"
#include "cli_flags.h"
#include "commands.h"

static const cli_flag presets_flags[] = {{.type = CLI_END}};

static const cli_command presets_cli = {
    .name = "presets",
    .synopsis = "[NAME]",
    .about = "List the built-in scenes and what each shows; with NAME, print the settings that\n"
             "preset applies over the defaults (atmo params lists the defaults).\n"
             "Render one with: atmo render --preset NAME\n",
    .flags = presets_flags,
    .max_positional = 1,
};

int cmd_presets(int argc, char **argv)
{
    const char *name = NULL;
    int n = 0, rc;
    if (!cli_parse(&presets_cli, NULL, argc, argv, &name, &n, &rc))
        return rc;
    if (name) {
        const atmo_preset *p = atmo_preset_find(name);
        const char *near = p ? NULL : atmo_preset_closest(name);
        if (!p) {
            fprintf(stderr, "atmo presets: unknown preset '%s'%s%s%s; run 'atmo presets' for the "
                            "list\n",
                    name, near ? " (did you mean '" : "", near ? near : "", near ? "'?)" : "");
            return ATMO_ERR_USAGE;
        }
        printf("# %s: %s\n", p->name, p->summary);
        for (const char *const *s = p->settings; *s; s++)
            printf("%s\n", *s);
        return ATMO_OK;
    }
    for (const atmo_preset *p = atmo_presets; p->name; p++)
        printf("%-14s %s%s\n", p->name, p->summary,
               strcmp(p->name, atmo_default_preset) == 0 ? " [default]" : "");
    return ATMO_OK;
}
