/* main.c — the `atmo` command: dispatch to a subcommand. */
#include <stdio.h>
#include <string.h>
#include "atmo/status.h"
#include "atmo/cl_runtime.h"
#include "atmo/suggest.h"
#include "commands.h"

static const atmo_command commands[] = {
    {"render", "render a scene to images (PNG, HDR, EXR, PFM)", cmd_render},
    {"view", "a live window: move the camera and the sun, watch the image refine", cmd_view},
    {"merge", "join the parts of a split render into its images", cmd_merge},
    {"devices", "list OpenCL platforms and devices", cmd_devices},
    {"params", "list every scene parameter with unit, default and range", cmd_params},
    {"presets", "list the built-in scenes", cmd_presets},
    {"mie", "Lorenz-Mie optics of a droplet or a droplet size distribution", cmd_mie},
    {"bench", "measure error against time of the rendering methods", cmd_bench},
    {"radiance", "print sky radiance and luminance for view directions", cmd_radiance},
    {"cache", "list, verify or clear the cache of kernels, LUTs and Mie tables", cmd_cache},
    {"dem", "read a digital elevation model (GeoTIFF, PNG, EXR): size, extent, heights", cmd_dem},
    {"terrain", "print the terrain's height, normal, coverage and materials at points", cmd_terrain},
};

static void usage(FILE *f)
{
    fprintf(f, "usage: atmo COMMAND [options]   (atmo COMMAND --help for its options)\n\n"
               "A physically based renderer of Earth-like planets.\n\ncommands:\n");
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
        fprintf(f, "  %-10s %s\n", commands[i].name, commands[i].summary);
    fprintf(f, "\n  --version  print the version\n  --help     this text\n");
}

int main(int argc, char **argv)
{
    atmo_cl_prepare_environment(); /* before any thread: setenv is not thread-safe */
    if (argc < 2) {
        usage(stderr);
        return ATMO_ERR_USAGE;
    }
    if (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0 ||
        strcmp(argv[1], "help") == 0) {
        usage(stdout);
        return ATMO_OK;
    }
    if (strcmp(argv[1], "--version") == 0) {
        printf("atmo %s\n", ATMO_VERSION);
        return ATMO_OK;
    }
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
        if (strcmp(argv[1], commands[i].name) == 0)
            return commands[i].run(argc - 1, argv + 1);
    atmo_suggest near;
    atmo_suggest_begin(&near, argv[1]);
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
        atmo_suggest_offer(&near, commands[i].name);
    const char *hint = atmo_suggest_result(&near);
    fprintf(stderr, "atmo: unknown command '%s'%s%s%s; run 'atmo --help' for the list\n", argv[1],
            hint ? " (did you mean '" : "", hint ? hint : "", hint ? "'?)" : "");
    return ATMO_ERR_USAGE;
}
