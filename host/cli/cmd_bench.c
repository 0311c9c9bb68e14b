/* cmd_bench.c — `atmo bench SUITE --output DIR`: error against time for each method's knobs.
 *
 * Each suite (host/bench_*.c) measures a method or its knobs against a reference of much higher
 * quality and writes DIR/SUITE.csv (method, settings, seconds, error, device) and a log-log chart
 * DIR/SUITE.svg of error against time drawn by gnuplot (the CSV alone, with a note, when gnuplot
 * is missing). */
#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include "atmo/bench.h"
#include "commands.h"

static const char bench_usage[] =
    "usage: atmo bench SUITE [--output DIR] [--device N|NAME] [--quick] [--fit]\n"
    "\n"
    "Measures error against a high-quality reference and time for each setting of a method,\n"
    "and writes DIR/SUITE.csv and the chart DIR/SUITE.svg (gnuplot). DIR defaults to bench/.\n"
    "--quick runs fewer settings (for tests).\n"
    "\n"
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
    "              Carlo reference on four cloud views; --fit fits the multiple-scattering\n"
    "              octaves (clouds.ms_a, ms_b, ms_c, ms_octaves) to the reference instead\n"
    "  denoise     thesis-7 path traced at 1 to 64 spp, raw and denoised by Open Image\n"
    "              Denoise (fast, balanced, high): error against time, where denoising pays\n";

int cmd_bench(int argc, char **argv)
{
    const char *suite = NULL, *dir = "bench", *device = NULL;
    const char *reference = "tests/data/reference_sky.csv";
    int quick = 0, fit = 0;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            printf("%s", bench_usage);
            return ATMO_OK;
        } else if (strcmp(argv[i], "--quick") == 0)
            quick = 1;
        else if (strcmp(argv[i], "--fit") == 0)
            fit = 1;
        else if (strcmp(argv[i], "--output") == 0 && i + 1 < argc)
            dir = argv[++i];
        else if (strcmp(argv[i], "--device") == 0 && i + 1 < argc)
            device = argv[++i];
        else if (strcmp(argv[i], "--reference") == 0 && i + 1 < argc)
            reference = argv[++i];
        else if (argv[i][0] != '-' && !suite)
            suite = argv[i];
        else {
            fprintf(stderr, "atmo bench: unexpected argument '%s' (atmo bench --help)\n", argv[i]);
            return ATMO_ERR_USAGE;
        }
    }
    if (!suite) {
        fprintf(stderr, "atmo bench: name a suite (sky, atmosphere, mie, colour, panorama, "
                        "render, terrain, clouds, denoise); atmo bench --help\n");
        return ATMO_ERR_USAGE;
    }
    if (strcmp(suite, "sky") != 0 && strcmp(suite, "mie") != 0 &&
        strcmp(suite, "atmosphere") != 0 && strcmp(suite, "colour") != 0 &&
        strcmp(suite, "panorama") != 0 && strcmp(suite, "render") != 0 &&
        strcmp(suite, "terrain") != 0 && strcmp(suite, "clouds") != 0 &&
        strcmp(suite, "denoise") != 0) {
        fprintf(stderr, "atmo bench: unknown suite '%s' (suites: sky, atmosphere, mie, colour, "
                        "panorama, render, terrain, clouds, denoise)\n",
                suite);
        return ATMO_ERR_USAGE;
    }
    if (mkdir(dir, 0755) != 0 && errno != EEXIST) {
        fprintf(stderr, "atmo bench: cannot create output directory '%s': %s\n", dir,
                strerror(errno));
        return ATMO_ERR_USAGE;
    }
    atmo_err e;
    int rc = strcmp(suite, "mie") == 0   ? bench_mie(dir, quick, &e)
             : strcmp(suite, "sky") == 0 ? bench_sky(dir, device, quick, &e)
             : strcmp(suite, "colour") == 0 ? bench_colour(dir, device, quick, &e)
             : strcmp(suite, "panorama") == 0 ? bench_panorama(dir, device, quick, &e)
             : strcmp(suite, "render") == 0 ? bench_path(dir, device, quick, &e)
             : strcmp(suite, "terrain") == 0 ? bench_terrain(dir, device, quick, &e)
             : strcmp(suite, "clouds") == 0 ? bench_clouds(dir, device, quick, fit, &e)
             : strcmp(suite, "denoise") == 0 ? bench_denoise(dir, device, quick, &e)
                                         : bench_atmosphere(dir, device, reference, quick, &e);
    if (rc)
        fprintf(stderr, "atmo bench: %s\n", e.msg);
    return rc;
}
