/* SPDX-License-Identifier: MIT */
/* Fuzz finding (fuzz_queries, 2026-11-28; fixed the same day, see README.md): A is the hull of a unit sphere and a point
 * 1.15e6 away (a cone 1.15e6 long, aspect 1e6, inside the accuracy ranges), B a capsule of radius
 * 1 and half height 1 overlapping A's round end. kairos_signed_distance at tolerance 1e-10 (and
 * 1e-6) answers -1 exactly (termination 5, repeated support, 46 iterations) on the right axis,
 * while the shapes separate along that axis after 0.9933838: 0.0066 too deep, 5.7e-9 of the size
 * (the stated accuracy is 1e-9). At tolerance 1e-3 it answers -0.9933817. -1 is minus the
 * capsule's radius: the distance of B's core segment to A, 0.0066, was read as touching. Exits 1
 * while the answer is deeper than the separation along its own axis allows. */
#include <stdio.h>

#include <kairos/kairos.h>

int main(void) {
    kairos_vec3 far[64];
    for (int i = 0; i < 64; ++i) far[i] = (kairos_vec3){1000000, -500000, 250000};
    kairos_shape *tip = NULL, *ball = NULL, *a = NULL, *b = NULL;
    if (kairos_shape_convex_hull(far, 64, &tip) != KAIROS_OK || kairos_shape_sphere(1, &ball) != KAIROS_OK ||
        kairos_shape_hull(tip, ball, &a) != KAIROS_OK || kairos_shape_capsule(1, 1, &b) != KAIROS_OK)
        return 2;
    const kairos_pose pa = {{-4, -4, -4}, {0, 0, 0, 1}};
    const kairos_pose pb = {{-4, -3.9980468451972229, -1.9687190051117724}, {0, 0, 0, 1}};
    kairos_distance_result r;
    if (kairos_signed_distance(a, &pa, b, &pb, NULL, &r) != KAIROS_OK) return 2;
    /* The fuzz target's bound: along r.axis the shapes are -0.99338384670721195 apart. */
    const double separation = -0.99338384670721195, size = 1.15e6;
    printf("signed distance %.17g (termination %d, %u iterations); separation along its axis %.17g\n", r.distance,
           r.termination, r.iterations, separation);
    kairos_shape_release(a);
    kairos_shape_release(b);
    kairos_shape_release(ball);
    kairos_shape_release(tip);
    return r.distance < separation - 1e-9 * size ? 1 : 0;
}
