/* Limit profiles: named legacy GPUs whose limits, missing extensions, missing float features and GL
 * version any driver can be made to obey (macs_context_desc.profile). Each value says where it comes
 * from; docs/profiles.md has the same table for readers. "Mesa" is the open driver for the part, read
 * in its source: nv30/nv30_screen.c (nouveau, NV40 class = GeForce 6/7), r300/r300_screen.c (is_r500
 * = R5xx = Radeon X1000) and i965/brw_context.c with i965/brw_surface_formats.c (Gen4 = GMA X3100).
 * The GL 2.1 minimums are the GL 2.1 specification's state tables (6.36-6.37) and
 * ARB_framebuffer_object's. Where a vendor's own driver reported something else, the smaller value
 * is kept, as the profile should be the harder of the two. */
#include <stdio.h>
#include <string.h>

#include "internal.h"

static const macsi_profile profiles[] = {
    {
        "geforce7",
        {
            4,    /* draw buffers: nv30 PIPE_CAP_MAX_RENDER_TARGETS, 4 on NV40 class; NVIDIA's driver alike */
            4,    /* colour attachments: as many as draw buffers (NVIDIA's EXT_framebuffer_object on NV4x) */
            16,   /* texture units: nv30 fragment PIPE_SHADER_CAP_MAX_TEXTURE_SAMPLERS 16 */
            4096, /* texture size: nv30 PIPE_CAP_MAX_TEXTURE_2D_LEVELS 13 = 4096 */
            896,  /* uniform floats: nv30 fragment constant buffer 224 vec4 on NV40 (NVIDIA's driver
                     reports more; 896 is the harder) */
            32,   /* varying floats: nv30 fragment PIPE_SHADER_CAP_MAX_INPUTS 8 vec4 */
        },
        /* ARB_depth_buffer_float came with GeForce 8 (G80). EXT_timer_query (2006) was NVIDIA's for
         * the NV4x generation on; the ARB one (2010) is taken away as an estimate, the harder choice,
         * which also keeps MACS's EXT timer path in use. */
        "GL_ARB_depth_buffer_float GL_ARB_timer_query",
        /* GPU Gems 2, ch. 30 (NVIDIA, "The GeForce 6 Series GPU Architecture"): HDR through fp16
         * surfaces, texture filtering and blending; fp32 textures neither filter nor blend before
         * GeForce 8 (NVIDIA's GPU Programming Guide says the same); nouveau filters no float at all. */
        MACS_FLOAT32_FILTER | MACS_FLOAT32_BLEND,
        21,
    },
    {
        "radeon_x1600",
        {
            4,    /* draw buffers: r300 PIPE_CAP_MAX_RENDER_TARGETS 4 */
            4,    /* colour attachments: as many as draw buffers */
            16,   /* texture units: r300 caps.num_tex_units 16 (every R3xx-R5xx) */
            4096, /* texture size: r300 PIPE_CAP_MAX_TEXTURE_2D_SIZE 4096 on r500 (2048 before) */
            1024, /* uniform floats: r300 fragment constant buffer 256 vec4 on r500 */
            40,   /* varying floats: r300 PIPE_CAP_MAX_VARYINGS 10 vec4 (8 texcoords + 2 colours) */
        },
        /* No float depth on R5xx; ATI's last driver for the X1000 (Catalyst 9.3) offered only
         * EXT_framebuffer_object (an estimate from its extension lists; Mesa's r300 has the ARB one),
         * so the profile takes MACS down the EXT path. r300 answers no time-elapsed query: no timers. */
        "GL_ARB_depth_buffer_float GL_ARB_framebuffer_object GL_ARB_timer_query GL_EXT_timer_query",
        /* r300 r300_is_blending_supported: RGBA16F blends on r500 only, no 32-bit float blends; r300
         * exposes no float texture filtering, and R5xx hardware filters no float format. */
        MACS_FLOAT32_FILTER | MACS_FLOAT16_FILTER | MACS_FLOAT32_BLEND,
        21,
    },
    {
        "gma_x3100",
        {
            8,    /* draw buffers: i965 BRW_MAX_DRAW_BUFFERS 8 */
            8,    /* colour attachments: as many as draw buffers */
            16,   /* texture units: i965 max_samplers 16 before Haswell */
            8192, /* texture size: i965 MaxTextureLevels 14 = 8192 and MaxRenderbufferSize 8192 before Gen7 */
            1024, /* uniform floats: an estimate. i965 keeps Mesa's default (4096 vec4) before Gen6, which
                     no Gen4 could push; 1024 is Intel's Windows driver's order and the harder */
            64,   /* varying floats: an estimate, Mesa's 16 vec4 default for pre-Gen6 (Gen6 has 32) */
        },
        /* Timer queries: an estimate, none (the harder choice; Gen4's timestamps were unreliable). */
        "GL_ARB_depth_buffer_float GL_ARB_timer_query GL_EXT_timer_query",
        /* i965 brw_surface_formats.c: R32G32B32A32_FLOAT filters from Gen5 only ("50"); it renders
         * and alpha-blends on Gen4; R16G16B16A16_FLOAT samples, filters, renders and blends. */
        MACS_FLOAT32_FILTER,
        21,
    },
    {
        "gl21",
        {
            1,  /* draw buffers: GL 2.1 table 6.37, MAX_DRAW_BUFFERS at least 1 */
            1,  /* colour attachments: ARB_framebuffer_object, MAX_COLOR_ATTACHMENTS at least 1 */
            2,  /* texture units: GL 2.1 table 6.37, MAX_TEXTURE_IMAGE_UNITS at least 2 */
            64, /* texture size: GL 2.1 table 6.36, MAX_TEXTURE_SIZE at least 64 */
            64, /* uniform floats: GL 2.1 table 6.37, MAX_FRAGMENT_UNIFORM_COMPONENTS at least 64 */
            32, /* varying floats: GL 2.1 table 6.37, MAX_VARYING_FLOATS at least 32 */
        },
        /* Everything optional MACS uses is gone. */
        "GL_ARB_depth_buffer_float GL_ARB_color_buffer_float GL_ARB_half_float_pixel GL_ARB_timer_query "
        "GL_EXT_timer_query",
        /* GL 2.1 cannot be asked, so nothing may be assumed. */
        MACS_FLOAT32_FILTER | MACS_FLOAT16_FILTER | MACS_FLOAT32_BLEND | MACS_FLOAT16_BLEND,
        21,
    },
};

const macsi_profile *macsi_profile_find(const char *name)
{
    for (size_t i = 0; name && i < sizeof profiles / sizeof profiles[0]; i++)
        if (strcmp(profiles[i].name, name) == 0)
            return &profiles[i];
    return NULL;
}

void macsi_profile_names(char *out, size_t size)
{
    if (size == 0)
        return;
    out[0] = '\0';
    for (size_t i = 0; i < sizeof profiles / sizeof profiles[0]; i++) {
        size_t used = strlen(out);
        snprintf(out + used, size - used, "%s%s", i ? ", " : "", profiles[i].name);
    }
}
