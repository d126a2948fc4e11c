/* The passes of a frame that make, count, end and spawn rays (docs/gpu_pipeline.md): camera rays,
 * live-ray marking, the background where rays missed, reflected and refracted children, and the
 * resolve to the output encoding. What they are (background or not, bounces or not, encoding, minimum
 * weight) is read from the renderer's cache key, where multipass_frame.c decides it once from the settings:
 * the passes built and the key that keeps them cannot disagree.
 * Ray-map inputs are bound per ray set by multipass_frame.c at the fixed input positions of multipass.h. */
#include <string.h>

#include "../../common/scramble.h"
#include "multipass.h"

/* A pass over the live (and, with hit_bits, hit or missed) pixels with one or two ray-map inputs. */
static bg_status simple_pass(bg_renderer *r, const char *what, const char *const *files, const char *main,
                             const macs_input_desc *inputs, int input_count, macs_texture *const *input_tex,
                             const macs_uniform_desc *uniforms, int uniform_count, const char *value,
                             macs_texture *const *outputs, int output_count, macs_blend blend,
                             const macs_stencil_state *stencil, macs_pass **out)
{
    macs_output_desc out_desc[3] = {{"out0", value}, {"out1", NULL}, {"out2", NULL}};
    macs_pass_desc desc;
    bgi_gpu_pass_desc_init(&desc, main, inputs, input_tex, input_count, uniforms, uniform_count, out_desc, outputs,
                       output_count);
    desc.blend = blend;
    if (stencil) {
        desc.depth_stencil = r->multipass->depth;
        desc.stencil = *stencil;
    }
    if (output_count == 3) {
        /* Ray-map writers name their three outputs o0..o2 in main. */
        out_desc[0].value = "bg_o0";
        out_desc[1].value = "bg_o1";
        out_desc[2].value = "bg_o2";
        out_desc[1].name = "out1";
        out_desc[2].name = "out2";
    }
    return bgi_gpu_pass_create(r, what, files, NULL, &desc, out);
}

static macs_stencil_state stencil_equal(unsigned ref, unsigned mask)
{
    macs_stencil_state s;
    memset(&s, 0, sizeof s);
    s.test = true;
    s.func = MACS_COMPARE_EQUAL;
    s.ref = ref;
    s.read_mask = mask;
    s.write_mask = 0;
    return s;
}

static bool stencil_skip(const bg_renderer *r)
{
    return !(r->multipass->key.disable_skips & BG_SKIP_STENCIL);
}

/* The camera's frame as uniforms, relative to the camera (its eye is the frame's origin); the size
 * and aspect are the full frame's, the shift the view's window and sample (docs/shading.md 1.1). */
bg_status bgi_gpu_camera_uniforms_set(bg_renderer *r, const bg_scene_state *state)
{
    macs_pass *pass = r->multipass->passes.camera;
    const bg_camera_data *c = &state->camera;
    int fw_px = r->view.pixels.frame_width, fh_px = r->view.pixels.frame_height;
    float size[2] = {(float)fw_px, (float)fh_px};
    float eye[3];
    bgi_gpu_origin_point(state, &c->camera.position, eye); /* (0, 0, 0): the frame's origin */
    float fw[3], rt[3], up[3];
    for (int i = 0; i < 3; i++) {
        fw[i] = (float)c->forward[i];
        rt[i] = (float)c->right[i];
        up[i] = (float)c->up[i];
    }
    float th[2];
    bgi_gpu_camera_half(state, &r->view, th);
    macs_status ms = macs_pass_set_uniform(pass, "bg_size", size);
    if (!ms) ms = macs_pass_set_uniform(pass, "bg_eye", eye);
    if (!ms) ms = macs_pass_set_uniform(pass, "bg_forward", fw);
    if (!ms) ms = macs_pass_set_uniform(pass, "bg_right", rt);
    if (!ms) ms = macs_pass_set_uniform(pass, "bg_up", up);
    if (!ms) ms = macs_pass_set_uniform(pass, "bg_tan_half", th);
    if (!ms) ms = macs_pass_set_uniform(pass, "bg_shift", r->view.shift);
    if (!ms && r->multipass->features.lens) {
        float lens[2];
        bgi_gpu_lens(state, lens);
        ms = macs_pass_set_uniform(pass, "bg_lens", lens);
    }
    return ms ? bgi_gpu_fail_macs(r, ms, "camera pass uniforms") : BG_OK;
}

/* Camera rays: one per pixel, at the view's sample point (bgi_gpu_camera_uniforms_set), into ray
 * set 0. */
static bg_status build_camera_pass(bg_renderer *r, const bg_scene_state *state, const gpu_ray_set *set0)
{
    bool lens = r->multipass->features.lens;
    macs_uniform_desc u[11] = {{"bg_size", MACS_UNIFORM_VEC2, 0},    {"bg_eye", MACS_UNIFORM_VEC3, 0},
                               {"bg_forward", MACS_UNIFORM_VEC3, 0}, {"bg_right", MACS_UNIFORM_VEC3, 0},
                               {"bg_up", MACS_UNIFORM_VEC3, 0},      {"bg_tan_half", MACS_UNIFORM_VEC2, 0},
                               {"bg_shift", MACS_UNIFORM_VEC2, 0},   {"bg_pixel_at", MACS_UNIFORM_VEC2, 0},
                               {"bg_sample_of", MACS_UNIFORM_VEC4, 0}, {"bg_sample_perm", MACS_UNIFORM_VEC4, 0},
                               {"bg_lens", MACS_UNIFORM_VEC2, 0}};
    macs_texture *outs[3] = {set0->origin, set0->dir, set0->weight};
    const char *pinhole[] = {"bg_stage_camera.glsl", NULL};
    const char *thin_lens[] = {"bg_stage_camera.glsl", "bg_lens.glsl", NULL};
    /* Through a lens, each sample's ray leaves its own point of the lens (docs/shading.md 1.4). */
    char main[512];
    int n = snprintf(main, sizeof main,
                     "vec4 bg_o0, bg_o1, bg_o2;\n"
                     "%s(gl_FragCoord.xy + bg_shift, bg_size, bg_eye, bg_forward, bg_right, "
                     "bg_up, bg_tan_half, bg_o0, bg_o1, bg_o2);\n",
                     bgi_gpu_camera_function(r->multipass->features.orthographic));
    if (lens)
        snprintf(main + n, sizeof main - (size_t)n,
                 "bg_lens_ray(bg_sample_disc(bg_sample_square(bg_pixel_hash(gl_FragCoord.xy, bg_pixel_at), %d.0, "
                 "bg_sample_of, bg_sample_perm)), bg_lens.x, bg_lens.y, bg_forward, bg_right, bg_up, bg_o0, bg_o1);\n",
                 BGI_DIMENSION_LENS);
    bg_status st = simple_pass(r, "camera pass", lens ? thin_lens : pinhole, main, NULL, 0, NULL, u, lens ? 11 : 7, NULL,
                               outs, 3, MACS_BLEND_NONE, NULL, &r->multipass->passes.camera);
    return st == BG_OK ? bgi_gpu_camera_uniforms_set(r, state) : st;
}

/* Marking: counts a set's live rays (occlusion query) and, with the stencil skip on, sets their
 * live bit so that every later pass of the set rejects dead pixels before shading them. */
static bg_status build_mark_pass(bg_renderer *r)
{
    macs_input_desc in[1] = {{"bg_ray_weight"}};
    macs_texture *in_tex[1] = {NULL};
    macs_texture *outs[1] = {r->multipass->accum};
    macs_stencil_state s;
    memset(&s, 0, sizeof s);
    if (stencil_skip(r)) {
        s.test = true;
        s.func = MACS_COMPARE_ALWAYS;
        s.ref = GPU_STENCIL_LIVE;
        s.write_mask = GPU_STENCIL_LIVE;
        s.pass = MACS_STENCIL_OP_REPLACE;
    }
    macs_pass_desc desc;
    macs_output_desc od = {"none", "vec4(0.0)"};
    bgi_gpu_pass_desc_init(&desc, "if (texture2D(bg_ray_weight, macs_uv).a <= 0.0) discard;\n", in, in_tex, 1, NULL, 0,
                       &od, outs, 1);
    desc.depth_stencil = r->multipass->depth;
    desc.stencil = s;
    desc.color_mask = MACS_COLOR_MASK_NONE;
    return bgi_gpu_pass_create(r, "mark pass", NULL, NULL, &desc, &r->multipass->passes.mark);
}

/* Background where a live ray missed every object: the hit bit is clear. Its colour is a plain
 * uniform, set again by multipass_frame.c whenever the cached passes are reused. */
static bg_status build_background_pass(bg_renderer *r, const double background[3])
{
    macs_input_desc in[1] = {{"bg_ray_weight"}};
    macs_texture *in_tex[1] = {NULL};
    macs_uniform_desc u[1] = {{"bg_background", MACS_UNIFORM_VEC3, 0}};
    macs_texture *outs[1] = {r->multipass->accum};
    macs_stencil_state s = stencil_skip(r) ? stencil_equal(GPU_STENCIL_LIVE, GPU_STENCIL_LIVE | GPU_STENCIL_HIT)
                                           : stencil_equal(0, GPU_STENCIL_HIT);
    bg_status st = simple_pass(r, "background pass", NULL, "vec4 bg_w = texture2D(bg_ray_weight, macs_uv);\n", in, 1,
                               in_tex, u, 1, "vec4(bg_w.rgb * bg_background, 0.0)", outs, 1, MACS_BLEND_ADD, &s,
                               &r->multipass->passes.background);
    if (st != BG_OK)
        return st;
    float bgc[3] = {(float)background[0], (float)background[1], (float)background[2]};
    macs_status ms = macs_pass_set_uniform(r->multipass->passes.background, "bg_background", bgc);
    return ms ? bgi_gpu_fail_macs(r, ms, "background uniforms") : BG_OK;
}

/* Whether children are spawned at all: the settings ask for bounces (the key's choice) and some
 * material may bounce, unless the bounce cull is switched off. */
static bool spawn_passes_wanted(const bg_renderer *r)
{
    return r->multipass->key.bounces && (r->multipass->features.bounce || (r->multipass->key.disable_skips & BG_SKIP_BOUNCE_CULL));
}

enum { SPAWN_REFLECT = 0, SPAWN_REFRACT = 1, SPAWN_MAX_INPUTS = 9 };

/* The G-buffer slots a spawn pass reads, after the parent's direction and weight (at
 * GPU_SPAWN_IN_DIR and GPU_SPAWN_IN_WEIGHT, bound per ray set); returns how many inputs. */
static int spawn_inputs(const bg_renderer *r, int kind, macs_input_desc in[SPAWN_MAX_INPUTS],
                        macs_texture *in_tex[SPAWN_MAX_INPUTS])
{
    const gpu_features *f = &r->multipass->features;
    int ni = 0;
    in[ni].name = "bg_ray_dir", in_tex[ni++] = NULL;    /* GPU_SPAWN_IN_DIR */
    in[ni].name = "bg_ray_weight", in_tex[ni++] = NULL; /* GPU_SPAWN_IN_WEIGHT */
    in[ni].name = "bg_g_hit", in_tex[ni++] = r->multipass->gbuffer[GPU_SLOT_HIT];
    in[ni].name = "bg_g_normal", in_tex[ni++] = r->multipass->gbuffer[GPU_SLOT_NORMAL];
    if (kind == SPAWN_REFLECT)
        in[ni].name = "bg_g_base", in_tex[ni++] = r->multipass->gbuffer[GPU_SLOT_BASE];
    if (kind == SPAWN_REFLECT && f->slot[GPU_SLOT_COAT])
        in[ni].name = "bg_g_coat", in_tex[ni++] = r->multipass->gbuffer[GPU_SLOT_COAT];
    if (f->transparent)
        in[ni].name = "bg_g_xparent", in_tex[ni++] = r->multipass->gbuffer[GPU_SLOT_XPARENT];
    if (f->transparent || (kind == SPAWN_REFLECT && f->glossy))
        in[ni].name = "bg_g_once", in_tex[ni++] = r->multipass->gbuffer[GPU_SLOT_ONCE];
    if (f->mesh)
        in[ni].name = "bg_g_mesh", in_tex[ni++] = r->multipass->gbuffer[GPU_SLOT_MESH];
    return ni;
}

/* The spawn call of a pass's main, with the lanes a missing slot would have filled as constants. */
static void spawn_main(const bg_renderer *r, int kind, gpu_text *main)
{
    const gpu_features *f = &r->multipass->features;
    bool reflect = kind == SPAWN_REFLECT;
    bgi_gpu_text_append(main, "vec4 bg_o0, bg_o1, bg_o2;\n");
    bgi_gpu_text_printf(main,
                    "bg_spawn(%s, texture2D(bg_g_hit, macs_uv), texture2D(bg_g_normal, macs_uv), %s, %s, %s, %s, "
                    "texture2D(bg_ray_dir, macs_uv), texture2D(bg_ray_weight, macs_uv), bg_min_weight, "
                    "bg_o0, bg_o1, bg_o2);\n",
                    reflect ? "false" : "true", reflect ? "texture2D(bg_g_base, macs_uv)" : "vec4(0.0)",
                    reflect && f->slot[GPU_SLOT_COAT] ? "texture2D(bg_g_coat, macs_uv)" : "vec4(0.0, 0.0, 0.0, -1.0)",
                    f->transparent ? "texture2D(bg_g_xparent, macs_uv).a" : "0.0",
                    !f->transparent ? "1.0" : f->glossy ? "abs(texture2D(bg_g_once, macs_uv).a)" : "texture2D(bg_g_once, macs_uv).a");
    /* A glossy material's reflected child (a negative ior marks it), from the lobe's dimension of the
     * parent's level, a uniform set per spawn. */
    if (reflect && f->glossy)
        bgi_gpu_text_printf(main, "if (texture2D(bg_g_once, macs_uv).a < 0.0)\n"
                                  "    bg_glossy_child(texture2D(bg_ray_dir, macs_uv).xyz, texture2D(bg_g_normal, macs_uv), %s, "
                                  "bg_sample_square(bg_pixel_hash(gl_FragCoord.xy, bg_pixel_at), %d.0 + %d.0 * bg_level, "
                                  "bg_sample_of, bg_sample_perm), bg_o1, bg_o2);\n",
                            f->slot[GPU_SLOT_COAT] ? "texture2D(bg_g_coat, macs_uv)" : "vec4(0.0, 0.0, 0.0, -1.0)",
                            BGI_DIMENSION_GLOSSY(0), BGI_DIMENSION_GLOSSY(1) - BGI_DIMENSION_GLOSSY(0));
    /* A ray leaving a mesh starts off the surface on its side and skips its triangle (the lanes of
     * gpu/mesh_source.c); a pixel the CPU renders spawns nothing. */
    if (f->mesh)
        bgi_gpu_text_printf(main, "vec4 bg_m = texture2D(bg_g_mesh, macs_uv);\n"
                                  "if (bg_m.w >= 0.0) {\n"
                                  "    float bg_side = dot(bg_o1.xyz, bg_m.xyz) >= 0.0 ? 1.0 : -1.0;\n"
                                  "    bg_o0 = vec4(bg_o0.xyz + bg_side * bg_m.xyz, bg_hit_index(texture2D(bg_g_hit, macs_uv).w));\n"
                                  "    bg_o1.w = -2.0 - bg_m.w;\n"
                                  "} else if (bg_m.w < %.1f + 0.5)\n    bg_o2 = vec4(0.0);\n",
                            GPU_MESH_SHORT);
}

/* Secondary rays of one kind: every live hit pixel writes its child into ray set 0's maps, which
 * multipass_frame.c rebinds to the child set; the child set's mark pass counts them. */
static bg_status build_spawn_pass(bg_renderer *r, int kind, const gpu_ray_set *set0)
{
    macs_pass **out = kind == SPAWN_REFRACT ? &r->multipass->passes.refract : &r->multipass->passes.reflect;
    macs_input_desc in[SPAWN_MAX_INPUTS];
    macs_texture *in_tex[SPAWN_MAX_INPUTS];
    int ni = spawn_inputs(r, kind, in, in_tex);
    bool glossy = kind == SPAWN_REFLECT && r->multipass->features.glossy;
    macs_uniform_desc u[5] = {{"bg_min_weight", MACS_UNIFORM_FLOAT, 0}, {"bg_pixel_at", MACS_UNIFORM_VEC2, 0},
                              {"bg_sample_of", MACS_UNIFORM_VEC4, 0}, {"bg_sample_perm", MACS_UNIFORM_VEC4, 0},
                              {"bg_level", MACS_UNIFORM_FLOAT, 0}};
    macs_texture *outs[3] = {set0->origin, set0->dir, set0->weight};
    macs_stencil_state s = stencil_skip(r) ? stencil_equal(GPU_STENCIL_LIVE | GPU_STENCIL_HIT,
                                                           GPU_STENCIL_LIVE | GPU_STENCIL_HIT)
                                           : stencil_equal(GPU_STENCIL_HIT, GPU_STENCIL_HIT);
    const char *mirror_files[] = {"bg_stage_spawn.glsl", NULL};
    const char *glossy_files[] = {"bg_stage_spawn.glsl", "bg_scramble.glsl", "bg_glossy.glsl", NULL};
    const char **files = glossy ? glossy_files : mirror_files;
    gpu_text main;
    bgi_gpu_text_init(&main, &r->allocator);
    spawn_main(r, kind, &main);
    bg_status st;
    if (main.failed)
        st = bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory building the spawn shader");
    else
        st = simple_pass(r, kind == SPAWN_REFRACT ? "refraction pass" : "reflection pass", files, main.s, in, ni,
                         in_tex, u, glossy ? 5 : 1, NULL, outs, 3, MACS_BLEND_NONE, &s, out);
    bgi_gpu_text_free(&main);
    if (st != BG_OK)
        return st;
    float mw = (float)r->multipass->key.min_weight;
    macs_status ms = macs_pass_set_uniform(*out, "bg_min_weight", &mw);
    return ms ? bgi_gpu_fail_macs(r, ms, "spawn uniforms") : BG_OK;
}

/* The accumulation's radiance and, in bg_alpha, 0 where a mesh walk ran out of steps (the lighting
 * passes counted those hits in its alpha; multipass_frame.c then renders the pixel with the CPU reference),
 * else 1. */
static const char *const resolve_main = "vec4 bg_a = texture2D(bg_accum, macs_uv);\nvec3 bg_l = bg_a.rgb;\n"
                                        "float bg_alpha = bg_a.a > 0.5 ? 0.0 : 1.0;\n";

/* Resolve to the output encoding, into an RGBA8 target read back by multipass_frame.c (or, rebound there, the
 * caller's RGBA8 texture). */
static bg_status build_resolve_pass(bg_renderer *r)
{
    macs_input_desc in[1] = {{"bg_accum"}};
    macs_texture *in_tex[1] = {r->multipass->accum};
    macs_texture *outs[1] = {r->multipass->encoded};
    const char *files[] = {"bg_stage_resolve.glsl", NULL};
    return simple_pass(r, "resolve pass", files, resolve_main, in, 1, in_tex, NULL, 0,
                       r->multipass->key.encoding == BG_ENCODING_LINEAR ? "vec4(bg_encode(bg_l, false), bg_alpha)"
                                                             : "vec4(bg_encode(bg_l, true), bg_alpha)",
                       outs, 1, MACS_BLEND_NONE, NULL, &r->multipass->passes.resolve);
}

/* The accumulation as it is into a float target texture, alpha as the RGBA8 resolve writes it. */
bg_status bgi_gpu_resolve_float_pass_build(bg_renderer *r, macs_texture *target)
{
    macs_input_desc in[1] = {{"bg_accum"}};
    macs_texture *in_tex[1] = {r->multipass->accum};
    macs_texture *outs[1] = {target};
    return simple_pass(r, "float resolve pass", NULL, resolve_main, in, 1, in_tex, NULL, 0, "vec4(bg_l, bg_alpha)",
                       outs, 1, MACS_BLEND_NONE, NULL, &r->multipass->passes.resolve_float);
}

bg_status bgi_gpu_ray_passes_build(bg_renderer *r, const bg_scene_state *state, const bg_render_settings *settings)
{
    gpu_ray_set *set0 = NULL;
    bg_status st = bgi_gpu_ray_set_get(r, 0, &set0);
    if (st == BG_OK)
        st = build_camera_pass(r, state, set0);
    if (st == BG_OK)
        st = build_mark_pass(r);
    if (st == BG_OK && r->multipass->key.background_on)
        st = build_background_pass(r, settings->background);
    if (st == BG_OK && spawn_passes_wanted(r)) {
        st = build_spawn_pass(r, SPAWN_REFLECT, set0);
        if (st == BG_OK && r->multipass->features.transparent)
            st = build_spawn_pass(r, SPAWN_REFRACT, set0);
    }
    if (st == BG_OK)
        st = build_resolve_pass(r);
    return st;
}
