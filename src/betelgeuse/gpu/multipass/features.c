/* Which shader features and G-buffer slots a committed scene needs (docs/gpu_pipeline.md): a scene
 * pays only for what its materials can produce. Texture lanes count as "may": a textured roughness
 * may fall below 1/2 somewhere, so it may reflect. */
#include <string.h>

#include "multipass.h"

void bgi_gpu_features_detect(const bg_scene_state *state, bool generic, gpu_features *f)
{
    memset(f, 0, sizeof *f);
    f->generic = generic;
    for (uint32_t i = 0; i < state->object_count; i++) {
        const bg_material *m = &state->materials[state->objects[i].material];
        bool transparent = m->transparency.value > 0.0;
        f->transparent |= transparent;
        f->coat |= m->has_coat;
        f->aniso |= bgi_gpu_material_may_be_aniso(m);
        f->bounce |= bgi_gpu_material_may_bounce(m);
        f->glossy |= m->glossy;
    }
    f->mesh = state->mesh_object_count > 0;
    f->lens = state->camera.camera.aperture_radius > 0.0;
    f->orthographic = state->camera.orthographic;
    f->area = bgi_gpu_scene_has_area_lights(state);
    if (generic) {
        f->transparent = f->aniso = f->coat = f->bounce = true;
    }
    f->slot[GPU_SLOT_HIT] = f->slot[GPU_SLOT_NORMAL] = f->slot[GPU_SLOT_BASE] = f->slot[GPU_SLOT_ONCE] = true;
    f->slot[GPU_SLOT_XPARENT] = f->transparent;
    f->slot[GPU_SLOT_TANGENT] = f->aniso;
    f->slot[GPU_SLOT_COAT] = f->coat;
    f->slot[GPU_SLOT_MESH] = f->mesh;
    for (int s = 0; s < GPU_SLOT_COUNT; s++)
        f->slot_count += f->slot[s] ? 1 : 0;
}
