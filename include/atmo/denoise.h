/* denoise.h — Intel Open Image Denoise 2.x (OIDN) on a linear image, loaded at run time.
 *
 * The library is not linked: atmo_denoise_load opens libOpenImageDenoise.so.2 with dlopen the
 * first time it is called, from, in this order,
 *   1. the environment variable ATMO_OIDN_LIBRARY (the library file, or the folder holding it),
 *   2. the location that setup.sh recorded when the build was configured (the PyPI wheel
 *      `pyoidn` installed under build/oidn; CMake compiles the path in),
 *   3. the dynamic linker's usual search path (LD_LIBRARY_PATH, ld.so.cache).
 * It then creates a CPU device and requires the library's version to be 2.0 or later. Every
 * feature but denoising works without the library.
 *
 * atmo_denoise_run runs OIDN's "RT" filter (the ray-tracing denoiser) on a linear HDR colour
 * image (hdr = true: values are radiance, not display values), optionally guided by an albedo
 * and a normal image. OIDN's documentation (the "RT" filter) asks for the guides as follows;
 * atmo_denoise_run passes them as given:
 *   albedo  the first hit's reflectance in [0, 1]; for rays that hit nothing (the sky) the sky's
 *           colour clamped to [0, 1] or simply 1;
 *   normal  the first hit's shading normal in any consistent space, unit length or averaged
 *           (shorter) over the pixel; for rays that hit nothing 0.
 * clean_aux tells OIDN that the guides are free of noise (no prefiltering); otherwise it
 * denoises the guides first. The device uses one thread per processor online (OIDN's
 * "numThreads"). */
#ifndef ATMO_DENOISE_H
#define ATMO_DENOISE_H
#include "atmo/status.h"

/* OIDN's filter qualities (its "quality" parameter) */
enum { ATMO_DENOISE_FAST, ATMO_DENOISE_BALANCED, ATMO_DENOISE_HIGH };

/* "fast", "balanced" or "high" */
const char *atmo_denoise_quality_name(int quality);

/* Load the library once per process (later calls return the first call's result).
 * ATMO_ERR_USAGE when no library is found (the message says where it looked and how to install
 * it); ATMO_ERR_RUNTIME when one is found but cannot be used (a missing entry point, a version
 * before 2.0, a device that fails: the message names the call and OIDN's own words). */
int atmo_denoise_load(atmo_err *e);

/* After a successful atmo_denoise_load: OIDN's version as major * 10000 + minor * 100 + patch
 * (20501 for 2.5.1), and the file it was loaded from. 0 and "" before. */
int atmo_denoise_version(void);
const char *atmo_denoise_library_path(void);

typedef struct atmo_denoise_input {
    int width, height;
    const float *color;  /* 3 floats per pixel, linear, row-major, row 0 = top */
    const float *albedo; /* 3 floats per pixel, or NULL (no guides) */
    const float *normal; /* 3 floats per pixel, or NULL; needs albedo */
    int clean_aux;       /* 1: the guides are noise-free */
    int quality;         /* ATMO_DENOISE_* */
} atmo_denoise_input;

/* Denoise in->color into out (3 floats per pixel; may not alias the inputs). Loads the library
 * if needed (atmo_denoise_load's errors). ATMO_ERR_RUNTIME names the OIDN call that failed and
 * OIDN's message. */
int atmo_denoise_run(const atmo_denoise_input *in, float *out, atmo_err *e);

#endif
