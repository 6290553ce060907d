/* Files through the C ABI: PLY written and read back, the oriented mesh exported and its
 * geometry checked in the oriented frame, the profile as CSV (file and memory), and the
 * reading errors (missing file, malformed content) with their statuses and messages. */
#include "wall.h"

static double *read_back_positions(const char *path, size_t *count) {
    SherdMesh *mesh = NULL;
    double *positions;
    CHECK_OK(sherd_mesh_read(path, &mesh));
    CHECK_OK(sherd_mesh_vertex_count(mesh, count));
    positions = (double *)malloc(3 * *count * sizeof(double));
    CHECK(positions != NULL);
    CHECK_OK(sherd_mesh_copy_positions(mesh, positions, *count));
    sherd_mesh_free(mesh);
    return positions;
}

static void test_ply_round_trip(void) {
    SherdMesh *mesh = wall_mesh(), *back = NULL;
    double original[3 * WALL_VERTEX_COUNT];
    uint32_t triangles[3 * WALL_FACE_COUNT], triangles_back[3 * WALL_FACE_COUNT];
    double *positions;
    size_t count, faces, i;
    int binary;

    CHECK_OK(sherd_mesh_copy_positions(mesh, original, WALL_VERTEX_COUNT));
    CHECK_OK(sherd_mesh_copy_triangles(mesh, triangles, WALL_FACE_COUNT));
    for (binary = 0; binary <= 1; ++binary) {
        CHECK_OK(sherd_mesh_write_ply(mesh, "wall.ply", binary != 0));
        positions = read_back_positions("wall.ply", &count);
        CHECK(count == WALL_VERTEX_COUNT);
        /* Coordinates of scan size are stored as floats: binary keeps the float's bits,
         * ASCII its shortest decimal form. */
        for (i = 0; i < 3 * count; ++i) {
            if (binary) CHECK(positions[i] == (double)(float)original[i]);
            else CHECK_NEAR(positions[i], original[i], 1e-5);
        }
        free(positions);
        CHECK_OK(sherd_mesh_read("wall.ply", &back));
        CHECK_OK(sherd_mesh_face_count(back, &faces));
        CHECK(faces == WALL_FACE_COUNT);
        CHECK_OK(sherd_mesh_copy_triangles(back, triangles_back, WALL_FACE_COUNT));
        CHECK(memcmp(triangles, triangles_back, sizeof triangles) == 0);
        sherd_mesh_free(back);
    }
    remove("wall.ply");
    sherd_mesh_free(mesh);
}

static void test_oriented_export(void) {
    SherdMesh *mesh = wall_mesh();
    SherdAxis axis = wall_axis();
    double *positions, lowest = 1e9, highest = -1e9;
    size_t count, i;

    CHECK_OK(sherd_export_oriented_ply(mesh, &axis, "oriented.ply", true));
    positions = read_back_positions("oriented.ply", &count);
    CHECK(count == WALL_VERTEX_COUNT);
    for (i = 0; i < count; ++i) {
        const double *p = positions + 3 * i;
        double radius = sqrt(p[0] * p[0] + p[1] * p[1]);
        /* Every vertex is on one of the two skins about z (to the file's float
         * precision), and the piece faces +x. */
        CHECK(fabs(radius - 45.0) < 1e-4 || fabs(radius - 50.0) < 1e-4);
        CHECK(p[0] > 0.0);
        if (p[2] < lowest) lowest = p[2];
        if (p[2] > highest) highest = p[2];
    }
    CHECK_NEAR(lowest, 0.0, 1e-4);
    CHECK_NEAR(highest, 40.0, 1e-4);
    free(positions);
    remove("oriented.ply");
    sherd_mesh_free(mesh);
}

static void test_reconstruction(void) {
    SherdMesh *mesh = wall_mesh();
    SherdAxis axis = wall_axis();
    double *positions;
    size_t count, i, inner = 0, outer = 0;

    CHECK_OK(sherd_export_reconstruction_ply(mesh, &axis, NAN, 36, "reconstruction.ply", false));
    positions = read_back_positions("reconstruction.ply", &count);
    /* The whole ring: the section's rectangle turned a full turn, both skins present. */
    for (i = 0; i < count; ++i) {
        const double *p = positions + 3 * i;
        double radius = sqrt(p[0] * p[0] + p[1] * p[1]);
        CHECK(radius > 45.0 - 0.02 && radius < 50.0 + 1e-3 && p[2] > -1e-3 && p[2] < 40.0 + 1e-3);
        if (radius < 46.0) ++inner;
        if (radius > 49.0) ++outer;
    }
    CHECK(inner >= 36 && outer >= 36);
    free(positions);
    remove("reconstruction.ply");
    CHECK_STATUS(sherd_export_reconstruction_ply(mesh, &axis, NAN, 2, "reconstruction.ply", false),
                 SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("needs 3 to");
    CHECK_STATUS(sherd_export_reconstruction_ply(mesh, &axis, 2.0, 0, "reconstruction.ply", false),
                 SHERD_STATUS_DEGENERATE_GEOMETRY);
    CHECK_STATUS(sherd_export_reconstruction_ply(mesh, &axis, NAN, 0, NULL, false), SHERD_STATUS_NULL_POINTER);
    sherd_mesh_free(mesh);
}

static void test_profile_csv(void) {
    SherdMesh *mesh = wall_mesh();
    SherdAxis axis = wall_axis();
    SherdBuffer *csv = NULL;
    const uint8_t *data = NULL;
    size_t size = 0, lines = 0;
    double angle = 99.0;
    const char *line;
    FILE *file;
    char first[64];

    CHECK_OK(sherd_profile_most_informative_angle(mesh, &axis, &angle));
    CHECK(fabs(angle) < 3.14159265358979323846 / 6.0);
    CHECK_OK(sherd_profile_csv(mesh, &axis, NAN, &csv));
    CHECK_OK(sherd_buffer_contents(csv, &data, &size));
    CHECK(strncmp((const char *)data, "curve,index,r_mm,z_mm,closed\n", 29) == 0);
    CHECK(strlen((const char *)data) == size);
    /* The cut through a wall of constant thickness is the 5 x 40 mm rectangle (the
     * inner skin's chords dip up to 0.011 mm below 45 mm between vertices). */
    for (line = strchr((const char *)data, '\n') + 1; *line; line = strchr(line, '\n') + 1) {
        int curve, index;
        double r, z;
        CHECK(sscanf(line, "%d,%d,%lf,%lf", &curve, &index, &r, &z) == 4);
        CHECK(r > 45.0 - 0.02 && r < 50.0 + 1e-6 && z > -1e-6 && z < 40.0 + 1e-6);
        ++lines;
    }
    CHECK(lines >= 4);
    sherd_buffer_free(csv);

    CHECK_OK(sherd_export_profile_csv(mesh, &axis, 0.1, "profile.csv"));
    file = fopen("profile.csv", "r");
    CHECK(file != NULL);
    CHECK(fgets(first, sizeof first, file) != NULL);
    CHECK(strcmp(first, "curve,index,r_mm,z_mm,closed\n") == 0);
    fclose(file);
    remove("profile.csv");

    /* A cut that misses the piece (it spans -30 to 30 degrees). */
    CHECK_STATUS(sherd_profile_csv(mesh, &axis, 2.0, &csv), SHERD_STATUS_DEGENERATE_GEOMETRY);
    CHECK_STATUS(sherd_profile_csv(mesh, &axis, INFINITY, &csv), SHERD_STATUS_INVALID_ARGUMENT);
    sherd_mesh_free(mesh);
}

static void test_read_errors(void) {
    SherdMesh *mesh = NULL;
    FILE *file;
    CHECK_STATUS(sherd_mesh_read("does/not/exist.ply", &mesh), SHERD_STATUS_IO);
    CHECK_MESSAGE("does/not/exist.ply");
    CHECK_STATUS(sherd_mesh_read("", &mesh), SHERD_STATUS_INVALID_ARGUMENT);
    file = fopen("broken.ply", "w");
    CHECK(file != NULL);
    fputs("ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
          "property float z\nend_header\n1 2 3\n4 banana 6\n", file);
    fclose(file);
    CHECK_STATUS(sherd_mesh_read("broken.ply", &mesh), SHERD_STATUS_PARSE);
    CHECK_MESSAGE("broken.ply");
    remove("broken.ply");
    CHECK(mesh == NULL);
}

static void test_null_arguments(void) {
    SherdMesh *mesh = wall_mesh(), *out = NULL;
    SherdAxis axis = wall_axis();
    SherdBuffer *buffer = NULL;
    const uint8_t *data;
    size_t size;
    double angle;

    CHECK_STATUS(sherd_mesh_read(NULL, &out), SHERD_STATUS_NULL_POINTER);
    CHECK_MESSAGE("`path` is NULL");
    CHECK_STATUS(sherd_mesh_read("x.ply", NULL), SHERD_STATUS_NULL_POINTER);
    CHECK_STATUS(sherd_mesh_write_ply(NULL, "x.ply", true), SHERD_STATUS_NULL_POINTER);
    CHECK_STATUS(sherd_mesh_write_ply(mesh, NULL, true), SHERD_STATUS_NULL_POINTER);
    CHECK_STATUS(sherd_export_oriented_ply(NULL, &axis, "x.ply", true), SHERD_STATUS_NULL_POINTER);
    CHECK_STATUS(sherd_export_oriented_ply(mesh, NULL, "x.ply", true), SHERD_STATUS_NULL_POINTER);
    CHECK_STATUS(sherd_export_oriented_ply(mesh, &axis, NULL, true), SHERD_STATUS_NULL_POINTER);
    CHECK_STATUS(sherd_export_profile_csv(NULL, &axis, 0.0, "x.csv"), SHERD_STATUS_NULL_POINTER);
    CHECK_STATUS(sherd_export_profile_csv(mesh, NULL, 0.0, "x.csv"), SHERD_STATUS_NULL_POINTER);
    CHECK_STATUS(sherd_export_profile_csv(mesh, &axis, 0.0, NULL), SHERD_STATUS_NULL_POINTER);
    CHECK_STATUS(sherd_profile_csv(NULL, &axis, 0.0, &buffer), SHERD_STATUS_NULL_POINTER);
    CHECK_STATUS(sherd_profile_csv(mesh, NULL, 0.0, &buffer), SHERD_STATUS_NULL_POINTER);
    CHECK_STATUS(sherd_profile_csv(mesh, &axis, 0.0, NULL), SHERD_STATUS_NULL_POINTER);
    CHECK_STATUS(sherd_profile_most_informative_angle(NULL, &axis, &angle), SHERD_STATUS_NULL_POINTER);
    CHECK_STATUS(sherd_profile_most_informative_angle(mesh, NULL, &angle), SHERD_STATUS_NULL_POINTER);
    CHECK_STATUS(sherd_profile_most_informative_angle(mesh, &axis, NULL), SHERD_STATUS_NULL_POINTER);
    CHECK_OK(sherd_profile_csv(mesh, &axis, 0.0, &buffer));
    CHECK_STATUS(sherd_buffer_contents(NULL, &data, &size), SHERD_STATUS_NULL_POINTER);
    CHECK_STATUS(sherd_buffer_contents(buffer, NULL, &size), SHERD_STATUS_NULL_POINTER);
    CHECK_STATUS(sherd_buffer_contents(buffer, &data, NULL), SHERD_STATUS_NULL_POINTER);
    sherd_buffer_free(buffer);
    sherd_buffer_free(NULL);
    CHECK(out == NULL);
    sherd_mesh_free(mesh);
}

int main(void) {
    test_ply_round_trip();
    test_oriented_export();
    test_reconstruction();
    test_profile_csv();
    test_read_errors();
    test_null_arguments();
    printf("test_files: ok\n");
    return 0;
}
