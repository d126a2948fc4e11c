/* The uniforms through which a pass knows its frame pixel and camera sample, and the lens, for the
 * distribution effects (docs/shading.md 1.3 and 1.4, docs/gpu_pipeline.md "Distribution effects"). */
#include "../../common/scramble.h"
#include "shared.h"

void bgi_gpu_pixel_at(const gpu_view *view, float out[2])
{
    /* gl_FragCoord's floor is the window's GL column and row; frame row y counts down from the top,
     * and the window's bottom GL row is its last image row, y0 + height - 1. */
    out[0] = (float)view->pixels.x0;
    out[1] = (float)(view->pixels.y0 + view->pixels.height - 1);
}

void bgi_gpu_sample_of(const gpu_view *view, float out[4])
{
    int n = view->pixels.samples, rows = bgi_sample_rows(n);
    /* The pass's sample taken k-th is sample s of the pattern: the shaders see s. */
    out[0] = (float)bgi_sample_order(n, view->pixels.sample_first);
    out[1] = (float)n;
    out[2] = (float)(n / rows);
    out[3] = (float)rows;
}

void bgi_gpu_sample_perm(const gpu_view *view, float out[4])
{
    bgi_sample_point p;
    bgi_sample_point_make(0, 0, 0, view->pixels.samples, &p);
    int k = p.perm_bits, r = k / 2;
    out[0] = (float)(1 << k);
    out[1] = (float)(k > 0 ? 1 << (k - 1) : 1);
    out[2] = (float)(1 << r);
    out[3] = (float)(1 << (k - r));
}

void bgi_gpu_lens(const bg_scene_state *state, float out[2])
{
    out[0] = (float)state->camera.camera.aperture_radius;
    out[1] = (float)state->camera.focus;
}
