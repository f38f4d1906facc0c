/* SPDX-License-Identifier: MIT */
/* Fuzz finding (fuzz_queries, a campaign of 2026-11-29 on 0eb5b69; fixed the same day): an
 * ellipsoid (a sphere of radius 2.73 under diag(-1, 112.2, -112.2): 306 wide, 5.5 thick) and a unit
 * sphere moving apart-to-together at tolerance 1e-3. kairos_shape_cast took its normal from the
 * loop's final v (a rounded pair whose cores have no closed form), tilted 0.0116 rad from the
 * contact normal: at toi the normal's plane cut the shapes by 1.72, beyond the contract's slack of
 * (2 tolerance + 1e-6) of the size. Exits 1 while the shapes overlap along the reported normal at
 * toi by more than tolerance times their size. */
#include <math.h>
#include <stdio.h>

#include <kairos/kairos.h>

/* Component k of R(q) v. */
static double rotate(kairos_quat q, const double v[3], int k) {
    const double x = q.x, y = q.y, z = q.z, w = q.w;
    const double m[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
                            {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
                            {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
    return m[k][0] * v[0] + m[k][1] * v[1] + m[k][2] * v[2];
}

int main(void) {
    const double radius = 2.7294117647058824;
    const double lin[9] = {-1, 0, 0, 0, 112.15686274509804, 0, 0, 0, -112.15686274509804};
    const double off[3] = {-3.0274509803921568, -4, 1.1630426489662016};
    kairos_shape *ball = NULL, *a = NULL, *b = NULL;
    if (kairos_shape_sphere(radius, &ball) != KAIROS_OK) return 2;
    if (kairos_shape_transformed(ball, lin, (kairos_vec3){off[0], off[1], off[2]}, &a) != KAIROS_OK) return 2;
    if (kairos_shape_sphere(1, &b) != KAIROS_OK) return 2;
    const kairos_pose pa = {{3.5696955825131607, -3.9704585336079958, -0.031189440756847375},
                            {0, 0, 0.70710678118654757, 0.70710678118654757}};
    const kairos_pose pb = {{3.5930113679713127, 3.5921568627450977, 3.5921568627450977},
                            {0.54910647822128777, 0.54934906175031351, 0.61145044518090996, -0.15108288790439423}};
    const kairos_vec3 ta = {0.046631570916304099, 15.125230792706187, 7.2466926070038902};
    const kairos_vec3 tb = {-ta.x, -ta.y, -ta.z};
    kairos_query_settings settings;
    kairos_query_settings_init(&settings);
    settings.tolerance = 1e-3;
    kairos_cast_result r;
    if (kairos_shape_cast(a, &pa, ta, b, &pb, tb, &settings, &r) != KAIROS_OK) return 2;
    kairos_shape_release(ball);
    kairos_shape_release(a);
    kairos_shape_release(b);
    /* A's support along n: in A's frame m = R^T n, then the ellipsoid's radius * |lin^T m| + m.off. */
    const double n[3] = {r.normal.x, r.normal.y, r.normal.z};
    const kairos_quat inv = {-pa.orientation.x, -pa.orientation.y, -pa.orientation.z, pa.orientation.w};
    const double m[3] = {rotate(inv, n, 0), rotate(inv, n, 1), rotate(inv, n, 2)};
    const double k[3] = {lin[0] * m[0] + lin[3] * m[1] + lin[6] * m[2], lin[1] * m[0] + lin[4] * m[1] + lin[7] * m[2],
                         lin[2] * m[0] + lin[5] * m[1] + lin[8] * m[2]};
    const double at_a[3] = {pa.position.x + r.toi * ta.x, pa.position.y + r.toi * ta.y, pa.position.z + r.toi * ta.z};
    const double at_b[3] = {pb.position.x + r.toi * tb.x, pb.position.y + r.toi * tb.y, pb.position.z + r.toi * tb.z};
    const double high_a = radius * sqrt(k[0] * k[0] + k[1] * k[1] + k[2] * k[2]) + m[0] * off[0] + m[1] * off[1] +
                          m[2] * off[2] + n[0] * at_a[0] + n[1] * at_a[1] + n[2] * at_a[2];
    const double low_b = n[0] * at_b[0] + n[1] * at_b[1] + n[2] * at_b[2] - 1;
    const double overlap = high_a - low_b, size = 112.15686274509804 * radius;
    printf("hit %d toi %.17g normal (%.9g %.9g %.9g) termination %d; along it the shapes overlap by %.3g at toi\n",
           r.hit, r.toi, n[0], n[1], n[2], r.termination, overlap);
    return r.hit == 1 && overlap <= settings.tolerance * size ? 0 : 1;
}
