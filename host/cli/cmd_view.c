/* cmd_view.c — `atmo view`: the live viewer (atmo/view.h, host/view/).
 *
 * Scene assembly is `atmo render`'s, through the same flags (scene_options.h): the defaults,
 * --preset NAME (default atmo_default_preset) or --scene FILE, then --set KEY=VALUE and the
 * shorthands (--width, --height, --samples, --seed, --time, --camera) in order, reapplied like
 * --set over a thesis view chosen live; every file the viewer may write (--output,
 * --window-capture, --save's names; an existing --output only with --force) and the script are
 * checked before the window opens. The viewer is built only where GLFW 3 and OpenGL are found (CMakeLists.txt
 * defines ATMO_HAVE_GLFW for this file alone): elsewhere `atmo view` says how to get it and
 * exits 2. */
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/image.h"
#include "atmo/scene.h"
#include "atmo/view.h"
#include "cli_flags.h"
#include "commands.h"
#include "output_paths.h"
#include "overwrite.h"
#include "scene_options.h"

#ifndef ATMO_HAVE_GLFW
static const char view_unavailable[] =
    "atmo view: this atmo was built without GLFW 3 and OpenGL; install libglfw3-dev (Debian) "
    "and rebuild to get the viewer\n";
#endif

/* The flags' destinations (view_flags), holding the defaults before parsing. */
typedef struct view_args {
    scene_options so; /* its --set list is the viewer's o.sets until atmo_view_run returns */
    atmo_view_options o;
    int no_kernel_cache, no_lut_cache, force;
} view_args;

/* --window WxH */
static int take_window(void *args, const cli_flag *f, const char *v, atmo_err *e)
{
    atmo_view_options *o = &((view_args *)args)->o;
    char rest;
    (void)f;
    if (sscanf(v, "%dx%d%c", &o->window_width, &o->window_height, &rest) != 2 ||
        o->window_width < 16 || o->window_width > 16384 || o->window_height < 16 ||
        o->window_height > 16384)
        return atmo_fail(e, ATMO_ERR_USAGE, "--window needs WIDTHxHEIGHT in pixels (16 to "
                                            "16384), e.g. 1280x720, got '%s'", v);
    return ATMO_OK;
}

#define VIEW_FLAG(member) offsetof(view_args, member)

static const cli_flag view_flags[] = {
    {.type = CLI_SECTION, .help = "scene (the shorthands apply live, like --set):"},
    {.type = CLI_INCLUDE, .include = scene_option_flags, .offset = VIEW_FLAG(so)},
    {.type = CLI_SECTION, .help = "output:"},
    {.type = CLI_PATH, .name = "--save", .offset = VIEW_FLAG(o.save_path),
     .help = "where P saves: FILE-NNN.EXT and the scene FILE-NNN.json beside\n"
             "it (atmo render --scene reproduces the shot)"},
    {.type = CLI_INT, .name = "--screenshot-after", .min = 1, .max = 1000000,
     .offset = VIEW_FLAG(o.screenshot_after), .def = "off",
     .help = "once every pixel has N samples (after --script), write --output\n"
             "and exit (for tests and scripts)"},
    {.type = CLI_PATH, .name = "--output", .alias = "-o", .offset = VIEW_FLAG(o.output),
     .def = "none", .help = "the image --screenshot-after writes (.png .hdr .exr .pfm)"},
    {.type = CLI_BOOL, .name = "--force", .offset = VIEW_FLAG(force),
     .help = "overwrite --output and --window-capture if they exist"},
    {.type = CLI_PATH, .name = "--window-capture", .offset = VIEW_FLAG(o.window_capture),
     .def = "none", .help = "with --screenshot-after: also the window as drawn, as a PNG"},
    {.type = CLI_PATH, .name = "--script", .offset = VIEW_FLAG(o.script), .def = "none",
     .help = "timed synthetic input: wait S, wait-samples N, press KEY [shift|\n"
             "ctrl], hold W|A|S|D|Q|E S [shift|ctrl], look DX DY, quit"},
    {.type = CLI_STRING, .name = "--window", .metavar = "WxH", .take = take_window,
     .def = "the image, at most 1280x800", .help = "window size"},
    {.type = CLI_BOOL, .name = "--quiet", .alias = "-q", .offset = VIEW_FLAG(o.quiet),
     .help = "no messages on stderr"},
    {.type = CLI_SECTION, .help = "device:"},
    {.type = CLI_STRING, .name = "--device", .metavar = "N|NAME", .offset = VIEW_FLAG(o.render.device),
     .def = "$ATMO_DEVICE, else the first GPU, else the first device",
     .help = "OpenCL device by index or name part (atmo devices)"},
    {.type = CLI_INT, .name = "--tile-size", .min = 8, .max = 4096,
     .offset = VIEW_FLAG(o.render.tile_size), .help = "tile edge in pixels"},
    {.type = CLI_FLOAT, .name = "--launch-budget-ms", .metavar = "MS", .min = 1.0, .max = 1e5,
     .offset = VIEW_FLAG(o.render.launch_budget_ms),
     .help = "time per kernel launch to aim for (short launches keep changes\nquick)"},
    {.type = CLI_BOOL, .name = "--no-kernel-cache", .offset = VIEW_FLAG(no_kernel_cache),
     .help = "always compile the kernels, as for atmo render"},
    {.type = CLI_BOOL, .name = "--no-lut-cache", .offset = VIEW_FLAG(no_lut_cache),
     .help = "always precompute LUTs and Mie tables, as for atmo render"},
    {.type = CLI_END},
};

static const cli_command view_cli = {
    .name = "view",
    .synopsis = "[--preset NAME | --scene FILE] [--set KEY=VALUE ...] [options]",
    .about =
        "Opens a window that shows the scene as it renders and refines, and lets you move the\n"
        "camera and turn the sun. The image is tone mapped on the GPU with the scene's post.*\n"
        "settings, as `atmo render` writes PNGs. Quality mode renders the scene as given (method,\n"
        "size, image.samples); preview mode renders method fast at half size. Every change\n"
        "restarts the accumulation with a quarter-size draft, then refines. A path-traced scene\n"
        "(--set render.mode=path, e.g. --preset thesis-7) refines progressively like any other;\n"
        "render passes, --noise and the lens flare are atmo render's. --set and the shorthands\n"
        "are reapplied over thesis views 1-9 too, but for camera.* and sun.*.\n",
    .flags = view_flags,
    .scene_preset = &atmo_default_preset,
};

static void view_defaults(view_args *a)
{
    memset(a, 0, sizeof *a);
    scene_options_init(&a->so);
    atmo_render_settings_default(&a->o.render);
    a->o.render.launch_budget_ms = 30.0;
    a->o.save_path = "atmo-view.png";
}

#ifdef ATMO_HAVE_GLFW
/* The scene and every file the viewer may write, checked before the window opens. */
static int view_check(view_args *a, atmo_err *e)
{
    atmo_view_options *o = &a->o;
    output_paths files = {0};
    int rc;
    if ((rc = scene_options_scene(&a->so, NULL, &o->scene, e)))
        return rc;
    if (o->scene.render.spectral_bands > 0)
        return atmo_fail(e, ATMO_ERR_USAGE, "the viewer renders three wavelengths; drop "
                                            "render.spectral_bands (atmo render does the "
                                            "spectral mode)");
    if ((o->screenshot_after > 0) != (o->output != NULL))
        return atmo_fail(e, ATMO_ERR_USAGE, "--screenshot-after N and --output FILE go together; "
                                            "give both or neither");
    if (o->window_capture && !o->output)
        return atmo_fail(e, ATMO_ERR_USAGE, "--window-capture is written with the screenshot; "
                                            "add --screenshot-after N --output FILE");
    if (o->output && atmo_image_format_from_path(o->output) < 0)
        return atmo_fail(e, ATMO_ERR_USAGE, "--output '%s': unknown image format (use .png, "
                                            ".hdr, .exr or .pfm)", o->output);
    if (o->window_capture && atmo_image_format_from_path(o->window_capture) != ATMO_IMAGE_PNG)
        return atmo_fail(e, ATMO_ERR_USAGE, "--window-capture '%s' must be a .png",
                         o->window_capture);
    if (atmo_image_format_from_path(o->save_path) < 0)
        return atmo_fail(e, ATMO_ERR_USAGE, "--save '%s': unknown image format (use .png, .hdr, "
                                            ".exr or .pfm)", o->save_path);
    if (!(rc = o->output ? output_paths_add(&files, "--output", o->output, e) : 0) &&
        !(rc = o->window_capture ? output_paths_add(&files, "--window-capture",
                                                    o->window_capture, e) : 0) &&
        !(rc = output_paths_add(&files, "--save", o->save_path, e)) &&
        !(rc = o->output ? overwrite_check("--output", o->output, a->force, e) : 0))
        rc = o->window_capture ? overwrite_check("--window-capture", o->window_capture, a->force, e)
                               : 0;
    output_paths_free(&files);
    return rc;
}

/* Parse, check every output, run the viewer. */
static int view_main(int argc, char **argv)
{
    atmo_err e = {{0}};
    static view_args a; /* the scene options' sets live until atmo_view_run returns */
    int rc;
    view_defaults(&a);
    if (!cli_parse(&view_cli, &a, argc, argv, NULL, NULL, &rc))
        return rc;
    a.o.render.use_kernel_cache = !a.no_kernel_cache;
    a.o.lut_cache = !a.no_lut_cache;
    a.o.sets = a.so.sets;
    a.o.set_count = a.so.set_count;
    if ((rc = view_check(&a, &e)) || (rc = atmo_view_run(&a.o, &e)))
        return cli_fail(&view_cli, rc, &e);
    return ATMO_OK;
}
#endif

int cmd_view(int argc, char **argv)
{
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            static view_args defaults;
            view_defaults(&defaults);
            cli_print_help(&view_cli, &defaults, stdout);
#ifdef ATMO_HAVE_GLFW
            printf("\nkeys:\n%s", atmo_view_keys);
#else
            printf("\nkeys: (not built: see below)\n\n%s", view_unavailable);
#endif
            return ATMO_OK;
        }
    }
#ifdef ATMO_HAVE_GLFW
    return view_main(argc, argv);
#else
    fputs(view_unavailable, stderr);
    return ATMO_ERR_USAGE;
#endif
}
