/* Property test of the C ABI: rounds of calls with random arguments drawn from pools of
 * hostile values (NaN, infinities, 0, SIZE_MAX, out-of-range enum values, NULL handles
 * and out-pointers, `size` fields too small, too large or exact, meshes with NaN
 * coordinates, out-of-range indices or every point equal), run under valgrind or
 * AddressSanitizer by tests/c/run.sh. The properties, checked on every call:
 *
 *   - the status is a known SherdStatus, never SHERD_STATUS_PANIC (a caught Rust panic is
 *     still a bug), and a failing call leaves a non-empty message;
 *   - on failure the out-pointer is left as it was;
 *   - a sized result struct is written within its `size` bytes only: it lives in a heap
 *     block of exactly max(size, sizeof(size_t)) bytes (valgrind or ASan sees any write
 *     past it) followed by nothing;
 *   - an option value a setter accepts keeps the operation bounded: every operation of a
 *     round runs with the options as set, so an accepted SIZE_MAX iteration count would
 *     hang the test (and its time limit in tests/c/run.sh fails it);
 *   - every handle is freed (the leak checker sees the rest).
 *
 * Deterministic: a fixed seed (SHERD_ABI_SEED overrides it) and SHERD_ABI_ROUNDS rounds
 * (default 120: about a minute of CPU under valgrind for each linkage). A failure prints
 * the seed, the round and the arguments. */
#include <stdint.h>

#include "check.h"

static uint64_t rng_state;

static uint64_t next_random(void) {
    /* xorshift64*: enough for choosing among pools, and the same on every platform. */
    rng_state ^= rng_state >> 12;
    rng_state ^= rng_state << 25;
    rng_state ^= rng_state >> 27;
    return rng_state * 2685821657736338717ULL;
}

static size_t below(size_t n) { return (size_t)(next_random() % n); }

static int chance(unsigned percent) { return below(100) < percent; }

static double random_double(void) {
    static const double pool[] = {0.0, -0.0, 1.0, -1.0, 0.5, 0.05, 0.95, 0.999, 2.0, 3.0, 10.0, 44.9, 45.0, 89.9,
                                  90.0, 360.0, 1e-300, 4.9e-324, -1e-9, 1e9, 1e300, -1e300, 72.0, 150.0};
    switch (below(8)) {
        case 0: return NAN;
        case 1: return chance(50) ? INFINITY : -INFINITY;
        case 2: return ((double)next_random() / 18446744073709551616.0) * 200.0 - 100.0;
        default: return pool[below(sizeof pool / sizeof pool[0])];
    }
}

static size_t random_count(void) {
    static const size_t pool[] = {0, 1, 2, 3, 5, 7, 20, 100, 1000, 100000, 1000000000, (size_t)1 << 40,
                                  SIZE_MAX / 2, SIZE_MAX - 1, SIZE_MAX};
    return chance(10) ? (size_t)next_random() : pool[below(sizeof pool / sizeof pool[0])];
}

static uint32_t random_enum(void) {
    static const uint32_t pool[] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 63, 64, 255, 0x7fffffff, 0x80000000, UINT32_MAX};
    return chance(10) ? (uint32_t)next_random() : pool[below(sizeof pool / sizeof pool[0])];
}

/* Checks the properties every call shares; returns the status. */
#define CALL(call) check_call((call), #call, __LINE__)

static unsigned long round_number;

/* The arguments of the call under way, where they are not all in the call's text. */
static char context[256];

static SherdStatus check_call(SherdStatus status, const char *call, int line) {
    /* SHERD_STATUS_SENSE_UNCERTAIN is the last status (numbered after the panic). */
    if ((uint32_t)status > SHERD_STATUS_SENSE_UNCERTAIN || status == SHERD_STATUS_PANIC ||
        strcmp(sherd_status_name((uint32_t)status), "SHERD_STATUS_UNKNOWN") == 0 ||
        (status != SHERD_STATUS_OK && strlen(sherd_last_error_message()) == 0)) {
        fprintf(stderr, "round %lu, line %d: %s returned %s (%u)\n  arguments: %s\n  last error: %s\n", round_number,
                line, call, sherd_status_name((uint32_t)status), (unsigned)status, context, sherd_last_error_message());
        exit(1);
    }
    return status;
}

/* A sized struct in a heap block of exactly max(size, sizeof(size_t)) bytes, its `size`
 * field random: usually the right one, sometimes 0, too small, or larger than the struct
 * (then the block is that large: the library may write only what it knows). */
static void *sized_block(size_t struct_size) {
    size_t size;
    void *block;
    switch (below(6)) {
        case 0: size = 0; break;
        case 1: size = sizeof(size_t); break;
        case 2: size = struct_size - 1 - below(struct_size / 2); break;
        case 3: size = struct_size + 1 + below(64); break;
        default: size = struct_size; break;
    }
    block = malloc(size > sizeof(size_t) ? size : sizeof(size_t));
    CHECK(block != NULL);
    memset(block, 0xA5, size > sizeof(size_t) ? size : sizeof(size_t));
    memcpy(block, &size, sizeof size);
    return block;
}

/* An axis argument: usually sane, sometimes hostile (NaN, zero direction, huge point). */
static SherdAxis random_axis(void) {
    SherdAxis axis;
    int k;
    memset(&axis, 0, sizeof axis);
    axis.size = chance(90) ? sizeof axis : below(sizeof axis);
    for (k = 0; k < 3; ++k) {
        axis.point[k] = chance(80) ? (double)below(20) - 10.0 : random_double();
        axis.direction[k] = chance(80) ? (double)below(3) - 1.0 : random_double();
    }
    if (chance(60)) {
        axis.direction[0] = axis.direction[1] = 0.0;
        axis.direction[2] = 1.0;
    }
    return axis;
}

/* The meshes a round works on: a small synthetic sherd (made once), or a mesh from
 * random arrays, which sherd_mesh_from_arrays may refuse (then NULL). */
static SherdMesh *sherd_mesh;
static SherdAxis sherd_truth;

static SherdMesh *random_mesh(void) {
    SherdMesh *mesh = NULL;
    SherdMesh *const sentinel = (SherdMesh *)&mesh;
    double positions[3 * 24];
    uint32_t triangles[3 * 32];
    size_t vertex_count = 1 + below(24), triangle_count = below(33), i;
    int kind = (int)below(4);
    SherdStatus status;
    if (kind == 0) {
        CHECK_OK(sherd_mesh_clone(sherd_mesh, &mesh));
        return mesh;
    }
    for (i = 0; i < 3 * vertex_count; ++i) {
        positions[i] = kind == 1 ? 7.0 : (chance(97) ? (double)below(2000) / 10.0 - 100.0 : random_double());
    }
    for (i = 0; i < 3 * triangle_count; ++i) {
        triangles[i] = chance(98) ? (uint32_t)below(vertex_count) : random_enum();
    }
    mesh = sentinel;
    status = CALL(sherd_mesh_from_arrays(positions, vertex_count, triangle_count ? triangles : NULL, triangle_count, &mesh));
    if (status != SHERD_STATUS_OK) {
        CHECK(mesh == sentinel);
        return NULL;
    }
    return mesh;
}

/* Option builders with random settings; the setters' statuses are checked, and whatever
 * they accepted stays set for the operations of the round. */
static SherdOrientOptions *random_orient_options(void) {
    SherdOrientOptions *options = NULL;
    if (chance(30)) return NULL;
    CHECK_OK(sherd_orient_options_new(&options));
    if (chance(50)) CALL(sherd_orient_options_set_target_vertex_count(options, random_count()));
    if (chance(50)) CALL(sherd_orient_options_set_smoothing_iterations(options, random_count()));
    if (chance(50)) CALL(sherd_orient_options_set_opposite_normal_confidence(options, random_double()));
    return options;
}

static SherdManualOptions *random_manual_options(void) {
    SherdManualOptions *options = NULL;
    if (chance(30)) return NULL;
    CHECK_OK(sherd_manual_options_new(&options));
    if (chance(50)) CALL(sherd_manual_options_set_keep_fraction(options, random_double()));
    if (chance(50)) CALL(sherd_manual_options_set_max_pick_distance_mm(options, random_double()));
    return options;
}

static SherdRefineOptions *random_refine_options(void) {
    SherdRefineOptions *options = NULL;
    if (chance(30)) return NULL;
    CHECK_OK(sherd_refine_options_new(&options));
    if (chance(50)) CALL(sherd_refine_options_set_criterion(options, random_enum()));
    if (chance(50)) CALL(sherd_refine_options_set_surface(options, random_enum()));
    if (chance(50)) {
        /* Valid counts above 100 are slow under valgrind: those stay out of the pool. */
        size_t sections = random_count();
        if (sections > 100 && sections <= 10000) sections = 100;
        CALL(sherd_refine_options_set_section_count(options, sections));
    }
    if (chance(50)) CALL(sherd_refine_options_set_search_bound_deg(options, random_double()));
    if (chance(30)) CALL(sherd_refine_options_set_pareto_choice(options, random_enum(), (size_t)below(4)));
    if (chance(30)) CALL(sherd_refine_options_set_pareto_section_limits(options, (size_t)below(20), random_double()));
    if (chance(30)) CALL(sherd_refine_options_set_tangent_tolerance_mm(options, random_double()));
    if (chance(30)) CALL(sherd_refine_options_set_edge(options, random_enum()));
    if (chance(30)) CALL(sherd_refine_options_set_profile_method(options, random_enum(), random_double()));
    if (chance(30)) CALL(sherd_refine_options_set_circle_fit(options, random_enum()));
    return options;
}

static SherdMeasureOptions *random_measure_options(const SherdRefineOptions *refine) {
    SherdMeasureOptions *options = NULL;
    CHECK_OK(sherd_measure_options_new(&options));
    /* Few resamples unless the setter refuses the count: each is a refinement. */
    CHECK_OK(sherd_measure_options_set_bootstrap_samples(options, below(3)));
    if (chance(30)) {
        /* A valid count above 2 costs that many refinements: only the invalid ones. */
        size_t samples = random_count();
        if (samples <= 10000) samples = below(3);
        CALL(sherd_measure_options_set_bootstrap_samples(options, samples));
    }
    if (chance(50)) CALL(sherd_measure_options_set_bootstrap_seed(options, next_random()));
    if (chance(50)) CALL(sherd_measure_options_set_confidence(options, random_double()));
    if (refine != NULL && chance(50)) CALL(sherd_measure_options_set_refine_options(options, refine));
    return options;
}

static SherdDrawOptions *random_draw_options(void) {
    SherdDrawOptions *options = NULL;
    static const char *titles[] = {NULL, "", "A011", "caf\xc3\xa9 \xe2\x80\x94 sherd", "not utf-8 \xff\xfe"};
    CHECK_OK(sherd_draw_options_new(&options));
    /* Linear style at a low resolution by default, so that a round stays quick under
     * valgrind; the random settings below may change both. */
    CHECK_OK(sherd_draw_options_set_style(options, SHERD_STYLE_LINEAR));
    CHECK_OK(sherd_draw_options_set_dpi(options, 20.0));
    if (chance(40)) CALL(sherd_draw_options_set_style(options, random_enum()));
    if (chance(40)) CALL(sherd_draw_options_set_scale_denominator(options, random_enum()));
    if (chance(40)) {
        double dpi = random_double();
        /* 10 to 4800 dpi are valid; above 150 a drawing is slow under valgrind. */
        if (!(dpi > 150.0 && dpi <= 4800.0)) CALL(sherd_draw_options_set_dpi(options, dpi));
    }
    if (chance(40)) CALL(sherd_draw_options_set_section_angle_rad(options, random_double()));
    if (chance(40)) CALL(sherd_draw_options_set_section_fill(options, random_enum()));
    if (chance(40)) CALL(sherd_draw_options_set_placement(options, random_enum()));
    if (chance(40)) CALL(sherd_draw_options_set_regularity(options, random_enum()));
    if (chance(40)) CALL(sherd_draw_options_set_views(options, chance(50), chance(50)));
    if (chance(40)) CALL(sherd_draw_options_set_interior_view(options, chance(50)));
    if (chance(40)) CALL(sherd_draw_options_set_prolongation(options, chance(50)));
    if (chance(40)) CALL(sherd_draw_options_set_annotations(options, chance(50) ? (uint32_t)below(8) : random_enum()));
    if (chance(40)) CALL(sherd_draw_options_set_title(options, titles[below(5)]));
    return options;
}

/* Each operation on `mesh` (never NULL here) with random arguments. */
static void copy_out(SherdMesh *mesh) {
    size_t capacity = below(40), count = 0;
    double *f64 = malloc(3 * capacity * sizeof(double) + 1);
    float *f32 = malloc(3 * capacity * sizeof(float) + 1);
    uint32_t *u32 = malloc(3 * capacity * sizeof(uint32_t) + 1);
    uint8_t *u8 = malloc(4 * capacity + 1);
    uint32_t attributes = 0;
    CHECK(f64 && f32 && u32 && u8);
    CALL(sherd_mesh_vertex_count(mesh, &count));
    CALL(sherd_mesh_attributes(mesh, &attributes));
    CALL(sherd_mesh_copy_positions(mesh, f64, capacity));
    CALL(sherd_mesh_copy_positions_f32(mesh, f32, capacity));
    CALL(sherd_mesh_copy_triangles(mesh, u32, capacity));
    CALL(sherd_mesh_copy_normals(mesh, f64, capacity));
    CALL(sherd_mesh_copy_colors(mesh, u8, capacity));
    CALL(sherd_mesh_copy_quality(mesh, f32, capacity));
    /* corner UVs: 2 floats per corner, `capacity` corners fit in f32. */
    CALL(sherd_mesh_copy_corner_uvs(mesh, f32, capacity));
    /* Counts within what the buffers hold: the host's side of the contract. */
    count = chance(50) ? count : below(30);
    if (count > capacity) count = capacity;
    CALL(sherd_mesh_set_normals(mesh, f64, count));
    CALL(sherd_mesh_set_colors(mesh, u8, count));
    free(f64);
    free(f32);
    free(u32);
    free(u8);
}

static void repair_and_decimate(SherdMesh *mesh) {
    SherdRepairOptions *options = NULL;
    SherdBuffer *report = NULL;
    SherdMesh *decimated = NULL;
    if (chance(70)) {
        CHECK_OK(sherd_repair_options_new(&options));
        if (chance(50)) CALL(sherd_repair_options_set_merge_tolerance_mm(options, random_double()));
        if (chance(50)) CALL(sherd_repair_options_set_keep_largest_component(options, chance(50)));
    }
    if (CALL(sherd_mesh_repair(mesh, options, chance(50) ? &report : NULL)) == SHERD_STATUS_OK && report) {
        const uint8_t *data = NULL;
        size_t size = 0;
        CHECK_OK(sherd_buffer_contents(report, &data, &size));
        CHECK(data != NULL && data[size] == 0);
    }
    sherd_buffer_free(report);
    sherd_repair_options_free(options);
    if (CALL(sherd_mesh_decimate(mesh, random_count() % 5000, &decimated)) == SHERD_STATUS_OK) {
        sherd_mesh_free(decimated);
    }
}

/* Orients (automatic or from three points), then refines, measures and draws along the
 * axis found or a random one. */
static void orient_refine_measure_draw(SherdMesh *mesh) {
    SherdAxis *axis = sized_block(sizeof(SherdAxis));
    SherdOrientReport *report = chance(50) ? sized_block(sizeof(SherdOrientReport)) : NULL;
    SherdBuffer *json = NULL;
    SherdAxis used = chance(50) ? sherd_truth : random_axis();
    SherdStatus status;
    if (chance(60)) {
        SherdOrientOptions *options = random_orient_options();
        status = CALL(sherd_orient_automatic(mesh, options, axis, report, chance(50) ? &json : NULL));
        sherd_orient_options_free(options);
    } else {
        SherdManualOptions *options = random_manual_options();
        double points[9];
        size_t i, count = 0;
        double *positions;
        CHECK_OK(sherd_mesh_vertex_count(mesh, &count));
        positions = malloc(3 * count * sizeof(double));
        CHECK(positions != NULL);
        CHECK_OK(sherd_mesh_copy_positions(mesh, positions, count));
        for (i = 0; i < 9; ++i) points[i] = chance(95) ? positions[3 * below(count) + i % 3] : random_double();
        free(positions);
        status = CALL(sherd_orient_from_three_points(mesh, points, options, axis, report, chance(50) ? &json : NULL));
        sherd_manual_options_free(options);
    }
    if ((status == SHERD_STATUS_OK || status == SHERD_STATUS_NEEDS_MANUAL_ORIENTATION || status == SHERD_STATUS_SENSE_UNCERTAIN) &&
        axis->size >= sizeof(SherdAxis)) {
        used = *axis;
    }
    sherd_buffer_free(json);
    free(axis);
    free(report);

    {
        SherdRefineOptions *options = random_refine_options();
        SherdRefinement *refinement = NULL;
        if (chance(50) && CALL(sherd_refine(mesh, &used, options, &refinement)) == SHERD_STATUS_OK) {
            SherdAxis *refined = sized_block(sizeof(SherdAxis));
            SherdRefineReport *refine_report = sized_block(sizeof(SherdRefineReport));
            SherdParetoPoint points[4];
            size_t count = 0;
            if (CALL(sherd_refinement_axis(refinement, refined)) == SHERD_STATUS_OK) used = *refined;
            CALL(sherd_refinement_report(refinement, refine_report));
            CALL(sherd_refinement_pareto_front(refinement, chance(50) ? points : NULL, below(5), &count));
            free(refined);
            free(refine_report);
            sherd_refinement_free(refinement);
        }
        if (chance(40)) {
            SherdMeasureOptions *measure_options = random_measure_options(options);
            SherdMeasurements *measured = sized_block(sizeof(SherdMeasurements));
            json = NULL;
            CALL(sherd_measure(mesh, &used, measure_options, measured, chance(50) ? &json : NULL));
            sherd_buffer_free(json);
            free(measured);
            sherd_measure_options_free(measure_options);
        }
        sherd_refine_options_free(options);
    }

    if (chance(50)) {
        SherdDrawOptions *options = random_draw_options();
        SherdDrawing *drawing = NULL;
        if (CALL(sherd_drawing_build(mesh, &used, options, &drawing)) == SHERD_STATUS_OK) {
            SherdBuffer *bytes = NULL;
            uint32_t format = chance(70) ? (uint32_t)below(3) : random_enum(); /* PNG is slow under valgrind */
            if (format == SHERD_FORMAT_PNG) format = SHERD_FORMAT_SVG;
            if (CALL(sherd_drawing_to_buffer(drawing, format, &bytes)) == SHERD_STATUS_OK) {
                const uint8_t *data = NULL;
                size_t size = 0;
                CHECK_OK(sherd_buffer_contents(bytes, &data, &size));
                CHECK(size > 0);
            }
            sherd_buffer_free(bytes);
            sherd_drawing_free(drawing);
        }
        sherd_draw_options_free(options);
    }

    {
        double angle = 0.0, matrix[16], reference[3] = {random_double(), 0.0, 0.0};
        SherdBuffer *csv = NULL;
        CALL(sherd_profile_most_informative_angle(mesh, &used, &angle));
        if (CALL(sherd_profile_csv(mesh, &used, chance(50) ? angle : random_double(), &csv)) == SHERD_STATUS_OK) {
            const uint8_t *data = NULL;
            size_t size = 0;
            CHECK_OK(sherd_buffer_contents(csv, &data, &size));
        }
        sherd_buffer_free(csv);
        CALL(sherd_axis_oriented_transform(&used, reference, matrix));
        CALL(sherd_mesh_oriented_transform(mesh, &used, matrix));
        /* Every segment count, including SIZE_MAX, to a file that is never kept. */
        CALL(sherd_export_reconstruction_ply(mesh, &used, NAN, random_count(), "abi-properties-vessel.ply", chance(50)));
        remove("abi-properties-vessel.ply");
    }
}

/* NULL for each handle and out-pointer of a few calls, and calls with no mesh at all. */
static void null_arguments(void) {
    SherdMesh *mesh = NULL;
    SherdAxis axis = sherd_truth;
    SherdSynthKind kind = (SherdSynthKind)random_enum();
    uint64_t seed_value;
    CHECK(CALL(sherd_orient_automatic(NULL, NULL, &axis, NULL, NULL)) == SHERD_STATUS_NULL_POINTER);
    CHECK(CALL(sherd_orient_automatic(sherd_mesh, NULL, NULL, NULL, NULL)) == SHERD_STATUS_NULL_POINTER);
    CHECK(CALL(sherd_refine(sherd_mesh, NULL, NULL, NULL)) == SHERD_STATUS_NULL_POINTER);
    CHECK(CALL(sherd_drawing_build(sherd_mesh, &axis, NULL, NULL)) == SHERD_STATUS_NULL_POINTER);
    CHECK(CALL(sherd_mesh_read(NULL, &mesh)) == SHERD_STATUS_NULL_POINTER);
    CHECK(CALL(sherd_mesh_read("", &mesh)) != SHERD_STATUS_OK && mesh == NULL);
    CHECK(CALL(sherd_mesh_read("/dev/zero.ply", &mesh)) != SHERD_STATUS_OK && mesh == NULL);
    CHECK(sherd_status_name(random_enum()) != NULL);
    /* A synthetic sherd of a random kind and face count: huge counts must be refused. */
    if (chance(30)) {
        size_t faces = random_count();
        double noise = random_double();
        if (faces > 3000) faces = faces > 100000 ? faces : 3000; /* a valid large count is slow under valgrind */
        if (noise > 1.0) noise = -noise;
        seed_value = next_random();
        snprintf(context, sizeof context, "seed %llu, kind %u, faces %zu, noise %g", (unsigned long long)seed_value,
                 (unsigned)kind, faces, noise);
        if (CALL(sherd_synthetic_sherd(seed_value, kind, faces, noise, &mesh, NULL, NULL)) == SHERD_STATUS_OK) {
            sherd_mesh_free(mesh);
        }
    }
}

int main(void) {
    const char *seed = getenv("SHERD_ABI_SEED");
    const char *rounds_text = getenv("SHERD_ABI_ROUNDS");
    unsigned long rounds = rounds_text ? strtoul(rounds_text, NULL, 10) : 120;
    SherdBuffer *truth_json = NULL;
    rng_state = seed ? strtoull(seed, NULL, 10) | 1 : 20181126ULL;
    printf("seed %llu, %lu rounds\n", (unsigned long long)rng_state, rounds);

    sherd_truth.size = sizeof sherd_truth;
    CHECK_OK(sherd_synthetic_sherd(7, SHERD_SYNTH_KIND_RIM, 600, 0.02, &sherd_mesh, &sherd_truth, &truth_json));
    sherd_buffer_free(truth_json);

    for (round_number = 0; round_number < rounds; ++round_number) {
        SherdMesh *mesh = random_mesh();
        context[0] = 0;
        null_arguments();
        if (mesh != NULL) {
            switch (below(4)) {
                case 0: copy_out(mesh); break;
                case 1: repair_and_decimate(mesh); break;
                default: orient_refine_measure_draw(mesh); break;
            }
            sherd_mesh_free(mesh);
        }
    }
    sherd_mesh_free(sherd_mesh);
    printf("%lu rounds: every status known, no panic, no write past a struct's size\n", rounds);
    return 0;
}
