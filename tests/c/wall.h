/* A closed piece of a cylindrical vessel wall, built in C: inner radius 45 mm, outer
 * 50 mm, height 40 mm, 60 degrees of circumference, moved off the origin by a rigid
 * motion so that its axis is not a coordinate axis. */
#ifndef SHERD_TEST_WALL_H
#define SHERD_TEST_WALL_H

#include "check.h"

#define WALL_STEPS 24  /* around */
#define WALL_ROWS 10   /* up */
#define WALL_VERTEX_COUNT (2 * (WALL_STEPS + 1) * (WALL_ROWS + 1))
#define WALL_FACE_COUNT (4 * WALL_STEPS * WALL_ROWS + 4 * WALL_STEPS + 4 * WALL_ROWS)

/* The rigid motion: rotation by 30 degrees about (1, 1, 0)/sqrt(2), then a shift. */
static void wall_move(const double in[3], double out[3]) {
    const double c = cos(3.14159265358979323846 / 6.0), s = sin(3.14159265358979323846 / 6.0);
    const double u[3] = {0.70710678118654752, 0.70710678118654752, 0.0};
    const double shift[3] = {12.0, -7.0, 30.0};
    double dot = u[0] * in[0] + u[1] * in[1] + u[2] * in[2];
    double cross[3];
    int k;
    cross[0] = u[1] * in[2] - u[2] * in[1];
    cross[1] = u[2] * in[0] - u[0] * in[2];
    cross[2] = u[0] * in[1] - u[1] * in[0];
    for (k = 0; k < 3; ++k) out[k] = in[k] * c + cross[k] * s + u[k] * dot * (1.0 - c) + shift[k];
}

/* The wall's true axis after the motion: the image of the z axis. */
static SherdAxis wall_axis(void) {
    SherdAxis axis;
    const double origin[3] = {0, 0, 0}, up[3] = {0, 0, 1};
    double top[3];
    int k;
    memset(&axis, 0, sizeof axis);
    axis.size = sizeof axis;
    wall_move(origin, axis.point);
    wall_move(up, top);
    for (k = 0; k < 3; ++k) axis.direction[k] = top[k] - axis.point[k];
    return axis;
}

static size_t wall_index(int skin, int step, int row) {
    return (size_t)((skin * (WALL_STEPS + 1) + step) * (WALL_ROWS + 1) + row);
}

static void add_quad(uint32_t *triangles, size_t *face, size_t a, size_t b, size_t c, size_t d) {
    uint32_t *t = triangles + 3 * *face;
    t[0] = (uint32_t)a; t[1] = (uint32_t)b; t[2] = (uint32_t)c;
    t[3] = (uint32_t)a; t[4] = (uint32_t)c; t[5] = (uint32_t)d;
    *face += 2;
}

/* Fills `positions` (3 * WALL_VERTEX_COUNT) and `triangles` (3 * WALL_FACE_COUNT). */
static void wall_build(double *positions, uint32_t *triangles) {
    size_t face = 0;
    int skin, step, row;
    for (skin = 0; skin < 2; ++skin) {
        double radius = skin ? 50.0 : 45.0;
        for (step = 0; step <= WALL_STEPS; ++step) {
            double angle = (step / (double)WALL_STEPS - 0.5) * 3.14159265358979323846 / 3.0;
            for (row = 0; row <= WALL_ROWS; ++row) {
                double local[3];
                local[0] = radius * cos(angle);
                local[1] = radius * sin(angle);
                local[2] = 40.0 * row / WALL_ROWS;
                wall_move(local, positions + 3 * wall_index(skin, step, row));
            }
        }
    }
    for (step = 0; step < WALL_STEPS; ++step) {
        for (row = 0; row < WALL_ROWS; ++row) {
            /* Outer skin faces outward, inner skin inward (towards the axis). */
            add_quad(triangles, &face, wall_index(1, step, row), wall_index(1, step + 1, row),
                     wall_index(1, step + 1, row + 1), wall_index(1, step, row + 1));
            add_quad(triangles, &face, wall_index(0, step, row), wall_index(0, step, row + 1),
                     wall_index(0, step + 1, row + 1), wall_index(0, step + 1, row));
        }
        /* Top and bottom rims. */
        add_quad(triangles, &face, wall_index(0, step, WALL_ROWS), wall_index(1, step, WALL_ROWS),
                 wall_index(1, step + 1, WALL_ROWS), wall_index(0, step + 1, WALL_ROWS));
        add_quad(triangles, &face, wall_index(0, step, 0), wall_index(0, step + 1, 0),
                 wall_index(1, step + 1, 0), wall_index(1, step, 0));
    }
    for (row = 0; row < WALL_ROWS; ++row) {
        /* The two fracture faces. */
        add_quad(triangles, &face, wall_index(0, 0, row), wall_index(1, 0, row), wall_index(1, 0, row + 1),
                 wall_index(0, 0, row + 1));
        add_quad(triangles, &face, wall_index(0, WALL_STEPS, row), wall_index(0, WALL_STEPS, row + 1),
                 wall_index(1, WALL_STEPS, row + 1), wall_index(1, WALL_STEPS, row));
    }
    CHECK(face == WALL_FACE_COUNT);
}

static SherdMesh *wall_mesh(void) {
    static double positions[3 * WALL_VERTEX_COUNT];
    static uint32_t triangles[3 * WALL_FACE_COUNT];
    SherdMesh *mesh = NULL;
    wall_build(positions, triangles);
    CHECK_OK(sherd_mesh_from_arrays(positions, WALL_VERTEX_COUNT, triangles, WALL_FACE_COUNT, &mesh));
    return mesh;
}

#endif
