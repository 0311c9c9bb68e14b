/* part.h — the parts of a split render: what a part holds, its file, and merging parts into the
 * image one process would render.
 *
 * A render split into N parts (`atmo render --part I/N`) renders in part I only the pixel rows
 * of its bands (atmo/tiles.h: bands of ATMO_PART_BAND_ROWS rows, band b in part b mod N + 1).
 * Every pixel's sums are built in sample order on the device, the same in whichever process
 * and with whichever tiles or launch budget, so a part holds for its pixels exactly the S1, S2
 * and sample counts of the single render (atmo/session.h), and the merge is a copy: pixel by
 * pixel from the one part that owns it, then the mean S1/n as atmo_session_read computes it.
 * (A split of the sample range could not merge bit for bit: part 2's sum starts from 0, not
 * from part 1's, and float addition is not associative.)
 *
 * A part holds only its own rows, packed top to bottom (rows = the image rows y with
 * atmo_part_of_row(y, N) = I, about height / N of them), so N parts together are one image's
 * worth of sums, on disk and in the merge's memory. A part file is an EXR of width x rows
 * pixels (atmo_image_write: PIZ, lossless, so every float reads back bit for bit) with R, G, B
 * the part's mean (a look at it), the layers S1.R/G/B and S2.R/G/B (the raw sums) and
 * Samples.N (the samples per pixel, exact in float up to 2^24 > image.samples' maximum), and
 * string attributes: atmoPart "I/N", atmoBandRows, atmoImageSize "WxH" (the whole image),
 * atmoScene (the resolved scene as JSON, atmo_scene_to_json), atmoSceneHash (16 hex digits of
 * the FNV-1a 64 hash of that text), atmoDevice (platform, device and driver: the image is
 * bitwise the single render's on the same device).
 *
 * atmo_part_merge checks, before it merges anything: every file is a part of the same scene
 * (hash, size, N, band rows), each part 1..N is there exactly once, and every part holds the
 * scene's image.samples in each of its pixels. A failed check is one
 * usage error naming the file or the part. */
#ifndef ATMO_PART_H
#define ATMO_PART_H
#include "atmo/status.h"

typedef struct atmo_part {
    int width, height;         /* of the whole image */
    int part, parts, band_rows;
    int rows;                  /* the part's rows, packed: s1, s2 hold width x rows x 3 floats */
    float *s1, *s2;            /* the sums of the samples and of their squares */
    int *samples;              /* width x rows */
    char *scene_json;          /* the resolved scene (malloc'ed) */
    unsigned long long scene_hash;
    unsigned long long input_hash; /* FNV-1a 64 of the input data the render read beyond the
                                      scene text: the heightmap's size and heights (0: none) */
    char device[656];          /* "platform / device / driver" */
} atmo_part;

/* FNV-1a 64 of the scene text. */
unsigned long long atmo_part_scene_hash(const char *scene_json);
/* FNV-1a 64 of a heightmap's size and heights as read (atmo_dem); 0 when it has none. */
unsigned long long atmo_part_input_hash(int width, int height, const float *heights_m);
/* The number of rows of part `part` of `parts` in an image `height` rows high. */
int atmo_part_row_count(int height, int part, int parts);

/* Allocate part `part` of `parts` of a width x height image (zero sums) and copy the scene
 * text; *p is zeroed first. Part 1 of 1 is the whole image. */
int atmo_part_alloc(atmo_part *p, int width, int height, int part, int parts,
                    const char *scene_json, atmo_err *e);
void atmo_part_free(atmo_part *p);
/* Copy the part's rows out of whole-image sums (width x height x 3, and x 1 for samples). */
void atmo_part_pack(atmo_part *p, const float *s1, const float *s2, const int *samples);

int atmo_part_write(const char *path, const atmo_part *p, atmo_err *e);
/* A usage error naming the file when it is not a readable atmo part. */
int atmo_part_read(const char *path, atmo_part *p, atmo_err *e);

/* Check that parts[0..n-1] (read from paths[]) are the N parts of one scene, each complete
 * (`samples` samples in every pixel), and copy each one's rows into *out, part 1 of 1. */
int atmo_part_merge(const atmo_part *parts, const char *const *paths, int n, int samples,
                    atmo_part *out, atmo_err *e);

/* The part's mean, S1 * (1/n) per channel, exactly as atmo_session_read computes it (0 where
 * n = 0); rgb holds width x rows x 3 floats. */
void atmo_part_mean(const atmo_part *p, float *rgb);

#endif
