// The whole pipeline through sherd.hpp on a synthetic sherd, from its arrays and from a
// file: repair, decimate, orient (automatic, three points), refine with each criterion,
// measure, draw in each format, export. Built and run under valgrind by tests/c/run.sh.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "sherd.hpp"

#define CHECK(condition)                                                                       \
    do {                                                                                       \
        if (!(condition)) {                                                                    \
            std::fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #condition); \
            std::exit(1);                                                                      \
        }                                                                                      \
    } while (0)

namespace {

double line_angle_deg(const SherdAxis& a, const SherdAxis& b) {
    double dot = 0, na = 0, nb = 0;
    for (int k = 0; k < 3; ++k) {
        dot += a.direction[k] * b.direction[k];
        na += a.direction[k] * a.direction[k];
        nb += b.direction[k] * b.direction[k];
    }
    return std::acos(std::fmin(1.0, std::fabs(dot) / std::sqrt(na * nb))) * 180.0 / M_PI;
}

void pipeline(const sherd::Mesh& mesh, const SherdAxis& truth, bool all_criteria) {
    sherd::Orientation orientation = sherd::orient_automatic(mesh);
    CHECK(orientation.oriented && orientation.reason.empty());
    CHECK(line_angle_deg(orientation.axis, truth) < 3.0);
    CHECK(orientation.report_json.find("\"method\"") != std::string::npos);

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
    pipeline(from_arrays, sherd_.true_axis, true);

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
