/* The fused plan (BG_PLAN_FUSED): one fragment pass per frame computes the whole image, from the
 * camera ray of each pixel through every bounce to the output encoding (fused_source.c generates
 * it), where the multipass writes ray maps and a G-buffer and runs shadow, light and spawn passes
 * level by level. On llvmpipe the one pass saves what each of those passes costs whatever it
 * computes, and every G-buffer write and read: at 512x512 (medians of 7, interleaved with the
 * multipass, 2 quiet cores) paper_earth took 9.2 ms against 21.5, paper_earth_shadow 12.5 against
 * 29.5 and glass (max_depth 5) 44.4 against 651.6.
 *
 * Invariant: the program depends on the scene's structure alone (gpu_fused_layout), and its full
 * source is the cache key; values reach it as uniforms, so a re-commit that moves the camera or
 * changes a material's colour compiles nothing. Under BG_PLAN_AUTO the plan declines a frame beyond
 * the bounds below, where it was measured against the CPU reference (test_bg_gpu_plans) and against
 * the multipass, or when GL refuses the program; the driver's choice (plan.c) then renders it with
 * the multipass and says why at BG_LOG_INFO. */
#include <stdio.h>
#include <string.h>

#include "../../common/alloc.h"
#include "fused.h"

/* Bounds of BG_PLAN_AUTO, as measured on llvmpipe (2 cores shared, 512x512, medians): objects are
 * unrolled into the shader, so its compile time grows faster than their number: many_spheres with
 * 16, 32 and 64 spheres rendered in 0.46, 0.94 and 2.0 s where the multipass took 10, 13 and 45 s,
 * but its first frame, compile included, took 5.6, 19.5 and 71 s against the multipass's 13, 13
 * and 45 s. Lights beyond GPU_FUSED_UNROLLED_SHADOW_TESTS go in a loop: many_lights with 16 and 64
 * lights took 191 and 659 ms against 253 and 885 ms. A pixel's rays are bounded by what the tests
 * check: the glass tree of max_depth 5 (63 rays) by default, forced at max_depth 12 (5119 rays with
 * the default min_weight), both within the glass scene's thresholds. */
#define AUTO_MAX_OBJECTS 32
#define AUTO_MAX_LIGHTS 64
#define AUTO_MAX_RAYS 1023.0
/* The fewest walk steps per pixel the tree variant runs with: below, most pixels of an ordinary
 * scene would go to the CPU reference. */
#define MIN_WALK_BUDGET 1024

struct gpu_fused {
    char *key;     /* the cached program's source and declarations: its structure */
    char *refused; /* the last key GL refused; BG_PLAN_AUTO does not try it again */
    macs_pass *pass;
    gpu_fused_layout layout; /* of the cached pass */
    int width, height;       /* of the pass and its outputs */
    macs_texture *out_bytes, *out_float;
    gpu_tree_textures tree;  /* the tree variant's textures (tree_textures.c) */
    gpu_marks marks;         /* the marks of a one-sample texture frame's short walks (shared/fallback.c) */
    gpu_primary *primary;    /* the camera rays' rasterised first hits (primary.c); NULL until used */
};

/* ---- what the fused plan can render ---- */

/* The program's textures: the scene's, then the object tree's two where it walks one, then the
 * meshes', the environment's tables and the sRGB table (bind_frame sets them in this order). */
static int input_count(const gpu_fused_layout *l)
{
    return l->sampler_count + (bgi_gpu_fused_layout_walks(l) ? 2 : 0) + (l->mesh ? 2 : 0) + (l->env_importance ? 2 : 0) +
           (l->srgb ? 1 : 0) + (l->primary ? 1 : 0);
}

static int mesh_input(const gpu_fused_layout *l)
{
    return l->sampler_count + (bgi_gpu_fused_layout_walks(l) ? 2 : 0);
}

/* The environment's tables come after the meshes' textures. */
static int env_input(const gpu_fused_layout *l)
{
    return mesh_input(l) + (l->mesh ? 2 : 0);
}

/* The sRGB table is the last but the primary visibility map. */
static int srgb_input(const gpu_fused_layout *l)
{
    return env_input(l) + (l->env_importance ? 2 : 0);
}

static int primary_input(const gpu_fused_layout *l)
{
    return srgb_input(l) + (l->srgb ? 1 : 0);
}

/* False with the reason when the layout is beyond the GL limits or, for BG_PLAN_AUTO, beyond the
 * bounds the fused plan was measured within. */
static bool fits(const bg_renderer *r, const bg_scene_state *state, const gpu_fused_layout *l, bool forced, char *why,
                 size_t size)
{
    int comps = bgi_gpu_fused_uniform_components(l), budget = macs_context_max_uniform_components(r->ctx);
    int units = input_count(l);
    if (l->tree && !bgi_gpu_tree_textures_fit(r, state, why, size))
        return false;
    if (!l->tree && !bgi_gpu_meshes_fit(r, state, why, size))
        return false;
    if (bgi_gpu_fused_layout_budgeted(l) && l->walk_budget < MIN_WALK_BUDGET)
        snprintf(why, size, "%.0f rays per pixel with %u lights leave the tree walks %d loop steps, fewer than %d",
                 (double)l->loop_rays, l->light_count, l->walk_budget, MIN_WALK_BUDGET);
    else if (l->rays_needed > l->loop_rays)
        snprintf(why, size, "a pixel may follow up to %.0f rays at max_depth %d (min_weight counted), more than "
                 "the %d the fused shader's loop may run", l->rays_needed, l->max_depth, l->loop_rays);
    else if (comps > budget)
        snprintf(why, size, "the fused shader needs %d uniform components, GL allows %d", comps, budget);
    else if (units > r->limits.max_texture_units)
        snprintf(why, size, "the fused shader samples %d textures, GL has %d texture units", units,
                 r->limits.max_texture_units);
    else if (!forced && l->unrolled_count > AUTO_MAX_OBJECTS)
        snprintf(why, size, "%u objects outside the object tree, more than the %d the fused plan unrolls",
                 l->unrolled_count, AUTO_MAX_OBJECTS);
    else if (!forced && l->light_count > AUTO_MAX_LIGHTS)
        snprintf(why, size, "%u lights, more than the %d the fused plan was measured with", l->light_count,
                 AUTO_MAX_LIGHTS);
    else if (!forced && l->rays_needed > AUTO_MAX_RAYS)
        snprintf(why, size, "a pixel may follow up to %.0f rays, more than the %.0f the fused plan was measured with",
                 l->rays_needed, AUTO_MAX_RAYS);
    else
        return true;
    return false;
}

/* ---- the pass ---- */

static void outputs_release(struct gpu_fused *f)
{
    macs_texture_destroy(f->out_bytes);
    macs_texture_destroy(f->out_float);
    f->out_bytes = f->out_float = NULL;
}

/* The texture the pass writes: the caller's target, or the renderer's own of the image's format
 * and size, read back afterwards (the pass writes either format). */
static bg_status output_for(bg_renderer *r, struct gpu_fused *f, const gpu_frame_out *o, macs_texture **out)
{
    *out = NULL;
    if (o->texture) {
        *out = o->texture;
        return BG_OK;
    }
    macs_texture **slot = o->as_float ? &f->out_float : &f->out_bytes;
    bg_status st = bgi_gpu_texture_ensure(r, o->width, o->height, o->as_float ? MACS_FORMAT_RGBA32F : MACS_FORMAT_RGBA8,
                                      slot, "fused plan: output texture");
    if (st == BG_OK)
        *out = *slot;
    return st;
}

/* The source text, with the uniforms and samplers it is declared with: the key of the program. */
typedef struct program_text {
    gpu_text functions, main, key;
    const char *output;
    macs_uniform_desc *uniforms;
    char *uniform_names;
    int uniform_count;
} program_text;

static void program_text_free(bg_renderer *r, program_text *p)
{
    bgi_gpu_text_free(&p->functions);
    bgi_gpu_text_free(&p->main);
    bgi_gpu_text_free(&p->key);
    bgi_gpu_fused_uniforms_free(&r->allocator, p->uniforms, p->uniform_names);
    p->uniforms = NULL;
    p->uniform_names = NULL;
}

static bg_status program_text_make(bg_renderer *r, const gpu_fused_layout *l, program_text *p)
{
    memset(p, 0, sizeof *p);
    bgi_gpu_text_init(&p->functions, &r->allocator);
    bgi_gpu_text_init(&p->main, &r->allocator);
    bgi_gpu_text_init(&p->key, &r->allocator);
    if (!bgi_gpu_fused_source(l, &p->functions, &p->main, &p->output))
        return p->functions.failed || p->main.failed
                   ? bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory building the fused shader")
                   : bgi_gpu_fail(r, BG_ERR_GL, "fused shader: a glsl110/ file is missing");
    if (!bgi_gpu_fused_uniforms_declare(&r->allocator, l, &p->uniforms, &p->uniform_count, &p->uniform_names))
        return bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory declaring the fused uniforms");
    bgi_gpu_text_append(&p->key, p->functions.s);
    bgi_gpu_text_append(&p->key, p->main.s);
    bgi_gpu_text_printf(&p->key, "// out %s, samplers %d\n", p->output, l->sampler_count);
    for (int i = 0; i < p->uniform_count; i++)
        bgi_gpu_text_printf(&p->key, "// uniform %s %d %d\n", p->uniforms[i].name, (int)p->uniforms[i].type,
                        p->uniforms[i].count);
    if (p->key.failed)
        return bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory building the fused shader");
    return BG_OK;
}

/* Creates the pass of the program text for outputs of out's size. With trial (BG_PLAN_AUTO), a
 * program GL refuses is not an error: *refused gets the reason and the MACS error is forgotten. */
static bg_status pass_create(bg_renderer *r, const gpu_fused_layout *l, program_text *p, macs_texture *out, bool trial,
                             macs_pass **pass, char *refused, size_t refused_size)
{
    enum { NAME = 24 }; /* "bg_tex" and any int */
    int n = input_count(l);
    macs_input_desc *inputs = bgi_alloc(&r->allocator, (size_t)(n ? n : 1) * (sizeof *inputs + NAME));
    if (!inputs)
        return bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory creating the fused pass");
    char *names = (char *)(inputs + (n ? n : 1));
    for (int k = 0; k < l->sampler_count; k++) {
        snprintf(names + k * NAME, NAME, "bg_tex%d", k);
        inputs[k].name = names + k * NAME;
    }
    if (bgi_gpu_fused_layout_walks(l)) {
        inputs[l->sampler_count].name = "bg_nodes";
        inputs[l->sampler_count + 1].name = "bg_objects";
    }
    if (l->mesh) {
        inputs[mesh_input(l)].name = "bg_mesh_nodes";
        inputs[mesh_input(l) + 1].name = "bg_mesh_tris";
    }
    if (l->env_importance) {
        inputs[env_input(l)].name = "bg_env_marginal";
        inputs[env_input(l) + 1].name = "bg_env_conditional";
    }
    if (l->srgb)
        inputs[srgb_input(l)].name = "bg_srgb_table";
    if (l->primary)
        inputs[primary_input(l)].name = "bg_primary";
    macs_output_desc output = {"radiance", p->output};
    macs_texture *outs[1] = {out};
    macs_pass_desc desc;
    bgi_gpu_pass_desc_init(&desc, p->main.s, inputs, NULL, n, p->uniforms, p->uniform_count, &output, outs, 1);
    desc.functions = p->functions.s;
    macs_status ms;
    char why[MACS_MESSAGE_SIZE / 2]; /* GL's message, leaving room for the words around it in refused */
    bg_status st = bgi_gpu_pass_create_trial(r, trial ? "fused pass" : "fused pass (BG_PLAN_FUSED)", &desc, trial, pass,
                                         &ms, why, sizeof why);
    bgi_free(&r->allocator, inputs);
    if (st == BG_OK && ms != MACS_OK)
        snprintf(refused, refused_size, "GL refused the fused program (%s): %s", macs_status_string(ms), why);
    return st;
}

/* The frame's layout replaces the cached one: one program serves layouts that differ in what the
 * program does not hold (which objects the tree has, and the indices of the others), and the
 * uniforms and textures of the frame follow its own. */
static void adopt_layout(bg_renderer *r, struct gpu_fused *f, gpu_fused_layout *l)
{
    bgi_gpu_fused_layout_free(&r->allocator, &f->layout);
    f->layout = *l;
    memset(l, 0, sizeof *l); /* the cache owns its arrays now */
}

/* Makes f->pass the program of p at w x h, reusing the cached one when its key is the same. A size
 * change alone makes a pass of the same program, which MACS's program cache hands over while the
 * old pass still holds it: nothing is compiled. Under BG_PLAN_AUTO a program GL refused declines the
 * frame: BG_OK with the reason in why. */
static bg_status pass_prepare(bg_renderer *r, struct gpu_fused *f, gpu_fused_layout *l, program_text *p,
                              const gpu_frame_out *o, bool forced, char *why, size_t why_size)
{
    int w = o->width, h = o->height;
    bool same = f->pass && f->key && strcmp(f->key, p->key.s) == 0;
    if (same && f->width == w && f->height == h) {
        adopt_layout(r, f, l);
        return BG_OK;
    }
    if (!forced && f->refused && strcmp(f->refused, p->key.s) == 0) {
        snprintf(why, why_size, "GL refused the fused program for this scene before");
        return BG_OK;
    }
    if (f->width != w || f->height != h)
        outputs_release(f);
    macs_texture *out = NULL;
    bg_status st = output_for(r, f, o, &out);
    if (st != BG_OK)
        return st;
    macs_pass *pass = NULL;
    st = pass_create(r, l, p, out, !forced, &pass, why, why_size);
    if (st != BG_OK)
        return st;
    if (!pass) {
        bgi_free(&r->allocator, f->refused);
        f->refused = bgi_strdup(&r->allocator, p->key.s);
        return BG_OK;
    }
    macs_pass_destroy(f->pass);
    f->pass = pass;
    f->width = w;
    f->height = h;
    if (!same) {
        char *key = bgi_strdup(&r->allocator, p->key.s);
        if (!key)
            return bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory caching the fused program");
        bgi_free(&r->allocator, f->key);
        f->key = key;
    }
    adopt_layout(r, f, l);
    return BG_OK;
}

/* ---- one frame ---- */

/* Binds the frame's textures and output to the cached pass and sets every uniform; *out gets the
 * output texture. */
static bg_status bind_frame(bg_renderer *r, const bg_scene_state *state, const bg_render_settings *settings,
                            const gpu_frame_out *o, macs_texture **out)
{
    struct gpu_fused *f = r->fused;
    const gpu_fused_layout *l = &f->layout;
    bool walks = bgi_gpu_fused_layout_walks(l);
    bg_status st = bgi_gpu_scene_textures_prepare(r, state);
    /* The meshes first: the tree's objects texture holds their bases. */
    if (st == BG_OK && (walks || l->mesh))
        st = bgi_gpu_meshes_prepare(r, state);
    if (st == BG_OK && walks)
        st = bgi_gpu_tree_textures_prepare(r, &f->tree, state);
    if (st == BG_OK && l->env_importance)
        st = bgi_gpu_env_tables_prepare(r, state);
    if (st == BG_OK)
        st = output_for(r, f, o, out);
    if (st != BG_OK)
        return st;
    macs_status ms = MACS_OK;
    for (int k = 0; k < l->sampler_count && !ms; k++)
        ms = macs_pass_set_input(f->pass, k, r->scene_textures.texture[l->samplers[k] - 1]);
    if (!ms && walks)
        ms = macs_pass_set_input(f->pass, l->sampler_count, f->tree.nodes.texture);
    if (!ms && walks)
        ms = macs_pass_set_input(f->pass, l->sampler_count + 1, f->tree.objects.texture);
    if (!ms && l->mesh)
        ms = macs_pass_set_input(f->pass, mesh_input(l), r->meshes.nodes);
    if (!ms && l->mesh)
        ms = macs_pass_set_input(f->pass, mesh_input(l) + 1, r->meshes.triangles);
    if (!ms && l->env_importance)
        ms = macs_pass_set_input(f->pass, env_input(l), r->env_tables.marginal);
    if (!ms && l->env_importance)
        ms = macs_pass_set_input(f->pass, env_input(l) + 1, r->env_tables.conditional);
    if (!ms && l->srgb)
        ms = macs_pass_set_input(f->pass, srgb_input(l), r->scene_textures.srgb_table);
    if (!ms)
        ms = macs_pass_set_output(f->pass, 0, *out);
    if (ms)
        return bgi_gpu_fail_macs(r, ms, "binding the fused pass");
    gpu_fused_values v = {state, settings, l->tree ? &f->tree.dims : NULL, &r->meshes,
                          o->width, o->height, o->as_float, &r->view};
    return bgi_gpu_fused_uniforms_set(r, f->pass, l, &v);
}

/* The camera rays' first hits drawn into the map the pass reads (primary.c), as part of its
 * intersection phase. */
static bg_status primary_map(bg_renderer *r, const bg_scene_state *state, const gpu_frame_out *o)
{
    struct gpu_fused *f = r->fused;
    macs_texture *map = NULL;
    bg_status st = bgi_gpu_primary_draw(r, &f->primary, &f->layout, state, &f->tree, o->width, o->height, &map);
    if (st != BG_OK)
        return st;
    macs_status ms = macs_pass_set_input(f->pass, primary_input(&f->layout), map);
    return ms ? bgi_gpu_fail_macs(r, ms, "binding the primary visibility map") : BG_OK;
}

/* One pass did everything; it counts as the intersection pass it starts with. */
static void frame_stats(bg_renderer *r, const bg_scene_state *state, const gpu_frame_out *o)
{
    r->stats.passes[state->object_count ? BG_PASS_INTERSECT : BG_PASS_BACKGROUND] = 1;
    r->stats.chunks = macs_pass_chunk_count(r->fused->pass);
    r->stats.intersect_objects = (int)state->object_count;
    r->stats.intersect_pixels = (uint64_t)o->width * (uint64_t)o->height;
    r->stats.primary_raster = r->fused->layout.primary;
}

/* The frame's end: the image read back, or the texture as the pass left it. Either way the pixels
 * the tree walks marked are then rendered by the CPU reference (tree_textures.c, shared/fallback.c),
 * but for a pass of several samples, whose marks the sum keeps (accumulate.c). */
static bg_status finish(bg_renderer *r, const bg_scene_state *state, const bg_render_settings *settings,
                        const gpu_frame_out *o, macs_texture *out)
{
    bool walks = bgi_gpu_fused_layout_budgeted(&r->fused->layout);
    if (o->texture && walks && r->marks_deferred) {
        /* One of several samples: the sum's alpha keeps the marks for the sum's end (accumulate.c). */
        r->marks_left = true;
        return BG_OK;
    }
    if (o->texture)
        return walks ? bgi_gpu_fallback_texture(r, &r->fused->marks, state, settings, &r->view.pixels, o->texture,
                                                &r->stats.fallback_pixels)
                     : BG_OK;
    /* Without walks the read is the frame's last write (tiles.c may defer it); with them the CPU's
     * pixels go in after it. */
    if (!walks)
        return bgi_gpu_read_back_last(r, out, o->image, o->stride, true);
    bg_status st = bgi_gpu_read_back(r, out, o->image, o->stride, false);
    if (st == BG_OK)
        r->stats.fallback_pixels = bgi_gpu_fallback_image(state, settings, &r->view.pixels, o->image, o->stride);
    return st;
}

/* Everything after the layout: the program, the frame's inputs, the pass, the frame's end; BG_OK
 * with why set when GL refused the program under BG_PLAN_AUTO. */
static bg_status render(bg_renderer *r, const bg_scene_state *state, const bg_render_settings *settings,
                        const gpu_frame_out *o, gpu_fused_layout *l, bool forced, char *why, size_t why_size)
{
    bgi_gpu_phase_start(r);
    program_text p;
    bg_status st = program_text_make(r, l, &p);
    if (st == BG_OK)
        st = pass_prepare(r, r->fused, l, &p, o, forced, why, why_size);
    program_text_free(r, &p);
    if (st != BG_OK || why[0])
        return st;
    macs_texture *out = NULL;
    st = bind_frame(r, state, settings, o, &out);
    bgi_gpu_phase_end(r, BG_PHASE_SETUP);
    if (st == BG_OK && r->fused->layout.primary)
        st = primary_map(r, state, o);
    if (st == BG_OK) {
        macs_status ms = macs_pass_run(r->fused->pass, NULL);
        if (ms)
            st = bgi_gpu_fail_macs(r, ms, "running the fused pass");
    }
    bgi_gpu_phase_end(r, BG_PHASE_INTERSECT);
    if (st == BG_OK)
        st = finish(r, state, settings, o, out);
    bgi_gpu_phase_end(r, BG_PHASE_RESOLVE);
    if (st != BG_OK)
        return st;
    frame_stats(r, state, o);
    return BG_OK;
}

/* Whether the frame's camera rays take their tree hits from the rasterised map (settings.primary):
 * BG_PRIMARY_RASTER where the layout and GL allow it (else an error saying why), BG_PRIMARY_AUTO
 * where it also pays (primary.c). */
static bg_status primary_choose(bg_renderer *r, const gpu_plan_frame *f, gpu_fused_layout *l)
{
    l->primary = false;
    bg_primary_visibility asked = f->settings->primary;
    if (asked == BG_PRIMARY_WALK || (asked == BG_PRIMARY_AUTO && !l->tree))
        return BG_OK;
    char why[256];
    if (!bgi_gpu_primary_supported(r, l, why, sizeof why))
        return asked == BG_PRIMARY_RASTER
                   ? bgi_gpu_fail(r, BG_ERR_LIMIT, "settings.primary is BG_PRIMARY_RASTER, but %s", why)
                   : BG_OK;
    l->primary = asked == BG_PRIMARY_RASTER ||
                 bgi_gpu_primary_pays(f->state, l, (uint64_t)f->out->width * (uint64_t)f->out->height);
    return BG_OK;
}

/* One pass of the fused plan, unrolled or (tree) with the object tree walked from textures. */
static bg_status render_variant(bg_renderer *r, const gpu_plan_frame *f, bool tree, char *why, size_t why_size)
{
    why[0] = '\0';
    if (!r->fused) {
        r->fused = bgi_alloc(&r->allocator, sizeof *r->fused);
        if (!r->fused)
            return bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory for the fused plan");
        memset(r->fused, 0, sizeof *r->fused);
    }
    gpu_fused_layout l;
    if (!bgi_gpu_fused_layout_build(&r->allocator, f->state, f->settings, tree, bgi_gpu_srgb_table(r), &l))
        return bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory for the fused plan's layout");
    bg_status st = primary_choose(r, f, &l);
    if (st == BG_OK && fits(r, f->state, &l, f->forced, why, why_size)) {
        why[0] = '\0';
        st = render(r, f->state, f->settings, f->out, &l, f->forced, why, why_size);
    }
    bgi_gpu_fused_layout_free(&r->allocator, &l);
    if (st != BG_OK) {
        /* Start the next render from nothing: a failure may have left any object half made. */
        bgi_gpu_fused_release(r);
    }
    return st;
}

static bg_status render_unrolled(bg_renderer *r, const gpu_plan_frame *f, char *why, size_t why_size)
{
    return render_variant(r, f, false, why, why_size);
}

static bg_status render_tree(bg_renderer *r, const gpu_plan_frame *f, char *why, size_t why_size)
{
    return render_variant(r, f, true, why, why_size);
}

const gpu_plan bgi_gpu_fused_plan = {BG_PLAN_FUSED, "BG_PLAN_FUSED", render_unrolled, bgi_gpu_fused_release};
const gpu_plan bgi_gpu_fused_tree_plan = {BG_PLAN_FUSED_TREE, "BG_PLAN_FUSED_TREE", render_tree, bgi_gpu_fused_release};

void bgi_gpu_fused_release(bg_renderer *r)
{
    struct gpu_fused *f = r->fused;
    if (!f)
        return;
    macs_pass_destroy(f->pass);
    outputs_release(f);
    bgi_gpu_tree_textures_release(&r->allocator, &f->tree);
    bgi_gpu_marks_release(&f->marks);
    bgi_gpu_primary_release(&r->allocator, &f->primary);
    bgi_gpu_fused_layout_free(&r->allocator, &f->layout);
    bgi_free(&r->allocator, f->key);
    bgi_free(&r->allocator, f->refused);
    bgi_free(&r->allocator, f);
    r->fused = NULL;
}
