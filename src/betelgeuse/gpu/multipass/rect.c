/* Unions of screen rectangles {x, y, width, height}. A rectangle of zero width or height is empty
 * and adds nothing, so a union may start from {0, 0, 0, 0}. */
#include "multipass.h"

void bgi_gpu_rect_union(int a[4], const int b[4])
{
    if (b[2] == 0 || b[3] == 0)
        return;
    if (a[2] == 0 || a[3] == 0) {
        for (int i = 0; i < 4; i++)
            a[i] = b[i];
        return;
    }
    int x0 = a[0] < b[0] ? a[0] : b[0], y0 = a[1] < b[1] ? a[1] : b[1];
    int x1 = a[0] + a[2] > b[0] + b[2] ? a[0] + a[2] : b[0] + b[2];
    int y1 = a[1] + a[3] > b[1] + b[3] ? a[1] + a[3] : b[1] + b[3];
    a[0] = x0, a[1] = y0, a[2] = x1 - x0, a[3] = y1 - y0;
}
