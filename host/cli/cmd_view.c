/* cmd_view.c — `atmo view`: the live viewer (atmo/view.h, host/view/).
 *
 * Scene assembly is `atmo render`'s, through the same parser (scene_options.h): the defaults,
 * --preset NAME (default atmo_default_preset) or --scene FILE, then --set KEY=VALUE in order
 * (render's shorthands such as --width are not options of the viewer); every file the viewer
 * may write (--output, --window-capture, --save's names) and the script are checked before the
 * window opens. The viewer is built only where GLFW 3 and OpenGL are found (CMakeLists.txt
 * defines ATMO_HAVE_GLFW for this file alone): elsewhere `atmo view` says how to get it and
 * exits 2. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/image.h"
#include "atmo/scene.h"
#include "atmo/view.h"
#include "commands.h"
#include "output_paths.h"
#include "scene_options.h"

#ifndef ATMO_HAVE_GLFW
static const char view_unavailable[] =
    "atmo view: this atmo was built without GLFW 3 and OpenGL; install libglfw3-dev (Debian) "
    "and rebuild to get the viewer\n";
#endif

static const char view_usage[] =
    "usage: atmo view [--preset NAME | --scene FILE] [--set KEY=VALUE ...] [options]\n"
    "\n"
    "Opens a window that shows the scene as it renders and refines, and lets you move the\n"
    "camera and turn the sun. The image is tone mapped on the GPU with the scene's post.*\n"
    "settings, as `atmo render` writes PNGs. Quality mode renders the scene as given (method,\n"
    "size, image.samples); preview mode renders method fast at half size. Every change\n"
    "restarts the accumulation with a quarter-size draft, then refines. A path-traced scene\n"
    "(--set render.mode=path, e.g. --preset thesis-7) refines progressively like any other;\n"
    "render passes, --noise and the lens flare are atmo render's.\n"
    "\n"
    "scene:\n"
    "  --preset NAME          a built-in scene (atmo presets; default %s)\n"
    "  --scene FILE           a JSON scene file (atmo params lists every key)\n"
    "  --set KEY=VALUE        override one parameter (repeatable; over thesis views 1-9 too,\n"
    "                         but for camera.* and sun.*)\n"
    "output:\n"
    "  --save FILE            where P saves (default atmo-view.png): FILE-NNN.EXT and the scene\n"
    "                         FILE-NNN.json beside it (atmo render --scene reproduces the shot)\n"
    "  --screenshot-after N   once every pixel has N samples (after --script), write --output\n"
    "                         and exit (for tests and scripts)\n"
    "  --output FILE          the image --screenshot-after writes (.png .hdr .exr .pfm)\n"
    "  --window-capture FILE  with --screenshot-after: also the window as drawn, as a PNG\n"
    "  --script FILE          timed synthetic input: wait S, wait-samples N, press KEY [shift|\n"
    "                         ctrl], hold W|A|S|D|Q|E S [shift|ctrl], look DX DY, quit\n"
    "  --window WxH           window size (default: the image, at most 1280x800)\n"
    "  --quiet                no messages on stderr\n"
    "device:\n"
    "  --device N|NAME        OpenCL device (atmo devices)\n"
    "  --tile-size N          tile edge in pixels (default 64)\n"
    "  --launch-budget-ms MS  time per kernel launch to aim for (default 30: short launches\n"
    "                         keep changes quick)\n"
    "  --no-kernel-cache, --no-lut-cache   as for atmo render\n"
    "\n"
    "keys:\n%s";

#ifdef ATMO_HAVE_GLFW
static int usage_fail(atmo_err *e, output_paths *files)
{
    output_paths_free(files);
    fprintf(stderr, "atmo view: %s\n", e->msg);
    return ATMO_ERR_USAGE;
}

static int whole(const char *v, int lo, int hi, int *out)
{
    double x;
    if (!v || !atmo_parse_decimal(v, &x) || x != (int)x || x < lo || x > hi)
        return 0;
    *out = (int)x;
    return 1;
}

/* Parse, check every output, run the viewer. */
static int view_main(int argc, char **argv)
{
    atmo_err e = {{0}};
    atmo_view_options o;
    scene_options so; /* its --set list is the viewer's o.sets until atmo_view_run returns */
    output_paths files = {0};
    memset(&o, 0, sizeof o);
    scene_options_init(&so, "view", 0);
    atmo_render_settings_default(&o.render);
    o.render.launch_budget_ms = 30.0;
    o.lut_cache = 1;
    o.save_path = "atmo-view.png";

    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        int taken = scene_options_take(&so, argc, argv, &i);
        if (taken < 0)
            return ATMO_ERR_USAGE;
        if (taken)
            continue;
        if (strcmp(a, "--quiet") == 0 || strcmp(a, "-q") == 0) {
            o.quiet = 1;
            continue;
        }
        if (strcmp(a, "--no-kernel-cache") == 0) {
            o.render.use_kernel_cache = 0;
            continue;
        }
        if (strcmp(a, "--no-lut-cache") == 0) {
            o.lut_cache = 0;
            continue;
        }
        static const char *const with_value[] = {
            "--save", "--screenshot-after", "--output", "-o",
            "--window-capture", "--script", "--window", "--device", "--tile-size",
            "--launch-budget-ms", NULL};
        int known = 0;
        for (int k = 0; with_value[k]; k++)
            known |= strcmp(a, with_value[k]) == 0;
        if (!known) {
            fprintf(stderr, "atmo view: %s '%s' (atmo view --help)\n",
                    a[0] == '-' ? "unknown option" : "unexpected argument", a);
            return ATMO_ERR_USAGE;
        }
        if (!v) {
            fprintf(stderr, "atmo view: %s needs a value (atmo view --help)\n", a);
            return ATMO_ERR_USAGE;
        }
        i++;
        if (strcmp(a, "--save") == 0)
            o.save_path = v;
        else if (strcmp(a, "--screenshot-after") == 0) {
            if (!whole(v, 1, 1000000, &o.screenshot_after)) {
                fprintf(stderr, "atmo view: --screenshot-after needs samples per pixel in "
                                "[1, 1000000], got '%s'\n", v);
                return ATMO_ERR_USAGE;
            }
        } else if (strcmp(a, "--output") == 0 || strcmp(a, "-o") == 0)
            o.output = v;
        else if (strcmp(a, "--window-capture") == 0)
            o.window_capture = v;
        else if (strcmp(a, "--script") == 0)
            o.script = v;
        else if (strcmp(a, "--window") == 0) {
            char rest;
            if (sscanf(v, "%dx%d%c", &o.window_width, &o.window_height, &rest) != 2 ||
                o.window_width < 16 || o.window_width > 16384 || o.window_height < 16 ||
                o.window_height > 16384) {
                fprintf(stderr, "atmo view: --window needs WIDTHxHEIGHT in pixels (16 to 16384), "
                                "e.g. 1280x720, got '%s'\n", v);
                return ATMO_ERR_USAGE;
            }
        } else if (strcmp(a, "--device") == 0)
            o.render.device = v;
        else if (strcmp(a, "--tile-size") == 0) {
            if (!whole(v, 8, 4096, &o.render.tile_size)) {
                fprintf(stderr, "atmo view: --tile-size needs a whole number in [8, 4096], got "
                                "'%s'\n", v);
                return ATMO_ERR_USAGE;
            }
        } else { /* --launch-budget-ms, the last of with_value[] */
            char *end;
            o.render.launch_budget_ms = strtod(v, &end);
            if (*v == 0 || *end != 0 ||
                !(o.render.launch_budget_ms >= 1.0 && o.render.launch_budget_ms <= 1e5)) {
                fprintf(stderr, "atmo view: --launch-budget-ms needs milliseconds in [1, 100000], "
                                "got '%s'\n", v);
                return ATMO_ERR_USAGE;
            }
        }
    }

    if (scene_options_scene(&so, NULL, &o.scene, &e))
        return usage_fail(&e, &files);
    if (o.scene.render.spectral_bands > 0) {
        atmo_fail(&e, ATMO_ERR_USAGE, "the viewer renders three wavelengths; drop "
                                      "render.spectral_bands (atmo render does the spectral mode)");
        return usage_fail(&e, &files);
    }
    o.sets = so.sets;
    o.set_count = so.set_count;

    /* every file it may write, before the window opens */
    if ((o.screenshot_after > 0) != (o.output != NULL)) {
        atmo_fail(&e, ATMO_ERR_USAGE, "--screenshot-after N and --output FILE go together; give "
                                      "both or neither");
        return usage_fail(&e, &files);
    }
    if (o.window_capture && !o.output) {
        atmo_fail(&e, ATMO_ERR_USAGE, "--window-capture is written with the screenshot; add "
                                      "--screenshot-after N --output FILE");
        return usage_fail(&e, &files);
    }
    if (o.output && atmo_image_format_from_path(o.output) < 0) {
        atmo_fail(&e, ATMO_ERR_USAGE, "--output '%s': unknown image format (use .png, .hdr, .exr "
                                      "or .pfm)", o.output);
        return usage_fail(&e, &files);
    }
    if (o.window_capture && atmo_image_format_from_path(o.window_capture) != ATMO_IMAGE_PNG) {
        atmo_fail(&e, ATMO_ERR_USAGE, "--window-capture '%s' must be a .png", o.window_capture);
        return usage_fail(&e, &files);
    }
    if (atmo_image_format_from_path(o.save_path) < 0) {
        atmo_fail(&e, ATMO_ERR_USAGE, "--save '%s': unknown image format (use .png, .hdr, .exr "
                                      "or .pfm)", o.save_path);
        return usage_fail(&e, &files);
    }
    if ((o.output && output_paths_add(&files, "--output", o.output, &e)) ||
        (o.window_capture && output_paths_add(&files, "--window-capture", o.window_capture, &e)) ||
        output_paths_add(&files, "--save", o.save_path, &e))
        return usage_fail(&e, &files);
    output_paths_free(&files);

    int rc = atmo_view_run(&o, &e);
    if (rc)
        fprintf(stderr, "atmo view: %s\n", e.msg);
    return rc;
}
#endif

int cmd_view(int argc, char **argv)
{
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
#ifdef ATMO_HAVE_GLFW
            printf(view_usage, atmo_default_preset, atmo_view_keys);
#else
            printf(view_usage, atmo_default_preset, "  (not built: see below)\n");
            printf("\n%s", view_unavailable);
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
