// The whole pipeline through sherd.hpp on a synthetic sherd, from its arrays and from a
// file: repair, decimate, orient (automatic, three points), refine with each criterion,
// measure, draw in each format, export, reconstruct, map the regularity, and the
// pipeline in one call. Built and run under ASan, LSan and UBSan (or valgrind) by tests/c/run.sh.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "pipeline.h"  // CHECK, the axis angles and the rim picking the C tests use
#include "sherd.hpp"

namespace {

double line_angle_deg(const SherdAxis& a, const SherdAxis& b) { return ::line_angle_deg(&a, &b); }

void orient(const sherd::Mesh& mesh, const SherdAxis& truth) {
    sherd::Orientation orientation = sherd::orient_automatic(mesh);
    CHECK(orientation.oriented && orientation.reason.empty());
    CHECK(line_angle_deg(orientation.axis, truth) < 3.0);
    CHECK(orientation.report_json.find("\"method\"") != std::string::npos);

    std::array<double, 9> picked{};
    pick_rim_points(mesh.get(), &truth, picked.data());
    sherd::Orientation manual = sherd::orient_from_three_points(mesh, picked);
    CHECK(manual.oriented && line_angle_deg(manual.axis, truth) < 5.0);
    std::printf("  three points: %.3f deg from the truth\n", line_angle_deg(manual.axis, truth));
    picked[0] += 1000.0;  // a point off the mesh
    try {
        sherd::orient_from_three_points(mesh, picked);
        CHECK(!"a point off the mesh was accepted");
    } catch (const sherd::Error& error) {
        CHECK(error.status() == SHERD_STATUS_INVALID_ARGUMENT);
    }
}

// The axis distances are the radii of the vertices in the oriented frame; the
// reconstruction is a surface of revolution about z as wide as the sherd.
void reconstruct_and_map(const sherd::Mesh& mesh, const SherdAxis& axis) {
    sherd::Regularity radii = sherd::regularity(mesh, axis, SHERD_REGULARITY_AXIS_DISTANCE);
    std::array<double, 16> m = mesh.oriented_transform(axis);
    std::vector<double> p = mesh.positions();
    CHECK(radii.values.size() == mesh.vertex_count() && radii.rgba.size() == 4 * mesh.vertex_count());
    for (std::size_t i = 0; i < radii.values.size(); ++i) {
        const double* q = &p[3 * i];
        double x = m[0] * q[0] + m[1] * q[1] + m[2] * q[2] + m[3], y = m[4] * q[0] + m[5] * q[1] + m[6] * q[2] + m[7];
        CHECK(std::fabs(radii.values[i] - std::hypot(x, y)) < 1e-3);
    }
    sherd::Mesh vessel = sherd::reconstruct(mesh, axis, NAN, 36);
    std::vector<double> points = vessel.positions();
    double largest = 0.0;
    for (std::size_t i = 0; i < points.size(); i += 3) largest = std::max(largest, std::hypot(points[i], points[i + 1]));
    const double sherd_radius = *std::max_element(radii.values.begin(), radii.values.end());
    CHECK(vessel.vertex_count() % 36 == 0 && std::fabs(largest / sherd_radius - 1.0) < 0.01);
    sherd::Regularity ideal = sherd::regularity(mesh, axis);
    CHECK(ideal.value_range[0] == -ideal.value_range[1]);
    try {
        sherd::regularity(mesh, axis, 7);
        CHECK(!"an unknown map was accepted");
    } catch (const sherd::Error& error) {
        CHECK(error.status() == SHERD_STATUS_INVALID_ARGUMENT);
    }
}

void pipeline(const sherd::Mesh& mesh, const SherdAxis& truth, bool all_criteria) {
    sherd::Orientation orientation = sherd::orient_automatic(mesh);

    // Every explicit criterion when asked (valgrind makes each slow), then AUTO, kept.
    for (std::uint32_t criterion = SHERD_CRITERION_CIRCLES; all_criteria && criterion < SHERD_CRITERION_AUTO;
         ++criterion) {
        sherd::Refinement other = sherd::refine(mesh, orientation.axis, criterion);
        CHECK(line_angle_deg(other.axis, truth) < 5.0);
        CHECK((criterion == SHERD_CRITERION_PARETO) == !other.pareto_front.empty());
        std::printf("  refine %u: %.3f deg from the truth\n", static_cast<unsigned>(criterion),
                    line_angle_deg(other.axis, truth));
    }
    sherd::Refinement refined = sherd::refine(mesh, orientation.axis);
    CHECK(line_angle_deg(refined.axis, truth) < 3.0 && refined.pareto_front.empty());

    std::string json;
    SherdMeasurements measured = sherd::measure(mesh, refined.axis, 6, &json);
    CHECK(measured.rim_diameter_mm > 20.0 && std::isfinite(measured.rim_diameter_interval_mm[0]));
    CHECK(json.find("\"notes\"") != std::string::npos);

    sherd::Drawing drawing(mesh, refined.axis, SHERD_STYLE_LINEAR | SHERD_STYLE_LIGHT, 72.0, "C++ test sherd");
    CHECK(drawing.to_bytes(SHERD_FORMAT_SVG).find("<svg") != std::string::npos);
    CHECK(drawing.to_bytes(SHERD_FORMAT_EPS).rfind("%!PS-Adobe", 0) == 0);
    CHECK(drawing.to_bytes(SHERD_FORMAT_PDF).rfind("%PDF-", 0) == 0);
    CHECK(drawing.to_bytes(SHERD_FORMAT_PNG).rfind("\x89PNG", 0) == 0);
    drawing.write("cpp-pipeline.svg");
    std::remove("cpp-pipeline.svg");

    sherd::export_oriented_ply(mesh, refined.axis, "cpp-oriented.ply");
    CHECK(sherd::Mesh::read("cpp-oriented.ply").vertex_count() == mesh.vertex_count());
    sherd::export_reconstruction_ply(mesh, refined.axis, "cpp-reconstruction.ply");
    CHECK(sherd::Mesh::read("cpp-reconstruction.ply").vertex_count() > 180);
    CHECK(sherd::profile_csv(mesh, refined.axis).rfind("curve,index,r_mm,z_mm,closed\n", 0) == 0);
    std::remove("cpp-oriented.ply");
    std::remove("cpp-reconstruction.ply");
    reconstruct_and_map(mesh, refined.axis);
}

// The pipeline in one call, from memory and from a file, agrees with itself; a missing
// file throws with the status and the file's name.
void pipeline_in_one_call(const sherd::Mesh& mesh, const SherdAxis& truth) {
    sherd::Analysis memory = sherd::analyse(mesh);
    CHECK(memory.status == SHERD_STATUS_OK && line_angle_deg(memory.axis, truth) < 3.0);
    CHECK(memory.record_json.find("\"file\":\"<memory>\"") != std::string::npos);
    mesh.write_ply("cpp-process.ply");
    sherd::RefineOptions circles(sherd_refine_options_new);
    sherd::check(sherd_refine_options_set_criterion(circles.get(), SHERD_CRITERION_CIRCLES));
    sherd::Analysis file = sherd::process_file("cpp-process.ply", &circles);
    std::remove("cpp-process.ply");
    CHECK(file.status == SHERD_STATUS_OK && line_angle_deg(file.axis, truth) < 3.0);
    CHECK(file.record_json.find("circles") != std::string::npos);
    try {
        sherd::process_file("cpp-no-such-scan.ply");
        CHECK(!"a missing file was accepted");
    } catch (const sherd::Error& error) {
        CHECK(error.status() == SHERD_STATUS_IO);
        CHECK(std::string(error.what()).find("cpp-no-such-scan.ply") != std::string::npos);
    }
}

}  // namespace

int main() {
    // Seed 6: a rim piece the orientation layer orients (see tests/c/test_pipeline.c).
    sherd::SyntheticSherd sherd_ = sherd::synthetic_sherd(6, SHERD_SYNTH_KIND_RIM, 6000);
    CHECK(sherd_.truth_json.find("rim_radius_mm") != std::string::npos);

    // From arrays, as a host passes its buffers.
    sherd::Mesh from_arrays = sherd::Mesh::from_arrays(sherd_.mesh.positions(), sherd_.mesh.triangles());
    from_arrays.set_normals(*sherd_.mesh.normals());
    sherd::Mesh repaired = from_arrays;
    CHECK(sherd::repair(repaired).find("\"faces_after\"") != std::string::npos);
    CHECK(sherd::decimate(from_arrays, 2000).face_count() < 2400);
    orient(from_arrays, sherd_.true_axis);
    pipeline(from_arrays, sherd_.true_axis, true);
    pipeline_in_one_call(from_arrays, sherd_.true_axis);

    // From a file.
    sherd_.mesh.write_ply("cpp-sherd.ply");
    pipeline(sherd::Mesh::read("cpp-sherd.ply"), sherd_.true_axis, false);
    std::remove("cpp-sherd.ply");

    // A flat base piece the layer refuses comes back as an answer with its reason.
    bool refused = false;
    for (std::uint64_t seed = 1; seed <= 8 && !refused; ++seed) {
        sherd::Orientation flat =
            sherd::orient_automatic(sherd::synthetic_sherd(seed, SHERD_SYNTH_KIND_FLAT_BASE, 6000).mesh);
        refused = !flat.oriented;
        if (refused) CHECK(flat.reason.find("sherd_orient_automatic: ") == 0);
    }
    CHECK(refused);
    std::printf("test_pipeline (C++): ok\n");
    return 0;
}
