/* view_mode.c — the viewer's modes: the one place that turns the user's scene into the scene a
 * mode renders, so a new mode is one more case here. The path tracer needs none: it is the
 * scene key render.mode=path, which both modes keep (preview then path traces at half size
 * with method fast).
 *
 *   preview  method `fast` (per-frame LUTs: the quickest full image) at half the width and
 *            height, for moving around; a scene with the cloud shell or the observer sphere,
 *            which `fast` does not render (plan_cloud.c), keeps its own method.
 *   quality  the scene as given: its method, its size and its sample count, so the image the
 *            viewer converges to is the one `atmo render` of the saved scene writes.
 *
 * The draft after a change is the mode's scene at a quarter of its width and height (at least
 * 1 pixel each way) with one sample per pixel: 1/16 of the pixels, on screen within one launch. */
#include "view_mode.h"

static int at_least_one(int n) { return n > 1 ? n : 1; }

void view_mode_scene(const atmo_scene *user, int mode, atmo_scene *out)
{
    *out = *user;
    if (mode != VIEW_MODE_PREVIEW)
        return;
    out->image.width = at_least_one(user->image.width / 2);
    out->image.height = at_least_one(user->image.height / 2);
    if (!user->cloud.enabled && !user->observer.enabled)
        out->atmosphere.method = ATMO_METHOD_FAST;
}

void view_mode_draft(const atmo_scene *rendered, atmo_scene *out)
{
    *out = *rendered;
    out->image.width = at_least_one(rendered->image.width / 4);
    out->image.height = at_least_one(rendered->image.height / 4);
    out->image.samples = 1;
}

const char *view_mode_name(int mode) { return mode == VIEW_MODE_PREVIEW ? "preview" : "quality"; }
