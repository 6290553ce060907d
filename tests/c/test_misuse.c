/* Misuse from C: NULL for every pointer argument, wrong struct sizes, out-of-range
 * values, indices past the vertex count, NaN coordinates, short buffers. Each must give
 * its status code and a message naming the problem, never a crash; the valgrind run
 * checks that nothing is written where it should not be.
 *
 * Not tested because it cannot be detected: using or freeing a handle (a mesh, a buffer,
 * option builders) after its sherd_*_free (undefined behaviour, as with free(); the
 * header says so on each _free function). */
#include "check.h"

static const double positions[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
static const float positions_f32[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
static const uint32_t triangles[12] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};

#define NULL_ARGUMENT(call, name)                         \
    do {                                                  \
        CHECK_STATUS(call, SHERD_STATUS_NULL_POINTER);    \
        CHECK_MESSAGE("`" name "` is NULL");              \
    } while (0)

static SherdMesh *make_mesh(void) {
    SherdMesh *mesh = NULL;
    CHECK_OK(sherd_mesh_from_arrays(positions, 4, triangles, 4, &mesh));
    return mesh;
}

static SherdAxis z_axis(void) {
    SherdAxis axis;
    memset(&axis, 0, sizeof axis);
    axis.size = sizeof axis;
    axis.direction[2] = 1.0;
    return axis;
}

static void test_null_pointers(void) {
    SherdMesh *mesh = make_mesh();
    SherdMesh *out = (SherdMesh *)&out; /* must stay untouched on error */
    SherdMesh *const untouched = out;
    SherdAxis axis = z_axis();
    double buffer_f64[64];
    float buffer_f32[64];
    uint32_t buffer_u32[64];
    uint8_t buffer_u8[64];
    size_t count;
    uint32_t attributes;
    const double reference[3] = {1, 0, 0};

    NULL_ARGUMENT(sherd_mesh_from_arrays(NULL, 4, triangles, 4, &out), "positions");
    NULL_ARGUMENT(sherd_mesh_from_arrays(positions, 4, NULL, 4, &out), "triangles");
    NULL_ARGUMENT(sherd_mesh_from_arrays(positions, 4, triangles, 4, NULL), "out_mesh");
    NULL_ARGUMENT(sherd_mesh_from_arrays_f32(NULL, 4, triangles, 4, &out), "positions");
    NULL_ARGUMENT(sherd_mesh_from_arrays_f32(positions_f32, 4, NULL, 4, &out), "triangles");
    NULL_ARGUMENT(sherd_mesh_from_arrays_f32(positions_f32, 4, triangles, 4, NULL), "out_mesh");
    CHECK(out == untouched);
    NULL_ARGUMENT(sherd_mesh_clone(NULL, &out), "mesh");
    NULL_ARGUMENT(sherd_mesh_clone(mesh, NULL), "out_mesh");
    CHECK(out == untouched);

    NULL_ARGUMENT(sherd_mesh_set_normals(NULL, buffer_f64, 4), "mesh");
    NULL_ARGUMENT(sherd_mesh_set_normals(mesh, NULL, 4), "normals");
    NULL_ARGUMENT(sherd_mesh_set_normals_f32(NULL, buffer_f32, 4), "mesh");
    NULL_ARGUMENT(sherd_mesh_set_normals_f32(mesh, NULL, 4), "normals");
    NULL_ARGUMENT(sherd_mesh_set_colors(NULL, buffer_u8, 4), "mesh");
    NULL_ARGUMENT(sherd_mesh_set_colors(mesh, NULL, 4), "rgba");
    NULL_ARGUMENT(sherd_mesh_set_corner_uvs(NULL, buffer_f32, 12), "mesh");
    NULL_ARGUMENT(sherd_mesh_set_corner_uvs(mesh, NULL, 12), "uvs");

    NULL_ARGUMENT(sherd_mesh_vertex_count(NULL, &count), "mesh");
    NULL_ARGUMENT(sherd_mesh_vertex_count(mesh, NULL), "out_count");
    NULL_ARGUMENT(sherd_mesh_face_count(NULL, &count), "mesh");
    NULL_ARGUMENT(sherd_mesh_face_count(mesh, NULL), "out_count");
    NULL_ARGUMENT(sherd_mesh_attributes(NULL, &attributes), "mesh");
    NULL_ARGUMENT(sherd_mesh_attributes(mesh, NULL), "out_attributes");
    NULL_ARGUMENT(sherd_mesh_copy_positions(NULL, buffer_f64, 4), "mesh");
    NULL_ARGUMENT(sherd_mesh_copy_positions(mesh, NULL, 4), "out");
    NULL_ARGUMENT(sherd_mesh_copy_positions_f32(NULL, buffer_f32, 4), "mesh");
    NULL_ARGUMENT(sherd_mesh_copy_positions_f32(mesh, NULL, 4), "out");
    NULL_ARGUMENT(sherd_mesh_copy_triangles(NULL, buffer_u32, 4), "mesh");
    NULL_ARGUMENT(sherd_mesh_copy_triangles(mesh, NULL, 4), "out");
    NULL_ARGUMENT(sherd_mesh_copy_normals(NULL, buffer_f64, 4), "mesh");
    NULL_ARGUMENT(sherd_mesh_copy_colors(NULL, buffer_u8, 4), "mesh");
    NULL_ARGUMENT(sherd_mesh_copy_corner_uvs(NULL, buffer_f32, 12), "mesh");
    NULL_ARGUMENT(sherd_mesh_copy_quality(NULL, buffer_f32, 4), "mesh");

    NULL_ARGUMENT(sherd_axis_oriented_transform(NULL, reference, buffer_f64), "axis");
    NULL_ARGUMENT(sherd_axis_oriented_transform(&axis, NULL, buffer_f64), "reference_point");
    NULL_ARGUMENT(sherd_axis_oriented_transform(&axis, reference, NULL), "out_matrix");
    NULL_ARGUMENT(sherd_mesh_oriented_transform(NULL, &axis, buffer_f64), "mesh");
    NULL_ARGUMENT(sherd_mesh_oriented_transform(mesh, NULL, buffer_f64), "axis");
    NULL_ARGUMENT(sherd_mesh_oriented_transform(mesh, &axis, NULL), "out_matrix");

    /* The optional attributes' copy functions check the mesh's content before `out`. */
    {
        double normals[12] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
        CHECK_OK(sherd_mesh_set_normals(mesh, normals, 4));
        NULL_ARGUMENT(sherd_mesh_copy_normals(mesh, NULL, 4), "out");
    }

    /* sherd_mesh_free(NULL) is a no-op. */
    sherd_mesh_free(NULL);
    sherd_mesh_free(mesh);
}

static void test_invalid_mesh_arrays(void) {
    SherdMesh *out = NULL;
    double bad[12];
    uint32_t bad_triangles[12];

    memcpy(bad, positions, sizeof bad);
    bad[7] = NAN;
    CHECK_STATUS(sherd_mesh_from_arrays(bad, 4, triangles, 4, &out), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("vertex 2");
    bad[7] = INFINITY;
    CHECK_STATUS(sherd_mesh_from_arrays(bad, 4, triangles, 4, &out), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("vertex 2");

    memcpy(bad_triangles, triangles, sizeof bad_triangles);
    bad_triangles[10] = 4;
    CHECK_STATUS(sherd_mesh_from_arrays(positions, 4, bad_triangles, 4, &out), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("face 3 refers to vertex 4");
    CHECK_STATUS(sherd_mesh_from_arrays_f32(positions_f32, 4, bad_triangles, 4, &out), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("face 3 refers to vertex 4");
    /* Fewer vertices than the triangles use. */
    CHECK_STATUS(sherd_mesh_from_arrays(positions, 3, triangles, 4, &out), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("only 3 vertices");

    CHECK_STATUS(sherd_mesh_from_arrays(positions, 0, NULL, 0, &out), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("vertex_count");
    /* A count whose byte size overflows is refused before any read. */
    CHECK_STATUS(sherd_mesh_from_arrays(positions, (size_t)-1 / 2, triangles, 4, &out), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("too large");
    CHECK(out == NULL);

    /* A point cloud (no triangles) is accepted, with NULL triangles. */
    CHECK_OK(sherd_mesh_from_arrays(positions, 4, NULL, 0, &out));
    sherd_mesh_free(out);
}

static void test_invalid_attributes(void) {
    SherdMesh *mesh = make_mesh();
    double normals[12] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    float uvs[24] = {0};
    uint8_t colors[16] = {0};

    CHECK_STATUS(sherd_mesh_set_normals(mesh, normals, 3), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("the mesh has 4 vertices");
    normals[4] = NAN;
    CHECK_STATUS(sherd_mesh_set_normals(mesh, normals, 4), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("normal of vertex 1");
    CHECK_STATUS(sherd_mesh_set_colors(mesh, colors, 5), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(sherd_mesh_set_corner_uvs(mesh, uvs, 4), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("expected 3 * 4 triangles = 12");
    uvs[5] = NAN;
    CHECK_STATUS(sherd_mesh_set_corner_uvs(mesh, uvs, 12), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("corner 2");
    sherd_mesh_free(mesh);
}

static void test_short_buffers(void) {
    SherdMesh *mesh = make_mesh();
    double out[12];
    uint32_t indices[12];
    size_t i;

    for (i = 0; i < 12; ++i) out[i] = -7.0;
    CHECK_STATUS(sherd_mesh_copy_positions(mesh, out, 3), SHERD_STATUS_BUFFER_TOO_SMALL);
    CHECK_MESSAGE("4 vertices");
    for (i = 0; i < 12; ++i) CHECK(out[i] == -7.0); /* nothing written */
    CHECK_STATUS(sherd_mesh_copy_triangles(mesh, indices, 0), SHERD_STATUS_BUFFER_TOO_SMALL);
    /* A larger buffer is fine: only the mesh's values are written. */
    {
        double larger[15];
        larger[12] = 42.0;
        CHECK_OK(sherd_mesh_copy_positions(mesh, larger, 5));
        CHECK(larger[12] == 42.0);
    }
    sherd_mesh_free(mesh);
}

static void test_axis_struct(void) {
    SherdAxis axis = z_axis();
    double matrix[16];
    const double reference[3] = {1, 0, 0};
    const double nan_reference[3] = {1, NAN, 0};

    axis.size = 0;
    CHECK_STATUS(sherd_axis_oriented_transform(&axis, reference, matrix), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("`axis->size` is 0");
    axis.size = sizeof axis - 1;
    CHECK_STATUS(sherd_axis_oriented_transform(&axis, reference, matrix), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("sizeof(SherdAxis)");

    axis = z_axis();
    axis.direction[2] = 0.0;
    CHECK_STATUS(sherd_axis_oriented_transform(&axis, reference, matrix), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("non-zero direction");
    axis = z_axis();
    axis.point[1] = NAN;
    CHECK_STATUS(sherd_axis_oriented_transform(&axis, reference, matrix), SHERD_STATUS_INVALID_ARGUMENT);
    axis = z_axis();
    CHECK_STATUS(sherd_axis_oriented_transform(&axis, nan_reference, matrix), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("reference_point");
}

static void test_pipeline_misuse(void) {
    SherdMesh *mesh = make_mesh(), *out = NULL;
    SherdAxis axis = z_axis(), short_axis = z_axis();
    SherdOrientReport report;
    SherdOrientOptions *orient_options = NULL;
    SherdManualOptions *manual_options = NULL;
    SherdRepairOptions *repair_options = NULL;
    SherdBuffer *buffer = NULL;
    const double points[9] = {1, 0, 0, 0, 1, 0, -1, 0, 0};
    double nan_points[9] = {1, 0, 0, 0, 1, 0, -1, 0, 0};
    double rill_points[9];
    size_t count = 0;

    memset(&report, 0, sizeof report);
    report.size = sizeof report;

    /* Synthetic sherds: an out-of-range kind, bad noise, NULL outputs. */
    CHECK_STATUS(sherd_synthetic_sherd(1, 99u, 1000, 0.0, &out, NULL, NULL), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("`kind` 99 is not a SHERD_SYNTH_KIND_* value");
    CHECK_STATUS(sherd_synthetic_sherd(1, SHERD_SYNTH_KIND_RIM, 1000, NAN, &out, NULL, NULL),
                 SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(sherd_synthetic_sherd(1, SHERD_SYNTH_KIND_RIM, 1000, -1.0, &out, NULL, NULL),
                 SHERD_STATUS_INVALID_ARGUMENT);
    NULL_ARGUMENT(sherd_synthetic_sherd(1, SHERD_SYNTH_KIND_RIM, 1000, 0.0, NULL, NULL, NULL), "out_mesh");
    short_axis.size = 8;
    CHECK_STATUS(sherd_synthetic_sherd(1, SHERD_SYNTH_KIND_RIM, 1000, 0.0, &out, &short_axis, NULL),
                 SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("out_true_axis->size");
    CHECK(out == NULL);

    /* Option builders: NULL handles, values out of range. */
    NULL_ARGUMENT(sherd_orient_options_new(NULL), "out_options");
    NULL_ARGUMENT(sherd_manual_options_new(NULL), "out_options");
    NULL_ARGUMENT(sherd_repair_options_new(NULL), "out_options");
    NULL_ARGUMENT(sherd_orient_options_set_target_vertex_count(NULL, 10), "options");
    NULL_ARGUMENT(sherd_orient_options_set_smoothing_iterations(NULL, 1), "options");
    NULL_ARGUMENT(sherd_orient_options_set_opposite_normal_confidence(NULL, 0.9), "options");
    NULL_ARGUMENT(sherd_manual_options_set_keep_fraction(NULL, 0.5), "options");
    NULL_ARGUMENT(sherd_manual_options_set_max_pick_distance_mm(NULL, 1.0), "options");
    NULL_ARGUMENT(sherd_repair_options_set_merge_tolerance_mm(NULL, 0.1), "options");
    NULL_ARGUMENT(sherd_repair_options_set_keep_largest_component(NULL, true), "options");
    CHECK_OK(sherd_orient_options_new(&orient_options));
    CHECK_OK(sherd_manual_options_new(&manual_options));
    CHECK_OK(sherd_repair_options_new(&repair_options));
    CHECK_STATUS(sherd_orient_options_set_target_vertex_count(orient_options, 0), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(sherd_orient_options_set_opposite_normal_confidence(orient_options, 1.0),
                 SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(sherd_orient_options_set_opposite_normal_confidence(orient_options, NAN),
                 SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_OK(sherd_orient_options_set_opposite_normal_confidence(orient_options, 0.0));
    CHECK_STATUS(sherd_manual_options_set_keep_fraction(manual_options, 0.0), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(sherd_manual_options_set_keep_fraction(manual_options, 1.5), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(sherd_manual_options_set_max_pick_distance_mm(manual_options, -2.0), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(sherd_repair_options_set_merge_tolerance_mm(repair_options, INFINITY), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("finite and positive");

    /* Orientation: NULL for each pointer, sizes not set, NaN points. */
    NULL_ARGUMENT(sherd_orient_automatic(NULL, NULL, &axis, NULL, NULL), "mesh");
    NULL_ARGUMENT(sherd_orient_automatic(mesh, NULL, NULL, NULL, NULL), "out_axis");
    short_axis.size = 0;
    CHECK_STATUS(sherd_orient_automatic(mesh, orient_options, &short_axis, NULL, NULL), SHERD_STATUS_INVALID_ARGUMENT);
    report.size = 1;
    CHECK_STATUS(sherd_orient_automatic(mesh, orient_options, &axis, &report, NULL), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("out_report->size");
    report.size = sizeof report;
    NULL_ARGUMENT(sherd_orient_from_three_points(NULL, points, NULL, &axis, NULL, NULL), "mesh");
    NULL_ARGUMENT(sherd_orient_from_three_points(mesh, NULL, NULL, &axis, NULL, NULL), "points");
    NULL_ARGUMENT(sherd_orient_from_three_points(mesh, points, manual_options, NULL, NULL, NULL), "out_axis");
    NULL_ARGUMENT(sherd_points_on_longest_rill(NULL, &axis, rill_points, &count), "mesh");
    NULL_ARGUMENT(sherd_points_on_longest_rill(mesh, NULL, rill_points, &count), "axis");
    NULL_ARGUMENT(sherd_points_on_longest_rill(mesh, &axis, NULL, &count), "out_points");
    NULL_ARGUMENT(sherd_points_on_longest_rill(mesh, &axis, rill_points, NULL), "out_point_count");
    /* A tetrahedron has no rill: nothing written, the count 0. */
    rill_points[0] = 42.0;
    CHECK_OK(sherd_points_on_longest_rill(mesh, &axis, rill_points, &count));
    CHECK(count == 0 && rill_points[0] == 42.0);
    nan_points[4] = NAN;
    CHECK_STATUS(sherd_orient_from_three_points(mesh, nan_points, NULL, &axis, NULL, NULL),
                 SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("point 2");
    /* Points far from the mesh are refused by the orientation layer, with their number. */
    {
        const double far[9] = {100, 0, 0, 0, 100, 0, -100, 0, 0};
        CHECK_STATUS(sherd_orient_from_three_points(mesh, far, NULL, &axis, NULL, NULL), SHERD_STATUS_INVALID_ARGUMENT);
        CHECK_MESSAGE("point 1");
    }

    /* Repair and decimation. */
    NULL_ARGUMENT(sherd_mesh_repair(NULL, repair_options, &buffer), "mesh");
    NULL_ARGUMENT(sherd_mesh_decimate(NULL, 2, &out), "mesh");
    NULL_ARGUMENT(sherd_mesh_decimate(mesh, 2, NULL), "out_mesh");
    CHECK_STATUS(sherd_mesh_decimate(mesh, 0, &out), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK(out == NULL && buffer == NULL);

    sherd_orient_options_free(orient_options);
    sherd_manual_options_free(manual_options);
    sherd_repair_options_free(repair_options);
    sherd_orient_options_free(NULL);
    sherd_manual_options_free(NULL);
    sherd_repair_options_free(NULL);
    sherd_mesh_free(mesh);
}

static void test_refine_measure_draw_misuse(void) {
    SherdMesh *mesh = make_mesh();
    SherdAxis axis = z_axis();
    SherdRefineOptions *refine_options = NULL;
    SherdMeasureOptions *measure_options = NULL;
    SherdDrawOptions *draw_options = NULL;
    SherdRefinement *refinement = NULL;
    SherdDrawing *drawing = NULL;
    SherdMeasurements measurements;
    SherdRefineReport summary;
    SherdParetoPoint points[2];
    SherdBuffer *buffer = NULL;
    size_t count = 0;

    memset(&measurements, 0, sizeof measurements);
    memset(&summary, 0, sizeof summary);

    /* Enum values out of range are refused by the setters, which keep the old value. */
    CHECK_OK(sherd_refine_options_new(&refine_options));
    CHECK_STATUS(sherd_refine_options_set_criterion(refine_options, 5u), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("`criterion` 5 is not a SHERD_CRITERION_* value");
    CHECK_STATUS(sherd_refine_options_set_criterion(refine_options, 0xffffffffu), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(sherd_refine_options_set_surface(refine_options, 3u), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(sherd_refine_options_set_search_bound_deg(refine_options, 90.0), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(sherd_refine_options_set_search_bound_deg(refine_options, 46.0), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("at most 45");
    CHECK_OK(sherd_refine_options_set_search_bound_deg(refine_options, 45.0));
    CHECK_STATUS(sherd_refine_options_set_search_bound_deg(refine_options, NAN), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(sherd_refine_options_set_pareto_choice(refine_options, 4u, 2), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("SHERD_PARETO_CHOICE_");
    CHECK_STATUS(sherd_refine_options_set_pareto_choice(refine_options, SHERD_PARETO_CHOICE_MEAN_OF_BEST, 0),
                 SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("count of at least 1");
    CHECK_OK(sherd_refine_options_set_pareto_choice(refine_options, SHERD_PARETO_CHOICE_MEAN_OF_BEST, 2));
    CHECK_STATUS(sherd_refine_options_set_pareto_section_limits(refine_options, 2, 3.0), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("min_points must be at least 3");
    CHECK_STATUS(sherd_refine_options_set_pareto_section_limits(refine_options, 10, NAN), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(sherd_refine_options_set_pareto_section_limits(refine_options, 10, 361.0), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(sherd_refine_options_set_tangent_tolerance_mm(refine_options, 0.0), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("`tolerance_mm` must be finite and positive");
    CHECK_STATUS(sherd_refine_options_set_tangent_tolerance_mm(refine_options, INFINITY), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(sherd_refine_options_set_edge(refine_options, 3u), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("SHERD_EDGE_");
    NULL_ARGUMENT(sherd_refine_options_set_edge(NULL, SHERD_EDGE_RIM), "options");
    CHECK_STATUS(sherd_refine_options_set_profile_method(refine_options, 3u, 1.0), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("SHERD_PROFILE_METHOD_");
    CHECK_STATUS(sherd_refine_options_set_profile_method(refine_options, SHERD_PROFILE_METHOD_POLYNOMIAL, 2.5),
                 SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("whole number");
    CHECK_STATUS(sherd_refine_options_set_profile_method(refine_options, SHERD_PROFILE_METHOD_POLYNOMIAL, 21.0),
                 SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(sherd_refine_options_set_profile_method(refine_options, SHERD_PROFILE_METHOD_REFERENCE, 1.0),
                 SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(sherd_refine_options_set_profile_method(refine_options, SHERD_PROFILE_METHOD_SPLINE, NAN),
                 SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("knot spacing");
    CHECK_OK(sherd_refine_options_set_profile_method(refine_options, SHERD_PROFILE_METHOD_SPLINE, 2.0));
    CHECK_STATUS(sherd_refine_options_set_circle_fit(refine_options, 4u), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("SHERD_CIRCLE_FIT_");
    NULL_ARGUMENT(sherd_refine_options_set_criterion(NULL, 0), "options");
    NULL_ARGUMENT(sherd_refine_options_new(NULL), "out_options");

    CHECK_OK(sherd_draw_options_new(&draw_options));
    CHECK_STATUS(sherd_draw_options_set_style(draw_options, 0u), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(sherd_draw_options_set_style(draw_options, 64u), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("SHERD_STYLE_");
    CHECK_STATUS(sherd_draw_options_set_annotations(draw_options, 8u), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("SHERD_ANNOTATION_");
    CHECK_OK(sherd_draw_options_set_annotations(draw_options, 0u));
    CHECK_OK(sherd_draw_options_set_annotations(draw_options, SHERD_ANNOTATION_HEIGHT | SHERD_ANNOTATION_WALL_THICKNESS |
                                                                  SHERD_ANNOTATION_CAPACITY));
    CHECK_STATUS(sherd_draw_options_set_section_fill(draw_options, 2u), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(sherd_draw_options_set_placement(draw_options, 9u), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(sherd_draw_options_set_regularity(draw_options, 5u), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(sherd_draw_options_set_dpi(draw_options, 0.0), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("dpi");
    CHECK_STATUS(sherd_draw_options_set_scale_denominator(draw_options, 0u), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(sherd_draw_options_set_section_angle_rad(draw_options, INFINITY), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_OK(sherd_draw_options_set_section_angle_rad(draw_options, NAN));
    CHECK_OK(sherd_draw_options_set_title(draw_options, NULL));
    CHECK_STATUS(sherd_draw_options_set_title(draw_options, "\xff\xfe"), SHERD_STATUS_INVALID_ARGUMENT);
    NULL_ARGUMENT(sherd_draw_options_set_style(NULL, 1u), "options");
    NULL_ARGUMENT(sherd_draw_options_set_interior_view(NULL, true), "options");
    NULL_ARGUMENT(sherd_draw_options_set_prolongation(NULL, false), "options");
    NULL_ARGUMENT(sherd_draw_options_set_annotations(NULL, SHERD_ANNOTATION_HEIGHT), "options");
    NULL_ARGUMENT(sherd_draw_options_new(NULL), "out_options");

    CHECK_OK(sherd_measure_options_new(&measure_options));
    CHECK_STATUS(sherd_measure_options_set_confidence(measure_options, 1.0), SHERD_STATUS_INVALID_ARGUMENT);
    NULL_ARGUMENT(sherd_measure_options_set_refine_options(measure_options, NULL), "refine_options");
    NULL_ARGUMENT(sherd_measure_options_set_refine_options(NULL, refine_options), "options");
    CHECK_OK(sherd_measure_options_set_refine_options(measure_options, refine_options));

    /* Entry points: NULL for each pointer, sizes not set. */
    NULL_ARGUMENT(sherd_refine(NULL, &axis, NULL, &refinement), "mesh");
    NULL_ARGUMENT(sherd_refine(mesh, NULL, NULL, &refinement), "axis");
    NULL_ARGUMENT(sherd_refine(mesh, &axis, NULL, NULL), "out_refinement");
    NULL_ARGUMENT(sherd_refinement_axis(NULL, &axis), "refinement");
    NULL_ARGUMENT(sherd_refinement_report(NULL, &summary), "refinement");
    NULL_ARGUMENT(sherd_refinement_report_json(NULL, &buffer), "refinement");
    NULL_ARGUMENT(sherd_refinement_pareto_front(NULL, points, 2, &count), "refinement");
    NULL_ARGUMENT(sherd_measure(NULL, &axis, NULL, &measurements, NULL), "mesh");
    NULL_ARGUMENT(sherd_measure(mesh, NULL, NULL, &measurements, NULL), "axis");
    NULL_ARGUMENT(sherd_measure(mesh, &axis, NULL, NULL, NULL), "out_measurements");
    CHECK_STATUS(sherd_measure(mesh, &axis, measure_options, &measurements, NULL), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("`out_measurements->size` is 0");
    NULL_ARGUMENT(sherd_drawing_build(NULL, &axis, NULL, &drawing), "mesh");
    NULL_ARGUMENT(sherd_drawing_build(mesh, NULL, NULL, &drawing), "axis");
    NULL_ARGUMENT(sherd_drawing_build(mesh, &axis, draw_options, NULL), "out_drawing");
    NULL_ARGUMENT(sherd_drawing_write(NULL, "x.svg"), "drawing");
    NULL_ARGUMENT(sherd_drawing_to_buffer(NULL, SHERD_FORMAT_SVG, &buffer), "drawing");
    CHECK(refinement == NULL && drawing == NULL && buffer == NULL);

    sherd_refine_options_free(refine_options);
    sherd_measure_options_free(measure_options);
    sherd_draw_options_free(draw_options);
    sherd_refinement_free(NULL);
    sherd_drawing_free(NULL);
    sherd_measure_options_free(NULL);
    sherd_draw_options_free(NULL);
    sherd_refine_options_free(NULL);
    sherd_mesh_free(mesh);
}

static void test_messages_survive_success(void) {
    SherdMesh *mesh = NULL;
    CHECK_STATUS(sherd_mesh_from_arrays(NULL, 4, triangles, 4, &mesh), SHERD_STATUS_NULL_POINTER);
    CHECK_OK(sherd_mesh_from_arrays(positions, 4, triangles, 4, &mesh));
    CHECK_MESSAGE("sherd_mesh_from_arrays: `positions` is NULL");
    sherd_mesh_free(mesh);
}

int main(void) {
    test_null_pointers();
    test_invalid_mesh_arrays();
    test_invalid_attributes();
    test_short_buffers();
    test_axis_struct();
    test_pipeline_misuse();
    test_refine_measure_draw_misuse();
    test_messages_survive_success();
    printf("test_misuse: ok\n");
    return 0;
}
