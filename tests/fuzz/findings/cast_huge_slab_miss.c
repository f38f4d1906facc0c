/* SPDX-License-Identifier: MIT */
/* Fuzz finding (fuzz_world, 2026-11-26): a unit sphere travelling 1.5e11 ends inside a box whose
 * half extents are 6.7e19, 3.28 and 6.7e10 (aspect 2e19), yet kairos_shape_cast reports no hit.
 * The world step misses the contact the same way. Exits 1 while the cast misses. */
#include <stdio.h>

#include <kairos/kairos.h>

int main(void) {
    kairos_shape *sphere = NULL, *slab = NULL;
    if (kairos_shape_sphere(1, &sphere) != KAIROS_OK ||
        kairos_shape_box((kairos_vec3){6.7030899519340806e+19, 3.279560540169375, 67030899519.340813}, &slab) !=
            KAIROS_OK)
        return 2;
    const kairos_pose start = {{99999999999, -100000000001, 49999999999}, {0, 0, 0, 1}};
    const kairos_pose end = {{-3.7108110170138096, -3.99487296864271, -4}, {0, 0, 0, 1}};
    const kairos_pose box = {{-4, -4, -3.4321202410925462},
                             {0.49327263250092857, 0.060854646124513738, -0.49041242649878691, 0.71587322481444715}};
    const kairos_vec3 motion = {end.position.x - start.position.x, end.position.y - start.position.y,
                                end.position.z - start.position.z};
    kairos_distance_result d;
    kairos_cast_result c;
    if (kairos_distance(sphere, &end, slab, &box, NULL, &d) != KAIROS_OK ||
        kairos_shape_cast(sphere, &start, motion, slab, &box, (kairos_vec3){0, 0, 0}, NULL, &c) != KAIROS_OK)
        return 2;
    printf("at the end: intersecting %d (distance %.17g); cast: hit %d toi %.17g termination %d\n", d.intersecting,
           d.distance, c.hit, c.toi, c.termination);
    kairos_shape_release(sphere);
    kairos_shape_release(slab);
    return d.intersecting && !c.hit ? 1 : 0;
}
