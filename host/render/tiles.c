/* tiles.c — the tile scheduler (atmo/tiles.h). */
#include <stdlib.h>
#include <string.h>
#include "atmo/tiles.h"

int atmo_tiles_init(atmo_tiles *t, int width, int height, int size, atmo_err *e)
{
    memset(t, 0, sizeof *t);
    if (width < 1 || height < 1 || size < 1)
        return atmo_fail(e, ATMO_ERR_USAGE, "tiles of %d px for a %dx%d image: sizes must be > 0",
                         size, width, height);
    t->width = width;
    t->height = height;
    t->size = size;
    t->columns = (width + size - 1) / size;
    t->count = t->columns * ((height + size - 1) / size);
    t->batch = 1;
    t->samples = calloc((size_t)t->count, sizeof *t->samples);
    t->converged = calloc((size_t)t->count, 1);
    if (!t->samples || !t->converged)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for %d tiles", t->count);
    return ATMO_OK;
}

void atmo_tiles_free(atmo_tiles *t)
{
    free(t->samples);
    free(t->converged);
    memset(t, 0, sizeof *t);
}

void atmo_tiles_reset(atmo_tiles *t)
{
    memset(t->samples, 0, sizeof *t->samples * (size_t)t->count);
    memset(t->converged, 0, (size_t)t->count);
    t->cursor = 0;
}

int atmo_tiles_is_checkpoint(int n)
{
    return n >= ATMO_TILES_FIRST_CHECKPOINT && (n & (n - 1)) == 0;
}

void atmo_tiles_converge(atmo_tiles *t, int index) { t->converged[index] = 1; }

/* The first checkpoint after n samples. */
static int next_checkpoint(int n)
{
    int c = ATMO_TILES_FIRST_CHECKPOINT;
    while (c <= n && c < (1 << 30))
        c *= 2;
    return c;
}

int atmo_tiles_next(atmo_tiles *t, int target, atmo_tile *launch)
{
    for (int k = 0; k < t->count; k++) {
        int i = (t->cursor + k) % t->count;
        int remaining = target - t->samples[i];
        if (remaining <= 0 || t->converged[i])
            continue;
        if (t->checkpoints && next_checkpoint(t->samples[i]) - t->samples[i] < remaining)
            remaining = next_checkpoint(t->samples[i]) - t->samples[i];
        launch->index = i;
        launch->x = i % t->columns * t->size;
        launch->y = i / t->columns * t->size;
        launch->w = t->width - launch->x < t->size ? t->width - launch->x : t->size;
        launch->h = t->height - launch->y < t->size ? t->height - launch->y : t->size;
        launch->sample_begin = t->samples[i];
        launch->sample_count = t->batch < remaining ? t->batch : remaining;
        launch->samples = t->samples[i] + launch->sample_count;
        return 1;
    }
    return 0;
}

void atmo_tiles_done(atmo_tiles *t, atmo_tile *launch, double ms, double budget_ms, int max_batch)
{
    t->samples[launch->index] = launch->samples;
    t->cursor = (launch->index + 1) % t->count;
    if (launch->w != t->size || launch->h != t->size)
        return;
    double target = (double)launch->sample_count * budget_ms / (ms > 1e-3 ? ms : 1e-3);
    int next = target > 2.0 * t->batch ? 2 * t->batch : (int)target;
    t->batch = next < 1 ? 1 : next;
    if (max_batch > 0 && t->batch > max_batch)
        t->batch = max_batch;
}

int atmo_tiles_pixel_samples(const atmo_tiles *t, int x, int y)
{
    return t->samples[(y / t->size) * t->columns + x / t->size];
}

void atmo_tiles_range(const atmo_tiles *t, int *min, int *max)
{
    *min = t->samples[0];
    *max = t->samples[0];
    for (int i = 1; i < t->count; i++) {
        *min = t->samples[i] < *min ? t->samples[i] : *min;
        *max = t->samples[i] > *max ? t->samples[i] : *max;
    }
}
