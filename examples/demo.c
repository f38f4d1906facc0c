/* Kairos demo: why continuous collision detection matters, and what the library answers today. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <kairos/kairos.h>

/* Stops the demo with the library's own message when a call fails unexpectedly. */
static void check(int32_t status, const char* what) {
    if (status != KAIROS_OK) {
        fprintf(stderr, "%s failed: %s (%s)\n", what, kairos_status_name(status), kairos_last_error());
        exit(1);
    }
}

static int boxes_overlap(kairos_vec3 amin, kairos_vec3 amax, kairos_vec3 bmin, kairos_vec3 bmax) {
    return amin.x <= bmax.x && bmin.x <= amax.x && amin.y <= bmax.y && bmin.y <= amax.y && amin.z <= bmax.z &&
           bmin.z <= amax.z;
}

int main(void) {
    const kairos_quat identity = {0, 0, 0, 1};
    printf("Kairos %u (header %d)\n\n", kairos_version(), KAIROS_VERSION_NUMBER);

    /* The scene: a 1 cm bullet at 400 m/s and a 2 cm thick wall, checked at 60 frames per second. */
    kairos_shape *bullet = NULL, *wall = NULL;
    check(kairos_shape_sphere(0.005, &bullet), "kairos_shape_sphere");
    check(kairos_shape_box((kairos_vec3){0.01, 1.0, 1.0}, &wall), "kairos_shape_box");
    const double dt = 1.0 / 60.0, speed = 400.0;
    const kairos_pose wall_pose = {{0, 0, 0}, identity};
    kairos_vec3 wmin, wmax;
    check(kairos_shape_bounds(wall, &wall_pose, &wmin, &wmax), "kairos_shape_bounds");

    printf("A bullet (sphere, r = 5 mm) flies at %.0f m/s toward a wall 2 cm thick, frames every %.1f ms.\n", speed,
           1000 * dt);
    int frame_hits = 0;
    double x = -3.0;
    for (int frame = 0; frame <= 2; ++frame, x += speed * dt) {
        const kairos_pose p = {{x, 0.1, 0}, identity};
        kairos_vec3 bmin, bmax;
        check(kairos_shape_bounds(bullet, &p, &bmin, &bmax), "kairos_shape_bounds");
        const int hit = boxes_overlap(bmin, bmax, wmin, wmax);
        frame_hits += hit;
        printf("  frame %d: bullet at x = %+7.3f m   overlap with the wall: %s\n", frame, x, hit ? "yes" : "no");
    }
    printf("Checked only at the frames, the bullet passes through the wall: %s.\n\n",
           frame_hits ? "no (caught)" : "it tunnels, the hit is missed");

    /* The continuous answer: sweep the bullet over each frame's step and find the time of impact. */
    const kairos_pose start = {{-3.0, 0.1, 0}, identity};
    const kairos_vec3 step = {speed * dt, 0, 0};
    kairos_cast_result cast;
    const int32_t status =
        kairos_shape_cast(bullet, &start, step, wall, &wall_pose, (kairos_vec3){0, 0, 0}, NULL, &cast);
    if (status == KAIROS_OK) {
        printf("kairos_shape_cast over frame 0 -> 1: hit = %d at t = %.6f of the step (%.3f ms), normal (%.2f, %.2f, %.2f)\n",
               cast.hit, cast.toi, 1000 * dt * cast.toi, cast.normal.x, cast.normal.y, cast.normal.z);
    } else {
        printf("kairos_shape_cast: %s in this version (%s)\n", kairos_status_name(status), kairos_last_error());
        printf("  The exact answer, by hand: the bullet's front reaches the wall at t = %.6f of the step.\n",
               ((wmin.x - 0.005) - start.position.x) / step.x);
    }

    /* Every shape kind is a support mapping: its farthest point along any direction. */
    printf("\nShapes and their farthest point along (1, 1, 1):\n");
    kairos_shape* shapes[8];
    const char* names[8] = {"point", "segment", "sphere", "box", "capsule", "cylinder", "cone", "hull of 8 points"};
    check(kairos_shape_point(&shapes[0]), "point");
    check(kairos_shape_segment(1, &shapes[1]), "segment");
    check(kairos_shape_sphere(1, &shapes[2]), "sphere");
    check(kairos_shape_box((kairos_vec3){1, 2, 3}, &shapes[3]), "box");
    check(kairos_shape_capsule(0.5, 1, &shapes[4]), "capsule");
    check(kairos_shape_cylinder(1, 2, &shapes[5]), "cylinder");
    check(kairos_shape_cone(1, 2, &shapes[6]), "cone");
    const kairos_vec3 cube[8] = {{-1, -1, -1}, {1, -1, -1}, {-1, 1, -1}, {1, 1, -1},
                                 {-1, -1, 1},  {1, -1, 1},  {-1, 1, 1},  {1, 1, 1}};
    check(kairos_shape_convex_hull(cube, 8, &shapes[7]), "convex hull");
    for (int i = 0; i < 8; ++i) {
        kairos_vec3 s;
        check(kairos_shape_support(shapes[i], (kairos_vec3){1, 1, 1}, &s), "kairos_shape_support");
        printf("  %-17s (%+.4f, %+.4f, %+.4f)\n", names[i], s.x, s.y, s.z);
    }

    /* Bad input gets a status and a message naming the argument, never a crash. */
    kairos_shape* bad = NULL;
    const int32_t err = kairos_shape_sphere(-1.0, &bad);
    printf("\nkairos_shape_sphere(-1.0): %s: %s\n", kairos_status_name(err), kairos_last_error());

    for (int i = 0; i < 8; ++i) kairos_shape_release(shapes[i]);
    kairos_shape_release(bullet);
    kairos_shape_release(wall);
    return 0;
}
