// sherd.hpp: a header-only C++17 wrapper over the sherd C ABI (sherd.h).
//
// Handles become RAII objects (copyable by deep copy, cheaply movable); every status
// other than SHERD_STATUS_OK becomes a sherd::Error carrying the status and the
// library's message. NEEDS_MANUAL_ORIENTATION is not an exception where a result still
// comes back (orientation): the result says so.
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

}  // namespace sherd

#endif  // SHERD_HPP
