/* SPDX-License-Identifier: MIT */
/* Fuzz finding (fuzz_world, 2026-11-28, open): a ray from (1e-300, 1e-300, 1e-300) along
 * (-6.05, -3.00, 7.99) passes about 1.7e-300 from the origin. Against a point shape the closed
 * form says miss; against the Minkowski sum of two points (the same point, through the GJK ray
 * cast) kairos_ray_cast reports a hit at toi 9.7e-303. The world's ray cast misses. The cast's
 * scale cannot bring both the ray point (1e-300) and the motion (8) near 1: it stops where the
 * motion reaches 2^400, the gap stays near 1e-181 and its square underflows, so the clip test
 * v.w > 0 reads 0 and the stop ||v||^2 <= eps^2 size^2 reads 0 <= 0. Origins of 1e-260 and above
 * miss as they should. Exits 1 while the GJK cast hits. */
#include <stdio.h>

#include <kairos/kairos.h>

int main(void) {
    kairos_shape *point = NULL, *sum = NULL;
    if (kairos_shape_point(&point) != KAIROS_OK || kairos_shape_minkowski_sum(point, point, &sum) != KAIROS_OK)
        return 2;
    const kairos_pose at = {{0, 0, 0}, {0, 0, 0, 1}};
    const kairos_vec3 origin = {1e-300, 1e-300, 1e-300};
    const kairos_vec3 motion = {-6.0549019607843135, -2.9984588387884337, 7.9887693598840315};
    kairos_cast_result closed, gjk;
    if (kairos_ray_cast(point, &at, origin, motion, NULL, &closed) != KAIROS_OK ||
        kairos_ray_cast(sum, &at, origin, motion, NULL, &gjk) != KAIROS_OK)
        return 2;
    printf("point: hit %d; Minkowski sum of two points: hit %d toi %.17g termination %d\n", closed.hit, gjk.hit,
           gjk.toi, gjk.termination);
    kairos_shape_release(sum);
    kairos_shape_release(point);
    return !closed.hit && gjk.hit ? 1 : 0;
}
