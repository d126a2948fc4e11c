/* The vertical field of view of a glTF camera as assimp hands it over. glTF stores yfov and the
 * aspect ratio; assimp turns them into aiCamera::mHorizontalFOV, and its formula changed in 5.3
 * (its fix of the glTF importer's horizontal angle, merged January 2023):
 *   before 5.3:    mHorizontalFOV = yfov * aspect, a product that is no angle of the view;
 *   5.3 and later: mHorizontalFOV = 2 atan(aspect tan(yfov / 2)), the full horizontal angle.
 * With no aspect ratio (0) both pass yfov through. Each formula is inverted exactly here, chosen by
 * the version of the assimp the program runs with, so that a file keeps its framing on either. */
#include <math.h>

#include "scenefile_internal.h"

double bgi_sf_gltf_fov_y(double horizontal_fov, double aspect, unsigned assimp_major, unsigned assimp_minor)
{
    if (!(aspect > 0) || !isfinite(aspect))
        return horizontal_fov;
    bool full_angle = assimp_major > 5 || (assimp_major == 5 && assimp_minor >= 3);
    return full_angle ? 2.0 * atan(tan(horizontal_fov / 2.0) / aspect) : horizontal_fov / aspect;
}
