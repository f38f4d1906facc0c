/* SPDX-License-Identifier: MIT */
/* Kairos: continuous (space-time) collision detection of convex shapes. The one public C header. */
#ifndef KAIROS_KAIROS_H
#define KAIROS_KAIROS_H

/*
 * Conventions that hold for every function below.
 *
 * Units and frames. Lengths are in the caller's unit (any unit, used consistently). Times are
 * fractions of one step, in [0, 1]. Every point and vector in a result is in the world frame
 * unless its comment says otherwise. A pose maps a shape's local frame to the world frame:
 * x -> R(orientation) * x + position.
 *
 * Status. Every fallible function returns an int32_t status: KAIROS_OK (0) or a negative
 * KAIROS_ERROR_* value. On failure nothing is written to any output and no object is changed;
 * kairos_last_error() then names the argument that was wrong and why. No function aborts,
 * prints, or lets a C++ exception escape.
 *
 * Numbers. Every double given to the library must be finite (no NaN, no infinity); a
 * quaternion must have unit length within KAIROS_QUAT_TOLERANCE (it is then normalised).
 * Magnitudes: every coordinate, length and size given (positions, translations, ray origins,
 * radii, half extents, hull points, transform translations) must lie within
 * +-KAIROS_MAX_MAGNITUDE (1e100), and so must every shape's extent in its local frame (a
 * transformed shape, Minkowski sum or hull whose points reach beyond it is refused). Beyond that
 * squared lengths would overflow; such input gets KAIROS_ERROR_INVALID_ARGUMENT naming it, so a
 * successful call never returns NaN or infinity. Directions (kairos_shape_support) may have any
 * finite length.
 *
 * Extensible input structs (kairos_query_settings, kairos_world_settings) start with
 * uint32_t struct_size and are passed by pointer only. Fill them with their
 * kairos_*_init function, which sets struct_size and the library's defaults. Fields are only
 * ever appended. The library accepts any struct_size from the first published size up: a
 * larger size (a caller built against a newer header) is accepted when every byte past the
 * fields this library knows is zero. A smaller size is KAIROS_ERROR_STRUCT_SIZE.
 *
 * Embedded settings. kairos_world_settings holds a kairos_query_settings by value. To keep the
 * fields after it from ever shifting, kairos_query_settings is frozen: its size and layout are
 * fixed for the whole major version 0, and its struct_size must equal
 * sizeof(kairos_query_settings) (checked, to catch an uninitialised struct). Should queries need more options, they will come as a new struct with
 * its own struct_size, taken by new functions and appended at the end of kairos_world_settings.
 *
 * Result structs (kairos_distance_result, kairos_cast_result, kairos_contact) are frozen: no
 * struct_size, layout fixed for the major version. Growth goes through new functions with new
 * result structs. kairos_step_stats is the one growing output: the library writes at most
 * out->struct_size bytes of it (any size from 4 up: an older caller gets the fields it knows;
 * below 4, KAIROS_ERROR_STRUCT_SIZE).
 *
 * Threads. Shapes are immutable once made: any number of threads may query them at once, and
 * retain/release are atomic. A world is used by one thread at a time (no internal locking).
 * kairos_last_error() is per thread. There is no global state to set.
 *
 * Determinism. The same inputs on the same build give bit-identical results.
 *
 * Completeness. Every function declared here is built in this version; no function returns
 * KAIROS_ERROR_NOT_IMPLEMENTED. That status is kept for contract additions that a version
 * declares before it builds them.
 */

#include <stddef.h>
#include <stdint.h>

#include "kairos/kairos_version.h"

#if defined(_WIN32)
#  if defined(KAIROS_BUILDING_LIBRARY)
#    define KAIROS_API __declspec(dllexport)
#  else
#    define KAIROS_API __declspec(dllimport)
#  endif
#elif defined(__GNUC__)
#  define KAIROS_API __attribute__((visibility("default")))
#else
#  define KAIROS_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* ---------------------------------------------------------------------------------------------
 * Status codes. Values are explicit and never renumbered; new codes take new values.
 */
#define KAIROS_OK                          0
#define KAIROS_ERROR_NULL_ARGUMENT        (-1)  /* a required pointer was NULL */
#define KAIROS_ERROR_INVALID_ARGUMENT     (-2)  /* NaN or infinite number, size <= 0, non-unit quaternion, singular matrix, unknown enum value */
#define KAIROS_ERROR_STRUCT_SIZE          (-3)  /* struct_size too small, or a larger struct with a non-zero unknown tail */
#define KAIROS_ERROR_DEGENERATE           (-4)  /* input that names no shape: an empty point set, a triangle of collinear points */
#define KAIROS_ERROR_STALE_ID             (-5)  /* an object id that is 0, unknown, or of a removed object */
#define KAIROS_ERROR_OUT_OF_MEMORY        (-6)  /* an allocation failed; nothing was changed */
#define KAIROS_ERROR_NOT_IMPLEMENTED      (-7)  /* declared in the contract, not yet built in this version */
#define KAIROS_ERROR_UNSUPPORTED_VERSION  (-8)  /* kairos_get_api was asked for an ABI version this library does not provide */
#define KAIROS_ERROR_INTERNAL             (-9)  /* a bug in Kairos: please report it with kairos_last_error() */
#define KAIROS_ERROR_LIMIT               (-10)  /* a count beyond what the library supports (e.g. more than 2^32 - 1 objects) */

/* Which rule ended an iteration (distance_result.termination, cast_result.termination).
 * See docs/algorithms.md section 2 for the rules. */
#define KAIROS_TERMINATION_NONE              0  /* not reported by this version: every query runs at least one iteration */
#define KAIROS_TERMINATION_RELATIVE_ERROR    1  /* ||v||^2 - v.w <= tolerance * ||v||^2 (distance within tolerance) */
#define KAIROS_TERMINATION_NEAR_CONTACT      2  /* ||v||^2 <= eps * max ||y||^2: touching within rounding */
#define KAIROS_TERMINATION_FULL_SIMPLEX      3  /* the simplex holds the origin: the shapes intersect */
#define KAIROS_TERMINATION_JOHNSON_FAILED    4  /* no valid sub-simplex after the backup pass, or one below the proven lower bound (rounding): last estimate returned */
#define KAIROS_TERMINATION_REPEATED_SUPPORT  5  /* the support point was already in the simplex: converged to rounding */
#define KAIROS_TERMINATION_NO_PROGRESS       6  /* ||v|| stopped decreasing by more than machine epsilon */
#define KAIROS_TERMINATION_MAX_ITERATIONS    7  /* the iteration guard fired; the result is the best estimate so far */
#define KAIROS_TERMINATION_SEPARATED         8  /* intersection test / cast: a separating axis was found (or the ray misses) */
#define KAIROS_TERMINATION_HIT               9  /* cast: the ray point is within tolerance of the surface */

/* Broad phases (kairos_world_settings.broad_phase). */
#define KAIROS_BROAD_PHASE_SPACETIME_SAP     0  /* default: space-time sweep and prune, pairs at their first overlap moment */
#define KAIROS_BROAD_PHASE_ENCAPSULATING_SAP 1  /* sweep and prune on boxes swept over the whole step (false positives) */
#define KAIROS_BROAD_PHASE_BRUTE_FORCE       2  /* exact 4D box overlap of every pair, O(n^2): a reference */
/* The talks' space-time sweep and prune exactly (docs/algorithms.md): one sorted endpoint array
 * per axis, each swap of two endpoints queued at the time it happens in a heap and done in time
 * order. Same pairs as SPACETIME_SAP; costs O((n + s) log n) per step for s swaps, which grows
 * with crowding and speed (SPACETIME_SAP sorts per region instead, and is the faster default). */
#define KAIROS_BROAD_PHASE_SPACETIME_SAP_QUEUED 3

/* How far a quaternion's length may differ from 1 before it is rejected. */
#define KAIROS_QUAT_TOLERANCE 1e-6
/* The largest magnitude of a coordinate, length or size the library accepts (see "Numbers"). */
#define KAIROS_MAX_MAGNITUDE 1e100

/* Version of the function table returned by kairos_get_api. */
#define KAIROS_ABI_VERSION 2u

/* ---------------------------------------------------------------------------------------------
 * Plain types. All are C structs of doubles with no padding surprises; layouts are frozen.
 */
typedef struct kairos_vec3 { double x, y, z; } kairos_vec3;
/* A unit quaternion, x y z imaginary parts, w real part. The identity is {0, 0, 0, 1}. */
typedef struct kairos_quat { double x, y, z, w; } kairos_quat;
/* Maps a shape's local frame to the world: x -> R(orientation) * x + position. */
typedef struct kairos_pose { kairos_vec3 position; kairos_quat orientation; } kairos_pose;
/* One step, t in [0, 1]: the local origin moves linearly from start.position to end.position,
 * and turns about it at constant angular velocity along the shortest arc from
 * start.orientation to end.orientation. */
typedef struct kairos_motion { kairos_pose start, end; } kairos_motion;

/* A convex shape: opaque, immutable, reference counted. Composites retain their parts. */
typedef struct kairos_shape kairos_shape;
/* A world of moving objects: opaque; one thread at a time. */
typedef struct kairos_world kairos_world;
/* An object in a world: index and generation packed into 64 bits; 0 is never valid. A removed
 * object's id stays invalid (KAIROS_ERROR_STALE_ID) even when its slot is reused. */
typedef uint64_t kairos_object_id;

/* ---------------------------------------------------------------------------------------------
 * Library information.
 */

/* A static name for any status value, e.g. "KAIROS_ERROR_NULL_ARGUMENT"; "KAIROS_UNKNOWN_STATUS"
 * for values this version does not know. Never NULL. Thread safe. */
KAIROS_API const char* kairos_status_name(int32_t status);

/* The message of the last failed call on this thread, naming the argument and the bad value.
 * Never NULL; "" when nothing has failed on this thread yet. A successful call leaves it as it
 * was. The buffer is per thread and is overwritten by the next failure on the same thread. */
KAIROS_API const char* kairos_last_error(void);

/* The runtime library's version as major*10000 + minor*100 + patch. Compare it with
 * KAIROS_VERSION_NUMBER of the header you built against: equal majors are ABI compatible. */
KAIROS_API uint32_t kairos_version(void);

/* ---------------------------------------------------------------------------------------------
 * Shapes. Every constructor writes a new shape with one reference to *out, which the caller
 * owns and gives back with kairos_shape_release. Sizes must be finite and > 0 unless noted.
 * Frames are those of docs/c-api.md "Primitive frames".
 */

/* Ball of the given radius centred at the local origin. */
KAIROS_API int32_t kairos_shape_sphere(double radius, kairos_shape** out);
/* Box [-h, h] on each axis; every half extent finite and > 0. */
KAIROS_API int32_t kairos_shape_box(kairos_vec3 half_extents, kairos_shape** out);
/* The segment from (0,0,-half_height) to (0,0,+half_height) grown by radius: it spans
 * +-(half_height + radius) along z. radius > 0; half_height >= 0 (0 gives a sphere). */
KAIROS_API int32_t kairos_shape_capsule(double radius, double half_height, kairos_shape** out);
/* Solid cylinder, axis z, z in [-half_height, half_height], radius radius. */
KAIROS_API int32_t kairos_shape_cylinder(double radius, double half_height, kairos_shape** out);
/* Solid cone, apex (0,0,+half_height), base disk of radius radius at z = -half_height. Its
 * origin is the axis midpoint (as in FCL and Bullet), not its centre of mass. */
KAIROS_API int32_t kairos_shape_cone(double radius, double half_height, kairos_shape** out);
/* The local origin alone. */
KAIROS_API int32_t kairos_shape_point(kairos_shape** out);
/* The segment from (0,0,-half_length) to (0,0,+half_length). */
KAIROS_API int32_t kairos_shape_segment(double half_length, kairos_shape** out);
/* Convex hull of count points (local frame, never recentred). The points are copied; only the
 * hull's vertices are kept (interior and duplicate points are dropped). Every non-empty set of
 * finite points gives a shape, of the set's own dimension: points all within 1e-10 of the set's
 * extent (the widest side of its bounding box) of a plane give a flat convex polygon, of a line a
 * segment, and one distinct point (repeated or not) a point. Flat shapes work in every query and
 * in worlds like solids. count 0 is KAIROS_ERROR_DEGENERATE; points may be NULL only then. */
KAIROS_API int32_t kairos_shape_convex_hull(const kairos_vec3* points, size_t count, kairos_shape** out);
/* The flat triangle a, b, c (local frame, as given): a floor or terrain piece, a thin plate.
 * Collinear points (a corner within 1e-10 of the longest side's length from the line of the
 * other two), coinciding ones, or a triangle whose sides are within the rounding of its
 * coordinates (64 ulps of the largest) give KAIROS_ERROR_DEGENERATE. */
KAIROS_API int32_t kairos_shape_triangle(kairos_vec3 a, kairos_vec3 b, kairos_vec3 c, kairos_shape** out);
/* Minkowski sum a + b = {x + y}: e.g. a rounded box as box + sphere. Retains a and b. */
KAIROS_API int32_t kairos_shape_minkowski_sum(const kairos_shape* a, const kairos_shape* b, kairos_shape** out);
/* Convex hull of the union of a and b (both in the same local frame). Retains a and b. */
KAIROS_API int32_t kairos_shape_hull(const kairos_shape* a, const kairos_shape* b, kairos_shape** out);
/* s mapped by x -> linear * x + translation. linear is a row-major 3x3, finite and invertible
 * (|det| > 1e-12 times the product of its row lengths); it may scale, shear or mirror. Retains s.
 * When linear is a rotation (orthonormal to 2^-48, det > 0) queries answer s itself at the composed
 * pose, with s's closed forms and speed; other maps go through a generic support. */
KAIROS_API int32_t kairos_shape_transformed(const kairos_shape* s, const double linear[9],
                                            kairos_vec3 translation, kairos_shape** out);
/* Adds one reference. NULL is ignored. Thread safe. */
KAIROS_API void kairos_shape_retain(kairos_shape* s);
/* Drops one reference; the shape is freed with its last reference. NULL is ignored. */
KAIROS_API void kairos_shape_release(kairos_shape* s);

/* A point of s (local frame) farthest along direction: out maximises direction . x over s.
 * direction need not be unit; it must be finite. For a zero direction every point qualifies and
 * some point of s is returned. */
KAIROS_API int32_t kairos_shape_support(const kairos_shape* s, kairos_vec3 direction, kairos_vec3* out);
/* The tight axis-aligned box (world frame) of s at pose; pose NULL means identity. */
KAIROS_API int32_t kairos_shape_bounds(const kairos_shape* s, const kairos_pose* pose,
                                       kairos_vec3* min, kairos_vec3* max);

/* ---------------------------------------------------------------------------------------------
 * Pair queries. Shapes are posed by pose (NULL means identity). Queries only read the shapes, so
 * any number may run at once on shared shapes.
 */

/* Frozen layout (see "Embedded settings" above). */
typedef struct kairos_query_settings {
    uint32_t struct_size;     /* must equal sizeof(kairos_query_settings) */
    double   tolerance;       /* relative accuracy, in (0, 1); default 1e-10. The accuracy/speed knob */
    uint32_t max_iterations;  /* a guard only, >= 1; default 256 */
} kairos_query_settings;
/* Fills *s with struct_size and the defaults. NULL is ignored. */
KAIROS_API void kairos_query_settings_init(kairos_query_settings* s);

/* Frozen layout. */
typedef struct kairos_distance_result {
    double      distance;          /* >= 0; 0 when the shapes intersect */
    kairos_vec3 point_a, point_b;  /* closest points on A and on B, world frame (equal when touching) */
    kairos_vec3 axis;              /* unit, from A toward B; a separating axis when apart */
    int32_t     intersecting;      /* 1 when the shapes overlap or touch, else 0 */
    uint32_t    iterations;        /* GJK iterations used (1 for a pair with a closed form: docs/algorithms.md §2) */
    int32_t     termination;       /* KAIROS_TERMINATION_*: which rule ended the iteration */
} kairos_distance_result;

/* Frozen layout. */
typedef struct kairos_cast_result {
    int32_t     hit;          /* 1 when contact happens within the step, else 0 */
    double      toi;          /* time of impact, fraction of the step in [0, 1]; 1 when no hit */
    kairos_vec3 point;        /* contact point at toi, world frame (unspecified when no hit) */
    kairos_vec3 normal;       /* unit contact normal at toi, from A toward B (ray cast: outward from the shape) */
    uint32_t    iterations;   /* iterations used */
    int32_t     termination;  /* KAIROS_TERMINATION_* */
} kairos_cast_result;

/* Distance, closest points and separating axis of a at pose_a and b at pose_b.
 * settings NULL means defaults; tolerance is the relative error of the distance. Near contact on
 * the rims of cylinders and cones the distance converges to about 1e-11 of the shapes' size in
 * double precision; a tighter tolerance stops there, with the distance too large (by rounding, at
 * most about 2e-11 of the size too small). Touching a cylinder (distance 0), it may stop up to 5e-8
 * of the size above 0 (NO_PROGRESS); a rim against a box's or a hull's edge may stop on a rounding
 * rule (NO_PROGRESS, JOHNSON_FAILED) up to about 2e-9 of the size above the distance at clear gaps
 * too, its witness points then up to about 1e-9 of the size farther apart than the distance
 * (README, "Known issues"). */
KAIROS_API int32_t kairos_distance(const kairos_shape* a, const kairos_pose* pose_a,
                                   const kairos_shape* b, const kairos_pose* pose_b,
                                   const kairos_query_settings* settings, kairos_distance_result* out);
/* Signed distance (version 0.2): apart, the same result as kairos_distance. Overlapping:
 * distance = -depth (< 0), axis the unit direction (world frame) from A toward B along which
 * translating B by depth leaves the shapes touching (the minimum translation), point_a and
 * point_b the deepest points on A's and B's surfaces with point_b - point_a = distance * axis
 * (to rounding), intersecting 1. Touching within rounding gives 0. Spheres, capsules and shapes
 * grown by a sphere are their cores plus the radii. The depth is found by the expanding polytope
 * algorithm (docs/algorithms.md); termination: RELATIVE_ERROR (depth within the tolerance),
 * REPEATED_SUPPORT (polytopes: exact to rounding), NEAR_CONTACT (the cores' difference is flat: a
 * segment crossing a segment, coplanar triangles), NO_PROGRESS or MAX_ITERATIONS (rounding or the
 * guard, at most min(max(max_iterations, 16), 128) support calls, min(max(max_iterations, 16), 252)
 * for curved and general shapes: the depth is then a bound, not converged). */
KAIROS_API int32_t kairos_signed_distance(const kairos_shape* a, const kairos_pose* pose_a,
                                          const kairos_shape* b, const kairos_pose* pose_b,
                                          const kairos_query_settings* settings, kairos_distance_result* out);
/* *out = 1 when the shapes overlap or touch, else 0. axis_cache (world frame, any length, may be
 * NULL) seeds the search and receives a separating axis when one is found: keep one per pair
 * and pass it again next frame, and a smoothly moving pair needs about one iteration. A zero or
 * non-finite cached axis is replaced by a fresh start (not an error). */
KAIROS_API int32_t kairos_intersect(const kairos_shape* a, const kairos_pose* pose_a,
                                    const kairos_shape* b, const kairos_pose* pose_b,
                                    kairos_vec3* axis_cache, int32_t* out);
/* First hit of the ray origin + lambda * translation, lambda in [0, 1], on s at pose (GJK ray
 * cast: each support plane that separates the ray point from the shape clips the ray).
 * toi is lambda, never later than the true hit by more than the tolerance and never a missed hit;
 * the iteration stops when the ray point is within tolerance times the shape's size (seen from
 * the ray point) of the surface. normal: unit, outward from the shape at the hit (the latest
 * clipping plane; for spheres and capsules the radius direction at the hit; for boxes, rounded or
 * not, exact, from a closed form: docs/algorithms.md §3). point: the hit point on the surface,
 * world frame. A ray starting inside (or on the surface): hit, toi 0, normal
 * -translation (unit), or for a zero translation the unit direction from the shape's local origin
 * toward the ray's origin (+z when they coincide). No hit: hit 0, toi 1, point and normal
 * unspecified. On curved shapes (cylinders, cones) the double-precision iteration may stop short of
 * the surface by up to about 5e-8 of their size whatever tighter tolerance is asked: early, never late.
 * When max_iterations ends the iteration first (termination KAIROS_TERMINATION_MAX_ITERATIONS),
 * the result is a hit at the lower bound reached so far: no contact before toi, but the ray may
 * still be apart from the shape there, or miss it (point unspecified); raise max_iterations.
 * kairos_shape_cast does the same. */
KAIROS_API int32_t kairos_ray_cast(const kairos_shape* s, const kairos_pose* pose,
                                   kairos_vec3 origin, kairos_vec3 translation,
                                   const kairos_query_settings* settings, kairos_cast_result* out);
/* a translates by translation_a and b by translation_b over the step, from their poses: the
 * first time of impact in [0, 1] (a ray from the origin along translation_b - translation_a cast
 * onto A - B, computed in a's frame so positions far from the world origin keep their precision).
 * toi: never later than the true first contact by more than the tolerance, never a missed
 * contact. normal: unit, from A toward B (the latest clipping plane; for spheres and capsules
 * among themselves and a sphere with a box, the direction between the cores' closest points at
 * toi, exact for that toi at any tolerance; for two boxes clearly apart at the start, the
 * entering axis of the separating axis test, exact (docs/algorithms.md §3);
 * normal . (translation_b - translation_a) < 0). point: the contact point at toi, world frame
 * (from the final simplex's barycentric coordinates, or those closest points pushed out by the
 * radii, or for two boxes a point where their touching features meet). Shapes that overlap at the start: hit 1, toi 0, normal the minimum
 * translation's axis from A toward B and point midway between the deepest points, as
 * kairos_signed_distance gives them (call it for the depth). Shapes that touch at the start (depth
 * 0 within rounding): hit 1, toi 0, normal = -(translation_b - translation_a), unit (the contact
 * opposes the relative motion as every later contact does); with no relative motion the unit
 * direction from A's local origin toward B's (+z when they coincide). No hit: hit 0, toi 1,
 * point and normal unspecified. */
KAIROS_API int32_t kairos_shape_cast(const kairos_shape* a, const kairos_pose* pose_a, kairos_vec3 translation_a,
                                     const kairos_shape* b, const kairos_pose* pose_b, kairos_vec3 translation_b,
                                     const kairos_query_settings* settings, kairos_cast_result* out);
/* a and b follow their motions (translation and rotation) over the step. Conservative: toi is
 * never later than the true first contact by more than tolerance (a fraction of the step), and
 * a contact is never missed. A hit is reported at the first time found at which the shapes are
 * within tolerance * min(rA, rB) of each other (rA, rB: each shape's bounding radius about its
 * local origin, the distance from that origin to the farthest corner of the shape's local
 * axis-aligned bounding box; the other one when one shape is a point; translations included:
 * the gap bound holds whether or not the shapes turn), so a near miss closer than that counts
 * as a contact; normal (unit, A toward B) and point (world, midway between the closest points)
 * come from the distance there. Shapes overlapping at the start: toi 0, normal and point as
 * kairos_shape_cast gives them (the minimum translation); touching at the start: normal opposing the
 * relative velocity of the contact point. Motions whose start and end orientations are equal
 * (q or -q) take the exact shape cast. iterations: GJK support evaluations of all the distance
 * queries and casts used. termination: HIT, SEPARATED (no hit), or MAX_ITERATIONS / NO_PROGRESS
 * when a guard stopped the search (a motion that does not turn reports its shape cast's rule): still a hit at a time before which there is no contact, but
 * the shapes may be apart there (a near miss grazed for thousands of steps, or curved surfaces
 * closer than double precision resolves, about 1e-7 of their size). */
KAIROS_API int32_t kairos_motion_cast(const kairos_shape* a, const kairos_motion* motion_a,
                                      const kairos_shape* b, const kairos_motion* motion_b,
                                      const kairos_query_settings* settings, kairos_cast_result* out);

/* ---------------------------------------------------------------------------------------------
 * World: broad phase and narrow phase over many moving objects. One thread at a time changes a
 * world (its step may use more, see worker_count); the const functions may run on several threads
 * at once while none changes it.
 */
/* A task system hook (as Box2D v3's enqueueTask / finishTask), for an engine that runs the step's
 * work on its own scheduler. The world calls enqueue_task with a task and item_count items; the
 * engine runs task(begin, end, worker, task_context) over ranges [begin, end) that cover
 * [0, item_count) exactly once (ranges of at least min_range items, but the last, are enough), on
 * any of its threads at once, passing any worker index (the world keeps no state per worker), and
 * returns a handle, or NULL after running every range itself. The world then calls
 * finish_task(handle, user_context) for a non-NULL handle, which must return once every range has
 * run. task does not throw or longjmp; ranges write disjoint results, so any order is fine. */
typedef void kairos_task_fn(uint32_t begin, uint32_t end, uint32_t worker, void* task_context);
typedef void* kairos_enqueue_task_fn(kairos_task_fn* task, uint32_t item_count, uint32_t min_range,
                                     void* task_context, void* user_context);
typedef void kairos_finish_task_fn(void* user_task, void* user_context);

typedef struct kairos_world_settings {
    uint32_t struct_size;            /* sizeof(kairos_world_settings) */
    int32_t  broad_phase;            /* KAIROS_BROAD_PHASE_*; default SPACETIME_SAP */
    kairos_query_settings query;     /* narrow-phase settings; frozen layout, never shifts */
    /* ABI version 2 (Kairos 0.2) appends the following; a caller whose struct_size ends before a
     * field gets its default. */
    uint32_t worker_count;           /* threads that run the narrow phase (and the movers' motion
                                        bounds), the caller's included:
                                        0 (default) or 1: the calling thread alone; n > 1 (at most
                                        256): n - 1 threads the world starts and keeps, unless
                                        enqueue_task is set (then the engine's threads run it and
                                        the world starts none). Results are bit for bit the same
                                        for every worker_count and scheduler. */
    kairos_enqueue_task_fn* enqueue_task;  /* NULL (default): the world's own threads */
    kairos_finish_task_fn*  finish_task;   /* required with enqueue_task */
    void* task_user_context;               /* passed to both */
} kairos_world_settings;

/* Frozen layout. */
typedef struct kairos_contact {
    kairos_object_id a, b;        /* a < b */
    uint64_t    user_a, user_b;   /* the user data given to kairos_world_add */
    double      toi;              /* first contact of the pair, fraction of the step in [0, 1] */
    kairos_vec3 point, normal;    /* world frame at toi; normal unit, from a toward b */
} kairos_contact;

/* Counters of the last step. Growing struct: the library writes at most struct_size bytes. */
typedef struct kairos_step_stats {
    uint32_t struct_size;           /* sizeof(kairos_step_stats) */
    uint64_t broad_phase_pairs;     /* pairs the broad phase reported */
    uint64_t swaps;                 /* endpoint swaps performed */
    uint64_t heap_operations;       /* event-heap pushes, pops and key changes */
    uint64_t narrow_phase_queries;  /* pair casts run */
    uint64_t gjk_iterations;        /* GJK iterations summed over the narrow phase */
    double   broad_phase_seconds;   /* wall time of the broad phase */
    double   narrow_phase_seconds;  /* wall time of the narrow phase */
} kairos_step_stats;

/* Fills *s with struct_size and defaults. NULL is ignored. Binaries linked against 0.1, whose
 * struct ends before worker_count, keep the 0.1 version of this function (symbol version
 * KAIROS_0), which writes only that struct; new ones get KAIROS_0.2. */
KAIROS_API void kairos_world_settings_init(kairos_world_settings* s);
/* Creates an empty world; settings NULL means defaults. Free it with kairos_world_destroy. */
KAIROS_API int32_t kairos_world_create(const kairos_world_settings* settings, kairos_world** out);
/* Destroys the world and releases its references to shapes. NULL is ignored. */
KAIROS_API void kairos_world_destroy(kairos_world* w);
/* Adds an object with shape s (retained by the world) at pose (NULL: identity), standing still
 * until moved. user_data is returned in contacts. */
KAIROS_API int32_t kairos_world_add(kairos_world* w, kairos_shape* s, const kairos_pose* pose,
                                    uint64_t user_data, kairos_object_id* out);
/* Removes an object; its id becomes stale. */
KAIROS_API int32_t kairos_world_remove(kairos_world* w, kairos_object_id id);
/* Teleports an object at once, without a sweep, and cancels its pending move. */
KAIROS_API int32_t kairos_world_set_pose(kairos_world* w, kairos_object_id id, const kairos_pose* pose);
/* Sets the object's pose at the end of the next step (for that step only). */
KAIROS_API int32_t kairos_world_move(kairos_world* w, kairos_object_id id, const kairos_pose* end);
/* Finds each pair's first contact in [0, 1], then moves every object to its end pose. */
KAIROS_API int32_t kairos_world_step(kairos_world* w);
/* Contacts of the last step: one per pair, sorted by toi, ties by (a, b). *out stays valid until
 * the next call that changes the world; do not store it. */
KAIROS_API int32_t kairos_world_contacts(const kairos_world* w, const kairos_contact** out, size_t* count);
/* Broad-phase pairs of the last step as 2 * count ids, smaller id first in each pair. Valid
 * until the next call that changes the world. */
KAIROS_API int32_t kairos_world_overlaps(const kairos_world* w, const kairos_object_id** pairs, size_t* count);
/* Fills *s with struct_size (zeroed counters). NULL is ignored. */
KAIROS_API void kairos_step_stats_init(kairos_step_stats* s);
/* Counters of the last step; writes at most out->struct_size bytes. */
KAIROS_API int32_t kairos_world_step_stats(const kairos_world* w, kairos_step_stats* out);

/* Which pairs collide (frozen layout). Two objects of the same non-zero group always collide when
 * the group is > 0 and never when it is < 0; otherwise a pair collides when
 * (a.category_bits & b.mask_bits) != 0 and (b.category_bits & a.mask_bits) != 0. Every object
 * starts with the default: category_bits 1, mask_bits 0xFFFFFFFF (all), group 0. */
typedef struct kairos_filter {
    uint32_t category_bits;
    uint32_t mask_bits;
    int32_t  group;
} kairos_filter;

/* Sets the object's filter (*f copied). A pair it rejects never reaches the narrow phase, the
 * contacts or the overlaps, from the next step on. */
KAIROS_API int32_t kairos_world_set_filter(kairos_world* w, kairos_object_id id, const kairos_filter* f);
/* is_static 1: the object never moves in a step (kairos_world_move on it is
 * KAIROS_ERROR_INVALID_ARGUMENT; a pending move is cancelled; kairos_world_set_pose still places
 * it), and a pair of two static objects is never tested or reported. 0: an ordinary object again.
 * Other values: KAIROS_ERROR_INVALID_ARGUMENT. */
KAIROS_API int32_t kairos_world_set_static(kairos_world* w, kairos_object_id id, int32_t is_static);
/* The object's pose now (the start of the next step; after a step, the end pose it was moved to),
 * world frame, with the unit quaternion the world keeps. */
KAIROS_API int32_t kairos_world_get_pose(const kairos_world* w, kairos_object_id id, kairos_pose* out);
/* The user data given to kairos_world_add. */
KAIROS_API int32_t kairos_world_get_user_data(const kairos_world* w, kairos_object_id id, uint64_t* out);

/* World queries. Each sees the objects at their current poses (the start of the next step: moves
 * given for that step are not applied), takes an optional filter (NULL: every object; otherwise
 * only the objects whose filter collides with *filter by the rule above, so category_bits says
 * what the query is and mask_bits what it sees), and changes nothing. They are const: several
 * threads may query one world at once while no thread changes it. Found through the broad phase
 * (the space-time sweeps visit only the columns, or the stretch of their sorted axis, that the
 * query reaches; the encapsulating and brute-force references scan every object). */

/* The earliest hit of a world query. Frozen layout. On a miss: hit 0, id 0, user_data 0, toi 1,
 * point and normal 0. */
typedef struct kairos_world_hit {
    int32_t          hit;        /* 1: something was hit */
    kairos_object_id id;         /* the object hit (ties at one toi: the smaller id) */
    uint64_t         user_data;  /* its user data */
    double           toi;        /* fraction of the query's motion in [0, 1] */
    kairos_vec3      point;      /* world frame, the contact at toi */
    kairos_vec3      normal;     /* world frame, unit, outward from the object hit */
} kairos_world_hit;

/* The earliest object the ray origin + t * translation (t in [0, 1], world frame) hits, as
 * kairos_ray_cast against each object with the world's query settings. A ray starting inside an
 * object hits it at toi 0. */
KAIROS_API int32_t kairos_world_ray_cast(const kairos_world* w, kairos_vec3 origin, kairos_vec3 translation,
                                         const kairos_filter* filter, kairos_world_hit* out);
/* The earliest object that shape s hits while it follows *motion (world frame, the objects
 * standing still): kairos_shape_cast when the motion's orientations are the same, otherwise
 * kairos_motion_cast (with its tolerance rule), against each object. settings: NULL takes the
 * world's query settings. The shape is only read; the world does not retain it. Only objects near
 * the path are cast: a pair cast that would end on its iteration guard with a conservative hit far
 * from every object (max_iterations too small) is not made up for. */
KAIROS_API int32_t kairos_world_shape_cast(const kairos_world* w, const kairos_shape* s, const kairos_motion* motion,
                                           const kairos_filter* filter, const kairos_query_settings* settings,
                                           kairos_world_hit* out);
/* The ids of the objects whose bounding box at the current pose (the box kairos_shape_bounds gives)
 * overlaps the closed box [min, max] (world frame, finite, min <= max on every axis), in
 * increasing order. At most `capacity` ids are written to `ids` (NULL when capacity is 0);
 * *count receives the number found, which may exceed capacity (call again with a larger array). */
KAIROS_API int32_t kairos_world_query_box(const kairos_world* w, kairos_vec3 min, kairos_vec3 max,
                                          const kairos_filter* filter, kairos_object_id* ids, size_t capacity,
                                          size_t* count);

/* ---------------------------------------------------------------------------------------------
 * Batches (version 0.2): one pair query applied to `count` queries laid out as flat arrays (C
 * arrays of the structs above, or numpy arrays of the same layout: no copy is needed). Query i
 * reads element i of every array and writes out[i]; the results are bit for bit those of the
 * single calls. a and b are arrays of count shape pointers (one shape against many poses: repeat
 * the pointer); a NULL pose array means identity poses, a NULL translation array zero
 * translations, NULL settings the defaults. count 0 succeeds and writes nothing (the arrays may
 * then be NULL).
 * One status for the batch: every query is checked before any is computed, the message of a
 * failure names the first bad query ("poses_a[17].orientation must be ..."), and on failure
 * nothing is written to out.
 * workers: NULL runs the batch on the calling thread. A world runs it on that world's threads
 * (kairos_world_settings.worker_count, the caller's included) or its task hook, in ranges of
 * queries; the world is otherwise neither read nor changed, but as during kairos_world_step no
 * other thread may use it until the batch returns. The arrays must not change meanwhile, and out
 * must not overlap them.
 */
KAIROS_API int32_t kairos_distance_batch(const kairos_shape* const* a, const kairos_pose* poses_a,
                                         const kairos_shape* const* b, const kairos_pose* poses_b, size_t count,
                                         const kairos_query_settings* settings, kairos_world* workers,
                                         kairos_distance_result* out);
/* kairos_shape_cast over count queries: translations_a[i], translations_b[i] (world frame). */
KAIROS_API int32_t kairos_shape_cast_batch(const kairos_shape* const* a, const kairos_pose* poses_a,
                                           const kairos_vec3* translations_a, const kairos_shape* const* b,
                                           const kairos_pose* poses_b, const kairos_vec3* translations_b,
                                           size_t count, const kairos_query_settings* settings,
                                           kairos_world* workers, kairos_cast_result* out);
/* kairos_motion_cast over count queries (motions_a and motions_b: count motions each, not NULL). */
KAIROS_API int32_t kairos_motion_cast_batch(const kairos_shape* const* a, const kairos_motion* motions_a,
                                            const kairos_shape* const* b, const kairos_motion* motions_b,
                                            size_t count, const kairos_query_settings* settings,
                                            kairos_world* workers, kairos_cast_result* out);
/* kairos_world_move for count objects: ids[i] moves to ends[i] over the next step (world frame).
 * All or nothing: every id must be live and not static and every pose valid, or nothing moves
 * and the message names the first bad index. An id given twice keeps its last end pose, as two
 * calls of kairos_world_move would. */
KAIROS_API int32_t kairos_world_move_batch(kairos_world* w, const kairos_object_id* ids, const kairos_pose* ends,
                                           size_t count);

/* ---------------------------------------------------------------------------------------------
 * Function table for dlopen users: dlsym only "kairos_get_api", then call through the table.
 * The table begins with struct_size and abi_version; function pointers are only ever appended,
 * so a caller may use every entry that lies within struct_size.
 */
typedef struct kairos_api {
    uint32_t struct_size;   /* sizeof the table this library provides */
    uint32_t abi_version;   /* KAIROS_ABI_VERSION of this library */
    const char* (*status_name)(int32_t);
    const char* (*last_error)(void);
    uint32_t (*version)(void);
    int32_t (*shape_sphere)(double, kairos_shape**);
    int32_t (*shape_box)(kairos_vec3, kairos_shape**);
    int32_t (*shape_capsule)(double, double, kairos_shape**);
    int32_t (*shape_cylinder)(double, double, kairos_shape**);
    int32_t (*shape_cone)(double, double, kairos_shape**);
    int32_t (*shape_point)(kairos_shape**);
    int32_t (*shape_segment)(double, kairos_shape**);
    int32_t (*shape_convex_hull)(const kairos_vec3*, size_t, kairos_shape**);
    int32_t (*shape_minkowski_sum)(const kairos_shape*, const kairos_shape*, kairos_shape**);
    int32_t (*shape_hull)(const kairos_shape*, const kairos_shape*, kairos_shape**);
    int32_t (*shape_transformed)(const kairos_shape*, const double*, kairos_vec3, kairos_shape**);
    void    (*shape_retain)(kairos_shape*);
    void    (*shape_release)(kairos_shape*);
    int32_t (*shape_support)(const kairos_shape*, kairos_vec3, kairos_vec3*);
    int32_t (*shape_bounds)(const kairos_shape*, const kairos_pose*, kairos_vec3*, kairos_vec3*);
    void    (*query_settings_init)(kairos_query_settings*);
    int32_t (*distance)(const kairos_shape*, const kairos_pose*, const kairos_shape*, const kairos_pose*,
                        const kairos_query_settings*, kairos_distance_result*);
    int32_t (*intersect)(const kairos_shape*, const kairos_pose*, const kairos_shape*, const kairos_pose*,
                         kairos_vec3*, int32_t*);
    int32_t (*ray_cast)(const kairos_shape*, const kairos_pose*, kairos_vec3, kairos_vec3,
                        const kairos_query_settings*, kairos_cast_result*);
    int32_t (*shape_cast)(const kairos_shape*, const kairos_pose*, kairos_vec3,
                          const kairos_shape*, const kairos_pose*, kairos_vec3,
                          const kairos_query_settings*, kairos_cast_result*);
    int32_t (*motion_cast)(const kairos_shape*, const kairos_motion*, const kairos_shape*, const kairos_motion*,
                           const kairos_query_settings*, kairos_cast_result*);
    void    (*world_settings_init)(kairos_world_settings*);
    int32_t (*world_create)(const kairos_world_settings*, kairos_world**);
    void    (*world_destroy)(kairos_world*);
    int32_t (*world_add)(kairos_world*, kairos_shape*, const kairos_pose*, uint64_t, kairos_object_id*);
    int32_t (*world_remove)(kairos_world*, kairos_object_id);
    int32_t (*world_set_pose)(kairos_world*, kairos_object_id, const kairos_pose*);
    int32_t (*world_move)(kairos_world*, kairos_object_id, const kairos_pose*);
    int32_t (*world_step)(kairos_world*);
    int32_t (*world_contacts)(const kairos_world*, const kairos_contact**, size_t*);
    int32_t (*world_overlaps)(const kairos_world*, const kairos_object_id**, size_t*);
    void    (*step_stats_init)(kairos_step_stats*);
    int32_t (*world_step_stats)(const kairos_world*, kairos_step_stats*);
    /* ABI version 2 (Kairos 0.2) */
    int32_t (*shape_triangle)(kairos_vec3, kairos_vec3, kairos_vec3, kairos_shape**);
    int32_t (*signed_distance)(const kairos_shape*, const kairos_pose*, const kairos_shape*, const kairos_pose*,
                               const kairos_query_settings*, kairos_distance_result*);
    int32_t (*world_set_filter)(kairos_world*, kairos_object_id, const kairos_filter*);
    int32_t (*world_set_static)(kairos_world*, kairos_object_id, int32_t);
    int32_t (*world_get_pose)(const kairos_world*, kairos_object_id, kairos_pose*);
    int32_t (*world_get_user_data)(const kairos_world*, kairos_object_id, uint64_t*);
    int32_t (*world_ray_cast)(const kairos_world*, kairos_vec3, kairos_vec3, const kairos_filter*, kairos_world_hit*);
    int32_t (*world_shape_cast)(const kairos_world*, const kairos_shape*, const kairos_motion*, const kairos_filter*,
                                const kairos_query_settings*, kairos_world_hit*);
    int32_t (*world_query_box)(const kairos_world*, kairos_vec3, kairos_vec3, const kairos_filter*, kairos_object_id*,
                               size_t, size_t*);
    int32_t (*distance_batch)(const kairos_shape* const*, const kairos_pose*, const kairos_shape* const*,
                              const kairos_pose*, size_t, const kairos_query_settings*, kairos_world*,
                              kairos_distance_result*);
    int32_t (*shape_cast_batch)(const kairos_shape* const*, const kairos_pose*, const kairos_vec3*,
                                const kairos_shape* const*, const kairos_pose*, const kairos_vec3*, size_t,
                                const kairos_query_settings*, kairos_world*, kairos_cast_result*);
    int32_t (*motion_cast_batch)(const kairos_shape* const*, const kairos_motion*, const kairos_shape* const*,
                                 const kairos_motion*, size_t, const kairos_query_settings*, kairos_world*,
                                 kairos_cast_result*);
    int32_t (*world_move_batch)(kairos_world*, const kairos_object_id*, const kairos_pose*, size_t);
} kairos_api;

/* The function table for abi_version (1 <= abi_version <= KAIROS_ABI_VERSION of the library).
 * The table is static: it lives as long as the library stays loaded. An unknown version gives
 * KAIROS_ERROR_UNSUPPORTED_VERSION. */
KAIROS_API int32_t kairos_get_api(uint32_t abi_version, const kairos_api** out);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* KAIROS_KAIROS_H */
