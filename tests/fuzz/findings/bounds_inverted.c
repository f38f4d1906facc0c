/* SPDX-License-Identifier: MIT */
/* Finding: kairos_shape_bounds returns a box with min > max. A nearly flat triangle (0.0004 thick
 * in z) moved 1e15 away by kairos_shape_transformed, at a pose turned by 2e-4 rad about x: the z
 * range comes back as [999799980002000.38, 999799980002000.25]. The two ends come from two support
 * evaluations, each rounded at 1e15 (ulp 0.125), and nothing keeps them ordered; a broad phase fed
 * this box sorts its ends the wrong way round.
 * Found by fuzz_shapes (raw input: fuzz_shapes-bounds_inverted.bin). Exits 1 while the bug is
 * present. Build: see README.md. */
#include <stdio.h>
#include <kairos/kairos.h>

int main(void) {
    static const kairos_vec3 corners[3] = {{1.7316338444847723, -72.489093712961605, 0.062259943263133145},
                                           {30.486359147260803, 89.340274662267035, 0.062640718247545968},
                                           {15.696015592689774, 10.428587958854427, 0.062455043690596505}};
    static const double linear[9] = {1, 0, 0, 0, 1, 1.5609979400320384e-16, 1.17647058823529e-16, 0, 1};
    kairos_shape *triangle = NULL, *moved = NULL;
    if (kairos_shape_convex_hull(corners, 3, &triangle) != KAIROS_OK ||
        kairos_shape_transformed(triangle, linear, (kairos_vec3){1e15, 1e15, 1e15}, &moved) != KAIROS_OK) {
        printf("setup failed: %s\n", kairos_last_error());
        return 2;
    }
    const kairos_pose pose = {{9.2941176470588236e-191, -3.5576409552147701e-191, 9.6078431372549014e-191}, {-0.0001, 0, 0, 1}};
    kairos_vec3 lo, hi;
    const int32_t s = kairos_shape_bounds(moved, &pose, &lo, &hi);
    printf("%s: min (%.17g %.17g %.17g)\n    max (%.17g %.17g %.17g)\n", kairos_status_name(s), lo.x, lo.y, lo.z, hi.x, hi.y, hi.z);
    kairos_shape_release(triangle);
    kairos_shape_release(moved);
    if (s == KAIROS_OK && (lo.x > hi.x || lo.y > hi.y || lo.z > hi.z)) {
        printf("BUG: min > max\n");
        return 1;
    }
    return 0;
}
