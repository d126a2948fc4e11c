/* What a material may do, as both plans decide their code by it: texture lanes count as "may" (a
 * textured roughness may fall below 1/2 somewhere, so it may reflect). */
#include "shared.h"

static bool layer_may_reflect(const bg_schlick_layer *l)
{
    return l->roughness.value < 0.5 || l->roughness.texture != 0;
}

bool bgi_gpu_material_may_bounce(const bg_material *m)
{
    return m->transparency.value > 0.0 || layer_may_reflect(&m->base) || (m->has_coat && layer_may_reflect(&m->coat));
}

static bool layer_may_be_aniso(const bg_schlick_layer *l)
{
    return l->isotropy.value < 1.0 || l->isotropy.texture != 0;
}

bool bgi_gpu_material_may_be_aniso(const bg_material *m)
{
    return layer_may_be_aniso(&m->base) || (m->has_coat && layer_may_be_aniso(&m->coat));
}
