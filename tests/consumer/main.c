/* SPDX-License-Identifier: MIT */
/* Consumer test: a small C program built against an installed Kairos (CMake package or pkg-config). */
#include <stdio.h>
#include <string.h>

#include <kairos/kairos.h>

static int near(double a, double b) { return (a > b ? a - b : b - a) <= 1e-12; }

int main(void) {
    kairos_shape* sphere = NULL;
    kairos_vec3 direction = {0.0, 3.0, 4.0};
    kairos_vec3 support = {0.0, 0.0, 0.0};
    int32_t status;

    /* The library found at run time is the one whose header we compiled against. */
    if (kairos_version() != KAIROS_VERSION_NUMBER) {
        fprintf(stderr, "runtime version %u differs from header version %d\n",
                (unsigned)kairos_version(), KAIROS_VERSION_NUMBER);
        return 1;
    }
    status = kairos_shape_sphere(5.0, &sphere);
    if (status != KAIROS_OK) {
        fprintf(stderr, "kairos_shape_sphere: %s: %s\n", kairos_status_name(status), kairos_last_error());
        return 1;
    }
    status = kairos_shape_support(sphere, direction, &support);
    kairos_shape_release(sphere);
    /* Support of a radius-5 ball along (0, 3, 4): the point (0, 3, 4) itself. */
    if (status != KAIROS_OK || !near(support.x, 0.0) || !near(support.y, 3.0) || !near(support.z, 4.0)) {
        fprintf(stderr, "kairos_shape_support: %s, got (%g, %g, %g)\n", kairos_status_name(status),
                support.x, support.y, support.z);
        return 1;
    }
    if (kairos_shape_sphere(1.0, NULL) != KAIROS_ERROR_NULL_ARGUMENT ||
        strstr(kairos_last_error(), "out") == NULL) {
        fprintf(stderr, "a NULL out did not give KAIROS_ERROR_NULL_ARGUMENT naming it\n");
        return 1;
    }
    printf("consumer: Kairos %s (runtime %u) works\n", KAIROS_VERSION_STRING, (unsigned)kairos_version());
    return 0;
}
