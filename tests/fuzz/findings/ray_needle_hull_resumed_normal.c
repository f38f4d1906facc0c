/* SPDX-License-Identifier: MIT */
/* Fuzz finding (fuzz_queries, CI's run of 2026-11-29 on a324f47; fixed the same day): a ray from
 * (0.3385, 0.3385, 0.3385) along (-1, -1, -1) through a 7-point hull about 1.2 long and 1e-9 thick
 * (a needle along x). kairos_ray_cast at the default tolerance stops on a rounding rule beside the
 * needle, resumes from the distance at toi, and the resumed loop hits without clipping: its normal
 * was the start-inside rule's -translation, (1, 1, 1)/sqrt(3), whose plane lies 0.18 beyond the
 * ray point at toi (the hit is late against that normal). Exits 1 while the ray point at toi is
 * behind the plane of the reported normal by more than 1e-7 of the needle's length. */
#include <stdio.h>

#include <kairos/kairos.h>

int main(void) {
    const kairos_vec3 p[7] = {{-0.708804908193434, -4.9428390493058186e-10, 2.5151679775209227e-10},
                              {0.31553503025768292, 2.0043614714960279e-10, -5.9696493772804645e-10},
                              {-0.27022296730402595, 5.7635633552808283e-10, 1.2959494650487071e-10},
                              {-0.70554886919519011, 5.2275246691693367e-11, -2.5008513694090828e-10},
                              {0.22333106430154115, 2.7786044856814266e-10, 7.7647054127806842e-10},
                              {-0.88585322493029039, 7.1768201110823498e-10, 6.6655694668278187e-10},
                              {-0.064699289083533396, -8.6946893826560246e-10, 1.0107706880905055e-10}};
    kairos_shape* needle = NULL;
    if (kairos_shape_convex_hull(p, 7, &needle) != KAIROS_OK) return 2;
    const kairos_pose pose = {{0, 0, 0}, {0, 0, 0, 1}};
    const kairos_vec3 o = {0.33852880429294913, 0.33852880429294913, 0.33852880429294913};
    const kairos_vec3 t = {-0.33852914282175339, -0.33852914282175339, -0.33852914282175339};
    kairos_cast_result r;
    if (kairos_ray_cast(needle, &pose, o, t, NULL, &r) != KAIROS_OK) return 2;
    kairos_shape_release(needle);
    const double x[3] = {o.x + r.toi * t.x, o.y + r.toi * t.y, o.z + r.toi * t.z};
    double h = -1e300;
    for (int i = 0; i < 7; ++i) {
        const double s = r.normal.x * p[i].x + r.normal.y * p[i].y + r.normal.z * p[i].z;
        if (s > h) h = s;
    }
    const double behind = h - (r.normal.x * x[0] + r.normal.y * x[1] + r.normal.z * x[2]);
    printf("hit %d toi %.17g normal (%.6g %.6g %.6g) termination %d; the ray point is %.3g behind the normal's plane\n",
           r.hit, r.toi, r.normal.x, r.normal.y, r.normal.z, r.termination, behind);
    return r.hit == 1 && behind <= 1e-7 * 1.2 ? 0 : 1;
}
