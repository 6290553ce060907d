// sherd.hpp: a header-only C++17 wrapper over the sherd C ABI (sherd.h).
//
// Handles become RAII objects (copyable by deep copy, cheaply movable); every status
// other than SHERD_STATUS_OK becomes a sherd::Error carrying the status and the
// library's message. NEEDS_MANUAL_ORIENTATION and SENSE_UNCERTAIN are not exceptions where
// a result still comes back (orientation): the result says so.
//
//   sherd::Mesh mesh = sherd::Mesh::from_arrays(positions, triangles);
//   std::array<double, 16> m = mesh.oriented_transform(axis);
#ifndef SHERD_HPP
#define SHERD_HPP

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "sherd.h"

namespace sherd {

/// A failed call: the library's status code and its message.
class Error : public std::runtime_error {
public:
    Error(SherdStatus status, const std::string& message)
        : std::runtime_error(std::string(sherd_status_name(status)) + ": " + message), status_(status) {}

    /// The SHERD_STATUS_* code.
    SherdStatus status() const noexcept { return status_; }

private:
    SherdStatus status_;
};

/// Throws sherd::Error unless `status` is SHERD_STATUS_OK.
inline void check(SherdStatus status) {
    if (status != SHERD_STATUS_OK) throw Error(status, sherd_last_error_message());
}

/// The library's version string.
inline std::string version() { return sherd_version(); }

/// Throws when the library loaded at run time has another ABI than this header.
inline void check_abi() {
    if (sherd_abi_version() != SHERD_ABI_VERSION) {
        throw Error(SHERD_STATUS_INVALID_ARGUMENT,
                    "library ABI " + std::to_string(sherd_abi_version()) + " but header ABI " +
                        std::to_string(SHERD_ABI_VERSION));
    }
}

/// One named value of a vocabulary (a SHERD_VOCABULARY_* value): the library's name
/// ("circles"), the constant's value (SHERD_CRITERION_CIRCLES) and what it does.
struct VocabularyEntry {
    std::string name;
    std::uint32_t value;
    std::string description;
};

/// Every named value of `vocabulary`, in the order the library lists them to users, so
/// that a host offers the library's names rather than a copy of them.
inline std::vector<VocabularyEntry> vocabulary(std::uint32_t vocabulary) {
    std::size_t count = 0;
    check(sherd_vocabulary_count(vocabulary, &count));
    std::vector<VocabularyEntry> entries;
    for (std::size_t index = 0; index < count; ++index) {
        SherdVocabularyEntry entry{};
        entry.size = sizeof entry;
        check(sherd_vocabulary_entry(vocabulary, index, &entry));
        entries.push_back({entry.name, entry.value, entry.description});
    }
    return entries;
}

/// The names of `vocabulary` at the index of their values, for a menu whose index is the
/// value (the values of such a vocabulary run from 0 without a gap).
inline std::vector<std::string> names_by_value(std::uint32_t vocabulary) {
    std::vector<VocabularyEntry> entries = sherd::vocabulary(vocabulary);
    std::vector<std::string> names(entries.size());
    for (const VocabularyEntry& entry : entries) {
        if (entry.value >= names.size() || !names[entry.value].empty())
            throw Error(SHERD_STATUS_INVALID_ARGUMENT,
                        "vocabulary " + std::to_string(vocabulary) + " is not numbered from 0 without a gap");
        names[entry.value] = entry.name;
    }
    return names;
}

/// Takes the bytes of a library buffer and frees it.
inline std::string take_buffer(SherdBuffer* buffer) {
    struct Release {
        SherdBuffer* buffer;
        ~Release() { sherd_buffer_free(buffer); }
    } release{buffer};
    const std::uint8_t* data = nullptr;
    std::size_t size = 0;
    check(sherd_buffer_contents(buffer, &data, &size));
    return std::string(reinterpret_cast<const char*>(data), size);
}

/// A rotation axis (point, unit direction base to rim) with its `size` field set.
inline SherdAxis make_axis(const std::array<double, 3>& point, const std::array<double, 3>& direction) {
    SherdAxis axis{};
    axis.size = sizeof(SherdAxis);
    for (std::size_t k = 0; k < 3; ++k) {
        axis.point[k] = point[k];
        axis.direction[k] = direction[k];
    }
    return axis;
}

/// Row-major 4x4 transform from the scan's frame to the oriented frame, `reference`
/// landing on +x (sherd_axis_oriented_transform).
inline std::array<double, 16> oriented_transform(const SherdAxis& axis, const std::array<double, 3>& reference) {
    std::array<double, 16> matrix{};
    check(sherd_axis_oriented_transform(&axis, reference.data(), matrix.data()));
    return matrix;
}

/// An owned mesh (SherdMesh).
class Mesh {
public:
    /// Takes ownership of a handle from the C API.
    explicit Mesh(SherdMesh* handle) noexcept : handle_(handle) {}

    /// From pointers to `3 * vertex_count` positions and `3 * triangle_count` indices.
    static Mesh from_arrays(const double* positions, std::size_t vertex_count, const std::uint32_t* triangles,
                            std::size_t triangle_count) {
        SherdMesh* handle = nullptr;
        check(sherd_mesh_from_arrays(positions, vertex_count, triangles, triangle_count, &handle));
        return Mesh(handle);
    }

    /// Single-precision positions, as in Blender's and MeshLab's buffers.
    static Mesh from_arrays(const float* positions, std::size_t vertex_count, const std::uint32_t* triangles,
                            std::size_t triangle_count) {
        SherdMesh* handle = nullptr;
        check(sherd_mesh_from_arrays_f32(positions, vertex_count, triangles, triangle_count, &handle));
        return Mesh(handle);
    }

    /// From flat vectors `x0 y0 z0 x1 ...` and `a0 b0 c0 a1 ...`.
    static Mesh from_arrays(const std::vector<double>& positions, const std::vector<std::uint32_t>& triangles) {
        require_multiple(positions.size(), 3, "positions");
        require_multiple(triangles.size(), 3, "triangles");
        return from_arrays(positions.data(), positions.size() / 3, triangles.data(), triangles.size() / 3);
    }

    /// Single-precision variant of the vector constructor.
    static Mesh from_arrays(const std::vector<float>& positions, const std::vector<std::uint32_t>& triangles) {
        require_multiple(positions.size(), 3, "positions");
        require_multiple(triangles.size(), 3, "triangles");
        return from_arrays(positions.data(), positions.size() / 3, triangles.data(), triangles.size() / 3);
    }

    /// Reads a scan (PLY, OBJ, STL, XYZ, PTS by extension).
    static Mesh read(const std::string& path) {
        SherdMesh* handle = nullptr;
        check(sherd_mesh_read(path.c_str(), &handle));
        return Mesh(handle);
    }

    Mesh(const Mesh& other) : handle_(nullptr) {
        if (other.handle_) check(sherd_mesh_clone(other.handle_, &handle_));
    }
    Mesh(Mesh&& other) noexcept : handle_(std::exchange(other.handle_, nullptr)) {}
    Mesh& operator=(Mesh other) noexcept {
        std::swap(handle_, other.handle_);
        return *this;
    }
    ~Mesh() { sherd_mesh_free(handle_); }

    /// The C handle, still owned by this object.
    SherdMesh* get() noexcept { return handle_; }
    const SherdMesh* get() const noexcept { return handle_; }

    std::size_t vertex_count() const {
        std::size_t count = 0;
        check(sherd_mesh_vertex_count(handle_, &count));
        return count;
    }

    std::size_t face_count() const {
        std::size_t count = 0;
        check(sherd_mesh_face_count(handle_, &count));
        return count;
    }

    /// The SHERD_MESH_ATTRIBUTE_* bits present.
    std::uint32_t attributes() const {
        std::uint32_t bits = 0;
        check(sherd_mesh_attributes(handle_, &bits));
        return bits;
    }

    bool has(SherdMeshAttribute attribute) const { return (attributes() & attribute) != 0; }

    std::vector<double> positions() const {
        std::vector<double> out(3 * vertex_count());
        check(sherd_mesh_copy_positions(handle_, out.data(), out.size() / 3));
        return out;
    }

    std::vector<std::uint32_t> triangles() const {
        std::vector<std::uint32_t> out(3 * face_count());
        check(sherd_mesh_copy_triangles(handle_, out.data(), out.size() / 3));
        return out;
    }

    /// Unit normals (3 per vertex), or nothing when the mesh has none.
    std::optional<std::vector<double>> normals() const {
        if (!has(SHERD_MESH_ATTRIBUTE_NORMALS)) return std::nullopt;
        std::vector<double> out(3 * vertex_count());
        check(sherd_mesh_copy_normals(handle_, out.data(), out.size() / 3));
        return out;
    }

    /// RGBA colours (4 bytes per vertex), or nothing.
    std::optional<std::vector<std::uint8_t>> colors() const {
        if (!has(SHERD_MESH_ATTRIBUTE_COLORS)) return std::nullopt;
        std::vector<std::uint8_t> out(4 * vertex_count());
        check(sherd_mesh_copy_colors(handle_, out.data(), out.size() / 4));
        return out;
    }

    /// Texture coordinates (2 per corner, 3 corners per triangle), or nothing.
    std::optional<std::vector<float>> corner_uvs() const {
        if (!has(SHERD_MESH_ATTRIBUTE_CORNER_UVS)) return std::nullopt;
        std::vector<float> out(6 * face_count());
        check(sherd_mesh_copy_corner_uvs(handle_, out.data(), out.size() / 2));
        return out;
    }

    /// A scalar per vertex (occlusion, regularity), or nothing.
    std::optional<std::vector<float>> quality() const {
        if (!has(SHERD_MESH_ATTRIBUTE_QUALITY)) return std::nullopt;
        std::vector<float> out(vertex_count());
        check(sherd_mesh_copy_quality(handle_, out.data(), out.size()));
        return out;
    }

    void set_normals(const std::vector<double>& normals) {
        require_multiple(normals.size(), 3, "normals");
        check(sherd_mesh_set_normals(handle_, normals.data(), normals.size() / 3));
    }

    void set_normals(const std::vector<float>& normals) {
        require_multiple(normals.size(), 3, "normals");
        check(sherd_mesh_set_normals_f32(handle_, normals.data(), normals.size() / 3));
    }

    void set_colors(const std::vector<std::uint8_t>& rgba) {
        require_multiple(rgba.size(), 4, "rgba");
        check(sherd_mesh_set_colors(handle_, rgba.data(), rgba.size() / 4));
    }

    void set_corner_uvs(const std::vector<float>& uvs) {
        require_multiple(uvs.size(), 2, "uvs");
        check(sherd_mesh_set_corner_uvs(handle_, uvs.data(), uvs.size() / 2));
    }

    /// Row-major 4x4 transform placing this fragment in the oriented frame
    /// (sherd_mesh_oriented_transform).
    std::array<double, 16> oriented_transform(const SherdAxis& axis) const {
        std::array<double, 16> matrix{};
        check(sherd_mesh_oriented_transform(handle_, &axis, matrix.data()));
        return matrix;
    }

    /// Writes PLY atomically (binary little-endian or ASCII).
    void write_ply(const std::string& path, bool binary = true) const {
        check(sherd_mesh_write_ply(handle_, path.c_str(), binary));
    }

private:
    static void require_multiple(std::size_t size, std::size_t group, const char* name) {
        if (size % group != 0) {
            throw Error(SHERD_STATUS_INVALID_ARGUMENT, std::string(name) + " has " + std::to_string(size) +
                                                           " values, not a multiple of " + std::to_string(group));
        }
    }

    SherdMesh* handle_;
};

/// An option builder handle with its `_free` function, released on scope exit.
template <typename Handle, void (*Free)(Handle*)>
class Options {
public:
    explicit Options(SherdStatus (*create)(Handle**)) { check(create(&handle_)); }
    Options(const Options&) = delete;
    Options& operator=(const Options&) = delete;
    ~Options() { Free(handle_); }
    Handle* get() const noexcept { return handle_; }

private:
    Handle* handle_ = nullptr;
};

using RepairOptions = Options<SherdRepairOptions, sherd_repair_options_free>;
using OrientOptions = Options<SherdOrientOptions, sherd_orient_options_free>;
using ManualOptions = Options<SherdManualOptions, sherd_manual_options_free>;
using RefineOptions = Options<SherdRefineOptions, sherd_refine_options_free>;
using MeasureOptions = Options<SherdMeasureOptions, sherd_measure_options_free>;
using DrawOptions = Options<SherdDrawOptions, sherd_draw_options_free>;

/// A synthetic sherd with its true axis and the ground truth as JSON.
struct SyntheticSherd {
    Mesh mesh;
    SherdAxis true_axis;
    std::string truth_json;
};

/// A synthetic sherd (`kind` a SHERD_SYNTH_KIND_* value; `target_faces` 0 for the default).
inline SyntheticSherd synthetic_sherd(std::uint64_t seed, std::uint32_t kind, std::size_t target_faces = 0,
                                      double noise_mm = 0.02) {
    SherdMesh* handle = nullptr;
    SherdBuffer* truth = nullptr;
    SherdAxis axis = make_axis({0, 0, 0}, {0, 0, 1});
    check(sherd_synthetic_sherd(seed, kind, target_faces, noise_mm, &handle, &axis, &truth));
    Mesh mesh(handle);
    return SyntheticSherd{std::move(mesh), axis, take_buffer(truth)};
}

/// Repairs `mesh` in place; returns the report as JSON.
inline std::string repair(Mesh& mesh, bool keep_largest_component = true) {
    RepairOptions options(sherd_repair_options_new);
    check(sherd_repair_options_set_keep_largest_component(options.get(), keep_largest_component));
    SherdBuffer* report = nullptr;
    check(sherd_mesh_repair(mesh.get(), options.get(), &report));
    return take_buffer(report);
}

/// A decimated copy with about `target_faces` triangles.
inline Mesh decimate(const Mesh& mesh, std::size_t target_faces) {
    SherdMesh* handle = nullptr;
    check(sherd_mesh_decimate(mesh.get(), target_faces, &handle));
    return Mesh(handle);
}

/// The outcome of an orientation: when `oriented` is false the axis is a guess and
/// `reason` says why (NEEDS_MANUAL_ORIENTATION and SENSE_UNCERTAIN are answers, not
/// exceptions; with SENSE_UNCERTAIN the axis line is good, its sense a guess).
struct Orientation {
    SherdAxis axis;
    SherdOrientReport report;
    bool oriented;
    std::string reason;
    std::string report_json;
};

namespace detail {
inline Orientation finish_orientation(SherdStatus status, const SherdAxis& axis, const SherdOrientReport& report,
                                      SherdBuffer* json) {
    if (status != SHERD_STATUS_OK && status != SHERD_STATUS_NEEDS_MANUAL_ORIENTATION &&
        status != SHERD_STATUS_SENSE_UNCERTAIN) {
        sherd_buffer_free(json);
        throw Error(status, sherd_last_error_message());
    }
    std::string reason = status == SHERD_STATUS_OK ? std::string() : std::string(sherd_last_error_message());
    return Orientation{axis, report, status == SHERD_STATUS_OK, reason, take_buffer(json)};
}

inline SherdOrientReport empty_report() {
    SherdOrientReport report{};
    report.size = sizeof(SherdOrientReport);
    return report;
}
}  // namespace detail

/// Automatic orientation from the normals (default options).
inline Orientation orient_automatic(const Mesh& mesh) {
    SherdAxis axis = make_axis({0, 0, 0}, {0, 0, 1});
    SherdOrientReport report = detail::empty_report();
    SherdBuffer* json = nullptr;
    SherdStatus status = sherd_orient_automatic(mesh.get(), nullptr, &axis, &report, &json);
    return detail::finish_orientation(status, axis, report, json);
}

/// Orientation from three points (x y z each) picked on one horizontal feature.
inline Orientation orient_from_three_points(const Mesh& mesh, const std::array<double, 9>& points) {
    SherdAxis axis = make_axis({0, 0, 0}, {0, 0, 1});
    SherdOrientReport report = detail::empty_report();
    SherdBuffer* json = nullptr;
    SherdStatus status = sherd_orient_from_three_points(mesh.get(), points.data(), nullptr, &axis, &report, &json);
    return detail::finish_orientation(status, axis, report, json);
}

/// Three points (x y z each) on the longest wheel rill traced under `axis`: where to pick
/// for orient_from_three_points on a sherd orient_automatic declines, under the axis it
/// still gives. Empty on a smooth wall.
inline std::optional<std::array<double, 9>> points_on_longest_rill(const Mesh& mesh, const SherdAxis& axis) {
    std::array<double, 9> points{};
    std::size_t count = 0;
    check(sherd_points_on_longest_rill(mesh.get(), &axis, points.data(), &count));
    if (count != 3) return std::nullopt;
    return points;
}

/// A refinement: the refined axis, its summary, the Pareto front and the report as JSON.
struct Refinement {
    SherdAxis axis;
    SherdRefineReport report;
    std::vector<SherdParetoPoint> pareto_front;
    std::string report_json;
};

/// Refines `axis` with `criterion` (SHERD_CRITERION_*) on `surface` (SHERD_SURFACE_*).
inline Refinement refine(const Mesh& mesh, const SherdAxis& axis, std::uint32_t criterion = SHERD_CRITERION_AUTO,
                         std::uint32_t surface = SHERD_SURFACE_BOTH) {
    RefineOptions options(sherd_refine_options_new);
    check(sherd_refine_options_set_criterion(options.get(), criterion));
    check(sherd_refine_options_set_surface(options.get(), surface));
    SherdRefinement* handle = nullptr;
    check(sherd_refine(mesh.get(), &axis, options.get(), &handle));
    struct Release {
        SherdRefinement* handle;
        ~Release() { sherd_refinement_free(handle); }
    } release{handle};
    Refinement result{make_axis({0, 0, 0}, {0, 0, 1}), SherdRefineReport{}, {}, {}};
    result.report.size = sizeof(SherdRefineReport);
    check(sherd_refinement_axis(handle, &result.axis));
    check(sherd_refinement_report(handle, &result.report));
    result.pareto_front.resize(result.report.pareto_point_count);
    std::size_t count = 0;
    check(sherd_refinement_pareto_front(handle, result.pareto_front.data(), result.pareto_front.size(), &count));
    SherdBuffer* json = nullptr;
    check(sherd_refinement_report_json(handle, &json));
    result.report_json = take_buffer(json);
    return result;
}

/// Measurements with intervals (`bootstrap_samples` resamples; 0: none, NaN intervals).
inline SherdMeasurements measure(const Mesh& mesh, const SherdAxis& axis, std::size_t bootstrap_samples = 20,
                                 std::string* json = nullptr) {
    MeasureOptions options(sherd_measure_options_new);
    check(sherd_measure_options_set_bootstrap_samples(options.get(), bootstrap_samples));
    SherdMeasurements measurements{};
    measurements.size = sizeof(SherdMeasurements);
    SherdBuffer* buffer = nullptr;
    check(sherd_measure(mesh.get(), &axis, options.get(), &measurements, json ? &buffer : nullptr));
    if (json) *json = take_buffer(buffer);
    return measurements;
}

/// A finished drawing (SherdDrawing).
class Drawing {
public:
    /// Builds the drawing; `styles` is a combination of SHERD_STYLE_* bits.
    Drawing(const Mesh& mesh, const SherdAxis& axis, std::uint32_t styles, double dpi = 300.0,
            const std::string& title = std::string()) {
        DrawOptions options(sherd_draw_options_new);
        check(sherd_draw_options_set_style(options.get(), styles));
        check(sherd_draw_options_set_dpi(options.get(), dpi));
        if (!title.empty()) check(sherd_draw_options_set_title(options.get(), title.c_str()));
        check(sherd_drawing_build(mesh.get(), &axis, options.get(), &handle_));
    }
    Drawing(const Drawing&) = delete;
    Drawing& operator=(const Drawing&) = delete;
    Drawing(Drawing&& other) noexcept : handle_(std::exchange(other.handle_, nullptr)) {}
    ~Drawing() { sherd_drawing_free(handle_); }

    /// The drawing in `format` (SHERD_FORMAT_*).
    std::string to_bytes(std::uint32_t format) const {
        SherdBuffer* buffer = nullptr;
        check(sherd_drawing_to_buffer(handle_, format, &buffer));
        return take_buffer(buffer);
    }

    /// Writes the drawing, the format by the extension.
    void write(const std::string& path) const { check(sherd_drawing_write(handle_, path.c_str())); }

private:
    SherdDrawing* handle_ = nullptr;
};

/// Writes the 3D reconstruction (the profile revolved) as PLY.
inline void export_reconstruction_ply(const Mesh& mesh, const SherdAxis& axis, const std::string& path,
                                      double angle_rad = NAN, std::size_t segments = 0, bool binary = true) {
    check(sherd_export_reconstruction_ply(mesh.get(), &axis, angle_rad, segments, path.c_str(), binary));
}

/// Writes `mesh` moved into the oriented frame as PLY.
inline void export_oriented_ply(const Mesh& mesh, const SherdAxis& axis, const std::string& path, bool binary = true) {
    check(sherd_export_oriented_ply(mesh.get(), &axis, path.c_str(), binary));
}

/// The most informative profile angle, radians about the axis.
inline double most_informative_angle(const Mesh& mesh, const SherdAxis& axis) {
    double angle = 0.0;
    check(sherd_profile_most_informative_angle(mesh.get(), &axis, &angle));
    return angle;
}

/// The profile section as CSV (`curve,index,r_mm,z_mm,closed`); NaN: the most informative angle.
inline std::string profile_csv(const Mesh& mesh, const SherdAxis& axis, double angle_rad = NAN) {
    SherdBuffer* buffer = nullptr;
    check(sherd_profile_csv(mesh.get(), &axis, angle_rad, &buffer));
    return take_buffer(buffer);
}

/// Writes the profile section as CSV.
inline void export_profile_csv(const Mesh& mesh, const SherdAxis& axis, const std::string& path,
                               double angle_rad = NAN) {
    check(sherd_export_profile_csv(mesh.get(), &axis, angle_rad, path.c_str()));
}

/// The 3D reconstruction: the profile section at `angle_rad` (NaN: the most informative)
/// revolved in `segments` steps (0: 180), a closed mesh in the oriented frame (apply the
/// inverse of `mesh.oriented_transform(axis)` to place it with the scan).
inline Mesh reconstruct(const Mesh& mesh, const SherdAxis& axis, double angle_rad = NAN, std::size_t segments = 0) {
    SherdMesh* handle = nullptr;
    check(sherd_reconstruct(mesh.get(), &axis, angle_rad, segments, &handle));
    return Mesh(handle);
}

/// A regularity map: one value (mm) and one RGBA colour per vertex of the mesh, and the
/// values at the ends of the colour scale.
struct Regularity {
    std::vector<float> values;
    std::vector<std::uint8_t> rgba;
    std::array<double, 2> value_range;
};

/// The regularity map `kind` (SHERD_REGULARITY_*) of `mesh` about `axis`; `angle_rad` is
/// the section of the ideal vessel (NaN: the most informative).
inline Regularity regularity(const Mesh& mesh, const SherdAxis& axis,
                             std::uint32_t kind = SHERD_REGULARITY_IDEAL_VESSEL, double angle_rad = NAN) {
    const std::size_t count = mesh.vertex_count();
    Regularity map{std::vector<float>(count), std::vector<std::uint8_t>(4 * count), {}};
    check(sherd_regularity(mesh.get(), &axis, kind, angle_rad, map.values.data(), map.rgba.data(), count,
                           map.value_range.data()));
    return map;
}

/// What the whole pipeline found (`sherd orient --json`'s record): `status` is
/// SHERD_STATUS_OK, SHERD_STATUS_SENSE_UNCERTAIN (axis set, its sense a guess, `reason`
/// says why) or SHERD_STATUS_NEEDS_MANUAL_ORIENTATION (then `axis` is unset, `reason`
/// says why, and `record_json`'s "best_guess" holds the axis the orientation still found,
/// not to be trusted, when it found one); errors throw.
struct Analysis {
    SherdStatus status;
    SherdAxis axis;
    std::string reason;
    std::string record_json;
};

namespace detail {
template <typename Call>
Analysis finish_analysis(Call call) {
    Analysis result{SHERD_STATUS_OK, make_axis({0, 0, 0}, {0, 0, 0}), {}, {}};
    SherdBuffer* json = nullptr;
    result.status = call(&result.axis, &json);
    if (result.status != SHERD_STATUS_OK && result.status != SHERD_STATUS_NEEDS_MANUAL_ORIENTATION &&
        result.status != SHERD_STATUS_SENSE_UNCERTAIN) {
        const std::string message = sherd_last_error_message();
        if (json) sherd_buffer_free(json);
        throw Error(result.status, message);
    }
    if (result.status != SHERD_STATUS_OK) result.reason = sherd_last_error_message();
    result.record_json = take_buffer(json);
    return result;
}

inline SherdRefineOptions* refine_options_or_default(const RefineOptions* options) {
    return options ? options->get() : nullptr;
}
}  // namespace detail

/// Reads, repairs, orients, refines and measures the scan at `path` as `sherd orient
/// --json` does; `refine_options` NULL for the command's default (AUTO, both surfaces).
inline Analysis process_file(const std::string& path, const RefineOptions* refine_options = nullptr,
                             double millimetres_per_unit = 1.0) {
    return detail::finish_analysis([&](SherdAxis* axis, SherdBuffer** json) {
        return sherd_process_file(path.c_str(), detail::refine_options_or_default(refine_options),
                                  millimetres_per_unit, axis, json);
    });
}

/// Like process_file for a mesh already in memory (the record's file is "<memory>").
inline Analysis analyse(const Mesh& mesh, const RefineOptions* refine_options = nullptr,
                        double millimetres_per_unit = 1.0) {
    return detail::finish_analysis([&](SherdAxis* axis, SherdBuffer** json) {
        return sherd_analyse(mesh.get(), detail::refine_options_or_default(refine_options), millimetres_per_unit,
                             axis, json);
    });
}

}  // namespace sherd

#endif  // SHERD_HPP
