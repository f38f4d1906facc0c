/* SPDX-License-Identifier: MIT */
/* Fuzz finding (fuzz_queries, a campaign of 2026-11-29 on 0eb5b69; fixed the same day): an
 * ellipsoid (a sphere of radius 2.73 under diag(-1, 112.2, -112.2): 306 wide, 5.5 thick) and a ball
 * of radius 325 whose centre lies 0.48 off the ellipsoid's thin side. kairos_signed_distance with
 * max_iterations 3 (16 support calls: the guard) reported a depth of 324.52375, while along x the
 * shapes overlap by only 324.52215: the radii less a separation along an axis (a lower bound of the
 * cores' gap) overstated the depth. Exits 1 while the depth exceeds the overlap along x. */
#include <stdio.h>

#include <kairos/kairos.h>

int main(void) {
    const double radius = 2.7292744335088122, ball = 325.00343327992675;
    const double lin[9] = {-1, 0, 0, 0, 112.15686274509804, 0, 0, 0, -112.15686274509804};
    const kairos_vec3 off = {-3.0274509803921568, -4, 1.1630426489662016};
    kairos_shape *s = NULL, *a = NULL, *b = NULL;
    if (kairos_shape_sphere(radius, &s) != KAIROS_OK || kairos_shape_transformed(s, lin, off, &a) != KAIROS_OK ||
        kairos_shape_sphere(ball, &b) != KAIROS_OK)
        return 2;
    const kairos_pose pa = {{-0.86274509803921573, -0.86762798504615857, -0.86274509803921573}, {0, 0, 0, 1}};
    const kairos_pose pb = {{-0.67963683527885843, -3.8436255436026552, -0.86274509803921573}, {0, 0, 0, 1}};
    kairos_query_settings settings;
    kairos_query_settings_init(&settings);
    settings.max_iterations = 3;
    kairos_distance_result r;
    if (kairos_signed_distance(a, &pa, b, &pb, &settings, &r) != KAIROS_OK) return 2;
    kairos_shape_release(s);
    kairos_shape_release(a);
    kairos_shape_release(b);
    /* Along +x: the ellipsoid reaches pa.x + off.x + radius (its x radius is 1 * radius), the ball
     * starts at pb.x - ball. */
    const double overlap_x = (pa.position.x + off.x + radius) - (pb.position.x - ball);
    printf("signed distance %.17g (termination %d); along x the shapes overlap by %.17g\n", r.distance,
           r.termination, overlap_x);
    return -r.distance <= overlap_x + 1e-9 * ball ? 0 : 1;
}
