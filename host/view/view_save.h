/* view_save.h — the viewer's image and scene files (view_save.c). */
#ifndef ATMO_VIEW_SAVE_H
#define ATMO_VIEW_SAVE_H
#include "atmo/image.h"
#include "atmo/outputs.h"
#include "atmo/scene.h"
#include "atmo/status.h"

#define VIEW_PATH_MAX 4096

/* "DIR/NAME.EXT" with counter n: "DIR/NAME-NNN.EXT" for the image and "DIR/NAME-NNN.json" for
 * the scene; ATMO_ERR_USAGE if they do not fit VIEW_PATH_MAX. */
int view_save_names(const char *base, int n, char image[VIEW_PATH_MAX],
                    char scene[VIEW_PATH_MAX], atmo_err *e);
/* Write img (a render of `rendered`, samples_min samples per pixel, partial when below the
 * target) through atmo_outputs_write_denoised with the view's guides (NULL or none: the
 * colour alone): the files `atmo render` writes. */
int view_save_image(const char *path, const atmo_image *img,
                    const atmo_outputs_guides *guides, const atmo_scene *rendered,
                    int samples_min, int partial, atmo_err *e);

#endif
