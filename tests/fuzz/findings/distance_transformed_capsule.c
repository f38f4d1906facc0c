/* SPDX-License-Identifier: MIT */
/* Finding: a capsule behind an identity kairos_shape_transformed answers differently from the bare
 * capsule, and wrongly for long ones. A unit sphere at the centre of capsule(r 26.23, half_height
 * 1e10) is inside it; the bare capsule gives distance 0, intersecting. Transformed by the identity:
 * distance 12.116, intersecting 0, termination NO_PROGRESS (a missed collision). At half_height
 * 7e13: intersecting, but point_b = (-4, -4, -6.2e6), 6e6 outside the unit sphere; the error of
 * point_b grows with the length already from 1e3 (3e-14, 3e-11, 7e-9, ..., 6e-5 at 1e12).
 * The same happens for needle hulls (distance_witness_points.c): GJK on a long, thin simplex.
 * Found by fuzz_queries (reduced here by hand from its report). Exits 1 while the bug is present.
 * Build: see README.md. */
#include <math.h>
#include <stdio.h>
#include <kairos/kairos.h>

int main(void) {
    static const double identity[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    static const double lengths[] = {1e3, 1e6, 1e8, 1e10, 1e12, 69850308995193.406};
    const kairos_pose pose = {{-4, -4, -4}, {0, 0, 0, 1}};
    int bugs = 0;
    for (size_t i = 0; i < sizeof lengths / sizeof lengths[0]; ++i) {
        kairos_shape *capsule = NULL, *moved = NULL, *ball = NULL;
        if (kairos_shape_capsule(26.232547493705653, lengths[i], &capsule) != KAIROS_OK ||
            kairos_shape_transformed(capsule, identity, (kairos_vec3){0, 0, 0}, &moved) != KAIROS_OK ||
            kairos_shape_sphere(1, &ball) != KAIROS_OK) {
            printf("setup failed: %s\n", kairos_last_error());
            return 2;
        }
        kairos_distance_result bare, wrapped;
        const int32_t s1 = kairos_distance(capsule, &pose, ball, &pose, NULL, &bare);
        const int32_t s2 = kairos_distance(moved, &pose, ball, &pose, NULL, &wrapped);
        const double off = sqrt((wrapped.point_b.x + 4) * (wrapped.point_b.x + 4) + (wrapped.point_b.y + 4) * (wrapped.point_b.y + 4) +
                                (wrapped.point_b.z + 4) * (wrapped.point_b.z + 4));
        const int bad = s1 == KAIROS_OK && s2 == KAIROS_OK && (wrapped.intersecting != 1 || off > 1 + 1e-9);
        printf("half_height %g: bare %s distance %g intersecting %d; identity-transformed %s distance %.17g intersecting %d "
               "termination %d, point_b %.3g from the sphere's centre%s\n",
               lengths[i], kairos_status_name(s1), bare.distance, bare.intersecting, kairos_status_name(s2), wrapped.distance,
               wrapped.intersecting, wrapped.termination, off, bad ? "  BUG" : "");
        bugs += bad;
        kairos_shape_release(capsule);
        kairos_shape_release(moved);
        kairos_shape_release(ball);
    }
    return bugs > 0 ? 1 : 0;
}
