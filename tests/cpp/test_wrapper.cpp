// The C++17 wrapper: RAII ownership, deep copies, exceptions carrying the status and
// the library's message. Built and run under ASan, LSan and UBSan (or valgrind) by tests/c/run.sh.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "sherd.hpp"

#define CHECK(condition)                                                                     \
    do {                                                                                     \
        if (!(condition)) {                                                                  \
            std::fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #condition); \
            std::exit(1);                                                                    \
        }                                                                                    \
    } while (0)

namespace {

const std::vector<double> positions = {0, 0, 0, 10, 0, 0, 0, 10, 0, 0, 0, 10};
const std::vector<std::uint32_t> triangles = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};

// Runs `body`, which must throw sherd::Error with `status` and a message containing `fragment`.
template <typename Body>
void expect_error(Body body, SherdStatus status, const std::string& fragment) {
    try {
        body();
    } catch (const sherd::Error& error) {
        CHECK(error.status() == status);
        CHECK(std::string(error.what()).find(fragment) != std::string::npos);
        CHECK(std::string(error.what()).find(sherd_status_name(status)) == 0);
        return;
    }
    std::fprintf(stderr, "expected an error containing \"%s\"\n", fragment.c_str());
    std::exit(1);
}

void test_round_trip_and_ownership() {
    sherd::check_abi();
    sherd::Mesh mesh = sherd::Mesh::from_arrays(positions, triangles);
    CHECK(mesh.vertex_count() == 4 && mesh.face_count() == 4);
    CHECK(mesh.positions() == positions);
    CHECK(mesh.triangles() == triangles);
    CHECK(!mesh.normals() && !mesh.colors() && !mesh.corner_uvs() && !mesh.quality());

    mesh.set_normals(std::vector<float>{0, 0, 2, 0, 0, 2, 0, 0, 2, 0, 0, 2});
    mesh.set_colors(std::vector<std::uint8_t>(16, 200));
    mesh.set_corner_uvs(std::vector<float>(24, 0.5f));

    sherd::Mesh copy = mesh;  // deep copy
    sherd::Mesh moved = std::move(mesh);
    CHECK(mesh.get() == nullptr);
    CHECK(copy.get() != moved.get());
    CHECK((*copy.normals())[2] == 1.0);
    CHECK(*copy.colors() == std::vector<std::uint8_t>(16, 200));
    CHECK(copy.corner_uvs()->size() == 24);

    moved = sherd::Mesh::from_arrays(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, 2});
    CHECK(moved.face_count() == 1);
}

void test_transform() {
    SherdAxis axis = sherd::make_axis({1, 2, 3}, {0, 0, 5});
    std::array<double, 16> matrix = sherd::oriented_transform(axis, {4, 2, 0});
    // Axis along z through (1, 2): a translation by (-1, -2, -3) with the reference on +x.
    const std::array<double, 16> expected = {1, 0, 0, -1, 0, 1, 0, -2, 0, 0, 1, -3, 0, 0, 0, 1};
    for (std::size_t k = 0; k < 16; ++k) CHECK(std::fabs(matrix[k] - expected[k]) < 1e-12);

    sherd::Mesh mesh = sherd::Mesh::from_arrays(positions, triangles);
    std::array<double, 16> placed = mesh.oriented_transform(axis);
    CHECK(placed == sherd::oriented_transform(axis, {2.5, 2.5, 2.5}));
}

void test_errors() {
    expect_error([] { sherd::Mesh::from_arrays(std::vector<double>{0, 0, 0, 1}, triangles); },
                 SHERD_STATUS_INVALID_ARGUMENT, "not a multiple of 3");
    expect_error([] { sherd::Mesh::from_arrays(positions, {0, 1, 7}); }, SHERD_STATUS_INVALID_ARGUMENT,
                 "face 0 refers to vertex 7");
    expect_error([] { sherd::Mesh::from_arrays(static_cast<const double*>(nullptr), 4, triangles.data(), 4); },
                 SHERD_STATUS_NULL_POINTER, "`positions` is NULL");
    sherd::Mesh mesh = sherd::Mesh::from_arrays(positions, triangles);
    expect_error([&] { mesh.set_normals(std::vector<double>{0, 0, 1}); }, SHERD_STATUS_INVALID_ARGUMENT,
                 "the mesh has 4 vertices");
    SherdAxis axis = sherd::make_axis({0, 0, 0}, {0, 0, 0});
    expect_error([&] { mesh.oriented_transform(axis); }, SHERD_STATUS_INVALID_ARGUMENT, "non-zero direction");
    axis = sherd::make_axis({0, 0, 0}, {0, 0, 1});
    axis.size = 4;
    expect_error([&] { mesh.oriented_transform(axis); }, SHERD_STATUS_INVALID_ARGUMENT, "axis->size");
}

void test_files() {
    sherd::Mesh mesh = sherd::Mesh::from_arrays(positions, triangles);
    mesh.write_ply("wrapper.ply", false);
    sherd::Mesh back = sherd::Mesh::read("wrapper.ply");
    CHECK(back.triangles() == triangles);
    CHECK(back.positions() == positions);  // small integers survive the float format exactly

    // The tetrahedron about the axis x = y = 1: the cut at angle 0 gives a profile.
    SherdAxis axis = sherd::make_axis({1, 1, 0}, {0, 0, 1});
    sherd::export_oriented_ply(mesh, axis, "wrapper-oriented.ply");
    CHECK(sherd::Mesh::read("wrapper-oriented.ply").vertex_count() == 4);
    const std::string csv = sherd::profile_csv(mesh, axis);
    CHECK(csv.rfind("curve,index,r_mm,z_mm,closed\n", 0) == 0);
    CHECK(csv.size() > 40);
    std::remove("wrapper.ply");
    std::remove("wrapper-oriented.ply");
    expect_error([] { sherd::Mesh::read("no/such/scan.ply"); }, SHERD_STATUS_IO, "no/such/scan.ply");
}

}  // namespace

// The wrapper's vocabulary listing is the C ABI's, and a menu indexed by value (as
// MeshLab's enum parameters are) holds each name at its constant.
void test_vocabulary() {
    std::vector<sherd::VocabularyEntry> criteria = sherd::vocabulary(SHERD_VOCABULARY_CRITERION);
    CHECK(criteria.size() == 5);
    CHECK(criteria.front().name == "auto" && criteria.front().value == SHERD_CRITERION_AUTO);
    std::vector<std::string> by_value = sherd::names_by_value(SHERD_VOCABULARY_CRITERION);
    CHECK(by_value.size() == criteria.size());
    CHECK(by_value[SHERD_CRITERION_CIRCLES] == "circles" && by_value[SHERD_CRITERION_AUTO] == "auto");
    for (const sherd::VocabularyEntry& entry : criteria) CHECK(by_value.at(entry.value) == entry.name);
    // Styles are bits: no menu indexed by value can hold them.
    expect_error([] { sherd::names_by_value(SHERD_VOCABULARY_STYLE); }, SHERD_STATUS_INVALID_ARGUMENT, "without a gap");
    expect_error([] { sherd::vocabulary(99); }, SHERD_STATUS_INVALID_ARGUMENT, "SHERD_VOCABULARY_*");
}

int main() {
    test_round_trip_and_ownership();
    test_vocabulary();
    test_transform();
    test_errors();
    test_files();
    std::printf("test_wrapper: ok (sherd %s)\n", sherd::version().c_str());
    return 0;
}
