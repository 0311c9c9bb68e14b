/* cmd_bench.c — `atmo bench SUITE --output DIR`: error against time for each method's knobs.
 *
 * Each suite (host/bench_*.c) measures a method or its knobs against a reference of much higher
 * quality and writes DIR/SUITE.csv (method, settings, seconds, error, device) and a log-log chart
 * DIR/SUITE.svg of error against time drawn by gnuplot (the CSV alone, with a note, when gnuplot
 * is missing). */
#include <errno.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include "atmo/bench.h"
#include "atmo/suggest.h"
#include "cli_flags.h"
#include "commands.h"

static const char *const bench_suites[] = {"sky",    "atmosphere", "mie",     "colour",
                                           "panorama", "render",   "terrain", "clouds",
                                           "denoise",  "guides",   "views",    NULL};

/* The flags' destinations (bench_flags), holding the defaults before parsing. */
typedef struct bench_args {
    const char *dir, *device, *reference, *views;
    int quick, fit, noise_only;
} bench_args;

#define BENCH_FLAG(member) offsetof(bench_args, member)

static const cli_flag bench_flags[] = {
    {.type = CLI_PATH, .name = "--output", .metavar = "DIR", .offset = BENCH_FLAG(dir),
     .help = "where SUITE.csv and SUITE.svg go (created if missing)"},
    {.type = CLI_STRING, .name = "--device", .metavar = "N|NAME", .offset = BENCH_FLAG(device),
     .def = "$ATMO_DEVICE, else the first GPU, else the first device",
     .help = "OpenCL device by index or name part (atmo devices)"},
    {.type = CLI_BOOL, .name = "--quick", .offset = BENCH_FLAG(quick),
     .help = "fewer settings (for tests)"},
    {.type = CLI_BOOL, .name = "--fit", .offset = BENCH_FLAG(fit),
     .help = "clouds: fit the multiple-scattering octaves and diffuse orders instead"},
    {.type = CLI_STRING, .name = "--views", .metavar = "LIST", .offset = BENCH_FLAG(views),
     .def = "all: thesis-1,...,thesis-9",
     .help = "views: the thesis views to measure, comma-separated"},
    {.type = CLI_BOOL, .name = "--noise-only", .offset = BENCH_FLAG(noise_only),
     .help = "views: the two-seed noise alone, no path-traced reference or bias"},
    {.type = CLI_PATH, .name = "--reference", .offset = BENCH_FLAG(reference),
     .help = "atmosphere: the Monte Carlo reference table"},
    {.type = CLI_END},
};

static const cli_command bench_cli = {
    .name = "bench",
    .synopsis = "SUITE [--output DIR] [--device N|NAME] [--quick] [--fit] [--views LIST]\n"
                "            [--noise-only]",
    .about =
        "Measures error against a high-quality reference and time for each setting of a method,\n"
        "and writes DIR/SUITE.csv and the chart DIR/SUITE.svg (gnuplot).\n",
    .flags = bench_flags,
    .epilogue =
        "suites:\n"
        "  sky         single-scattering sky: view-ray steps and transmittance LUT size\n"
        "  atmosphere  every atmosphere method and its knobs against the Monte Carlo reference table\n"
        "              (tests/data/reference_sky.csv; --reference FILE to use another)\n"
        "  mie         cloud phase options against the tabulated Mie phase; phase table build time\n"
        "  colour      colour difference (CIE76) of the 3-wavelength mode from the spectral mode\n"
        "              with 15, 30 and 48 bands, by sun zenith; and their time\n"
        "  panorama    whole-process stages of a fast sky panorama to EXR, warm, new atmosphere\n"
        "              and cold, 512x256 to 4096x2048 (wall seconds, not error)\n"
        "  render      the path tracer: time to 1% noise of thesis views 1, 6 and 7 at 1280x720\n"
        "              (extrapolated from a central crop), its split between the atmosphere and\n"
        "              the bounces, and the cost of an unused objects feature\n"
        "  terrain     heightmap sizes and formats against direct evaluation, sphere-tracing\n"
        "              optimism and steps, exact against estimated shadows, light-shaft shortcuts,\n"
        "              thesis-1's time per sample\n"
        "  clouds      the fBm clouds' marcher (steps, light steps, octaves) against the Monte\n"
        "              Carlo reference on six cloud views and a held-out seventh (thesis-8's\n"
        "              near cloud); --fit fits the multiple-scattering octaves and diffuse\n"
        "              orders (clouds.ms_a, ms_b, ms_c, ms_octaves, ms_d) to the six instead\n"
        "  denoise     thesis-7 path traced at 1 to 64 spp, raw and denoised by Open Image\n"
        "              Denoise (fast, balanced, high): error against time, where denoising pays\n"
        "  guides      4-spp path-traced sky, terrain, limb and objects at 256x144, raw and\n"
        "              denoised on the colour alone and with the albedo and normal guides\n"
        "  views       each thesis view in the default mode: two-seed noise against time at\n"
        "              1280x720 (1-16 spp) and bias against the path-traced reference at 320x180\n"
        "              (cached in DIR/views_ref/); --quick: 320x180 and 80x45; --views to choose;\n"
        "              --noise-only: no reference, no bias\n",
    .max_positional = 1,
};

/* The suite named, or a usage error naming the nearest one. */
static int bench_check_suite(const char *suite, atmo_err *e)
{
    if (!suite)
        return atmo_fail(e, ATMO_ERR_USAGE, "name a suite (sky, atmosphere, mie, colour, "
                         "panorama, render, terrain, clouds, denoise, guides, views); atmo bench --help");
    for (const char *const *s = bench_suites; *s; s++)
        if (strcmp(suite, *s) == 0)
            return ATMO_OK;
    const char *near = atmo_suggest_among(suite, bench_suites);
    return atmo_fail(e, ATMO_ERR_USAGE, "unknown suite '%s' (%s%s%ssuites: sky, atmosphere, mie, "
                     "colour, panorama, render, terrain, clouds, denoise, guides, views)", suite,
                     near ? "did you mean '" : "", near ? near : "", near ? "'? " : "");
}

int cmd_bench(int argc, char **argv)
{
    bench_args a = {.dir = "bench", .reference = "tests/data/reference_sky.csv"};
    const char *suite = NULL;
    atmo_err e = {{0}};
    int rc, n = 0;
    if (!cli_parse(&bench_cli, &a, argc, argv, &suite, &n, &rc))
        return rc;
    if ((rc = bench_check_suite(suite, &e)) || (rc = bench_views_check(a.views, &e)))
        return cli_fail(&bench_cli, rc, &e);
    if (mkdir(a.dir, 0755) != 0 && errno != EEXIST) {
        fprintf(stderr, "atmo bench: cannot create output directory '%s': %s\n", a.dir,
                strerror(errno));
        return ATMO_ERR_USAGE;
    }
    const char *dir = a.dir, *device = a.device;
    int quick = a.quick;
    rc = strcmp(suite, "mie") == 0   ? bench_mie(dir, quick, &e)
             : strcmp(suite, "sky") == 0 ? bench_sky(dir, device, quick, &e)
             : strcmp(suite, "colour") == 0 ? bench_colour(dir, device, quick, &e)
             : strcmp(suite, "panorama") == 0 ? bench_panorama(dir, device, quick, &e)
             : strcmp(suite, "render") == 0 ? bench_path(dir, device, quick, &e)
             : strcmp(suite, "terrain") == 0 ? bench_terrain(dir, device, quick, &e)
             : strcmp(suite, "clouds") == 0 ? bench_clouds(dir, device, quick, a.fit, &e)
             : strcmp(suite, "denoise") == 0 ? bench_denoise(dir, device, quick, &e)
             : strcmp(suite, "guides") == 0 ? bench_guides(dir, device, quick, &e)
             : strcmp(suite, "views") == 0 ? bench_views(dir, device, a.views, quick, a.noise_only, &e)
                                         : bench_atmosphere(dir, device, a.reference, quick, &e);
    if (rc)
        fprintf(stderr, "atmo bench: %s\n", e.msg);
    return rc;
}
