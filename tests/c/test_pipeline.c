/* The whole pipeline through the C ABI on a synthetic sherd with a known axis, once from
 * host arrays and once from a file: repair, decimate, orient (automatic and three points),
 * refine with each criterion (the Pareto front as an array), measure with intervals,
 * export (oriented PLY, reconstruction PLY, profile CSV), draw in each format (memory and file).
 * Asserts real properties: the axis within a few degrees of the truth, the formats'
 * signatures, the exported files readable again. */
#include <stddef.h>

#include "pipeline.h"

/* A seed where the orientation layer orients the rim piece (it refuses or misorients
 * some synthetic sherds: see the report). */
#define SEED 6u

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

/* Measurements with intervals and the three exports, on the refined axis. */
static void measure_and_export(const SherdMesh *mesh, const SherdAxis *axis, const char *origin) {
    SherdMeasureOptions *options = NULL;
    SherdMeasurements measurements;
    SherdBuffer *json = NULL;
    const uint8_t *data = NULL;
    size_t size = 0, vertices = 0;
    SherdMesh *back = NULL;

    memset(&measurements, 0, sizeof measurements);
    measurements.size = sizeof measurements;
    CHECK_OK(sherd_measure_options_new(&options));
    CHECK_OK(sherd_measure_options_set_bootstrap_samples(options, 6));
    CHECK_OK(sherd_measure_options_set_bootstrap_seed(options, 3));
    CHECK_OK(sherd_measure(mesh, axis, options, &measurements, &json));
    sherd_measure_options_free(options);
    printf("  %s: rim diameter %.2f mm [%.2f, %.2f], sector %.1f deg, height %.1f mm\n", origin,
           measurements.rim_diameter_mm, measurements.rim_diameter_interval_mm[0],
           measurements.rim_diameter_interval_mm[1], measurements.sector_angle_deg, measurements.height_mm);
    CHECK(measurements.rim_radius_mm > 10.0 && measurements.rim_radius_mm < 500.0);
    CHECK_NEAR(measurements.rim_diameter_mm, 2.0 * measurements.rim_radius_mm, 1e-9);
    /* Six bootstrap samples (five usable ones are the least for an interval; valgrind is
     * slow) give a rough interval: ordered, and near the value. */
    CHECK(measurements.rim_diameter_interval_mm[0] <= measurements.rim_diameter_interval_mm[1]);
    CHECK(fabs(measurements.rim_diameter_interval_mm[0] / measurements.rim_diameter_mm - 1.0) < 0.05);
    CHECK(fabs(measurements.rim_diameter_interval_mm[1] / measurements.rim_diameter_mm - 1.0) < 0.05);
    CHECK(measurements.sector_angle_deg > 0.0 && measurements.sector_angle_deg < 360.0);
    CHECK(measurements.axis_distance_interval_mm[0] == 0.0 && measurements.axis_distance_interval_mm[1] >= 0.0);
    CHECK(measurements.axis_uncertain ==
          (measurements.axis_angle_interval_deg[1] > 4.0 || measurements.axis_distance_interval_mm[1] > 5.0));
    CHECK_NEAR(measurements.sector_percent, measurements.sector_angle_deg / 3.6, 1e-9);
    CHECK(measurements.height_mm > 0.0);
    CHECK(isnan(measurements.capacity_litres)); /* a rim piece: no complete profile */
    CHECK_OK(sherd_buffer_contents(json, &data, &size));
    CHECK(strstr((const char *)data, "\"wall_thickness_profile\"") != NULL);
    sherd_buffer_free(json);

    CHECK_OK(sherd_export_oriented_ply(mesh, axis, "pipeline-oriented.ply", true));
    CHECK_OK(sherd_mesh_read("pipeline-oriented.ply", &back));
    CHECK_OK(sherd_mesh_vertex_count(back, &vertices));
    CHECK_OK(sherd_mesh_vertex_count(mesh, &size));
    CHECK(vertices == size);
    sherd_mesh_free(back);
    CHECK_OK(sherd_export_reconstruction_ply(mesh, axis, NAN, 0, "pipeline-reconstruction.ply", true));
    CHECK_OK(sherd_mesh_read("pipeline-reconstruction.ply", &back));
    CHECK_OK(sherd_mesh_vertex_count(back, &vertices));
    CHECK(vertices > 180);
    sherd_mesh_free(back);
    CHECK_OK(sherd_export_profile_csv(mesh, axis, NAN, "pipeline-profile.csv"));
    remove("pipeline-oriented.ply");
    remove("pipeline-reconstruction.ply");
    remove("pipeline-profile.csv");
}

/* The drawing, built once, written in each format to memory and to a file. */
static void draw(const SherdMesh *mesh, const SherdAxis *axis) {
    static const char *const signatures[4] = {"<svg", "%!PS-Adobe", "%PDF-", "\x89PNG\r\n\x1a\n"};
    SherdDrawOptions *options = NULL;
    SherdDrawing *drawing = NULL;
    uint32_t format;
    FILE *file;
    char head[8];

    CHECK_OK(sherd_draw_options_new(&options));
    CHECK_OK(sherd_draw_options_set_style(options, SHERD_STYLE_LINEAR | SHERD_STYLE_LIGHT));
    CHECK_OK(sherd_draw_options_set_dpi(options, 72.0));
    CHECK_OK(sherd_draw_options_set_section_fill(options, SHERD_SECTION_FILL_HATCHED));
    CHECK_OK(sherd_draw_options_set_title(options, "C99 test sherd"));
    CHECK_OK(sherd_draw_options_set_placement(options, SHERD_PLACEMENT_TRUE_DISTANCE));
    CHECK_OK(sherd_draw_options_set_interior_view(options, false));
    CHECK_OK(sherd_draw_options_set_prolongation(options, true));
    CHECK_OK(sherd_draw_options_set_annotations(options, SHERD_ANNOTATION_HEIGHT | SHERD_ANNOTATION_WALL_THICKNESS));
    CHECK_OK(sherd_drawing_build(mesh, axis, options, &drawing));
    sherd_draw_options_free(options);
    for (format = SHERD_FORMAT_SVG; format <= SHERD_FORMAT_PNG; ++format) {
        SherdBuffer *buffer = NULL;
        const uint8_t *data = NULL;
        size_t size = 0;
        const char *expected = signatures[format];
        CHECK_OK(sherd_drawing_to_buffer(drawing, format, &buffer));
        CHECK_OK(sherd_buffer_contents(buffer, &data, &size));
        CHECK(size > 100);
        if (format == SHERD_FORMAT_SVG) {
            CHECK(strstr((const char *)data, expected) != NULL && strstr((const char *)data, "C99 test sherd"));
            /* The annotations asked for, and only those: a rim sherd has no capacity. */
            CHECK(strstr((const char *)data, ">height ") != NULL && strstr((const char *)data, ">wall ") != NULL);
            CHECK(strstr((const char *)data, ">capacity ") == NULL);
        } else {
            CHECK(memcmp(data, expected, strlen(expected)) == 0);
        }
        sherd_buffer_free(buffer);
    }
    CHECK_STATUS(sherd_drawing_to_buffer(drawing, 4u, NULL), SHERD_STATUS_INVALID_ARGUMENT);
    CHECK_MESSAGE("SHERD_FORMAT_");
    CHECK_OK(sherd_drawing_write(drawing, "pipeline-drawing.pdf"));
    file = fopen("pipeline-drawing.pdf", "rb");
    CHECK(file != NULL && fread(head, 1, 5, file) == 5 && memcmp(head, "%PDF-", 5) == 0);
    fclose(file);
    remove("pipeline-drawing.pdf");
    CHECK_STATUS(sherd_drawing_write(drawing, "pipeline-drawing.tiff"), SHERD_STATUS_INVALID_ARGUMENT);
    sherd_drawing_free(drawing);
}

/* The Pareto criterion's choice of solution and the tangent plane's options reach the
 * library: the best centre dispersion and the best circle residual are the two ends of one
 * front (different axes), the mean of the single best is a third; the tangent plane on the
 * rim with a tighter epsilon still levels it. */
static SherdAxis refine_with(SherdMesh *mesh, const SherdAxis *start, uint32_t criterion, uint32_t choice,
                             size_t count, uint32_t edge, double tolerance_mm, SherdRefineReport *summary) {
    SherdRefineOptions *options = NULL;
    SherdRefinement *refinement = NULL;
    SherdAxis refined = new_axis();

    memset(summary, 0, sizeof *summary);
    summary->size = sizeof *summary;
    CHECK_OK(sherd_refine_options_new(&options));
    CHECK_OK(sherd_refine_options_set_criterion(options, criterion));
    CHECK_OK(sherd_refine_options_set_pareto_choice(options, choice, count));
    CHECK_OK(sherd_refine_options_set_pareto_section_limits(options, 10, 3.0));
    CHECK_OK(sherd_refine_options_set_edge(options, edge));
    CHECK_OK(sherd_refine_options_set_tangent_tolerance_mm(options, tolerance_mm));
    CHECK_OK(sherd_refine(mesh, start, options, &refinement));
    sherd_refine_options_free(options);
    CHECK_OK(sherd_refinement_axis(refinement, &refined));
    CHECK_OK(sherd_refinement_report(refinement, summary));
    sherd_refinement_free(refinement);
    return refined;
}

static void pareto_choice_and_tangent_options(SherdMesh *mesh, const SherdAxis *start, const SherdAxis *truth) {
    SherdRefineReport summary;
    SherdAxis centres = refine_with(mesh, start, SHERD_CRITERION_PARETO, SHERD_PARETO_CHOICE_CENTRES, 0,
                                    SHERD_EDGE_DETECT, 3.0, &summary);
    size_t front_size = summary.pareto_point_count;
    SherdAxis residuals = refine_with(mesh, start, SHERD_CRITERION_PARETO, SHERD_PARETO_CHOICE_RESIDUALS, 0,
                                      SHERD_EDGE_DETECT, 3.0, &summary);
    SherdAxis tangent;

    CHECK(front_size >= 2 && summary.pareto_point_count == front_size);
    CHECK(line_angle_deg(&centres, &residuals) > 1e-6);
    printf("  Pareto: the best centres and the best residuals %.3f deg apart on a front of %u points\n",
           line_angle_deg(&centres, &residuals), (unsigned)front_size);
    tangent = refine_with(mesh, start, SHERD_CRITERION_TANGENT, SHERD_PARETO_CHOICE_KNEE, 0, SHERD_EDGE_RIM, 1.0, &summary);
    CHECK(summary.criterion == SHERD_CRITERION_TANGENT);
    CHECK(line_angle_deg(&tangent, truth) < 3.0);
    printf("  tangent plane on the rim, epsilon 1 mm: %.3f deg from the truth\n", line_angle_deg(&tangent, truth));

    /* Each form of the profile criterion (Eq. 5, Eq. 6's polynomial and spline) gives its
     * own axis, and the geometric circle fit serves the Pareto criterion. */
    {
        const uint32_t methods[3] = {SHERD_PROFILE_METHOD_REFERENCE, SHERD_PROFILE_METHOD_POLYNOMIAL,
                                     SHERD_PROFILE_METHOD_SPLINE};
        const double parameters[3] = {12.0, 4.0, 1.5};
        SherdAxis results[3];
        size_t k;
        for (k = 0; k < 3; ++k) {
            SherdRefineOptions *options = NULL;
            SherdRefinement *refinement = NULL;
            results[k] = new_axis();
            CHECK_OK(sherd_refine_options_new(&options));
            CHECK_OK(sherd_refine_options_set_criterion(options, SHERD_CRITERION_PROFILE));
            CHECK_OK(sherd_refine_options_set_profile_method(options, methods[k], parameters[k]));
            CHECK_OK(sherd_refine(mesh, start, options, &refinement));
            CHECK_OK(sherd_refinement_axis(refinement, &results[k]));
            sherd_refinement_free(refinement);
            sherd_refine_options_free(options);
        }
        /* A degree-4 polynomial cannot follow this rim's rounded lip (9.5 deg off here):
         * why the spline is the default; Eq. 5 and the spline level it. */
        CHECK(line_angle_deg(&results[0], truth) < 3.0 && line_angle_deg(&results[2], truth) < 3.0);
        CHECK(line_angle_deg(&results[0], &results[1]) > 1e-9 && line_angle_deg(&results[1], &results[2]) > 1e-9);
        printf("  profile criterion: Eq. 5 %.3f, polynomial %.3f, spline %.3f deg from the truth\n",
               line_angle_deg(&results[0], truth), line_angle_deg(&results[1], truth), line_angle_deg(&results[2], truth));
    }
    {
        SherdRefineOptions *options = NULL;
        SherdRefinement *refinement = NULL;
        CHECK_OK(sherd_refine_options_new(&options));
        CHECK_OK(sherd_refine_options_set_criterion(options, SHERD_CRITERION_PARETO));
        CHECK_OK(sherd_refine_options_set_circle_fit(options, SHERD_CIRCLE_FIT_GEOMETRIC));
        CHECK_OK(sherd_refine(mesh, start, options, &refinement));
        CHECK_OK(sherd_refinement_report(refinement, &summary));
        CHECK(summary.pareto_point_count >= 2);
        sherd_refinement_free(refinement);
        sherd_refine_options_free(options);
    }
}

/* Orientation both ways, refinement (every criterion when `all_criteria`, AUTO
 * otherwise: valgrind makes each one slow), then measurements, exports and drawing. */
static void orient_and_refine(SherdMesh *mesh, const SherdAxis *truth, const char *origin, int all_criteria) {
    SherdAxis axis = new_axis(), manual = new_axis(), refined = new_axis();
    SherdOrientReport report;
    SherdOrientOptions *orient_options = NULL;
    SherdBuffer *json = NULL;
    const uint8_t *data = NULL;
    size_t size = 0;
    double picked[9];
    uint32_t criterion;

    memset(&report, 0, sizeof report);
    report.size = sizeof report;
    CHECK_OK(sherd_orient_options_new(&orient_options));
    CHECK_OK(sherd_orient_options_set_target_vertex_count(orient_options, 10000));
    CHECK_OK(sherd_orient_automatic(mesh, orient_options, &axis, &report, &json));
    sherd_orient_options_free(orient_options);
    CHECK(report.oriented);
    CHECK(report.kept_vertex_count > 100);
    CHECK(angle_deg(&axis, truth) < 3.0);
    CHECK_OK(sherd_buffer_contents(json, &data, &size));
    CHECK(size > 2 && data[0] == '{' && data[size - 1] == '}' && data[size] == '\0');
    CHECK(strstr((const char *)data, "\"method\"") != NULL);
    sherd_buffer_free(json);
    printf("  %s: automatic axis %.3f deg from the truth line, %.3f deg with its sense (uncertainty %.3f deg)\n",
           origin, line_angle_deg(&axis, truth), angle_deg(&axis, truth), report.angle_uncertainty_deg);

    pick_rim_points(mesh, truth, picked);
    CHECK_OK(sherd_orient_from_three_points(mesh, picked, NULL, &manual, NULL, NULL));
    CHECK(line_angle_deg(&manual, truth) < 5.0);
    printf("  %s: three-point axis %.3f deg from the truth\n", origin, line_angle_deg(&manual, truth));

    for (criterion = all_criteria ? SHERD_CRITERION_CIRCLES : SHERD_CRITERION_AUTO; criterion <= SHERD_CRITERION_AUTO;
         ++criterion) {
        SherdRefineOptions *options = NULL;
        SherdRefinement *refinement = NULL;
        SherdRefineReport summary;
        size_t count = 0;

        memset(&summary, 0, sizeof summary);
        summary.size = sizeof summary;
        CHECK_OK(sherd_refine_options_new(&options));
        CHECK_OK(sherd_refine_options_set_criterion(options, criterion));
        CHECK_OK(sherd_refine_options_set_surface(options, SHERD_SURFACE_BOTH));
        CHECK_OK(sherd_refine(mesh, &axis, options, &refinement));
        sherd_refine_options_free(options);
        CHECK_OK(sherd_refinement_axis(refinement, &refined));
        CHECK_OK(sherd_refinement_report(refinement, &summary));
        CHECK(summary.residual_mm >= 0.0 && summary.section_count > 0);
        CHECK(summary.flagged == 0 || summary.flagged == 1);
        {
            /* A caller built against the first header (its struct ends before `flagged`)
             * is answered, and nothing is written past its struct. */
            SherdRefineReport old;
            memset(&old, 0xA5, sizeof old);
            old.size = offsetof(SherdRefineReport, flagged);
            CHECK_OK(sherd_refinement_report(refinement, &old));
            CHECK(old.residual_mm == summary.residual_mm && old.flagged == 0xA5A5A5A5u);
        }
        CHECK(criterion == SHERD_CRITERION_AUTO || summary.criterion == criterion);
        /* Asking with no room gives the count (and BUFFER_TOO_SMALL when there are points). */
        CHECK_STATUS(sherd_refinement_pareto_front(refinement, NULL, 0, &count),
                     summary.pareto_point_count ? SHERD_STATUS_BUFFER_TOO_SMALL : SHERD_STATUS_OK);
        CHECK(count == summary.pareto_point_count);
        if (criterion == SHERD_CRITERION_PARETO) {
            SherdParetoPoint *front = (SherdParetoPoint *)malloc(count * sizeof *front);
            size_t i;
            CHECK(count >= 2);
            CHECK_STATUS(sherd_refinement_pareto_front(refinement, front, count - 1, &count),
                         SHERD_STATUS_BUFFER_TOO_SMALL);
            CHECK_OK(sherd_refinement_pareto_front(refinement, front, count, &count));
            /* Non-dominated: along the front one cost falls as the other rises. */
            for (i = 0; i < count; ++i) {
                size_t j;
                for (j = 0; j < count; ++j) {
                    CHECK(!(front[j].centre_dispersion_mm2 < front[i].centre_dispersion_mm2 &&
                            front[j].circle_residual_mm2 < front[i].circle_residual_mm2));
                }
            }
            free(front);
            {
                /* The front drawn, for a host to save or show. */
                SherdBuffer *svg = NULL;
                const uint8_t *text = NULL;
                size_t length = 0;
                CHECK_OK(sherd_refinement_pareto_plot_svg(refinement, &svg));
                CHECK_OK(sherd_buffer_contents(svg, &text, &length));
                CHECK(length > 100 && memcmp(text, "<svg", 4) == 0 && text[length] == '\0');
                CHECK(strstr((const char *)text, "circle residual, Eq. 4") != NULL);
                sherd_buffer_free(svg);
            }
        } else {
            SherdBuffer *svg = NULL;
            CHECK(count == 0);
            CHECK_STATUS(sherd_refinement_pareto_plot_svg(refinement, &svg), SHERD_STATUS_INVALID_ARGUMENT);
            CHECK(svg == NULL);
            CHECK_MESSAGE("no Pareto front");
        }
        printf("  %s: refine criterion %u -> %u, %.3f deg from the truth, residual %.4f mm\n", origin,
               (unsigned)criterion, (unsigned)summary.criterion, line_angle_deg(&refined, truth),
               summary.residual_mm);
        /* A sanity bound: the criteria's accuracy is the refinement layer's to measure
         * (on this sherd the profile criterion moves the axis 3.7 degrees: see the report). */
        CHECK(line_angle_deg(&refined, truth) < 5.0);
        sherd_refinement_free(refinement);
    }

    if (all_criteria) pareto_choice_and_tangent_options(mesh, &axis, truth);
    measure_and_export(mesh, &refined, origin);
    draw(mesh, &refined);
}

static void test_from_arrays_and_file(void) {
    SherdMesh *synthetic = NULL, *mesh = NULL, *repaired = NULL, *decimated = NULL, *from_file = NULL;
    SherdAxis truth = new_axis();
    SherdRepairOptions *repair_options = NULL;
    SherdBuffer *report = NULL;
    const uint8_t *data = NULL;
    size_t size = 0, faces = 0, vertices_before = 0, vertices_after = 0;
    char path[] = "pipeline_sherd.ply";

    CHECK_OK(sherd_synthetic_sherd(SEED, SHERD_SYNTH_KIND_RIM, 6000, 0.02, &synthetic, &truth, NULL));

    /* From host arrays. Repair runs on a copy: this synthetic mesh is clean, and
     * the repaired copy only has to keep it whole. */
    mesh = mesh_from_host_arrays(synthetic);
    CHECK_OK(sherd_mesh_clone(mesh, &repaired));
    CHECK_OK(sherd_repair_options_new(&repair_options));
    CHECK_OK(sherd_repair_options_set_keep_largest_component(repair_options, true));
    CHECK_OK(sherd_mesh_vertex_count(mesh, &vertices_before));
    CHECK_OK(sherd_mesh_repair(repaired, repair_options, &report));
    sherd_repair_options_free(repair_options);
    CHECK_OK(sherd_mesh_vertex_count(repaired, &vertices_after));
    CHECK(vertices_after <= vertices_before && vertices_after > vertices_before / 2);
    CHECK_OK(sherd_buffer_contents(report, &data, &size));
    CHECK(strstr((const char *)data, "\"faces_after\"") != NULL);
    sherd_buffer_free(report);
    sherd_mesh_free(repaired);

    CHECK_OK(sherd_mesh_decimate(mesh, 2000, &decimated));
    CHECK_OK(sherd_mesh_face_count(decimated, &faces));
    CHECK(faces <= 2300 && faces >= 1700);
    orient_and_refine(mesh, &truth, "arrays", 1);

    /* From a file. */
    CHECK_OK(sherd_mesh_write_ply(synthetic, path, true));
    CHECK_OK(sherd_mesh_read(path, &from_file));
    CHECK_OK(sherd_mesh_vertex_count(from_file, &vertices_after));
    CHECK_OK(sherd_mesh_vertex_count(synthetic, &vertices_before));
    CHECK(vertices_after == vertices_before);
    orient_and_refine(from_file, &truth, "file", 0);
    remove(path);

    sherd_mesh_free(from_file);
    sherd_mesh_free(decimated);
    sherd_mesh_free(mesh);
    sherd_mesh_free(synthetic);
}

/* Flat base pieces do not determine their axis's position: the first of a few seeds the
 * orientation layer refuses must come back with the status, its reason and a written
 * (untrusted) axis. (That layer refuses some flat pieces and not others: see the report.) */
static void test_needs_manual_orientation(void) {
    uint64_t seed;
    for (seed = 1; seed <= 8; ++seed) {
        SherdMesh *flat = NULL;
        SherdAxis truth = new_axis(), axis = new_axis();
        SherdOrientReport report;
        SherdStatus status;

        memset(&report, 0, sizeof report);
        report.size = sizeof report;
        CHECK_OK(sherd_synthetic_sherd(seed, SHERD_SYNTH_KIND_FLAT_BASE, 6000, 0.02, &flat, &truth, NULL));
        status = sherd_orient_automatic(flat, NULL, &axis, &report, NULL);
        sherd_mesh_free(flat);
        CHECK(status == SHERD_STATUS_OK || status == SHERD_STATUS_NEEDS_MANUAL_ORIENTATION);
        CHECK(report.oriented == (status == SHERD_STATUS_OK));
        CHECK(axis.direction[0] != 0.0 || axis.direction[1] != 0.0 || axis.direction[2] != 0.0);
        if (status == SHERD_STATUS_NEEDS_MANUAL_ORIENTATION) {
            CHECK_MESSAGE("sherd_orient_automatic: ");
            printf("  flat base (seed %u): %s\n", (unsigned)seed, sherd_last_error_message());
            return;
        }
    }
    CHECK(!"no flat base piece was refused");
}

int main(void) {
    test_from_arrays_and_file();
    test_needs_manual_orientation();
    printf("test_pipeline: ok\n");
    return 0;
}
