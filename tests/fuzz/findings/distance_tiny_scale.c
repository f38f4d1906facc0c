/* SPDX-License-Identifier: MIT */
/* Finding: kairos_distance calls two separated tetrahedra touching once they are small. The same
 * pair scaled by s (gap 2.01 s) gives distance/s = 2.0124611797498106 at s = 1 .. 1e-150,
 * 2.01242 at s = 1e-160 (relative error 2e-5) and 0 with termination NEAR_CONTACT at s = 1e-200
 * and below: squared lengths underflow. Sizes have no lower limit (only KAIROS_MAX_MAGNITUDE
 * above), so such shapes are accepted and then answered wrongly.
 * Found by fuzz_queries once its slack lost an absolute 1e-300 floor. Exits 1 while the bug is
 * present. Build: see README.md. */
#include <math.h>
#include <stdio.h>
#include <kairos/kairos.h>

int main(void) {
    static const double scales[] = {1, 1e-100, 1e-150, 1e-160, 1e-200, 1e-250, 1e-300};
    int bugs = 0;
    for (size_t i = 0; i < sizeof scales / sizeof scales[0]; ++i) {
        const double s = scales[i];
        const kairos_vec3 pa[4] = {{0, 0, 0}, {s, 0, 0}, {0, s, 0}, {0, 0, s}};
        const kairos_vec3 pb[4] = {{3 * s, 0.2 * s, 0.1 * s}, {4 * s, 0.1 * s, 0}, {3.5 * s, s, 0.2 * s}, {3.2 * s, 0.3 * s, s}};
        kairos_shape *a = NULL, *b = NULL;
        if (kairos_shape_convex_hull(pa, 4, &a) != KAIROS_OK || kairos_shape_convex_hull(pb, 4, &b) != KAIROS_OK) {
            printf("scale %g: refused: %s\n", s, kairos_last_error());
            kairos_shape_release(a);
            continue;
        }
        kairos_distance_result r;
        const int32_t status = kairos_distance(a, NULL, b, NULL, NULL, &r);
        kairos_shape_release(a);
        kairos_shape_release(b);
        if (status != KAIROS_OK) {
            printf("scale %g: %s\n", s, kairos_status_name(status));
            continue;
        }
        const double relative = fabs(r.distance / s - 2.0124611797498106) / 2.0124611797498106;
        printf("scale %g: distance / scale %.17g (intersecting %d, termination %d)%s\n", s, r.distance / s,
               r.intersecting, r.termination, relative > 1e-9 ? "  BUG" : "");
        bugs += relative > 1e-9;
    }
    return bugs > 0 ? 1 : 0;
}
