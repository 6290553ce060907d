/* Results handed to hosts as meshes (the MeshLab plugin makes layers of them): the
 * reconstruction by revolution (sherd_reconstruction_mesh), watertight and identical to
 * the PLY export, and the regularity painted on a copy of the mesh
 * (sherd_regularity_mesh) as quality and colours; their errors. */
#include "wall.h"

static double *mesh_positions(const SherdMesh *mesh, size_t *count) {
    double *positions;
    CHECK_OK(sherd_mesh_vertex_count(mesh, count));
    positions = (double *)malloc(3 * *count * sizeof(double));
    CHECK(positions != NULL);
    CHECK_OK(sherd_mesh_copy_positions(mesh, positions, *count));
    return positions;
}

/* Every edge of a closed manifold mesh is shared by exactly two triangles, once in each
 * direction. */
static void check_watertight(const SherdMesh *mesh) {
    size_t faces, f, g, k, l;
    uint32_t *triangles;
    CHECK_OK(sherd_mesh_face_count(mesh, &faces));
    CHECK(faces > 0);
    triangles = (uint32_t *)malloc(3 * faces * sizeof(uint32_t));
    CHECK(triangles != NULL);
    CHECK_OK(sherd_mesh_copy_triangles(mesh, triangles, faces));
    for (f = 0; f < faces; ++f) {
        for (k = 0; k < 3; ++k) {
            uint32_t a = triangles[3 * f + k], b = triangles[3 * f + (k + 1) % 3];
            size_t opposite = 0;
            for (g = 0; g < faces; ++g) {
                for (l = 0; l < 3; ++l) {
                    if (triangles[3 * g + l] == b && triangles[3 * g + (l + 1) % 3] == a) ++opposite;
                }
            }
            CHECK(opposite == 1);
        }
    }
    free(triangles);
}

static void test_reconstruction_mesh(void) {
    SherdMesh *mesh = wall_mesh(), *vessel = NULL, *exported = NULL;
    SherdAxis axis = wall_axis();
    double *positions, *written;
    size_t count, written_count, i;

    CHECK_OK(sherd_reconstruction_mesh(mesh, &axis, NAN, 36, &vessel));
    positions = mesh_positions(vessel, &count);
    for (i = 0; i < count; ++i) {
        const double *p = positions + 3 * i;
        double radius = sqrt(p[0] * p[0] + p[1] * p[1]);
        CHECK(radius > 45.0 - 0.02 && radius < 50.0 + 1e-3 && p[2] > -1e-3 && p[2] < 40.0 + 1e-3);
    }
    check_watertight(vessel);
    /* The same vessel as the PLY export (stored as floats). */
    CHECK_OK(sherd_export_reconstruction_ply(mesh, &axis, NAN, 36, "host-vessel.ply", true));
    CHECK_OK(sherd_mesh_read("host-vessel.ply", &exported));
    written = mesh_positions(exported, &written_count);
    CHECK(written_count == count);
    for (i = 0; i < 3 * count; ++i) CHECK(written[i] == (double)(float)positions[i]);
    remove("host-vessel.ply");
    free(written);
    free(positions);
    sherd_mesh_free(exported);
    sherd_mesh_free(vessel);

    vessel = NULL;
    CHECK_STATUS(sherd_reconstruction_mesh(mesh, &axis, NAN, 2, &vessel), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("at least 3 segments");
    CHECK_STATUS(sherd_reconstruction_mesh(mesh, &axis, 2.0, 0, &vessel), SHERD_STATUS_DEGENERATE_GEOMETRY);
    CHECK_STATUS(sherd_reconstruction_mesh(mesh, &axis, NAN, 0, NULL), SHERD_STATUS_NULL_POINTER);
    CHECK_STATUS(sherd_reconstruction_mesh(NULL, &axis, NAN, 0, &vessel), SHERD_STATUS_NULL_POINTER);
    CHECK_STATUS(sherd_reconstruction_mesh(mesh, NULL, NAN, 0, &vessel), SHERD_STATUS_NULL_POINTER);
    CHECK(vessel == NULL);
    sherd_mesh_free(mesh);
}

static void test_regularity_mesh(void) {
    SherdMesh *mesh = wall_mesh(), *painted = NULL;
    SherdAxis axis = wall_axis();
    double original[3 * WALL_VERTEX_COUNT], *positions;
    float quality[WALL_VERTEX_COUNT];
    uint8_t colors[4 * WALL_VERTEX_COUNT];
    size_t count, i;
    int inner_seen = 0, outer_seen = 0;

    CHECK_OK(sherd_mesh_copy_positions(mesh, original, WALL_VERTEX_COUNT));
    /* Distance to the axis: the skins' radii, in the mesh's own frame and vertex order. */
    CHECK_OK(sherd_regularity_mesh(mesh, &axis, SHERD_REGULARITY_AXIS_DISTANCE, NAN, &painted));
    positions = mesh_positions(painted, &count);
    CHECK(count == WALL_VERTEX_COUNT);
    CHECK(memcmp(positions, original, sizeof original) == 0);
    free(positions);
    CHECK_OK(sherd_mesh_copy_quality(painted, quality, WALL_VERTEX_COUNT));
    CHECK_OK(sherd_mesh_copy_colors(painted, colors, WALL_VERTEX_COUNT));
    for (i = 0; i < WALL_VERTEX_COUNT; ++i) {
        CHECK(fabsf(quality[i] - 45.0f) < 1e-3f || fabsf(quality[i] - 50.0f) < 1e-3f);
        if (quality[i] < 47.0f) {
            inner_seen = 1;
            CHECK(colors[4 * i + 2] > colors[4 * i]); /* low: blue */
        } else {
            outer_seen = 1;
            CHECK(colors[4 * i] > colors[4 * i + 2]); /* high: red */
        }
        CHECK(colors[4 * i + 3] == 255);
    }
    CHECK(inner_seen && outer_seen);
    sherd_mesh_free(painted);

    /* Distance to the ideal vessel: a regular wall lies on it, up to the chords. */
    CHECK_OK(sherd_regularity_mesh(mesh, &axis, SHERD_REGULARITY_IDEAL_VESSEL, NAN, &painted));
    CHECK_OK(sherd_mesh_copy_quality(painted, quality, WALL_VERTEX_COUNT));
    for (i = 0; i < WALL_VERTEX_COUNT; ++i) CHECK(fabsf(quality[i]) < 0.05f);
    sherd_mesh_free(painted);

    painted = NULL;
    CHECK_STATUS(sherd_regularity_mesh(mesh, &axis, 2, NAN, &painted), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("SHERD_REGULARITY_");
    CHECK_STATUS(sherd_regularity_mesh(mesh, &axis, SHERD_REGULARITY_IDEAL_VESSEL, 2.0, &painted),
                 SHERD_STATUS_DEGENERATE_GEOMETRY);
    CHECK_STATUS(sherd_regularity_mesh(mesh, &axis, SHERD_REGULARITY_AXIS_DISTANCE, NAN, NULL),
                 SHERD_STATUS_NULL_POINTER);
    CHECK_STATUS(sherd_regularity_mesh(NULL, &axis, SHERD_REGULARITY_AXIS_DISTANCE, NAN, &painted),
                 SHERD_STATUS_NULL_POINTER);
    CHECK(painted == NULL);
    sherd_mesh_free(mesh);
}

int main(void) {
    test_reconstruction_mesh();
    test_regularity_mesh();
    printf("test_host_meshes: ok\n");
    return 0;
}
