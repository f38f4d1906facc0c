/* SPDX-License-Identifier: MIT */
/* Finding (fuzz_queries campaign, 2026-11-27): a box of half extents (6.79, 1, 1e6) and a cylinder
 * of radius 1, half height 7.85, their centres 0.5 apart across the box's thickness, overlap by
 * about 1.5; kairos_distance answers 0.0311 apart (termination NO_PROGRESS after 28 iterations, the
 * recoveries spent), in both argument orders. A - B has an aspect of about 5e5, inside the
 * documented accuracy range (1e6). Present before this session too (5198fa6). Exits 1 while the
 * bug is present. Build: see README.md. */
#include <stdio.h>
#include <kairos/kairos.h>

int main(void) {
    kairos_shape *box = NULL, *cylinder = NULL;
    if (kairos_shape_box((kairos_vec3){6.785763332570383, 1, 1000000}, &box) != KAIROS_OK) return 2;
    if (kairos_shape_cylinder(1, 7.8455481803616385, &cylinder) != KAIROS_OK) return 2;
    const kairos_pose pa = {{-4, -3.4999923704890517, -3.9765621423666744}, {0, 0, 0, 1}};
    const kairos_pose pb = {{-4, -4, -4}, {0, 0, 0, 1}};
    kairos_distance_result r;
    int bad = 0;
    for (int order = 0; order < 2; ++order) {
        const int s = order == 0 ? kairos_distance(box, &pa, cylinder, &pb, NULL, &r)
                                 : kairos_distance(cylinder, &pb, box, &pa, NULL, &r);
        printf("order %d: status %d distance %.17g intersecting %d termination %d\n", order, s, r.distance,
               r.intersecting, r.termination);
        if (s != KAIROS_OK || !r.intersecting) bad = 1;
    }
    kairos_shape_release(box);
    kairos_shape_release(cylinder);
    return bad;
}
