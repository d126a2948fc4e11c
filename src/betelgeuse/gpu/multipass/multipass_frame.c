/* One frame of the multipass plan (docs/gpu_pipeline.md): camera rays, then ray sets traced
 * depth-first from the CPU. Each set is intersected batch by batch (batch.c) into the G-buffer, shaded
 * (background, shadows, lights, ambient and emission into the accumulation texture) and spawns at
 * most two child sets (reflected, transmitted). A child's live rays are marked in the stencil and
 * counted by an occlusion query; a set with none is never traced. Depth-first order keeps at most
 * max_depth + 2 sets alive at once. */
#include <string.h>

#include "../../common/alloc.h"
#include "multipass.h"

/* Counts pending at once; one more reads the oldest first. A frame has a light pass per light group
 * and a shadow pass per batch of each, so this is rarely reached. */
#define COUNTED_MAX 32

typedef struct frame {
    bg_renderer *r;
    const bg_scene_state *state;
    const bg_render_settings *settings;
    double dmax[BG_MAX_DEPTH + 1];
    bool timing;
    /* Shadow and light passes whose kept fragments are counted but not yet read (timing): read when
     * the pass runs again or after the frame's end, so that counting waits as little as it can. */
    macs_pass *counted[COUNTED_MAX];
    int counted_count;
    /* Secondary rays only live on pixels whose camera ray met an object that can bounce: the union
     * of those objects' screen rectangles bounds every secondary set (a pixel's rays stay its own). */
    bool bounce_scissor;
    int bounce_rect[4];
} frame;

static void phase_start(frame *f)
{
    bgi_gpu_phase_start(f->r);
}

static void phase_end(frame *f, bg_phase phase)
{
    bgi_gpu_phase_end(f->r, phase);
}

static bg_status run(frame *f, macs_pass *pass, bg_pass_kind kind, const macs_run_desc *desc)
{
    bg_renderer *r = f->r;
    macs_status ms = macs_pass_run(pass, desc);
    if (ms)
        return bgi_gpu_fail_macs(r, ms, "running a pass");
    r->stats.passes[kind]++;
    r->stats.chunks += macs_pass_chunk_count(pass);
    return BG_OK;
}

/* The run description of a pass over ray set `level`: scissored to the bounce rectangle below 0. */
static macs_run_desc set_run(const frame *f, int level)
{
    macs_run_desc d;
    memset(&d, 0, sizeof d);
    if (level > 0 && f->bounce_scissor) {
        d.scissor = true;
        d.scissor_x = f->bounce_rect[0];
        d.scissor_y = f->bounce_rect[1];
        d.scissor_width = f->bounce_rect[2];
        d.scissor_height = f->bounce_rect[3];
    }
    return d;
}

static void bounce_scissor(frame *f)
{
    const bg_scene_state *state = f->state;
    bg_renderer *r = f->r;
    f->bounce_scissor = !(r->multipass->key.disable_skips & BG_SKIP_SCISSOR);
    memset(f->bounce_rect, 0, sizeof f->bounce_rect);
    for (uint32_t o = 0; o < state->object_count && f->bounce_scissor; o++) {
        if (!bgi_gpu_material_may_bounce(&state->materials[state->objects[o].material]))
            continue;
        int rect[4];
        if (!bgi_gpu_object_scissor(state, o, &r->view, rect)) {
            f->bounce_scissor = false;
            break;
        }
        bgi_gpu_rect_union(f->bounce_rect, rect);
    }
}

/* Adds the kept fragments of counted pass i to the statistics (a query read: waits for that run). */
static bg_status count_read(frame *f, int i)
{
    uint64_t n = 0;
    macs_status ms = macs_pass_occlusion_result(f->counted[i], &n);
    if (ms)
        return bgi_gpu_fail_macs(f->r, ms, "fragment count");
    f->r->stats.shaded_fragments += n;
    f->counted[i] = f->counted[--f->counted_count];
    return BG_OK;
}

/* Reads every count still pending: after the frame's end, whose read-back has waited for them. */
static bg_status count_read_all(frame *f)
{
    bg_status st = BG_OK;
    while (f->counted_count > 0 && st == BG_OK)
        st = count_read(f, f->counted_count - 1);
    return st;
}

/* Runs a shadow or light pass, counting its kept fragments when timing. A pass's count is read
 * before its next run (a query holds one run's); the last ones after the frame. */
static bg_status run_counted(frame *f, macs_pass *pass, bg_pass_kind kind, int level)
{
    macs_run_desc d = set_run(f, level);
    d.occlusion_query = f->timing;
    bg_status st = BG_OK;
    for (int i = 0; i < f->counted_count && st == BG_OK && f->timing; i++)
        if (f->counted[i] == pass)
            st = count_read(f, i);
    if (st == BG_OK && f->timing && f->counted_count == COUNTED_MAX)
        st = count_read(f, 0);
    if (st == BG_OK)
        st = run(f, pass, kind, &d);
    if (st == BG_OK && f->timing)
        f->counted[f->counted_count++] = pass;
    return st;
}

static bg_status bind(bg_renderer *r, macs_pass *pass, int index, macs_texture *t)
{
    macs_status ms = macs_pass_set_input(pass, index, t);
    return ms ? bgi_gpu_fail_macs(r, ms, "binding a ray map") : BG_OK;
}

static bg_status intersect(frame *f, const gpu_ray_set *set, int level)
{
    bg_renderer *r = f->r;
    bool scissor = level == 0 && !(r->multipass->key.disable_skips & BG_SKIP_SCISSOR);
    for (int b = 0; b < r->multipass->passes.hit_count; b++) {
        const gpu_batch *batch = &r->multipass->passes.hit[b];
        macs_pass *p = batch->pass;
        bg_status st = bind(r, p, GPU_HIT_IN_ORIGIN, set->origin);
        if (st == BG_OK)
            st = bind(r, p, GPU_HIT_IN_DIR, set->dir);
        if (st == BG_OK)
            st = bind(r, p, GPU_HIT_IN_WEIGHT, set->weight);
        if (st == BG_OK)
            st = bgi_gpu_hit_pass_set_dmax(r, p, f->dmax[level]);
        if (st != BG_OK)
            return st;
        macs_run_desc d = set_run(f, level);
        int rect[4];
        if (scissor && bgi_gpu_batch_scissor(f->state, batch, &r->view, rect)) {
            if (rect[2] == 0 || rect[3] == 0)
                continue; /* entirely off screen */
            d.scissor = true;
            d.scissor_x = rect[0];
            d.scissor_y = rect[1];
            d.scissor_width = rect[2];
            d.scissor_height = rect[3];
            r->stats.intersect_pixels += (uint64_t)rect[2] * (uint64_t)rect[3];
        } else if (d.scissor) {
            r->stats.intersect_pixels += (uint64_t)d.scissor_width * (uint64_t)d.scissor_height;
        } else {
            r->stats.intersect_pixels += (uint64_t)r->multipass->width * (uint64_t)r->multipass->height;
        }
        st = run(f, p, BG_PASS_INTERSECT, &d);
        if (st != BG_OK)
            return st;
        r->stats.intersect_objects += batch->count;
    }
    return BG_OK;
}

static bg_status shade(frame *f, const gpu_ray_set *set, int level)
{
    macs_run_desc d = set_run(f, level);
    bg_renderer *r = f->r;
    gpu_passes *p = &r->multipass->passes;
    bg_status st = BG_OK;
    phase_start(f);
    if (p->background) {
        st = bind(r, p->background, GPU_BACKGROUND_IN_WEIGHT, set->weight);
        if (st == BG_OK)
            st = run(f, p->background, BG_PASS_BACKGROUND, &d);
    }
    if (st == BG_OK && p->once)
        st = run(f, p->once, BG_PASS_LIGHT, &d);
    phase_end(f, BG_PHASE_LIGHT);
    static const float one[4] = {1.0f, 1.0f, 1.0f, 1.0f};
    for (int g = 0; g < p->group_count && st == BG_OK; g++) {
        phase_start(f);
        bool cleared = false;
        for (int b = 0; b < p->shadow_count && st == BG_OK; b++) {
            if (p->shadow[b].group != g)
                continue;
            macs_pass *sp = p->shadow[b].pass;
            if (!cleared) {
                macs_status ms = macs_texture_clear(r->multipass->vis, one);
                if (ms)
                    return bgi_gpu_fail_macs(r, ms, "clearing visibility");
                cleared = true;
            }
            st = run_counted(f, sp, BG_PASS_SHADOW, level);
            r->stats.shadow_objects += p->shadow[b].count;
        }
        phase_end(f, BG_PHASE_SHADOW);
        if (st != BG_OK)
            break;
        phase_start(f);
        macs_pass *lp = p->light[g];
        st = bind(r, lp, GPU_LIGHT_IN_DIR, set->dir);
        if (st == BG_OK && !r->multipass->features.slot[GPU_SLOT_XPARENT])
            st = bind(r, lp, GPU_LIGHT_IN_WEIGHT, set->weight);
        if (st == BG_OK)
            st = run_counted(f, lp, BG_PASS_LIGHT, level);
        phase_end(f, BG_PHASE_LIGHT);
    }
    return st;
}

/* Writes one child set of `set` with a spawn pass; the child's rays are counted when it is traced. */
static bg_status spawn(frame *f, macs_pass *pass, const gpu_ray_set *set, gpu_ray_set *child, int level)
{
    bg_renderer *r = f->r;
    static const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    /* Pixels the spawn does not write (missed or dead in the parent) must read as dead, and with the
     * stencil skip off they are traced too, so they need a ray that meets nothing: d = 0. */
    macs_status ms = macs_texture_clear(child->weight, zero);
    if (!ms && (r->multipass->key.disable_skips & BG_SKIP_STENCIL)) {
        ms = macs_texture_clear(child->origin, zero);
        if (!ms)
            ms = macs_texture_clear(child->dir, zero);
    }
    /* Unbind the previous set first: MACS refuses a texture that is input and output at once. */
    if (!ms)
        ms = macs_pass_set_input(pass, GPU_SPAWN_IN_DIR, NULL);
    if (!ms)
        ms = macs_pass_set_input(pass, GPU_SPAWN_IN_WEIGHT, NULL);
    if (!ms)
        ms = macs_pass_set_output(pass, 0, child->origin);
    if (!ms)
        ms = macs_pass_set_output(pass, 1, child->dir);
    if (!ms)
        ms = macs_pass_set_output(pass, 2, child->weight);
    if (ms)
        return bgi_gpu_fail_macs(r, ms, "preparing a child ray set");
    /* The glossy lobe's dimension follows the parent's level (docs/shading.md 1.3). */
    if (pass == r->multipass->passes.reflect && r->multipass->features.glossy) {
        float lv = (float)level;
        ms = macs_pass_set_uniform(pass, "bg_level", &lv);
        if (ms)
            return bgi_gpu_fail_macs(r, ms, "the reflection pass's level");
    }
    bg_status st = bind(r, pass, GPU_SPAWN_IN_DIR, set->dir);
    if (st == BG_OK)
        st = bind(r, pass, GPU_SPAWN_IN_WEIGHT, set->weight);
    /* The children live where the next level does. */
    macs_run_desc d = set_run(f, level + 1);
    if (st == BG_OK)
        st = run(f, pass, BG_PASS_SPAWN, &d);
    return st;
}

/* Marks and counts a child set's live rays; *live gets the count. */
static bg_status mark(frame *f, const gpu_ray_set *set, int level, uint64_t *live)
{
    bg_renderer *r = f->r;
    macs_status ms = macs_depth_stencil_clear(r->multipass->depth, 1.0f, (r->multipass->key.disable_skips & BG_SKIP_STENCIL) ? GPU_STENCIL_LIVE : 0u,
                                              GPU_STENCIL_CLEAR_MASK);
    if (ms)
        return bgi_gpu_fail_macs(r, ms, "clearing depth and stencil");
    bg_status st = bind(r, r->multipass->passes.mark, GPU_MARK_IN_WEIGHT, set->weight);
    macs_run_desc d = set_run(f, level);
    d.occlusion_query = true;
    if (st == BG_OK)
        st = run(f, r->multipass->passes.mark, BG_PASS_MARK, &d);
    if (st != BG_OK)
        return st;
    ms = macs_pass_occlusion_result(r->multipass->passes.mark, live);
    return ms ? bgi_gpu_fail_macs(r, ms, "counting live rays") : BG_OK;
}

typedef struct pending {
    int slot, level;
} pending;

static bg_status trace(frame *f)
{
    bg_renderer *r = f->r;
    const bg_render_settings *s = f->settings;
    /* Depth-first: at most one pending set per level plus the one being traced. */
    pending stack[2 * (BG_MAX_DEPTH + 2)];
    bool used[2 * (BG_MAX_DEPTH + 2)];
    memset(used, 0, sizeof used);
    int top = 0;
    stack[top++] = (pending){0, 0};
    used[0] = true;
    bool first = true;
    bool skip_empty = !(r->multipass->key.disable_skips & BG_SKIP_OCCLUSION);

    while (top > 0) {
        pending cur = stack[--top];
        gpu_ray_set *set = NULL;
        bg_status st = bgi_gpu_ray_set_get(r, cur.slot, &set);
        if (st != BG_OK)
            return st;
        uint64_t live = (uint64_t)r->multipass->width * (uint64_t)r->multipass->height;
        if (first) {
            /* Camera rays are all alive. */
            macs_status ms = macs_depth_stencil_clear(r->multipass->depth, 1.0f, GPU_STENCIL_LIVE, GPU_STENCIL_CLEAR_MASK);
            if (ms)
                return bgi_gpu_fail_macs(r, ms, "clearing depth and stencil");
            first = false;
        } else {
            phase_start(f);
            st = mark(f, set, cur.level, &live);
            phase_end(f, BG_PHASE_BOUNCE);
            if (st != BG_OK)
                return st;
            if (live == 0 && skip_empty) {
                r->stats.ray_sets_skipped++;
                used[cur.slot] = false;
                continue;
            }
        }
        r->stats.ray_sets++;
        r->stats.live_pixels[cur.level] += live;
        r->stats.dmax[cur.level] = f->dmax[cur.level];
        if (cur.level > r->stats.levels)
            r->stats.levels = cur.level;

        phase_start(f);
        st = intersect(f, set, cur.level);
        phase_end(f, BG_PHASE_INTERSECT);
        if (st == BG_OK)
            st = shade(f, set, cur.level);
        if (st != BG_OK)
            return st;

        macs_pass *kinds[2] = {r->multipass->passes.refract, r->multipass->passes.reflect};
        if (cur.level < s->max_depth) {
            phase_start(f);
            for (int k = 0; k < 2 && st == BG_OK; k++) {
                if (!kinds[k])
                    continue;
                int slot = 0;
                while (used[slot])
                    slot++;
                gpu_ray_set *child = NULL;
                st = bgi_gpu_ray_set_get(r, slot, &child);
                if (st == BG_OK) {
                    set = &r->multipass->sets[cur.slot]; /* the pool may have moved */
                    st = spawn(f, kinds[k], set, child, cur.level);
                }
                if (st == BG_OK) {
                    used[slot] = true;
                    stack[top++] = (pending){slot, cur.level + 1};
                }
            }
            phase_end(f, BG_PHASE_BOUNCE);
            if (st != BG_OK)
                return st;
        }
        used[cur.slot] = false;
    }
    return BG_OK;
}

/* A float image read straight from the accumulation: its alpha counts the hits whose mesh walk ran
 * out of steps; made 0 there and 1 elsewhere, as the resolve passes write it. */
static void float_marks(const bg_image *image, size_t stride)
{
    for (int y = 0; y < image->height; y++) {
        unsigned char *row = (unsigned char *)image->pixels + (size_t)y * stride;
        for (int x = 0; x < image->width; x++) {
            float a;
            memcpy(&a, row + (size_t)x * 16 + 12, sizeof a);
            a = a > 0.5f ? 0.0f : 1.0f;
            memcpy(row + (size_t)x * 16 + 12, &a, sizeof a);
        }
    }
}

/* The GPU's part of the frame's end: the image or texture as the passes leave it. */
static bg_status finish_gpu(frame *f, const gpu_frame_out *o)
{
    bg_renderer *r = f->r;
    /* Without meshes the read is the frame's last write (tiles.c may defer it); with them finish()
     * goes on writing the image after it. */
    bool mesh = r->multipass->features.mesh;
    if (o->image && o->as_float)
        return mesh ? bgi_gpu_read_back(r, r->multipass->accum, o->image, o->stride, false)
                    : bgi_gpu_read_back_last(r, r->multipass->accum, o->image, o->stride, true);
    macs_pass *resolve = r->multipass->passes.resolve;
    macs_texture *target = o->texture ? o->texture : r->multipass->encoded;
    bg_status st = BG_OK;
    if (o->texture && o->as_float) {
        if (!r->multipass->passes.resolve_float) {
            st = bgi_gpu_resolve_float_pass_build(r, target);
            macs_pass_destroy(r->multipass->resolve_float_retired);
            r->multipass->resolve_float_retired = NULL;
        }
        resolve = r->multipass->passes.resolve_float;
    }
    if (st != BG_OK)
        return st;
    macs_status ms = macs_pass_set_output(resolve, 0, target);
    if (ms)
        return bgi_gpu_fail_macs(r, ms, "binding the frame's target");
    st = run(f, resolve, BG_PASS_RESOLVE, NULL);
    if (st != BG_OK || o->texture)
        return st;
    return mesh ? bgi_gpu_read_back(r, r->multipass->encoded, o->image, o->stride, true)
                : bgi_gpu_read_back_last(r, r->multipass->encoded, o->image, o->stride, true);
}

/* The frame's end. Into an image: RGBA32F reads the accumulation back, RGBA8 resolves it to the
 * encoding first. Into a texture: a resolve pass writes it, encoded or (a float target) as it is.
 * With meshes, the pixels a walk could not finish (alpha 0) are then rendered by the CPU reference,
 * as in the fused plans (shared/fallback.c), but for a pass of several samples, whose marks the sum
 * keeps (accumulate.c). */
static bg_status finish(frame *f, const gpu_frame_out *o)
{
    bg_status st = finish_gpu(f, o);
    if (st != BG_OK || !f->r->multipass->features.mesh)
        return st;
    if (o->texture && f->r->marks_deferred) {
        /* One of several samples: the sum's alpha keeps the marks for the sum's end (accumulate.c). */
        f->r->marks_left = true;
        return BG_OK;
    }
    if (o->texture)
        return bgi_gpu_fallback_texture(f->r, &f->r->multipass->marks, f->state, f->settings, &f->r->view.pixels,
                                        o->texture, &f->r->stats.fallback_pixels);
    if (o->as_float)
        float_marks(o->image, o->stride);
    f->r->stats.fallback_pixels = bgi_gpu_fallback_image(f->state, f->settings, &f->r->view.pixels, o->image, o->stride);
    return BG_OK;
}

static bool same_key(const gpu_cache_key *a, const gpu_cache_key *b)
{
    return a->valid && a->scene == b->scene && a->commit_count == b->commit_count &&
           a->fingerprint == b->fingerprint && a->width == b->width &&
           a->height == b->height && a->disable_skips == b->disable_skips && a->encoding == b->encoding &&
           a->bounces == b->bounces && a->background_on == b->background_on && a->min_weight == b->min_weight &&
           a->texture_uploads == b->texture_uploads && a->mesh_uploads == b->mesh_uploads;
}

/* The mesh textures of the passes: the fused plans' (shared/meshes.c). */
static bg_status meshes_prepare(bg_renderer *r, const bg_scene_state *state)
{
    char why[160];
    if (state->mesh_object_count == 0 || r->meshes.serial == state->serial)
        return BG_OK; /* nothing to check: they hold this commit */
    if (!bgi_gpu_meshes_fit(r, state, why, sizeof why))
        /* The fused plans checked this before they took the frame, so only the multipass, the last
         * plan, can find it here. */
        return bgi_gpu_fail(r, BG_ERR_LIMIT, "no plan can render these meshes: %s", why);
    return bgi_gpu_meshes_prepare(r, state);
}

static bg_status prepare(frame *f, const bg_scene *scene, int width, int height)
{
    bg_renderer *r = f->r;
    const bg_render_settings *s = f->settings;
    gpu_cache_key key;
    memset(&key, 0, sizeof key);
    key.scene = scene;
    key.commit_count = f->state->commit_count;
    /* The scene's and the mesh textures are the plans' one copy: brought to this commit before the
     * key is compared, since another plan may have remade them after this plan's passes bound them. */
    bg_status st = bgi_gpu_scene_textures_prepare(r, f->state);
    if (st == BG_OK)
        st = meshes_prepare(r, f->state);
    if (st != BG_OK)
        return st;
    key.texture_uploads = f->state->texture_count > 0 ? r->scene_textures.uploads : 0;
    key.mesh_uploads = f->state->mesh_object_count > 0 ? r->meshes.uploads : 0;
    key.textures = r->scene_textures.key;
    key.fingerprint = bgi_gpu_scene_fingerprint(f->state, key.textures);
    key.width = width;
    key.height = height;
    key.disable_skips = s->gpu_disable_skips;
    key.encoding = s->encoding;
    key.bounces = s->max_depth > 0;
    key.background_on = s->background[0] > 0.0 || s->background[1] > 0.0 || s->background[2] > 0.0;
    key.min_weight = s->min_weight;
    key.valid = true;
    if (same_key(&r->multipass->key, &key)) {
        /* The background colour is the only setting that is a plain uniform. */
        if (r->multipass->passes.background) {
            float bgc[3] = {(float)s->background[0], (float)s->background[1], (float)s->background[2]};
            macs_status ms = macs_pass_set_uniform(r->multipass->passes.background, "bg_background", bgc);
            if (ms)
                return bgi_gpu_fail_macs(r, ms, "background uniforms");
        }
        return BG_OK;
    }
    bgi_gpu_passes_retire(r);
    memset(&r->multipass->key, 0, sizeof r->multipass->key);
    bgi_gpu_features_detect(f->state, (s->gpu_disable_skips & BG_SKIP_SPECIALIZE) != 0, &r->multipass->features);
    r->multipass->textures = r->scene_textures.texture;
    st = bgi_gpu_white_prepare(r);
    r->multipass->key = key;
    r->multipass->key.valid = false;
    if (st == BG_OK)
        st = bgi_gpu_targets_prepare(r, width, height);
    if (st == BG_OK)
        st = bgi_gpu_passes_build(r, f->state, s);
    bgi_gpu_passes_release_retired(r);
    if (st != BG_OK)
        return st;
    r->multipass->key.valid = true;
    return BG_OK;
}

/* The paper's frame: ray maps, G-buffer, one pass per object batch, light group and ray set. */
static bg_status render(bg_renderer *r, const gpu_plan_frame *pf, char *why, size_t why_size)
{
    const bg_scene_state *state = pf->state;
    const bg_render_settings *settings = pf->settings;
    const gpu_frame_out *out = pf->out;
    if (why_size)
        why[0] = '\0'; /* the multipass renders every frame */
    if (!r->multipass) {
        r->multipass = bgi_alloc(&r->allocator, sizeof *r->multipass);
        if (!r->multipass)
            return bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory for the multipass plan");
        memset(r->multipass, 0, sizeof *r->multipass);
    }
    bg_status st = BG_OK;
    frame f;
    memset(&f, 0, sizeof f);
    f.r = r;
    f.state = state;
    f.settings = settings;
    f.timing = settings->gpu_timing;
    bgi_gpu_dmax_levels(state, settings, &r->view, f.dmax);

    phase_start(&f);
    st = prepare(&f, pf->scene, out->width, out->height);
    phase_end(&f, BG_PHASE_SETUP);
    /* The camera's shift follows the window and the sample: a uniform, set every frame. */
    if (st == BG_OK)
        st = bgi_gpu_camera_uniforms_set(r, state);
    if (st == BG_OK)
        st = bgi_gpu_sample_uniforms_set(r);
    if (st == BG_OK) {
        static const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        macs_status ms = macs_texture_clear(r->multipass->accum, zero);
        if (ms)
            st = bgi_gpu_fail_macs(r, ms, "clearing the accumulation");
    }
    if (st == BG_OK) {
        bounce_scissor(&f);
        phase_start(&f);
        st = run(&f, r->multipass->passes.camera, BG_PASS_RAYS, NULL);
        phase_end(&f, BG_PHASE_RAYS);
    }
    if (st == BG_OK)
        st = trace(&f);
    if (st == BG_OK) {
        phase_start(&f);
        st = finish(&f, out);
        phase_end(&f, BG_PHASE_RESOLVE);
    }
    if (st == BG_OK)
        st = count_read_all(&f);
    if (st != BG_OK) {
        /* Start the next render from nothing: a failure may have left any object half made. */
        bgi_gpu_multipass_release(r);
        return st;
    }
    r->stats.gbuffer_targets = r->multipass->features.slot_count;
    for (int s = 0; s < GPU_SLOT_COUNT; s++)
        if (r->multipass->features.slot[s] && macs_texture_format(r->multipass->gbuffer[s]) == MACS_FORMAT_RGBA16F)
            r->stats.gbuffer_half_targets++;
    r->stats.depth_bits = macs_depth_stencil_format(r->multipass->depth) == MACS_DEPTH32F_STENCIL8 ? 32 : 24;
    return BG_OK;
}

void bgi_gpu_multipass_release(bg_renderer *r)
{
    gpu_multipass *m = r->multipass;
    if (!m)
        return;
    bgi_gpu_passes_release(r);
    macs_pass_destroy(m->resolve_float_retired);
    bgi_gpu_targets_release(r);
    macs_texture_destroy(m->white);
    bgi_gpu_marks_release(&m->marks);
    bgi_free(&r->allocator, m);
    r->multipass = NULL;
}

const gpu_plan bgi_gpu_multipass_plan = {BG_PLAN_MULTIPASS, "BG_PLAN_MULTIPASS", render, bgi_gpu_multipass_release};
