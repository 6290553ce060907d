/* Meshes from host arrays and back, the axis struct and the oriented transform, as a
 * C99 host uses them. */
#include "check.h"

#define VERTEX_COUNT 4
#define TRIANGLE_COUNT 4

static const double positions[3 * VERTEX_COUNT] = {
    0.0, 0.0, 0.0, 10.0, 0.0, 0.0, 0.0, 10.0, 0.0, 0.0, 0.0, 10.0,
};
static const uint32_t triangles[3 * TRIANGLE_COUNT] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};

static void test_version(void) {
    CHECK(sherd_abi_version() == SHERD_ABI_VERSION);
    CHECK(strlen(sherd_version()) >= 5);
    CHECK(strcmp(sherd_status_name(SHERD_STATUS_OK), "SHERD_STATUS_OK") == 0);
    CHECK(strcmp(sherd_status_name(SHERD_STATUS_NEEDS_MANUAL_ORIENTATION),
                 "SHERD_STATUS_NEEDS_MANUAL_ORIENTATION") == 0);
    CHECK(strcmp(sherd_status_name(SHERD_STATUS_PANIC), "SHERD_STATUS_PANIC") == 0);
    CHECK(strcmp(sherd_status_name(12345u), "SHERD_STATUS_UNKNOWN") == 0);
}

static void test_round_trip(void) {
    SherdMesh *mesh = NULL;
    size_t count = 0;
    uint32_t attributes = 99;
    double positions_out[3 * VERTEX_COUNT];
    float positions_f32[3 * VERTEX_COUNT];
    uint32_t triangles_out[3 * TRIANGLE_COUNT];
    size_t i;

    CHECK_OK(sherd_mesh_from_arrays(positions, VERTEX_COUNT, triangles, TRIANGLE_COUNT, &mesh));
    CHECK(mesh != NULL);
    CHECK_OK(sherd_mesh_vertex_count(mesh, &count));
    CHECK(count == VERTEX_COUNT);
    CHECK_OK(sherd_mesh_face_count(mesh, &count));
    CHECK(count == TRIANGLE_COUNT);
    CHECK_OK(sherd_mesh_attributes(mesh, &attributes));
    CHECK(attributes == 0);

    CHECK_OK(sherd_mesh_copy_positions(mesh, positions_out, VERTEX_COUNT));
    CHECK(memcmp(positions_out, positions, sizeof positions) == 0);
    CHECK_OK(sherd_mesh_copy_positions_f32(mesh, positions_f32, VERTEX_COUNT));
    for (i = 0; i < 3 * VERTEX_COUNT; ++i) CHECK(positions_f32[i] == (float)positions[i]);
    CHECK_OK(sherd_mesh_copy_triangles(mesh, triangles_out, TRIANGLE_COUNT));
    CHECK(memcmp(triangles_out, triangles, sizeof triangles) == 0);
    sherd_mesh_free(mesh);
}

static void test_f32_and_attributes(void) {
    float positions_f32[3 * VERTEX_COUNT];
    float normals[3 * VERTEX_COUNT] = {0, 0, -2, 3, 0, 0, 0, 0.5f, 0, 0, 0, 0};
    uint8_t colors[4 * VERTEX_COUNT] = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 9, 8, 7, 6};
    float uvs[2 * 3 * TRIANGLE_COUNT];
    double normals_out[3 * VERTEX_COUNT];
    uint8_t colors_out[4 * VERTEX_COUNT];
    float uvs_out[2 * 3 * TRIANGLE_COUNT];
    double positions_out[3 * VERTEX_COUNT];
    SherdMesh *mesh = NULL, *copy = NULL;
    uint32_t attributes = 0;
    size_t i;

    for (i = 0; i < 3 * VERTEX_COUNT; ++i) positions_f32[i] = (float)positions[i] + 0.25f;
    for (i = 0; i < 2 * 3 * TRIANGLE_COUNT; ++i) uvs[i] = (float)i / 24.0f;

    CHECK_OK(sherd_mesh_from_arrays_f32(positions_f32, VERTEX_COUNT, triangles, TRIANGLE_COUNT, &mesh));
    CHECK_OK(sherd_mesh_copy_positions(mesh, positions_out, VERTEX_COUNT));
    for (i = 0; i < 3 * VERTEX_COUNT; ++i) CHECK(positions_out[i] == positions[i] + 0.25);

    CHECK_STATUS(sherd_mesh_copy_normals(mesh, normals_out, VERTEX_COUNT), SHERD_STATUS_NOT_AVAILABLE);
    CHECK_MESSAGE("no normals");
    CHECK_OK(sherd_mesh_set_normals_f32(mesh, normals, VERTEX_COUNT));
    CHECK_OK(sherd_mesh_set_colors(mesh, colors, VERTEX_COUNT));
    CHECK_OK(sherd_mesh_set_corner_uvs(mesh, uvs, 3 * TRIANGLE_COUNT));
    CHECK_OK(sherd_mesh_attributes(mesh, &attributes));
    CHECK(attributes == (SHERD_MESH_ATTRIBUTE_NORMALS | SHERD_MESH_ATTRIBUTE_COLORS |
                         SHERD_MESH_ATTRIBUTE_CORNER_UVS));

    /* The copy is independent: freeing the original leaves it whole. */
    CHECK_OK(sherd_mesh_clone(mesh, &copy));
    sherd_mesh_free(mesh);

    CHECK_OK(sherd_mesh_copy_normals(copy, normals_out, VERTEX_COUNT));
    CHECK(normals_out[2] == -1.0 && normals_out[3] == 1.0 && normals_out[7] == 1.0);
    CHECK(normals_out[9] == 0.0 && normals_out[10] == 0.0 && normals_out[11] == 0.0);
    CHECK_OK(sherd_mesh_copy_colors(copy, colors_out, VERTEX_COUNT));
    CHECK(memcmp(colors_out, colors, sizeof colors) == 0);
    CHECK_OK(sherd_mesh_copy_corner_uvs(copy, uvs_out, 3 * TRIANGLE_COUNT));
    CHECK(memcmp(uvs_out, uvs, sizeof uvs) == 0);
    CHECK_STATUS(sherd_mesh_copy_quality(copy, (float *)uvs_out, VERTEX_COUNT), SHERD_STATUS_NOT_AVAILABLE);
    sherd_mesh_free(copy);
}

static void apply(const double m[16], const double p[3], double out[3]) {
    int row;
    for (row = 0; row < 3; ++row) {
        out[row] = m[4 * row] * p[0] + m[4 * row + 1] * p[1] + m[4 * row + 2] * p[2] + m[4 * row + 3];
    }
}

static void test_oriented_transform(void) {
    SherdAxis axis;
    double matrix[16];
    const double reference[3] = {10.0, 4.0, 1.0};
    double on_axis[3], mapped[3], expected_radius;
    double d[3];
    int row, column, k;
    SherdMesh *mesh = NULL;

    memset(&axis, 0, sizeof axis);
    axis.size = sizeof axis;
    axis.point[0] = 3.0; axis.point[1] = -2.0; axis.point[2] = 5.0;
    axis.direction[0] = 0.3; axis.direction[1] = -0.5; axis.direction[2] = 0.8;
    CHECK_OK(sherd_axis_oriented_transform(&axis, reference, matrix));

    /* A rotation: orthonormal rows, determinant +1 (checked through the cross product). */
    for (row = 0; row < 3; ++row) {
        for (column = 0; column < 3; ++column) {
            double dot = 0.0;
            for (k = 0; k < 3; ++k) dot += matrix[4 * row + k] * matrix[4 * column + k];
            CHECK_NEAR(dot, row == column ? 1.0 : 0.0, 1e-12);
        }
    }
    CHECK_NEAR(matrix[0] * (matrix[5] * matrix[10] - matrix[6] * matrix[9]) -
                   matrix[1] * (matrix[4] * matrix[10] - matrix[6] * matrix[8]) +
                   matrix[2] * (matrix[4] * matrix[9] - matrix[5] * matrix[8]),
               1.0, 1e-12);
    CHECK(matrix[12] == 0.0 && matrix[13] == 0.0 && matrix[14] == 0.0 && matrix[15] == 1.0);

    /* Points of the axis go onto +z at their height along it. */
    {
        double length = sqrt(0.3 * 0.3 + 0.5 * 0.5 + 0.8 * 0.8);
        for (k = 0; k < 3; ++k) on_axis[k] = axis.point[k] + 7.0 * axis.direction[k] / length;
    }
    apply(matrix, on_axis, mapped);
    CHECK_NEAR(mapped[0], 0.0, 1e-12);
    CHECK_NEAR(mapped[1], 0.0, 1e-12);
    CHECK_NEAR(mapped[2], 7.0, 1e-12);

    /* The reference lands on +x at its distance from the axis. */
    apply(matrix, reference, mapped);
    {
        double length = sqrt(0.3 * 0.3 + 0.5 * 0.5 + 0.8 * 0.8), along = 0.0, squared = 0.0;
        for (k = 0; k < 3; ++k) d[k] = reference[k] - axis.point[k];
        for (k = 0; k < 3; ++k) along += d[k] * axis.direction[k] / length;
        for (k = 0; k < 3; ++k) {
            double perpendicular = d[k] - along * axis.direction[k] / length;
            squared += perpendicular * perpendicular;
        }
        expected_radius = sqrt(squared);
    }
    CHECK(mapped[0] > 0.0);
    CHECK_NEAR(mapped[0], expected_radius, 1e-12);
    CHECK_NEAR(mapped[1], 0.0, 1e-12);

    /* With a mesh the reference is its centroid (2.5, 2.5, 2.5). */
    CHECK_OK(sherd_mesh_from_arrays(positions, VERTEX_COUNT, triangles, TRIANGLE_COUNT, &mesh));
    CHECK_OK(sherd_mesh_oriented_transform(mesh, &axis, matrix));
    {
        const double centroid[3] = {2.5, 2.5, 2.5};
        double expected[16];
        CHECK_OK(sherd_axis_oriented_transform(&axis, centroid, expected));
        for (k = 0; k < 16; ++k) CHECK(matrix[k] == expected[k]);
    }
    sherd_mesh_free(mesh);
}

int main(void) {
    test_version();
    test_round_trip();
    test_f32_and_attributes();
    test_oriented_transform();
    printf("test_mesh: ok (sherd %s, ABI %u)\n", sherd_version(), (unsigned)sherd_abi_version());
    return 0;
}
