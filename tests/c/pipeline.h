/* Helpers shared by the pipeline tests (C and C++): synthetic sherds, axis angles,
 * picking three points on the rim. `static inline` so that a test using some of them
 * compiles without unused-function warnings. */
#ifndef SHERD_TEST_PIPELINE_H
#define SHERD_TEST_PIPELINE_H

#include "check.h"

static inline SherdAxis new_axis(void) {
    SherdAxis axis;
    memset(&axis, 0, sizeof axis);
    axis.size = sizeof axis;
    return axis;
}

/* Cosine of the angle between the two axes' directions. */
static inline double direction_cosine(const SherdAxis *a, const SherdAxis *b) {
    double dot = 0.0, na = 0.0, nb = 0.0, cosine;
    int k;
    for (k = 0; k < 3; ++k) {
        dot += a->direction[k] * b->direction[k];
        na += a->direction[k] * a->direction[k];
        nb += b->direction[k] * b->direction[k];
    }
    cosine = dot / sqrt(na * nb);
    return cosine > 1.0 ? 1.0 : (cosine < -1.0 ? -1.0 : cosine);
}

/* Angle in degrees between the directions, sense included (base to rim). */
static inline double angle_deg(const SherdAxis *a, const SherdAxis *b) {
    return acos(direction_cosine(a, b)) * 180.0 / 3.14159265358979323846;
}

/* Angle in degrees between the two axes' lines, ignoring their sense. */
static inline double line_angle_deg(const SherdAxis *a, const SherdAxis *b) {
    return acos(fabs(direction_cosine(a, b))) * 180.0 / 3.14159265358979323846;
}

/* Copies the mesh's positions into a new array (free it). */
static inline double *positions_of(const SherdMesh *mesh, size_t *vertex_count) {
    double *positions;
    CHECK_OK(sherd_mesh_vertex_count(mesh, vertex_count));
    positions = (double *)malloc(3 * *vertex_count * sizeof(double));
    CHECK(positions != NULL);
    CHECK_OK(sherd_mesh_copy_positions(mesh, positions, *vertex_count));
    return positions;
}

/* Three vertices on the rim as a user would pick them: in the oriented frame of the
 * true axis, split the fragment's angular extent in three and take the highest vertex
 * of each third. */
static inline void pick_rim_points(const SherdMesh *mesh, const SherdAxis *truth, double points[9]) {
    double matrix[16];
    size_t n, i;
    double *positions = positions_of(mesh, &n);
    double lowest_angle = 1e9, highest_angle = -1e9, best_height[3] = {-1e300, -1e300, -1e300};
    int third, k;

    CHECK_OK(sherd_mesh_oriented_transform(mesh, truth, matrix));
    /* The centroid lies on +x, so the fragment's angles stay near 0: no wrap-around. */
    for (i = 0; i < n; ++i) {
        const double *p = positions + 3 * i;
        double x = matrix[0] * p[0] + matrix[1] * p[1] + matrix[2] * p[2] + matrix[3];
        double y = matrix[4] * p[0] + matrix[5] * p[1] + matrix[6] * p[2] + matrix[7];
        double angle = atan2(y, x);
        if (angle < lowest_angle) lowest_angle = angle;
        if (angle > highest_angle) highest_angle = angle;
    }
    for (i = 0; i < n; ++i) {
        const double *p = positions + 3 * i;
        double x = matrix[0] * p[0] + matrix[1] * p[1] + matrix[2] * p[2] + matrix[3];
        double y = matrix[4] * p[0] + matrix[5] * p[1] + matrix[6] * p[2] + matrix[7];
        double z = matrix[8] * p[0] + matrix[9] * p[1] + matrix[10] * p[2] + matrix[11];
        double share = (atan2(y, x) - lowest_angle) / (highest_angle - lowest_angle);
        /* The middle of each third, away from the break lines. */
        third = (int)(share * 3.0);
        if (third > 2) third = 2;
        if (fabs(share * 3.0 - third - 0.5) > 0.3) continue;
        if (z > best_height[third]) {
            best_height[third] = z;
            for (k = 0; k < 3; ++k) points[3 * third + k] = p[k];
        }
    }
    for (third = 0; third < 3; ++third) CHECK(best_height[third] > -1e300);
    free(positions);
}

#endif
