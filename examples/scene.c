/* SPDX-License-Identifier: MIT */
/* Kairos scene: a few thousand objects (drifting dust, bullets, thin walls, spinning rods) stepped
 * through a world for a number of frames. Prints the contacts found, how many of them a check at
 * the frames alone would have missed, and the time per step by phase; draws the trajectories and
 * contacts into a picture: <prefix>.ppm, and <prefix>.gp, a gnuplot script that turns it into
 * <prefix>.png with a title, a legend of the colours and axes in scene units (scripts/demo.sh runs it).
 *
 * Usage: kairos_scene [frames (default 30)] [output prefix (default kairos_scene)]
 * The walls are static objects, the bullets carry a filter that lets them pass through each other,
 * the narrow phase runs on two threads, and at the end a ray cast asks the world for a line of sight.
 * Only the public C API is used. A bullet stops at its first contact and leaves the world;
 * everything else passes through (the point is what is found, not a physics response). Contacts
 * are counted per step: a pair that stays in touch is counted at each step. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <kairos/kairos.h>

#define PI 3.14159265358979323846

enum { DUST = 2000, BULLETS = 300, WALLS = 24, RODS = 120, COUNT = DUST + BULLETS + WALLS + RODS };
enum kind { K_DUST, K_BULLET, K_WALL, K_ROD };

static const double kWidth = 100, kHeight = 60; /* the scene's extent in x and y (z is flat) */

/* Stops with the library's own message when a call fails. */
static void check(int32_t status, const char* what) {
    if (status != KAIROS_OK) {
        fprintf(stderr, "%s failed: %s (%s)\n", what, kairos_status_name(status), kairos_last_error());
        exit(1);
    }
}

/* A fixed sequence (splitmix64), so every run draws the same scene. */
static uint64_t rng_state = 20240607;
static double uniform(double lo, double hi) {
    uint64_t z = (rng_state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return lo + (hi - lo) * ((double)(z >> 11) * 0x1p-53);
}

/* Orientation: a turn by `angle` about z; with `lie`, after a quarter turn about y that lays a
 * shape's local z axis along world x (the product q_z * q_y). */
static kairos_quat about_z(double angle, int lie) {
    const double zs = sin(0.5 * angle), zc = cos(0.5 * angle);
    if (!lie) return (kairos_quat){0, 0, zs, zc};
    const double ys = sin(0.25 * PI), yc = cos(0.25 * PI);
    return (kairos_quat){-zs * ys, zc * ys, zs * yc, zc * yc};
}

struct object {
    enum kind kind;
    kairos_shape* shape;
    kairos_object_id id;
    double x, y, angle;   /* pose now (in a plane of constant z) */
    double z;
    double vx, vy, spin;  /* per step */
    double half_length;   /* walls and rods: half their length along their axis in the plane */
    int stuck;            /* bullets: stopped at a contact */
    float* trail;         /* x, y per frame */
};

static struct object objs[COUNT];

static kairos_pose pose_of(const struct object* o, double x, double y, double angle) {
    kairos_pose p;
    p.position.x = x;
    p.position.y = y;
    p.position.z = o->z;
    p.orientation = about_z(angle, o->kind == K_ROD);
    return p;
}

/* ---- The picture: a small rasteriser into an RGB buffer --------------------------------------- */

enum { PW = 1600, PH = 960 };
static unsigned char image[PH][PW][3];

static void plot(int px, int py, const unsigned char rgb[3], double alpha) {
    if (px < 0 || py < 0 || px >= PW || py >= PH) return;
    for (int k = 0; k < 3; ++k) image[py][px][k] = (unsigned char)(image[py][px][k] * (1 - alpha) + rgb[k] * alpha + 0.5);
}
static double to_px(double x) { return (x + 5) / (kWidth + 10) * PW; }
static double to_py(double y) { return PH - (y + 3) / (kHeight + 6) * PH; }
static void line(double x0, double y0, double x1, double y1, double width, const unsigned char rgb[3], double alpha) {
    const double ax = to_px(x0), ay = to_py(y0), bx = to_px(x1), by = to_py(y1);
    const double len = hypot(bx - ax, by - ay);
    const int n = (int)(len * 2) + 1;
    const int r = (int)(width / 2);
    for (int i = 0; i <= n; ++i) {
        const double t = (double)i / n;
        const int cx = (int)(ax + t * (bx - ax)), cy = (int)(ay + t * (by - ay));
        for (int dy = -r; dy <= r; ++dy)
            for (int dx = -r; dx <= r; ++dx) plot(cx + dx, cy + dy, rgb, alpha);
    }
}
static void disk(double x, double y, double radius_px, const unsigned char rgb[3], double alpha, int ring) {
    const double cx = to_px(x), cy = to_py(y);
    const int r = (int)ceil(radius_px);
    for (int dy = -r; dy <= r; ++dy)
        for (int dx = -r; dx <= r; ++dx) {
            const double d = hypot(dx, dy);
            if (d > radius_px || (ring && d < radius_px - 1.6)) continue;
            plot((int)cx + dx, (int)cy + dy, rgb, alpha);
        }
}

/* The gnuplot script for <prefix>.png: the PPM drawn in scene units (x from -5 to kWidth + 5, y
 * from -3 to kHeight + 3, as to_px and to_py map them), a title with the counts, and a legend. */
static int write_plot_script(const char* prefix, long header_bytes, int frames, long long contacts,
                             long long missed) {
    char path[512];
    snprintf(path, sizeof path, "%s.gp", prefix);
    FILE* f = fopen(path, "w");
    if (!f) {
        fprintf(stderr, "cannot write %s\n", path);
        return 0;
    }
    fprintf(f,
            "set terminal pngcairo size 1760,940 font 'DejaVu Sans,11'\n"
            "set output '%s.png'\n"
            "set title \"Kairos world: %d objects over %d steps; %lld contacts found, %lld of them missed by a "
            "check at the frames alone\" font ',14'\n"
            "set xlabel 'x (scene units; a wall is 8 long)'\nset ylabel 'y (scene units)'\n"
            "set xrange [-5:%g]\nset yrange [-3:%g]\nset size ratio -1\n"
            "set key outside right top box opaque samplen 1 spacing 1.3\n"
            "plot '%s.ppm' binary array=(%d,%d) skip=%ld format='%%uchar' flipy dx=%.17g dy=%.17g "
            "origin=(-5,-3) with rgbimage notitle, \\\n"
            "  NaN with points pt 7 ps 0.8 lc rgb '#969696' title 'dust (drifting spheres)', \\\n"
            "  NaN with lines lw 3 lc rgb '#1e1e1e' title 'thin wall (a box at rest)', \\\n"
            "  NaN with linespoints pt 7 lc rgb '#e67e22' title 'bullet: path, end', \\\n"
            "  NaN with lines lw 3 lc rgb '#2471a3' title 'spinning rod: path, end, swept circle', \\\n"
            "  NaN with points pt 7 ps 0.8 lc rgb '#c81e1e' title 'contact point', \\\n"
            "  NaN with points pt 6 ps 1.8 lc rgb '#aa00aa' title 'contact missed at the frames'\n",
            prefix, COUNT, frames, contacts, missed, kWidth + 5, kHeight + 3, prefix, PW, PH, header_bytes,
            (kWidth + 10) / PW, (kHeight + 6) / PH);
    fclose(f);
    return 1;
}

static void write_picture(const char* prefix, int frames, const kairos_vec3* hit_points, const int* hit_missed,
                          int hits, long long contacts, long long missed) {
    static const unsigned char white[3] = {255, 255, 255}, grey[3] = {150, 150, 150}, wall[3] = {30, 30, 30},
                               bullet[3] = {230, 126, 34}, rod[3] = {36, 113, 163}, red[3] = {200, 30, 30},
                               magenta[3] = {170, 0, 170};
    for (int y = 0; y < PH; ++y)
        for (int x = 0; x < PW; ++x) plot(x, y, white, 1);
    for (int i = 0; i < COUNT; ++i) {
        const struct object* o = &objs[i];
        if (o->kind == K_DUST) {
            disk(o->x, o->y, 1.6, grey, 0.8, 0);
        } else if (o->kind == K_WALL) {
            const double c = cos(o->angle) * o->half_length, s = sin(o->angle) * o->half_length;
            line(o->x - s, o->y + c, o->x + s, o->y - c, 3, wall, 1); /* a wall's long side is its local y */
        } else if (o->kind == K_BULLET) {
            for (int f = 1; f <= frames && o->trail[2 * f] == o->trail[2 * f]; ++f)
                line(o->trail[2 * f - 2], o->trail[2 * f - 1], o->trail[2 * f], o->trail[2 * f + 1], 1, bullet, 0.6);
            disk(o->x, o->y, 2.5, bullet, 1, 0);
        } else {
            /* A rod: the circle its tips sweep (faint), its path, and where it ends (solid). */
            disk(o->x, o->y, o->half_length * PW / (kWidth + 10), rod, 0.25, 1);
            for (int f = 1; f <= frames; ++f)
                line(o->trail[2 * f - 2], o->trail[2 * f - 1], o->trail[2 * f], o->trail[2 * f + 1], 1, rod, 0.5);
            const double c = cos(o->angle) * o->half_length, s = sin(o->angle) * o->half_length;
            line(o->x - c, o->y - s, o->x + c, o->y + s, 3, rod, 1);
        }
    }
    /* Contacts: a red dot; those a check at the frames alone would miss, a magenta ring. */
    for (int i = 0; i < hits; ++i) {
        if (hit_missed[i] < 0) continue;
        disk(hit_points[i].x, hit_points[i].y, 1.8, red, 0.9, 0);
        if (hit_missed[i]) disk(hit_points[i].x, hit_points[i].y, 4.5, magenta, 0.8, 1);
    }
    char ppm[512];
    snprintf(ppm, sizeof ppm, "%s.ppm", prefix);
    FILE* f = fopen(ppm, "wb");
    if (!f) {
        fprintf(stderr, "cannot write %s\n", ppm);
        return;
    }
    const int header = fprintf(f, "P6\n%d %d\n255\n", PW, PH);
    fwrite(image, 1, sizeof image, f);
    fclose(f);
    if (header > 0 && write_plot_script(prefix, header, frames, contacts, missed))
        printf("picture: %s (%s.gp draws %s.png with a title, a legend and axes: gnuplot %s.gp)\n", ppm, prefix,
               prefix, prefix);
}

/* ---- The scene ----------------------------------------------------------------------------------- */

int main(int argc, char** argv) {
    const int frames = argc > 1 ? atoi(argv[1]) : 30;
    const char* prefix = argc > 2 ? argv[2] : "kairos_scene";
    if (frames < 1 || frames > 10000) {
        fprintf(stderr, "frames must be in 1..10000\n");
        return 1;
    }
    /* Two threads share the narrow phase (the results are the same with one). */
    kairos_world_settings ws;
    kairos_world_settings_init(&ws);
    ws.worker_count = 2;
    kairos_world* w;
    check(kairos_world_create(&ws, &w), "kairos_world_create");
    /* Bullets pass through each other: their category (2) is not in their own mask. */
    const kairos_filter bullet_filter = {2, ~2u, 0};

    kairos_shape *wall_shape, *rod_shape, *bullet_shape;
    check(kairos_shape_box((kairos_vec3){0.03, 4.0, 3.5}, &wall_shape), "box");
    check(kairos_shape_capsule(0.05, 1.2, &rod_shape), "capsule");
    check(kairos_shape_sphere(0.06, &bullet_shape), "sphere");

    for (int i = 0; i < COUNT; ++i) {
        struct object* o = &objs[i];
        o->trail = malloc(sizeof(float) * 2 * (size_t)(frames + 1));
        if (!o->trail) return 1;
        for (int k = 0; k < 2 * (frames + 1); ++k) o->trail[k] = NAN;
        if (i < DUST) {
            o->kind = K_DUST;
            if (i % 2) {
                check(kairos_shape_sphere(uniform(0.15, 0.3), &o->shape), "sphere");
            } else {
                const double h = uniform(0.1, 0.25);
                check(kairos_shape_box((kairos_vec3){h, uniform(0.1, 0.25), 0.2}, &o->shape), "box");
            }
            o->x = uniform(0, kWidth);
            o->y = uniform(0, kHeight);
            o->z = uniform(-3, 3);  /* dust and bullets fill a slab; walls span it; rods lie at z = 0 */
            o->angle = uniform(0, 2 * PI);
            o->vx = uniform(-0.15, 0.15);
            o->vy = uniform(-0.15, 0.15);
        } else if (i < DUST + BULLETS) {
            o->kind = K_BULLET;
            o->shape = bullet_shape;
            kairos_shape_retain(bullet_shape);
            o->x = uniform(-4, 4);
            o->y = uniform(0, kHeight);
            o->z = uniform(-3, 3);
            const double heading = uniform(-0.35, 0.35), speed = uniform(5, 9);
            o->vx = speed * cos(heading);
            o->vy = speed * sin(heading);
        } else if (i < DUST + BULLETS + WALLS) {
            o->kind = K_WALL;
            o->shape = wall_shape;
            kairos_shape_retain(wall_shape);
            const int k = i - DUST - BULLETS;
            o->x = 12 + (k % 6) * 15 + uniform(-2, 2);
            o->y = 8 + (k / 6) * 14 + uniform(-2, 2);
            o->angle = uniform(-0.6, 0.6);
            o->half_length = 4.0;
        } else {
            o->kind = K_ROD;
            o->shape = rod_shape;
            kairos_shape_retain(rod_shape);
            o->x = uniform(5, kWidth - 5);
            o->y = uniform(3, kHeight - 3);
            o->angle = uniform(0, 2 * PI);
            o->spin = uniform(1.0, 3.0) * (i % 2 ? 1 : -1); /* 57 to 172 degrees per step */
            o->vx = uniform(-0.05, 0.05);
            o->vy = uniform(-0.05, 0.05);
            o->half_length = 1.25;
        }
        const kairos_pose p = pose_of(o, o->x, o->y, o->angle);
        check(kairos_world_add(w, o->shape, &p, (uint64_t)i, &o->id), "kairos_world_add");
        /* Walls never move: static, they cost a step nothing unless something comes near. */
        if (o->kind == K_WALL) check(kairos_world_set_static(w, o->id, 1), "kairos_world_set_static");
        if (o->kind == K_BULLET) check(kairos_world_set_filter(w, o->id, &bullet_filter), "kairos_world_set_filter");
        o->trail[0] = (float)o->x;
        o->trail[1] = (float)o->y;
    }

    /* Contact points for the picture, and whether the frames alone would have seen each. */
    size_t cap = 4096, hits = 0;
    kairos_vec3* hit_points = malloc(cap * sizeof *hit_points);
    int* hit_missed = malloc(cap * sizeof *hit_missed);
    double* end_x = malloc(COUNT * sizeof *end_x);
    double* end_y = malloc(COUNT * sizeof *end_y);
    double* end_a = malloc(COUNT * sizeof *end_a);
    double* stop_t = malloc(COUNT * sizeof *stop_t);
    if (!hit_points || !hit_missed || !end_x || !end_y || !end_a || !stop_t) return 1;

    long long contacts = 0, missed = 0, by_kind[4][4] = {{0}}, missed_by_kind[4][4] = {{0}};
    double broad = 0, narrow = 0;
    unsigned long long pairs = 0, queries = 0, iterations = 0, swaps = 0;
    for (int f = 1; f <= frames; ++f) {
        for (int i = 0; i < COUNT; ++i) {
            struct object* o = &objs[i];
            end_x[i] = o->x;
            end_y[i] = o->y;
            end_a[i] = o->angle;
            stop_t[i] = 2;
            if (o->kind == K_WALL || o->stuck) continue;
            end_x[i] = o->x + o->vx;
            end_y[i] = o->y + o->vy;
            end_a[i] = o->angle + o->spin;
            const kairos_pose e = pose_of(o, end_x[i], end_y[i], end_a[i]);
            check(kairos_world_move(w, o->id, &e), "kairos_world_move");
        }
        check(kairos_world_step(w), "kairos_world_step");
        kairos_step_stats st;
        kairos_step_stats_init(&st);
        check(kairos_world_step_stats(w, &st), "kairos_world_step_stats");
        broad += st.broad_phase_seconds;
        narrow += st.narrow_phase_seconds;
        pairs += st.broad_phase_pairs;
        queries += st.narrow_phase_queries;
        iterations += st.gjk_iterations;
        swaps += st.swaps;

        const kairos_contact* cs;
        size_t n;
        check(kairos_world_contacts(w, &cs, &n), "kairos_world_contacts");
        for (size_t c = 0; c < n; ++c) {
            const int a = (int)cs[c].user_a, b = (int)cs[c].user_b;
            /* A frame-based check looks at t = 0 and t = 1 only. */
            const kairos_pose a0 = pose_of(&objs[a], objs[a].x, objs[a].y, objs[a].angle);
            const kairos_pose b0 = pose_of(&objs[b], objs[b].x, objs[b].y, objs[b].angle);
            const kairos_pose a1 = pose_of(&objs[a], end_x[a], end_y[a], end_a[a]);
            const kairos_pose b1 = pose_of(&objs[b], end_x[b], end_y[b], end_a[b]);
            int32_t at0 = 0, at1 = 0;
            check(kairos_intersect(objs[a].shape, &a0, objs[b].shape, &b0, NULL, &at0), "kairos_intersect");
            check(kairos_intersect(objs[a].shape, &a1, objs[b].shape, &b1, NULL, &at1), "kairos_intersect");
            const int miss = !at0 && !at1;
            ++contacts;
            missed += miss;
            const int ka = objs[a].kind, kb = objs[b].kind;
            const int lo = ka < kb ? ka : kb, hi = ka < kb ? kb : ka;
            ++by_kind[lo][hi];
            missed_by_kind[lo][hi] += miss;
            if (hits == cap) {
                cap *= 2;
                hit_points = realloc(hit_points, cap * sizeof *hit_points);
                hit_missed = realloc(hit_missed, cap * sizeof *hit_missed);
                if (!hit_points || !hit_missed) return 1;
            }
            hit_points[hits] = cs[c].point;
            /* Drawn: contacts with bullets, rods or walls (dust among itself stays undrawn). */
            hit_missed[hits] = hi == K_DUST ? -1 : miss;
            ++hits;
            /* Bullets stop at their first contact (contacts come sorted by time). */
            if (objs[a].kind == K_BULLET && stop_t[a] > 1) stop_t[a] = cs[c].toi;
            if (objs[b].kind == K_BULLET && stop_t[b] > 1) stop_t[b] = cs[c].toi;
        }
        /* Everyone is at the end pose now; a stopped bullet goes back to where it met. */
        for (int i = 0; i < COUNT; ++i) {
            struct object* o = &objs[i];
            if (o->kind == K_WALL || o->stuck) continue;
            if (stop_t[i] <= 1) {
                const double t = stop_t[i];
                o->x += t * o->vx;
                o->y += t * o->vy;
                o->stuck = 1;  /* it leaves the world; the picture keeps it where it met */
                check(kairos_world_remove(w, o->id), "kairos_world_remove");
            } else {
                o->x = end_x[i];
                o->y = end_y[i];
                o->angle = end_a[i];
            }
            /* Dust bounces off the edges of the scene. */
            if (o->kind == K_DUST || o->kind == K_ROD) {
                if ((o->x < 0 && o->vx < 0) || (o->x > kWidth && o->vx > 0)) o->vx = -o->vx;
                if ((o->y < 0 && o->vy < 0) || (o->y > kHeight && o->vy > 0)) o->vy = -o->vy;
            }
        }
        for (int i = 0; i < COUNT; ++i) {
            objs[i].trail[2 * f] = (float)objs[i].x;
            objs[i].trail[2 * f + 1] = (float)objs[i].y;
        }
    }

    static const char* names[4] = {"dust", "bullet", "wall", "rod"};
    printf("Kairos scene: %d objects (%d dust, %d bullets, %d thin walls, %d spinning rods), %d frames\n", COUNT, DUST,
           BULLETS, WALLS, RODS, frames);
    printf("contacts found: %lld; a check at the frames alone (t = 0 and t = 1) would have missed %lld (%.1f %%)\n",
           contacts, missed, contacts ? 100.0 * (double)missed / (double)contacts : 0.0);
    for (int a = 0; a < 4; ++a)
        for (int b = a; b < 4; ++b)
            if (by_kind[a][b])
                printf("  %-6s - %-6s %6lld contacts, %6lld missed at the frames\n", names[a], names[b], by_kind[a][b],
                       missed_by_kind[a][b]);
    printf("per step (mean of %d, narrow phase on %u threads): broad phase %.3f ms, narrow phase %.3f ms; %.0f "
           "broad-phase pairs, %.0f swaps, %.0f casts, %.1f GJK iterations per cast\n",
           frames, ws.worker_count, 1e3 * broad / frames, 1e3 * narrow / frames, (double)pairs / frames,
           (double)swaps / frames, (double)queries / frames, queries ? (double)iterations / (double)queries : 0.0);
    /* A line of sight across the scene at its end, as a game would ask the world. */
    kairos_world_hit sight;
    check(kairos_world_ray_cast(w, (kairos_vec3){-5, 0.5 * kHeight, 0}, (kairos_vec3){kWidth + 10, 0, 0}, NULL, &sight),
          "kairos_world_ray_cast");
    if (sight.hit)
        printf("line of sight along y = %.0f from x = -5: blocked at x = %.2f by object %llu (a %s)\n", 0.5 * kHeight,
               sight.point.x, (unsigned long long)sight.user_data, names[objs[sight.user_data].kind]);
    else
        printf("line of sight along y = %.0f: clear\n", 0.5 * kHeight);
    int stuck = 0;
    for (int i = 0; i < COUNT; ++i) stuck += objs[i].stuck;
    printf("bullets stopped at a contact: %d of %d\n", stuck, BULLETS);
    write_picture(prefix, frames, hit_points, hit_missed, (int)hits, contacts, missed);

    for (int i = 0; i < COUNT; ++i) {
        kairos_shape_release(objs[i].shape);
        free(objs[i].trail);
    }
    kairos_shape_release(wall_shape);
    kairos_shape_release(rod_shape);
    kairos_shape_release(bullet_shape);
    kairos_world_destroy(w);
    free(hit_points);
    free(hit_missed);
    free(end_x);
    free(end_y);
    free(end_a);
    free(stop_t);
    return 0;
}
