// Mesh loading and saving: byte-level checks (format_check), OpenMesh's readers and writers
// (openmesh_bridge), then validation and our own fan triangulation, so triangle order is ours.
#include "mesh/mesh_io.h"

#include "base/atomic_file.h"
#include "mesh/format_check.h"
#include "mesh/openmesh_bridge.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <fstream>
#include <iostream>
#include <iterator>
#include <mutex>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <system_error>

namespace rtlab {

namespace {

std::string name_of(const std::filesystem::path& path) {
    return path.string();
}

std::string lower_extension(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

std::string format_name(MeshFormat f) {
    switch (f) {
    case MeshFormat::obj:
        return "OBJ";
    case MeshFormat::ply:
        return "PLY";
    case MeshFormat::off:
        return "OFF";
    case MeshFormat::stl:
        return "STL";
    }
    return "?";
}

std::string read_bytes(const std::filesystem::path& path) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) {
        throw Error(name_of(path) + ": no such file");
    }
    if (!std::filesystem::is_regular_file(path, ec)) {
        throw Error(name_of(path) + ": not a regular file");
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        throw Error(name_of(path) + ": cannot open for reading");
    }
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) {
        throw Error(name_of(path) + ": read error");
    }
    return bytes;
}

/// Writes OBJ text with shortest round-trip floats. OpenMesh's OBJ writer prints fixed-point
/// coordinates, which lose small values, so OBJ is the one format we write ourselves.
bool write_obj(const TriangleMesh& mesh, const std::filesystem::path& path) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    if (!out) {
        return false;
    }
    out << "# rtlab: " << mesh.positions.size() << " vertices, " << mesh.triangles.size()
        << " triangles\n";
    char buf[64];
    for (const Vec3f& p : mesh.positions) {
        out << 'v';
        for (const float c : {p.x, p.y, p.z}) {
            const auto r = std::to_chars(buf, buf + sizeof(buf), c);
            out << ' ' << std::string_view(buf, static_cast<std::size_t>(r.ptr - buf));
        }
        out << '\n';
    }
    for (const auto& t : mesh.triangles) {
        out << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
    }
    out.close();
    return static_cast<bool>(out);
}

}  // namespace

MeshFormat mesh_format_of(const std::filesystem::path& path) {
    const std::string ext = lower_extension(path);
    if (ext == ".obj") {
        return MeshFormat::obj;
    }
    if (ext == ".ply") {
        return MeshFormat::ply;
    }
    if (ext == ".off") {
        return MeshFormat::off;
    }
    if (ext == ".stl") {
        return MeshFormat::stl;
    }
    throw Error(name_of(path) + ": unknown mesh extension '" + path.extension().string() +
                "' (expected .obj, .ply, .off or .stl)");
}

bool is_mesh_path(const std::filesystem::path& path) {
    const std::string ext = lower_extension(path);
    return ext == ".obj" || ext == ".ply" || ext == ".off" || ext == ".stl";
}

void validate_mesh(const TriangleMesh& mesh, std::string_view what) {
    const std::string w(what);
    if (mesh.triangles.empty()) {
        throw Error(w + ": mesh has no faces");
    }
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        if (!is_finite(mesh.positions[i])) {
            throw Error(w + ": vertex " + std::to_string(i) + " has a non-finite coordinate");
        }
    }
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
        for (const std::uint32_t v : mesh.triangles[i]) {
            if (v >= mesh.positions.size()) {
                throw Error(w + ": triangle " + std::to_string(i) + ": vertex index " +
                            std::to_string(v) + " out of range (" +
                            std::to_string(mesh.positions.size()) + " vertices)");
            }
        }
    }
}

TriangleMesh load_mesh(const std::filesystem::path& path) {
    const std::string what = name_of(path);
    const MeshFormat format = mesh_format_of(path);
    const std::string bytes = read_bytes(path);
    if (bytes.empty()) {
        throw Error(what + ": empty file");
    }
    const detail::DeclaredCounts declared = detail::check_mesh_bytes(bytes, format, what);
    if (declared.ignored_materials) {
        // Once per file and process: the scene's materials apply, not the OBJ's.
        static std::mutex mutex;
        static std::set<std::string> warned;
        const std::lock_guard<std::mutex> lock(mutex);
        if (warned.insert(what).second) {
            std::cerr << "rtlab: warning: " << what
                      << ": OBJ materials (mtllib/usemtl) are ignored; the scene's material "
                         "applies\n";
        }
    }

    detail::RawMesh raw;
    if (!detail::openmesh_read(path, raw)) {
        throw Error(what + ": OpenMesh could not parse the file as " + format_name(format));
    }
    const std::size_t faces = raw.face_offsets.size() - 1;
    // The byte check and the reader must agree; a difference means the reader dropped or invented
    // elements, which would break the face-order contract.
    if (faces != declared.faces ||
        (declared.vertices_known && raw.positions.size() != declared.vertices)) {
        throw Error(what + ": reader delivered " + std::to_string(raw.positions.size()) +
                    " vertices and " + std::to_string(faces) + " faces, file declares " +
                    std::to_string(declared.vertices) + " and " + std::to_string(declared.faces));
    }

    TriangleMesh mesh;
    mesh.positions = std::move(raw.positions);
    const auto nv = static_cast<std::int64_t>(mesh.positions.size());
    for (std::size_t k = 0; k < faces; ++k) {
        const std::size_t begin = raw.face_offsets[k];
        const std::size_t n = raw.face_offsets[k + 1] - begin;
        if (n < 3) {
            throw Error(what + ": face " + std::to_string(k) + " has " + std::to_string(n) +
                        " vertices, needs at least 3");
        }
        for (std::size_t j = 0; j < n; ++j) {
            const std::int64_t v = raw.face_indices[begin + j];
            if (v < 0 || v >= nv) {
                throw Error(what + ": face " + std::to_string(k) + ": vertex index " +
                            std::to_string(v) + " out of range (" + std::to_string(nv) +
                            " vertices)");
            }
        }
        // Fan from the first vertex: (v0, vj, vj+1) for j = 1 .. n-2, in order.
        const auto at = [&](std::size_t j) {
            return static_cast<std::uint32_t>(raw.face_indices[begin + j]);
        };
        for (std::size_t j = 1; j + 1 < n; ++j) {
            mesh.triangles.push_back({at(0), at(j), at(j + 1)});
        }
    }
    validate_mesh(mesh, what);
    return mesh;
}

void save_mesh(const TriangleMesh& mesh,
               const std::filesystem::path& path,
               const MeshSaveOptions& options) {
    const std::string what = name_of(path);
    const MeshFormat format = mesh_format_of(path);
    validate_mesh(mesh, what);
    if (mesh.positions.size() > 0x7fffffffu) {
        throw Error(what + ": too many vertices for OpenMesh");
    }
    if (format == MeshFormat::obj) {
        for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
            const auto& t = mesh.triangles[i];
            if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
                throw Error(what + ": triangle " + std::to_string(i) +
                            " repeats a vertex, which OBJ readers drop (use PLY or OFF)");
            }
        }
    }
    // base/atomic_file.h: a temporary in the same folder (so rename is atomic) keeping the
    // extension (OpenMesh picks the writer by it); FIFOs and devices are written into.
    const bool binary = options.binary && (format == MeshFormat::ply || format == MeshFormat::stl);
    write_atomically(path, [&](const std::filesystem::path& tmp) {
        const bool ok = format == MeshFormat::obj ? write_obj(mesh, tmp)
                                                  : detail::openmesh_write(mesh, tmp, binary);
        if (!ok) {
            throw Error(what + ": OpenMesh could not write the " + format_name(format) + " file");
        }
    });
}

}  // namespace rtlab
