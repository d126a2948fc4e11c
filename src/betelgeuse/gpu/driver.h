/* The driver of the GPU renderer: the entry points (bg_render_gpu, bg_render_gpu_to_texture), the
 * renderer object, tiles, the frame, samples and the plan choice. Calls go one way, entry -> tiles ->
 * frame -> (samples ->) plan choice -> a plan, and down into fused/ and multipass/ (and shared/);
 * nothing there calls back up. */
#ifndef BG_GPU_DRIVER_H
#define BG_GPU_DRIVER_H

#include "fused/fused.h"
#include "multipass/multipass.h"

/* ---- renderer.c ---- */
/* Frees every GPU object (both plans' and the shared ones) so the next render starts afresh. */
void bgi_gpu_release_all(bg_renderer *r);

/* What an entry call measures of itself: its GL work (stats.gl_work, the work since begin, whatever
 * the call did to the other statistics) and, with settings.gpu_timing, its phases (phase_clock.c).
 * settings may be NULL (not timed). end returns st, or the timers' failure. */
typedef struct gpu_entry {
    macs_work before;
} gpu_entry;
void bgi_gpu_entry_begin(bg_renderer *r, const bg_render_settings *settings, gpu_entry *e);
bg_status bgi_gpu_entry_end(bg_renderer *r, const gpu_entry *e, bg_status st);

/* ---- frame.c ---- */
/* One frame of the committed scene into out (whose arguments the entry point checked, view their
 * window and samples): progress at 0, the one pass of a single sample, or samples.c's passes,
 * progress at 1; fills the renderer's statistics. */
bg_status bgi_gpu_frame_render(bg_renderer *r, bg_scene *scene, const bg_render_settings *settings,
                               const gpu_frame_out *out, const bgi_render_view *view);

/* ---- tiles.c ---- */
/* bg_render_gpu's frame into out->image: in one piece through bgi_gpu_frame_render, or as tiles of
 * the frame when the image exceeds max_texture_size or the settings' GPU memory budget, each tile's
 * read queued while the next renders; tells settings.rows_done the bands of final rows; sets
 * stats.tiles. */
bg_status bgi_gpu_tiles_render(bg_renderer *r, bg_scene *scene, const bg_render_settings *settings,
                               const gpu_frame_out *out, const bgi_render_view *view);

/* ---- accumulate.c ---- */
/* An accumulation of width x height with no GPU objects yet (its textures are made at the first
 * samples); NULL when out of memory. */
bg_accumulation *bgi_gpu_accumulation_new(bg_renderer *r, int width, int height);
/* Whether a is of width x height. */
bool bgi_gpu_accumulation_fits(const bg_accumulation *a, int width, int height);
/* Adds samples [first, first + count) of view's pattern (checked by the caller) to a: each one pass
 * of the plan choice into a float texture, added on the GPU; progress after each but the pattern's
 * last. A failure or a cancel leaves a as it was; untouched names the caller's output in the cancel
 * message (NULL: the accumulation's own). Sums the statistics of the passes. The pixels whose walks
 * ran out: with keep_marks the sum's alpha marks them (below first + count) and r->marks_left says
 * whether any pass could; else the CPU reference's sums replace them in the sum, alpha included. */
bg_status bgi_gpu_accumulate_samples(bg_renderer *r, const bg_scene *scene, const bg_scene_state *state,
                                     const bg_render_settings *settings, const bgi_render_view *view,
                                     bg_accumulation *a, int first, int count, const char *untouched,
                                     bool keep_marks);
/* The mean of a's samples (samples > 0) as the host's RGBA8 bytes of the encoding (exact_bytes.c),
 * on the GPU: into target (RGBA8, a's size), or into a host image's pixels (rows top first, stride)
 * through a's own RGBA8 texture, one read-back of 4 bytes a pixel (parked for tiles.c while it
 * defers reads, when may_park says nothing writes the image after it: shared/read_back.c). Alpha is
 * 255, or 0 where the sum's alpha marks a pixel whose walks ran out. */
bg_status bgi_gpu_accumulation_bytes(bg_renderer *r, bg_accumulation *a, bg_output_encoding encoding,
                                     macs_texture *target);
bg_status bgi_gpu_accumulation_read_bytes(bg_renderer *r, bg_accumulation *a, bg_output_encoding encoding,
                                          unsigned char *pixels, size_t stride, bool may_park);
/* The sum of a (samples > 0) read back as float RGBA, rows top first. */
bg_status bgi_gpu_accumulation_read(bg_renderer *r, const bg_accumulation *a, float *top_down);

/* ---- exact_bytes.c ---- */
/* The state of the exact RGBA8 resolve: its thresholds texture and pass, made at the first run. */
typedef struct gpu_exact_bytes gpu_exact_bytes;
/* The host's bytes (bgi_encode_channel of sum / samples in float) of the float sum into target, an
 * RGBA8 texture of sum's size, by a GPU pass; *state is made on the first call. */
bg_status bgi_gpu_exact_bytes_run(bg_renderer *r, gpu_exact_bytes **state, macs_texture *sum, int samples,
                                  bg_output_encoding encoding, macs_texture *target);
void bgi_gpu_exact_bytes_destroy(gpu_exact_bytes *e, const bg_allocator *allocator);
/* T_k as float bits: the least non-negative float sum of n samples whose host byte is at least k
 * (1 .. 255); +inf's byte is 255. */
uint32_t bgi_gpu_exact_threshold(int k, int n, bg_output_encoding encoding);

/* ---- samples.c ---- */
/* The gpu_view of the sample view takes k-th (sample bgi_sample_order(samples, k)): that one sample,
 * and its camera shift (docs/shading.md 1.1). */
void bgi_gpu_view_for_sample(const bgi_render_view *view, int k, gpu_view *out);
/* A frame of view->samples > 1: one pass per sample, summed on the GPU in the order taken (accumulate.c),
 * read back once, divided by the count and encoded into out's image or uploaded into its texture;
 * progress after each pass, cancelling between passes leaves out untouched. */
bg_status bgi_gpu_samples_render(bg_renderer *r, const bg_scene *scene, const bg_scene_state *state,
                                 const bg_render_settings *settings, const gpu_frame_out *out,
                                 const bgi_render_view *view);
/* The mean of samples summed into sum (float RGBA, rows top first), encoded into out's image or
 * uploaded into its texture as bg_render_gpu's single pass would give it. With state, a pixel whose
 * alpha marks a run-out walk (below samples - 0.5) is the CPU reference's (bgi_gpu_fallback_sum over
 * view's samples), counted in *fallback. */
bg_status bgi_gpu_samples_write(bg_renderer *r, const bg_render_settings *settings, const gpu_frame_out *out,
                                const float *sum, int samples, const bg_scene_state *state,
                                const bgi_render_view *view, uint64_t *fallback);

/* ---- plan.c ---- */
/* One pass of the frame for r->view (one sample) by the plan the settings ask for, or under
 * BG_PLAN_AUTO the one that takes it; resets and fills the renderer's statistics. */
bg_status bgi_gpu_plan_render(bg_renderer *r, const bg_scene *scene, const bg_scene_state *state,
                              const bg_render_settings *settings, const gpu_frame_out *out);
/* Frees every plan's objects. */
void bgi_gpu_plans_release(bg_renderer *r);

#endif
