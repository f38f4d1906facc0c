/* SPDX-License-Identifier: MIT */
/* Kairos demo: fast and spinning objects that tunnel when checked only at the frames, and the
 * first times of impact Kairos finds for them, each beside its closed-form answer. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <kairos/kairos.h>

/* Stops the demo with the library's own message when a call fails. */
static void check(int32_t status, const char* what) {
    if (status != KAIROS_OK) {
        fprintf(stderr, "%s failed: %s (%s)\n", what, kairos_status_name(status), kairos_last_error());
        exit(1);
    }
}

static kairos_pose pose_at(double x, double y, double z, double angle_about_z) {
    kairos_pose p = {{x, y, z}, {0, 0, sin(0.5 * angle_about_z), cos(0.5 * angle_about_z)}};
    return p;
}

/* Do the two shapes touch at this frame? (the discrete check a frame-based engine makes) */
static int touching(const kairos_shape* a, const kairos_pose* pa, const kairos_shape* b, const kairos_pose* pb) {
    int32_t hit = 0;
    check(kairos_intersect(a, pa, b, pb, NULL, &hit), "kairos_intersect");
    return hit;
}

static void report(const char* title, int frames_hit, const kairos_cast_result* r, double exact) {
    printf("%s\n", title);
    printf("  checked at the frames only (t = 0 and t = 1): %s\n", frames_hit ? "contact" : "no contact -> tunnels");
    if (r->hit)
        printf("  Kairos: first contact at t = %.9f of the step (closed form %.9f, error %.1e)\n"
               "          normal (%+.3f, %+.3f, %+.3f), point (%+.4f, %+.4f, %+.4f), %u iterations\n",
               r->toi, exact, fabs(r->toi - exact), r->normal.x, r->normal.y, r->normal.z, r->point.x, r->point.y,
               r->point.z, r->iterations);
    else
        printf("  Kairos: no contact in the step\n");
}

int main(void) {
    printf("Kairos %u (header %d)\n\n", kairos_version(), KAIROS_VERSION_NUMBER);
    kairos_query_settings qs;
    kairos_query_settings_init(&qs);
    kairos_cast_result r;

    /* 1. A 5 mm bullet at 400 m/s toward a wall 2 cm thick, 60 frames per second. */
    {
        kairos_shape *bullet, *wall;
        check(kairos_shape_sphere(0.005, &bullet), "sphere");
        check(kairos_shape_box((kairos_vec3){0.01, 1.0, 1.0}, &wall), "box");
        const double step = 400.0 / 60.0;
        kairos_pose b0 = pose_at(-3.0, 0.1, 0, 0), b1 = pose_at(-3.0 + step, 0.1, 0, 0), w = pose_at(0, 0, 0, 0);
        const int frames = touching(bullet, &b0, wall, &w) || touching(bullet, &b1, wall, &w);
        check(kairos_shape_cast(bullet, &b0, (kairos_vec3){step, 0, 0}, wall, &w, (kairos_vec3){0, 0, 0}, &qs, &r),
              "kairos_shape_cast");
        report("1. Bullet (sphere r = 5 mm, 400 m/s) through a wall 2 cm thick, one 16.7 ms frame:", frames, &r,
               (3.0 - 0.01 - 0.005) / step);
        kairos_shape_release(bullet);
        kairos_shape_release(wall);
    }

    /* 2. A box 20 cm wide flying diagonally past the edge of a plate 1 cm thick: it clips the
     *    plate's corner region within the frame. */
    {
        kairos_shape *box, *plate;
        check(kairos_shape_box((kairos_vec3){0.1, 0.1, 0.1}, &box), "box");
        check(kairos_shape_box((kairos_vec3){0.005, 0.5, 0.5}, &plate), "plate");
        kairos_pose b0 = pose_at(-2.0, -1.0, 0, 0), p = pose_at(0, 0, 0, 0);
        const kairos_vec3 d = {4.0, 1.2, 0};
        kairos_pose b1 = pose_at(-2.0 + d.x, -1.0 + d.y, 0, 0);
        const int frames = touching(box, &b0, plate, &p) || touching(box, &b1, plate, &p);
        check(kairos_shape_cast(box, &b0, d, plate, &p, (kairos_vec3){0, 0, 0}, &qs, &r), "kairos_shape_cast");
        /* Closed form: the box's face x = +0.1 meets the plate's face x = -0.005 when
         * -2 + 4t + 0.1 = -0.005 (its y-extent [-1.1 + 1.2t, -0.9 + 1.2t] then overlaps [-0.5, 0.5]). */
        report("2. Box (20 cm) past a plate 1 cm thick, moving 4.2 m in one frame:", frames, &r, (2.0 - 0.1 - 0.005) / 4.0);
        kairos_shape_release(box);
        kairos_shape_release(plate);
    }

    /* 3. A rod 2 m long (a capsule of radius 2 cm) spinning 170 degrees about its centre in one
     *    frame, 0.6 m from a thin wall. At both frames it points nearly along the wall; while it
     *    turns, its tip sweeps through the wall. */
    {
        kairos_shape *rod, *wall;
        check(kairos_shape_capsule(0.02, 1.0, &rod), "capsule");
        check(kairos_shape_box((kairos_vec3){0.005, 2.0, 2.0}, &wall), "wall");
        /* The capsule's axis is z. Its orientation is rz(s) * rx(90 degrees): rx lays the axis along
         * y, then rz spins it about the world z axis by s, from 0 to -170 degrees over the step.
         * As quaternions rz(s) = (0, 0, sin(s/2), cos(s/2)) and rx(90) = (c, 0, 0, c), c = sqrt(1/2). */
        const double c = sqrt(0.5), s0 = 0.0, s1 = -170.0 * M_PI / 180.0;
        kairos_motion m;
        m.start.position = (kairos_vec3){0, 0, 0};
        m.end.position = m.start.position;
        m.start.orientation = (kairos_quat){cos(0.5 * s0) * c, sin(0.5 * s0) * c, sin(0.5 * s0) * c, cos(0.5 * s0) * c};
        m.end.orientation = (kairos_quat){cos(0.5 * s1) * c, sin(0.5 * s1) * c, sin(0.5 * s1) * c, cos(0.5 * s1) * c};
        kairos_motion still;
        still.start = pose_at(0.605, 0, 0, 0);
        still.end = still.start;
        const int frames = touching(rod, &m.start, wall, &still.start) || touching(rod, &m.end, wall, &still.start);
        check(kairos_motion_cast(rod, &m, wall, &still, &qs, &r), "kairos_motion_cast");
        /* Closed form: the rod's direction makes angle theta with +x; its farthest x is
         * cos(theta) + 0.02, which reaches the wall face x = 0.6 when cos(theta) = 0.58, i.e.
         * after turning from 90 degrees down to acos(0.58): t = (90 - acos(0.58)) / 170. */
        const double exact = (0.5 * M_PI - acos(0.58)) / (170.0 * M_PI / 180.0);
        report("3. Rod (2 m capsule) spinning 170 degrees in one frame, its centre 0.6 m from a thin wall:", frames, &r,
               exact);
        kairos_shape_release(rod);
        kairos_shape_release(wall);
    }

    /* Bad input gets a status and a message naming the argument, never a crash. */
    kairos_shape* bad = NULL;
    const int32_t err = kairos_shape_sphere(-1.0, &bad);
    printf("\nBad input: kairos_shape_sphere(-1.0) -> %s: %s\n", kairos_status_name(err), kairos_last_error());
    return 0;
}
