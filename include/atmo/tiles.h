/* tiles.h — the tile scheduler of a render session: which tile gets the next launch, and how
 * many samples.
 *
 * The image is cut into square tiles of one size (the last column and row partial). Samples are
 * added in round-robin passes over the tiles: the next launch goes to the first tile at or after
 * the cursor that has fewer samples than the target, so every tile gets a batch before any gets
 * a second. The batch (samples per launch) adapts so that a launch of a full tile takes about
 * the launch budget: after each full-tile launch of c samples that took m ms it becomes
 * c * budget / m, at most doubled and at least 1 (edge tiles are cheaper and would overshoot,
 * so their timings are not used). The scheduler holds the per-tile sample counts; it never
 * touches the device, so the split of samples into launches is its only effect on the image,
 * and the kernel makes that split invisible (sums in sample order).
 *
 * Noise target (the progressive mode): a tile can be marked converged (atmo_tiles_converge)
 * and then gets no more launches whatever the target. So that the decision does not depend on
 * the batches, the caller asks it only at checkpoints, the sample counts 2^k >= 16
 * (ATMO_TILES_FIRST_CHECKPOINT), and with `checkpoints` set the scheduler ends every launch at
 * or before the tile's next checkpoint: a tile is then judged on the same sums whatever the
 * tile size or launch budget, and a noise-targeted image is as deterministic as any other. */
#ifndef ATMO_TILES_H
#define ATMO_TILES_H
#include "atmo/status.h"

/* One launch, or a finished one as the session's tile callback sees it. */
typedef struct atmo_tile {
    int index;          /* tile number, row-major */
    int x, y, w, h;     /* rectangle in pixels, row 0 = top */
    int sample_begin;   /* first sample index of the launch */
    int sample_count;   /* samples in the launch */
    int samples;        /* samples per pixel the tile has once the launch is done */
} atmo_tile;

typedef struct atmo_tiles {
    int width, height, size;
    int columns, count;
    int *samples;       /* per tile */
    int cursor;         /* where the next search starts */
    int batch;          /* samples per launch, adapted */
    unsigned char *converged; /* per tile: 1 once its noise target is met */
    int checkpoints;    /* 1: launches end at the checkpoints (noise target) */
} atmo_tiles;

#define ATMO_TILES_FIRST_CHECKPOINT 16

/* 1 when n samples is a checkpoint: a power of two >= ATMO_TILES_FIRST_CHECKPOINT. */
int atmo_tiles_is_checkpoint(int n);
/* Mark tile `index` converged: no more launches for it until atmo_tiles_reset. */
void atmo_tiles_converge(atmo_tiles *t, int index);

int atmo_tiles_init(atmo_tiles *t, int width, int height, int size, atmo_err *e);
void atmo_tiles_free(atmo_tiles *t);
/* Every tile back to 0 samples, not converged, and the cursor to tile 0 (the adapted batch
 * stays). */
void atmo_tiles_reset(atmo_tiles *t);
/* The next launch towards `target` samples per pixel; 0 when every tile has them or has
 * converged. */
int atmo_tiles_next(atmo_tiles *t, int target, atmo_tile *launch);
/* Record a finished launch that took ms milliseconds; adapt the batch to budget_ms (at most
 * max_batch when max_batch > 0). */
void atmo_tiles_done(atmo_tiles *t, atmo_tile *launch, double ms, double budget_ms, int max_batch);
/* Samples of the tile that holds pixel (x, y). */
int atmo_tiles_pixel_samples(const atmo_tiles *t, int x, int y);
/* Fewest and most samples over the tiles. */
void atmo_tiles_range(const atmo_tiles *t, int *min, int *max);

#endif
